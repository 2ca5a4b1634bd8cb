"""The time schemes (crankgen.discrete.time_scheme) against their theory, on a linear problem with a closed
form: the rod at rest (the crank does not turn, approach C, exact Lagrange equations), whose reduced
equations M qdd + C qd + K q = 0 are exactly linear.  Its modes come from M and K assembled here;
a modal state's motion is known in closed form (undamped: q cos(omega t)).

- generalized-alpha converges at order 2 to the closed form (and Newmark too);
- one step maps a mode's (q, h qd, h^2 a) by Chung & Hulbert's amplification matrix, derived here
  from the scheme's three equations, and at omega h -> infinity its spectral radius is rho_inf;
- Chung & Hulbert's parameters at rho_inf = 1 (alpha_m = alpha_f = 1/2) give the trapezoidal rule;
- on a linear problem the form crankgen implements (Arnold & Bruls: the equations hold at t_{n+1})
  gives the very states of Chung & Hulbert's original form (the balance at t_{n+1-alpha}),
  integrated here by its own recurrence;
- the compiled engine and the NumPy reference agree (both are run on every check).
"""

import math

import numpy as np
import pytest
import scipy.linalg

from crankgen import engine
from crankgen.discrete import time_scheme
from crankgen.declaration.cases import Case
from crankgen.discrete.system import Model
from crankgen.discrete.newmark import NewmarkSettings, integrate

N_ELEMENTS = 4


def _rod(mu=0.0):
    """The case and model of the rod at rest, and its assembled M, C, K (dense)."""
    case = Case(omega=0.0, eps=0.02, mu=mu, approach="C", formulation="lagrange", damping="kelvin-voigt",
                n_elements=N_ELEMENTS, steps_per_rev=100)
    model = Model.from_case(case)
    zero = np.zeros(model.n_dofs)
    terms = model.element_terms(model.kinematics(0.0), zero, zero, zero)
    M, C, K = (model.assembler.dense(m) for m in (terms.M, terms.C, terms.K))
    return case, model, M, C, K


def _modes(M, K):
    """Natural frequencies (ascending) and M-orthonormal mode shapes (columns)."""
    w2, phi = scipy.linalg.eigh(K, M)
    return np.sqrt(w2), phi


def _march(case, model, h, n, d0, v0, a0=None, g0=None, rho_inf=0.8, which="compiled", integrator="newton"):
    """(d, v, qdd, a) after n steps of size h from (d0, v0) (a0: qdd, by default from the
    equations; g0: the algorithmic accelerations) with generalized-alpha of rho_inf, in either
    engine.  integrator="one-pass": one linear solve a step, exact on this linear problem (and
    free of Newton's stopping test, which cannot resolve increments at omega h = 1e7)."""
    from dataclasses import replace
    case = replace(case, rho_inf=rho_inf, integrator=integrator)
    if which == "numpy":
        hist = integrate(model, d0, v0, 0.0, h, n, NewmarkSettings.of_case(case, tol=1e-14), a0=a0, g0=g0)
        g = hist.a if hist.g is None else hist.g
        return hist.d[-1], hist.v[-1], hist.a[-1], g[-1]
    res = engine.march(engine.Batch([case], dt=h), n, D0=d0[None], V0=v0[None],
                       A0=None if a0 is None else a0[None], G0=None if g0 is None else g0[None], tol=1e-14)
    assert res.status[0] == engine.OK
    return res.D[0], res.V[0], res.A[0], res.G[0]


@pytest.mark.parametrize("rho_inf", [1.0, 0.8, 0.3])
def test_second_order_convergence_to_the_closed_form(rho_inf):
    """The first bending mode, started at rest with amplitude q: d(t) = q phi cos(omega t).  The
    error at t = 1.25 periods (where a phase error shows at first order) shrinks fourfold per
    halving of the step (order 2), in both engines."""
    case, model, M, C, K = _rod()
    w, phi = _modes(M, K)
    q = 1e-3 * phi[:, 0] / np.max(np.abs(phi[:, 0]))
    t = 1.25 * 2 * math.pi / w[0]
    for which in ("compiled", "numpy"):
        errors = []
        for n in (40, 80, 160):
            d = _march(case, model, t / n, n, q, np.zeros_like(q), rho_inf=rho_inf, which=which)[0]
            errors.append(np.max(np.abs(d - q * math.cos(w[0] * t))) / np.max(np.abs(q)))
        ratios = [errors[0] / errors[1], errors[1] / errors[2]]
        assert errors[-1] < 1e-2
        assert all(3.7 < r < 4.3 for r in ratios), (which, errors, ratios)


def _chung_hulbert_matrix(rho, wh):
    """One step of Chung & Hulbert's method on qdd + omega^2 q = 0, acting on (q, h qd, h^2 a),
    from its three equations (derived here, independently of crankgen.discrete.time_scheme):
        (1 - am) a1 + am a0 + w2 ((1 - af) q1 + af q0) = 0,
        q1 = q0 + v0 + (1/2 - beta) a0 + beta a1,   v1 = v0 + (1 - gamma) a0 + gamma a1."""
    am, af = (2 * rho - 1) / (rho + 1), rho / (rho + 1)
    g = 0.5 - am + af
    b = 0.25 * (1 - am + af) ** 2
    w2 = wh ** 2
    # unknowns (q1, v1, a1)
    lhs = np.array([[1.0, 0.0, -b], [0.0, 1.0, -g], [w2 * (1 - af), 0.0, 1 - am]])
    rhs = np.array([[1.0, 1.0, 0.5 - b], [0.0, 1.0, 1 - g], [-w2 * af, 0.0, -am]])
    return np.linalg.solve(lhs, rhs)


@pytest.mark.parametrize("rho_inf", [0.8, 0.5, 0.0])
def test_one_step_is_the_chung_hulbert_amplification_and_high_frequencies_decay_by_rho_inf(rho_inf):
    """The rod's highest mode at omega h = 1e3: the engine's step maps its (q, h qd, h^2 a) by the
    amplification matrix of the theory, whose spectral radius tends to rho_inf as omega h grows
    (1e8: to 2e-5, a triple root): what a step cannot resolve is damped by rho_inf per step.  The lowest mode at
    omega h = 0.01 is not damped (spectral radius 1 to 1e-7)."""
    case, model, M, C, K = _rod()
    w, phi = _modes(M, K)
    for mode, wh in ((-1, 1e3), (0, 0.01)):
        shape, omega = phi[:, mode], w[mode]
        h = wh / omega
        for which in ("compiled", "numpy"):
            columns = []
            for unit in np.eye(3):
                q, v, a = 1e-3 * unit * np.array([1.0, 1.0 / h, 1.0 / h ** 2])
                d0, v0 = q * shape, v * shape
                d, vv, acc, g = _march(case, model, h, 1, d0, v0, a0=-omega ** 2 * d0, g0=a * shape,
                                       rho_inf=rho_inf, which=which, integrator="one-pass")
                # modal co-ordinates (phi is M-orthonormal); the step keeps the mode's shape
                project = lambda x: float(shape @ M @ x)
                size = np.max(np.abs(shape)) * 1e-3
                assert np.max(np.abs(d - project(d) * shape)) < 1e-9 * size
                columns.append([project(d) / 1e-3, h * project(vv) / 1e-3, h ** 2 * project(g) / 1e-3])
            A = np.array(columns).T
            theory = _chung_hulbert_matrix(rho_inf, wh)
            assert np.allclose(A, theory, rtol=1e-7, atol=1e-7 * np.max(np.abs(theory))), (which, A, theory)
            radius = np.max(np.abs(np.linalg.eigvals(A)))
            if wh > 1:
                assert rho_inf <= radius < rho_inf + 0.03, (which, radius)
            else:
                assert abs(radius - 1.0) < 1e-7, (which, radius)
    limit = np.max(np.abs(np.linalg.eigvals(_chung_hulbert_matrix(rho_inf, 1e8))))
    assert abs(limit - rho_inf) < 2e-5          # a triple root there: eigenvalues to eps^(1/3)
    assert abs(time_scheme.spectral_radius(time_scheme.coefficients(rho_inf), 1e8) - limit) < 2e-5


def test_chung_hulbert_at_rho_one_is_the_trapezoidal_rule():
    """alpha_m = alpha_f = 1/2 (Chung & Hulbert's rho_inf = 1) through the generalized code path of
    the NumPy reference: the trapezoidal rule's states (crankgen runs rho_inf = 1 as Newmark, whose
    state needs no algorithmic acceleration), from a state mixing every mode, with damping."""
    case, model, M, C, K = _rod(mu=0.05)
    rng = np.random.default_rng(7)
    w, phi = _modes(M, K)
    d0 = 1e-3 * phi @ (rng.standard_normal(len(w)) / (1 + np.arange(len(w))))
    v0 = 1e-3 * phi @ rng.standard_normal(len(w))
    ch = time_scheme.chung_hulbert(1.0)
    assert (ch.alpha_m, ch.alpha_f, ch.beta, ch.gamma) == (0.5, 0.5, 0.25, 0.5)
    general = NewmarkSettings(alpha_m=ch.alpha_m, alpha_f=ch.alpha_f, beta=ch.beta, gamma=ch.gamma, tol=1e-14)
    trapezoid = NewmarkSettings(tol=1e-14)
    assert general.generalized and not trapezoid.generalized
    h = 0.3 / w[0]
    qdd0 = np.linalg.solve(M, -C @ v0 - K @ d0)
    a = integrate(model, d0, v0, 0.0, h, 60, general, g0=qdd0)       # a_0 = qdd_0: no starter step
    b = integrate(model, d0, v0, 0.0, h, 60, trapezoid)
    scale = np.max(np.abs(b.d))
    assert np.max(np.abs(a.d - b.d)) < 1e-9 * scale
    assert np.max(np.abs(a.g - b.a)) < 1e-9 * np.max(np.abs(b.a))          # a = qdd at every step
    assert time_scheme.coefficients(1.0) == time_scheme.Coefficients()     # rho_inf = 1: Newmark


def test_arnold_bruls_equals_chung_hulbert_on_a_linear_problem():
    """Chung & Hulbert's original form, M a_{n+1-alpha_m} + C v_{n+1-alpha_f} + K d_{n+1-alpha_f} = 0
    (x_{n+1-alpha} = (1 - alpha) x_{n+1} + alpha x_n) with Newmark's updates in a, integrated here by
    its recurrence, against crankgen's form (the equations at t_{n+1}, a carried beside qdd): the
    same displacements, in both engines (with Kelvin-Voigt damping, C = mu K), both started from
    a_0 = qdd_0 (crankgen's own start takes a damped first step instead: next test)."""
    rho = 0.6
    case, model, M, C, K = _rod(mu=0.05)
    assert np.max(np.abs(C)) > 0
    rng = np.random.default_rng(3)
    w, phi = _modes(M, K)
    d0 = 1e-3 * phi @ (rng.standard_normal(len(w)) / (1 + np.arange(len(w))))
    v0 = 1e-3 * phi @ (rng.standard_normal(len(w)) / (1 + np.arange(len(w))))
    c = time_scheme.coefficients(rho)
    am, af, b, g = c.alpha_m, c.alpha_f, c.beta, c.gamma
    h, n = 0.2 / w[0], 50
    d, v = d0.copy(), v0.copy()
    a = np.linalg.solve(M, -C @ v - K @ d)
    for _ in range(n):
        # unknown a1: d1 = dp + b h^2 a1, v1 = vp + g h a1
        dp = d + h * v + h * h * (0.5 - b) * a
        vp = v + h * (1 - g) * a
        lhs = (1 - am) * M + (1 - af) * (g * h * C + b * h * h * K)
        rhs = -(am * M @ a + C @ ((1 - af) * vp + af * v) + K @ ((1 - af) * dp + af * d))
        a1 = np.linalg.solve(lhs, rhs)
        d, v, a = dp + b * h * h * a1, vp + g * h * a1, a1
    qdd0 = np.linalg.solve(M, -C @ v0 - K @ d0)
    for which in ("compiled", "numpy"):
        mine = _march(case, model, h, n, d0, v0, g0=qdd0, rho_inf=rho, which=which)   # no starter
        assert np.max(np.abs(mine[0] - d)) < 1e-9 * np.max(np.abs(d)), which
        assert np.max(np.abs(mine[3] - a)) < 1e-8 * np.max(np.abs(a)), which    # a: Chung & Hulbert's acceleration


def test_the_step_warning_names_an_unresolved_undamped_mode():
    """The rod's first axial mode (lambda tan lambda = 1/ms*, omega = lambda / (pi^2 eps)) against
    a fixed-mass rod's closed form, and the warning: Newmark leaves it undamped at omega dt = 7.6
    (the README's steel mechanism), rho_inf = 0.8 damps it, physical damping mu does too."""
    ms = 0.5
    lam = time_scheme.first_axial_frequency(0.01, ms) * math.pi ** 2 * 0.01
    assert lam * math.tan(lam) == pytest.approx(1 / ms, rel=1e-12)
    assert time_scheme.first_axial_frequency(0.01, 0.0) == pytest.approx(0.5 / (math.pi * 0.01), rel=1e-12)
    dt = 7.6 / time_scheme.first_axial_frequency(0.0077, 0.5)
    assert [m[0] for m in time_scheme.unresolved_modes(1.0, dt, 100, 0.0077, 0.5, 0.0)] == ["axial"]
    assert time_scheme.unresolved_modes(0.8, dt, 100, 0.0077, 0.5, 0.0) == []
    assert time_scheme.unresolved_modes(1.0, dt, 100, 0.0077, 0.5, 0.5) == []
    case = Case(eps=0.001, omega=0.8, model="paper")
    assert case.rho_inf == 1.0 and "axial" in time_scheme.step_warning(case)
    assert time_scheme.step_warning(Case(eps=0.001, omega=0.8)) is None       # the consistent model


def test_a_start_takes_the_damped_starter_step_and_stays_second_order():
    """A run from a state without algorithmic accelerations starts with one step of Newmark's
    beta = 1/2, gamma = 1 (time_scheme.STARTER), then a = qdd: the step's coefficients are the
    starter's (checked here against that step done by the NumPy reference with Newmark's settings,
    in both engines), and the run stays second order (the convergence test above starts so)."""
    case, model, M, C, K = _rod(mu=0.05)
    w, phi = _modes(M, K)
    d0 = 1e-3 * (phi[:, 0] + 0.3 * phi[:, -1])
    v0 = np.zeros_like(d0)
    h = 0.2 / w[0]
    s = time_scheme.STARTER
    starter = integrate(model, d0, v0, 0.0, h, 1, NewmarkSettings(beta=s.beta, gamma=s.gamma, tol=1e-14))
    for which in ("compiled", "numpy"):
        d, v, acc, g = _march(case, model, h, 1, d0, v0, rho_inf=0.8, which=which)
        assert np.max(np.abs(d - starter.d[1])) < 1e-12 * np.max(np.abs(d0)), which
        assert np.array_equal(g, acc), which                    # a = qdd after the starter


@pytest.mark.parametrize("flags, scheme", [([], "generalized-alpha (rho_inf = 0.8)"),
                                           (["--model", "paper"], "Newmark's trapezoidal rule"),
                                           (["--rho-inf", "0.5"], "generalized-alpha (rho_inf = 0.5)")])
def test_the_command_lines_run_line_names_the_time_scheme(tmp_path, capsys, flags, scheme):
    from crankgen.cli.main import main
    rc = main(["simulate", "--omega", "0.5", "--elements", "2", "--revolutions", "0.1", "--out",
               str(tmp_path)] + flags)
    err = capsys.readouterr().err
    assert rc == 0
    line = next(ln for ln in err.splitlines() if ln.startswith("simulate: approach"))
    assert f"membrane, {scheme}, " in line
