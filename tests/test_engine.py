"""The compiled engine against the NumPy reference implementation, and its own pieces."""

import math

import numpy as np
import pytest
import scipy.linalg

import crankgen
from crankgen import engine
from crankgen.declaration import schema
from crankgen.declaration.cases import Case
from crankgen.analyses.steady import steady_state, steady_states

# every scheme with generalized-alpha (rho_inf = 0.8), Newton's also with Newmark (rho_inf = 1)
COMBOS = [(f, ap, dmp, integ, rho) for f in ("lagrange", "paper") for ap in "ABC"
          for dmp in ("paper", "kelvin-voigt") for integ in ("newton", "one-pass", "full-newton")
          for rho in ((0.8, 1.0) if integ == "newton" else (0.8,))]


@pytest.mark.parametrize("formulation, approach, damping, integrator, rho_inf", COMBOS)
def test_compiled_engine_equals_numpy_reference(formulation, approach, damping, integrator, rho_inf):
    mech = crankgen.Mechanism(a=0.2, eps=0.02, ms=0.7, mu=0.3)
    omega = 0.6 if approach != "B" else 0.3     # consistent B diverges at higher speeds
    kw = dict(omega=omega, approach=approach, formulation=formulation, damping=damping,
              integrator=integrator, n_elements=3, steps_per_rev=40, revolutions=1.5, rho_inf=rho_inf)
    ref = crankgen.simulate(mech, engine="numpy", **kw)
    fast = crankgen.simulate(mech, engine="compiled", **kw)
    scale = np.max(np.abs(ref.v_mid))
    assert scale > 0
    np.testing.assert_allclose(fast.v_mid, ref.v_mid, rtol=0, atol=1e-11 * scale)
    np.testing.assert_allclose(fast.u_end, ref.u_end, rtol=0, atol=1e-11 * np.max(np.abs(ref.u_end)))
    np.testing.assert_allclose(fast.extension, ref.extension, rtol=0,
                               atol=1e-11 * np.max(np.abs(ref.extension)))
    assert np.array_equal(fast.iterations, ref.iterations)


@pytest.mark.parametrize("approach", ["A", "B"])
def test_compiled_engine_equals_numpy_reference_with_averaged_membrane(approach):
    mech = crankgen.Mechanism(a=0.2, eps=0.02, ms=0.7, mu=0.3)
    kw = dict(omega=0.5 if approach == "A" else 0.2, approach=approach, formulation="lagrange",
              damping="kelvin-voigt",
              n_elements=3, steps_per_rev=40, revolutions=1.5, membrane="averaged")
    ref = crankgen.simulate(mech, engine="numpy", **kw)
    fast = crankgen.simulate(mech, engine="compiled", **kw)
    plain = crankgen.simulate(mech, **{**kw, "membrane": "pointwise"})
    np.testing.assert_allclose(fast.v_mid, ref.v_mid, rtol=0, atol=1e-11 * np.max(np.abs(ref.v_mid)))
    assert np.max(np.abs(plain.v_mid - fast.v_mid)) > 1e-4 * np.max(np.abs(fast.v_mid))   # the option acts


def test_progress_chunks_do_not_change_the_trajectory():
    mech = crankgen.Mechanism()
    calls = []
    a = crankgen.simulate(mech, n_elements=4, revolutions=2, integrator="one-pass")
    b = crankgen.simulate(mech, n_elements=4, revolutions=2, integrator="one-pass",
                          progress=lambda done, total: calls.append(done))
    assert np.array_equal(a.v_mid, b.v_mid)
    assert calls[-1] == 200 and len(calls) > 5


def test_band_solver_with_pivoting_matches_dense_solve():
    rng = np.random.default_rng(3)
    N, kb = 17, 3
    A = np.zeros((N, N))
    for i in range(N):
        for j in range(max(0, i - kb), min(N, i + kb + 1)):
            A[i, j] = rng.standard_normal()
    A[np.arange(N), np.arange(N)] *= 1e-3          # small diagonal: pivoting is needed
    W = np.zeros((N, 3 * kb + 1))
    for i in range(N):
        for j in range(max(0, i - kb), min(N, i + kb + 1)):
            W[i, j - i + kb] = A[i, j]
    B = rng.standard_normal((N, 4))
    X = B.copy()
    assert engine.band_solve(W, kb, X)
    np.testing.assert_allclose(X, scipy.linalg.solve(A, B), rtol=1e-9, atol=1e-12)


def _band_matrix(rng, N, kb, diagonal):
    A = np.zeros((N, N))
    for i in range(N):
        for j in range(max(0, i - kb), min(N, i + kb + 1)):
            A[i, j] = rng.standard_normal()
    A[np.arange(N), np.arange(N)] = diagonal
    return A


@pytest.mark.parametrize("kb", engine.FIXED_WIDTHS)
def test_fixed_bandwidth_solver_matches_dense_solve_and_refuses_small_pivots(kb):
    rng = np.random.default_rng(4)
    N = 23
    A = _band_matrix(rng, N, kb, 8.0 + rng.uniform(size=N))   # positive definite symmetric part
    F, diag = np.zeros((N + kb, 2 * kb + 1)), np.zeros(N)
    F[N:, kb] = 1.0
    for i in range(N):
        for j in range(max(0, i - kb), min(N, i + kb + 1)):
            F[i, j - i + kb] = A[i, j]
    F0 = F.copy()
    assert engine.factor_fixed(F, N, diag)
    b = np.concatenate([rng.standard_normal(N), np.full(kb, np.nan)])     # padding is reset
    x = b.copy()
    engine.solve_fixed(F, N, x)
    np.testing.assert_allclose(x[:N], scipy.linalg.solve(A, b[:N]), rtol=1e-11, atol=1e-13)
    B = rng.standard_normal((N, 3))                     # the shooting's tangent solves: many columns
    X = B.copy()
    engine.solve_fixed_columns(F, X)
    np.testing.assert_allclose(X, scipy.linalg.solve(A, B), rtol=1e-11, atol=1e-13)
    # the same matrix assembled from element matrices (consecutive blocks of kb + 1 DOFs)
    n = N - kb
    dofs = np.full((n, schema.ELEMENT_DOFS), N + 100, dtype=np.int64)     # >= N: left out
    dofs[:, :kb + 1] = np.arange(n)[:, None] + np.arange(kb + 1)
    SE = np.zeros((n, schema.ELEMENT_DOFS, schema.ELEMENT_DOFS))
    for i in range(N):                  # each entry of A given to the first element holding it
        for j in range(max(0, i - kb), min(N, i + kb + 1)):
            e = min(min(i, j), n - 1)
            SE[e, i - e, j - e] = A[i, j]
    G = np.full_like(F, np.nan)
    engine.assemble_fixed(dofs, SE, G, N)
    np.testing.assert_array_equal(G, F0)
    # matrices that need row interchanges are refused, so that the step falls back to band_factor
    for k, value in ((3, 0.0), (0, 1e-9)):      # zero diagonal; tiny first pivot (huge multipliers)
        B = A.copy()
        B[k, k] = value
        F[:N] = 0.0
        for i in range(N):
            for j in range(max(0, i - kb), min(N, i + kb + 1)):
                F[i, j - i + kb] = B[i, j]
        assert not engine.factor_fixed(F, N, diag)


@pytest.mark.parametrize("model, kb", [("consistent", 5), ("exact", 7)])
def test_iteration_matrix_factorizations_agree_on_a_real_step(model, kb):
    """The iteration matrix of a 16-element case (nodes (u, v, psi): bandwidth 5; the exact rod's
    (u, v, psi, chi): 7): fixed-bandwidth LU = pivoted band LU = dense."""
    fields = dict(damping="kelvin-voigt", membrane="pointwise") if model == "consistent" else {}
    case = Case(model=model, omega=0.8, n_elements=16, **fields)
    b = engine.Batch([case])
    assert b.meshdata.kb == kb and engine.fixed_width(kb)
    n, N = 16, b.mesh.n_rod          # the rod's nodal unknowns; the crank's co-ordinate follows them
    rng = np.random.default_rng(5)
    d, v, a = (1e-4 * rng.standard_normal(b.N) for _ in range(3))
    dofs, l = b.meshdata.dofs, b.meshdata.l
    w = engine.make_work(b.meshdata, b.N)
    sel, cf, params = b.records.select[0], b.records.coef[0], b.records.params[0]

    def loop(mode, cv, cd):
        engine.element_terms(mode, b.kernels, sel, cf, params, False, dofs, l, d, v, a, 1.3, cv, cd, w)
    loop(engine.NEWMARK, 0.04, 1.5e-3)
    rE, SE = w.rE.copy(), w.SE.copy()
    # the combined element matrices equal M + cv C + cd K of the full terms
    loop(engine.FULL, 0.0, 0.0)
    r2, K2, C2, M2 = w.rE.copy(), w.KE.copy(), w.CE.copy(), w.ME.copy()
    np.testing.assert_allclose(SE, M2 + 0.04 * C2 + 1.5e-3 * K2, rtol=1e-12, atol=1e-12 * np.abs(SE).max())
    np.testing.assert_allclose(rE, r2, rtol=1e-12, atol=1e-12 * np.abs(r2).max())
    loop(engine.RESIDUAL, 0.0, 0.0)
    res = w.rE.copy()
    np.testing.assert_allclose(res, r2, rtol=1e-12, atol=1e-12 * np.abs(r2).max())
    A = np.zeros((N, N))
    for e in range(n):
        for i in range(schema.ELEMENT_DOFS):          # the chi slots map to the dummy, >= N
            for j in range(schema.ELEMENT_DOFS):
                if dofs[e, i] < N and dofs[e, j] < N:
                    A[dofs[e, i], dofs[e, j]] += SE[e, i, j]
    rhs = rng.standard_normal(N)
    F, diag = np.zeros((N + kb, 2 * kb + 1)), np.zeros(N)
    engine.assemble_fixed(dofs, SE, F, N)
    assert engine.factor_fixed(F, N, diag)
    x = np.concatenate([rhs, np.zeros(kb)])
    engine.solve_fixed(F, N, x)
    W = np.zeros((N, 3 * kb + 1))
    engine.assemble_band_newmark(dofs, kb, SE, W)
    piv, ext = np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64)
    assert engine.band_factor(W, kb, piv, ext)
    y = rhs[:, None].copy()
    engine.band_lu_solve(W, kb, piv, ext, y)
    exact = scipy.linalg.solve(A, rhs)
    np.testing.assert_allclose(x[:N], exact, rtol=1e-10, atol=1e-12 * np.abs(exact).max())
    np.testing.assert_allclose(y[:, 0], exact, rtol=1e-10, atol=1e-12 * np.abs(exact).max())


def test_newton_with_reused_factorization_agrees_with_full_newton():
    """The default scheme (reused factorization, error-estimate stop, extrapolated start) converges
    to the full Newton solution well within tol (its speed is measured by make bench, not here)."""
    mech = crankgen.Mechanism()
    kw = dict(omega=0.9, n_elements=16, damping="kelvin-voigt", revolutions=3)
    fast = crankgen.simulate(mech, integrator="newton", **kw)
    full = crankgen.simulate(mech, integrator="full-newton", **kw)
    scale = np.max(np.abs(full.v_mid))
    assert np.max(np.abs(fast.v_mid - full.v_mid)) < 1e-9 * scale
    assert np.max(np.abs(fast.u_end - full.u_end)) < 1e-9 * np.max(np.abs(full.u_end))


def test_newton_control_is_one_code_for_engine_and_reference():
    """The engine compiles the very functions the NumPy reference calls (newton.py), so the
    schemes' constants and decisions cannot drift apart."""
    from crankgen.discrete import newton
    from crankgen.engine import kernels as compiled
    assert compiled.next_iteration.py_func is newton.next_iteration
    assert compiled.extrapolation_weight.py_func is newton.extrapolation_weight
    from crankgen.discrete import newmark
    assert newmark.SCHEMES is newton.SCHEMES and newmark.HISTORY is newton.HISTORY


NEW_OPTIONS = [dict(rotary_inertia=False), dict(gravity=(0.3, -0.7)), dict(offset=0.15),
               dict(gravity=(-0.2, 0.4), offset=-0.1, rotary_inertia=False)]


@pytest.mark.parametrize("formulation", ["lagrange", "paper"])
@pytest.mark.parametrize("options", NEW_OPTIONS, ids=["no-rotary", "gravity", "offset", "all"])
def test_compiled_engine_equals_numpy_reference_with_the_new_ingredients(formulation, options):
    mech_kw = {k: v for k, v in options.items() if k in ("gravity", "offset")}
    mech = crankgen.Mechanism(a=0.2, eps=0.02, ms=0.7, mu=0.3, **mech_kw)
    kw = dict(omega=0.6, approach="A", formulation=formulation, damping="kelvin-voigt",
              membrane="pointwise", n_elements=3, steps_per_rev=40, revolutions=1.5,
              rotary_inertia=options.get("rotary_inertia", True))
    ref = crankgen.simulate(mech, engine="numpy", **kw)
    fast = crankgen.simulate(mech, engine="compiled", **kw)
    plain = crankgen.simulate(crankgen.Mechanism(a=0.2, eps=0.02, ms=0.7, mu=0.3),
                              **{**kw, "rotary_inertia": True})
    scale = np.max(np.abs(ref.v_mid))
    np.testing.assert_allclose(fast.v_mid, ref.v_mid, rtol=0, atol=1e-11 * scale)
    np.testing.assert_allclose(fast.u_end, ref.u_end, rtol=0, atol=1e-11 * np.max(np.abs(ref.u_end)))
    assert np.array_equal(fast.iterations, ref.iterations)
    assert np.max(np.abs(plain.v_mid - fast.v_mid)) > 1e-6 * scale       # the ingredient acts


def test_chunked_marching_continues_the_starting_guess():
    """march(..., previous=...) continues a run exactly: same states and iteration counts (with
    generalized-alpha's algorithmic accelerations G carried on)."""
    b = engine.Batch([Case(omega=0.7, n_elements=6, damping="kelvin-voigt")])
    whole = engine.march(b, 120)
    first = engine.march(b, 50)
    rest = engine.march(b, 70, D0=first.D, V0=first.V, A0=first.A, G0=first.G, step0=50, previous=first.previous)
    assert np.array_equal(np.concatenate([first.iterations, rest.iterations], axis=1), whole.iterations)
    np.testing.assert_array_equal(rest.y[:, -1], whole.y[:, -1])


def test_lock_step_batch_equals_single_runs_and_isolates_failures():
    cases = [Case(omega=0.5, n_elements=4, steps_per_rev=50),
             Case(omega=0.8, approach="B", formulation="lagrange", n_elements=4, steps_per_rev=50),
             Case(omega=1.1, approach="C", formulation="paper", damping="kelvin-voigt",
                  n_elements=4, steps_per_rev=50)]
    batch = engine.march(engine.Batch(cases), 150)
    assert batch.status[0] == batch.status[2] == engine.OK and batch.status[1] in (engine.NOT_CONVERGED,
                                                                                  engine.TOO_LARGE)
    for i in (0, 2):
        single = engine.march(engine.Batch([cases[i]]), 150)
        assert np.array_equal(single.y[0], batch.y[i])


def test_balanced_slices_cover_every_case_and_share_the_active_ones_evenly():
    from crankgen.engine.batch import balanced_bounds
    rng = np.random.default_rng(3)
    for _ in range(200):
        lo = int(rng.integers(0, 5))
        hi = lo + int(rng.integers(1, 40))
        active = np.zeros(hi + 3, dtype=bool)
        active[lo:hi] = rng.random(hi - lo) < rng.random()
        if rng.random() < 0.3:                      # the active cases side by side, as in a sweep
            active[lo:hi] = False
            start = int(rng.integers(lo, hi))
            active[start:hi] = True
        parts = int(rng.integers(1, 10))
        bounds = balanced_bounds(lo, hi, active, parts)
        assert bounds[0] == lo and bounds[-1] == hi and all(a < b for a, b in zip(bounds, bounds[1:]))
        counts = [int(active[a:b].sum()) for a, b in zip(bounds, bounds[1:])]
        n = int(active[lo:hi].sum())
        assert len(counts) == max(1, min(parts, n))
        assert max(counts) - min(counts) <= 1


def test_a_batch_whose_active_cases_cluster_marches_the_same_on_threads_and_serially():
    """Only the last cases of the batch are active (as the slow, non-periodic cases of a sweep): the
    threads share them, and every case, active or not, comes back as a serial run gives it."""
    cases = [Case(omega=0.3 + 0.1 * k, n_elements=4, steps_per_rev=50) for k in range(10)]
    batch = engine.Batch(cases)
    rng = np.random.default_rng(0)
    D0 = 1e-3 * rng.standard_normal((len(cases), batch.N))
    status = np.array([engine.NOT_CONVERGED] * 7 + [engine.OK] * 3)
    runs = [engine.march(batch, 60, D0=D0, status=status, parallel=p) for p in (True, False)]
    for name in ("y", "D", "V", "A", "status", "iterations"):
        assert np.array_equal(getattr(runs[0], name), getattr(runs[1], name), equal_nan=True), name
    assert np.array_equal(runs[0].D[:7], D0[:7])                   # inactive: left where they were
    assert not np.array_equal(runs[0].D[7:], D0[7:])


def test_a_batch_like_another_shares_its_mesh_and_tables_and_marches_the_same():
    """Batch(cases, like=b) (the continuation's batch per parameter value) reuses b's mesh and kernel
    tables when the cases are of b's model and mesh, and is built anew otherwise."""
    base = engine.Batch([Case(omega=0.5, n_elements=4, steps_per_rev=50)])
    cases = [Case(omega=0.7, n_elements=4, steps_per_rev=50), Case(omega=0.9, n_elements=4, steps_per_rev=50)]
    like, fresh = engine.Batch(cases, like=base), engine.Batch(cases)
    assert like.meshdata is base.meshdata and like.kernels is base.kernels
    for a, b in zip(like.records, fresh.records):
        assert np.array_equal(a, b)
    assert np.array_equal(engine.march(like, 60).y, engine.march(fresh, 60).y)
    other = engine.Batch([Case(omega=0.7, n_elements=4, steps_per_rev=50, approach="C")], like=base)
    assert not np.array_equal(other.records.select[0], base.records.select[0])
    assert other.kernels is not base.kernels
    assert engine.Batch([Case(omega=0.7, n_elements=5, steps_per_rev=50)], like=base).N != base.N


@pytest.mark.parametrize("rho_inf", [1.0, 0.7])
def test_revolution_jacobian_matches_finite_differences(rho_inf):
    """The exact Jacobian of the revolution map against central differences of the map: Newmark's
    on (d, v), generalized-alpha's on (d, v, a) (its algorithmic accelerations' columns too)."""
    case = Case(omega=0.8, n_elements=3, steps_per_rev=30, mu=0.2, damping="paper", membrane="pointwise",
                rho_inf=rho_inf)
    b = engine.Batch([case])
    N = b.N
    warm = engine.march(b, 60)
    X0 = engine.join_state(warm, rho_inf < 1)
    X1, J, st = engine.revolution(b, X0)
    assert st[0] == engine.OK and J.shape[1:] == (b.state_size, b.state_size)
    S = np.concatenate([b.scales[0]] * (b.state_size // N))
    for k in (0, 4, N + 1, 2 * N - 1) + ((2 * N, 3 * N - 2) if rho_inf < 1 else ()):
        h = 1e-6 * S[k]
        cols = []
        for sign in (1, -1):
            X = X0.copy()
            X[0, k] += sign * h
            Y, _, _ = engine.revolution(b, X, tol=1e-14)
            cols.append(Y[0])
        fd = (cols[0] - cols[1]) / (2 * h)
        assert np.max(np.abs(fd - J[0, :, k]) * S[k] / S) < 1e-6 * max(1.0, np.max(np.abs(J[0, :, k]) * S[k] / S))


def test_shooting_and_marching_find_the_same_periodic_state():
    s = steady_state(omega=0.8, n_elements=4, method="shooting", tol=1e-10)
    m = steady_state(omega=0.8, n_elements=4, method="march", tol=1e-10)
    assert s.status == m.status == "periodic"
    assert s.iterations >= 1 and m.iterations == 0 and m.periods > s.periods
    assert s.amplitude == pytest.approx(m.amplitude, rel=1e-8)
    np.testing.assert_allclose(s.v_mid, m.v_mid, atol=1e-8 * s.amplitude)
    assert 0 < s.multiplier < 1


def test_steady_state_is_a_fixed_point_of_the_simulation():
    """Simulate from rest for many revolutions: the last revolution equals the steady state."""
    s = steady_state(omega=0.6, n_elements=4, steps_per_rev=60)
    r = crankgen.simulate(crankgen.Mechanism(), omega=0.6, n_elements=4, steps_per_rev=60,
                          revolutions=40)
    np.testing.assert_allclose(r.v_mid[-61:], s.v_mid, atol=1e-7 * s.amplitude)


def test_failed_cases_are_reported_not_hidden():
    res = steady_states([Case(omega=0.8, approach="B", formulation="lagrange", n_elements=4),
                         Case(omega=0.8, n_elements=4)])
    # B (no quartic term: its strain energy is unbounded below) diverges from rest within the
    # first revolution at Omega* = 0.8: Newton fails, which is reported as such
    assert res[0].status == "failed" and not res[0].ok
    assert "Newton did not converge in step" in res[0].message
    assert res[1].status == "periodic" and math.isfinite(res[1].amplitude)


@pytest.mark.parametrize("name", ["inertia_lagrange", "elastic_lagrange_A"])
def test_compiled_lane_function_gives_each_element_the_one_element_numbers_to_the_last_bit(name):
    """The engine runs the rod's families on lanes of elements (the compiled, vectorized
    `<name>_lanes`); each lane's numbers must be those of the compiled one-element function
    `<name>_element` exactly, in every mode (elastic_lagrange_A: negative powers, printed
    differently in the lane functions)."""
    import numba

    from crankgen.declaration import schema
    from crankgen.engine.calls import address, call
    from crankgen.engine.kernels import SIGNATURES, compiled

    lane = np.array([address(compiled("lanes", name), SIGNATURES["lanes"])], dtype=np.int64)
    one = np.array([address(compiled("element", name), SIGNATURES["element"])], dtype=np.int64)

    @numba.njit
    def run(table, args):
        call(table, 0, args)

    L, rows, n = schema.LANES, schema.LANE_ROWS, schema.ELEMENT_DOFS
    rng = np.random.default_rng(11)
    coef = np.array(Case().coefficients, dtype=float)
    kin = rng.uniform(0.1, 1.0, len(schema.KINEMATICS))
    for mode in range(len(schema.ELEMENT_MODES)):
        b = np.zeros(schema.LANE_SIZE)
        nodal = 1e-2 * rng.standard_normal((L, 3, n))
        geo = np.stack([rng.uniform(0.05, 0.5, L), rng.uniform(0.0, 0.9, L)], axis=1)
        for j in range(L):
            for block, value in zip(("q", "qd", "qdd", "geo"), (*nodal[j], geo[j])):
                b[(rows[block] + np.arange(value.size)) * L + j] = value
        run(lane, (mode, b, coef, kin, 0.037, 2.9e-4))
        for j in range(L):
            one_out = [np.zeros(n)] + [np.zeros((n, n)) for _ in range(4)]
            run(one, (mode, *nodal[j], geo[j], coef, kin, 0.037, 2.9e-4, *one_out))
            for block, value in zip(("r", "K", "C", "M", "S"), one_out):
                got = b[(rows[block] + np.arange(value.size)) * L + j]
                assert np.array_equal(got, value.ravel()), (name, mode, block, j)
            assert np.any(one_out[0] != 0)
