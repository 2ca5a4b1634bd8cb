"""The four-bar linkage with a flexible coupler (guide="circle") against independent truths.

* Rigid kinematics: crankgen's closure (two circles intersected, rates by implicit
  differentiation in SymPy) against Freudenstein's equation in the rocker angle solved through
  the half-angle tangent, rates from the loop equations (tests/four_bar.py), over a revolution of
  a crank whose speed fluctuates (thetadd != 0), both branches, an offset ground pivot and a drag
  link (the ground pivot inside the crank's circle: crank and rocker both turn fully): 1e-12.
* The end map: the end stays on the rocker's circle for any deviation s; its rows are the
  derivatives they claim (finite differences); the reduced tangents are the derivatives of the
  reduced residual (the g_ss term included).
* Refusals: a linkage whose crank cannot turn, guide parameters given to the line guide.
* The stiff limit (eps -> 0) and the quasi-static limit (Omega* -> 0), against the rigid
  four-bar and the static rod under its inertia loads.
* The compiled engine against the NumPy reference.
"""

import numpy as np
import pytest

import crankgen
from crankgen.discrete import kinematics as _kinematics
from crankgen.declaration import schema
from crankgen.declaration.cases import Case
from crankgen.errors import ParameterError
from crankgen.discrete.system import Model

import four_bar as fb

# (a, c, d, offset, branch): a crank-rocker, its other branch, an offset ground pivot with a long
# rocker, and a drag link (|D| < a)
GEOMETRIES = [(0.1, 0.8, 1.0, 0.0, 1), (0.3, 0.9, 1.1, 0.2, -1), (0.25, 1.2, 0.6, -0.3, 1),
              (0.5, 0.8, 0.1, 0.0, 1)]
IDS = ["crank-rocker", "other-branch", "offset", "drag-link"]
K = schema.KIN


def _angle(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=IDS)
def test_rigid_kinematics_agree_with_freudenstein(geometry):
    a, c, d, e, branch = geometry
    case = Case(guide="circle", a=a, c=c, d=d, offset=e, branch=branch,
                motion=crankgen.Fluctuation(omega=0.7, amplitude=0.4, order=2))
    t = np.linspace(0.0, _kinematics.period(case), 1001)
    kin = _kinematics.case_state(case, t).vector
    mine = fb.four_bar(kin[:, K["theta"]], kin[:, K["thetad"]], kin[:, K["thetadd"]], a, c, d, e, branch)
    assert np.ptp(kin[:, K["theta"]]) == pytest.approx(2 * np.pi)        # a whole revolution
    assert np.max(np.abs(kin[:, K["thetadd"]])) > 0.3                     # the crank accelerates
    for name in ("phi", "beta"):
        assert np.max(np.abs(_angle(kin[:, K[name]] - mine[name]))) < 1e-12, name
    for name in ("phid", "phidd", "betad", "betadd"):
        scale = max(1.0, np.max(np.abs(mine[name])))
        assert np.max(np.abs(kin[:, K[name]] - mine[name])) < 1e-12 * scale, name
    # the rocker's tip is B = A + e_i, on the side of A -> D the branch names
    B = np.stack([d + c * np.cos(mine["beta"]), e + c * np.sin(mine["beta"])], -1)
    A = a * np.stack([np.cos(mine["theta"]), np.sin(mine["theta"])], -1)
    np.testing.assert_allclose(np.hypot(*(B - A).T), 1.0, rtol=0, atol=1e-13)
    side = (d - A[:, 0]) * (B[:, 1] - A[:, 1]) - (e - A[:, 1]) * (B[:, 0] - A[:, 0])
    assert np.all(np.sign(side) == branch)
    np.testing.assert_allclose(_kinematics.rigid_end(case, kin), B, rtol=0, atol=1e-13)


def test_rigid_rates_are_time_derivatives():
    """The rates of both analyses are the time derivatives of their positions (central
    differences along the fluctuating crank's motion)."""
    a, c, d, e, branch = GEOMETRIES[2]
    case = Case(guide="circle", a=a, c=c, d=d, offset=e, branch=branch,
                motion=crankgen.Fluctuation(omega=0.7, amplitude=0.4, order=2))
    t = np.linspace(0.5, 8.0, 9)
    h = 1e-4

    def crankgen_kin(s):
        k = _kinematics.case_state(case, s).vector
        return {name: k[:, K[name]] for name in K}

    def independent(s):
        k = crankgen_kin(s)               # the crank's motion: tests/test_crank_motions.py checks it
        return fb.four_bar(k["theta"], k["thetad"], k["thetadd"], a, c, d, e, branch)

    for source in (crankgen_kin, independent):
        now, plus, minus = source(t), source(t + h), source(t - h)
        for value, rate in (("phi", "phid"), ("phid", "phidd"), ("beta", "betad"), ("betad", "betadd"),
                            ("theta", "thetad"), ("thetad", "thetadd")):
            step = plus[value] - minus[value]
            if value in ("phi", "beta"):
                step = _angle(step)
            np.testing.assert_allclose(step / (2 * h), now[rate], rtol=0, atol=1e-7,
                                       err_msg=f"{source.__name__}: {rate}")


def _trajectory(case, t):
    """kin(t) and a smooth deviation s(t) of the rocker angle with its rates."""
    kin = _kinematics.case_state(case, t).vector
    s = 0.05 * np.sin(1.3 * t) + 0.02
    sd = 0.05 * 1.3 * np.cos(1.3 * t)
    sdd = -0.05 * 1.3**2 * np.sin(1.3 * t)
    return kin, s, sd, sdd


def test_end_map_keeps_the_end_on_the_rocker_and_its_rows_are_derivatives():
    """(u, v) = g(s, t) puts B = A + (1 + u) e_i + v e_j on the circle |B - D| = c for finite s
    (s up to 0.07 rad); qd, qdd are the time derivatives of q along s(t); g_s, g_ss, dqd/ds,
    dqdd/ds, dqdd/dsd the derivatives in s and its rates (central differences)."""
    a, c, d, e, branch = GEOMETRIES[1]
    case = Case(guide="circle", a=a, c=c, d=d, offset=e, branch=branch,
                motion=crankgen.Fluctuation(omega=0.9, amplitude=0.3, order=1))
    R = schema.END_MAP_ROWS
    t = np.linspace(0.2, 6.0, 13)
    kin, s, sd, sdd = _trajectory(case, t)
    E = _kinematics.end_map(case, kin, s, sd, sdd)
    th, ph = kin[:, K["theta"]], kin[:, K["phi"]]
    ei = np.stack([np.cos(ph), -np.sin(ph)], -1)
    ej = np.stack([np.sin(ph), np.cos(ph)], -1)
    A = a * np.stack([np.cos(th), np.sin(th)], -1)
    B = A + (1 + E[:, R["q"], :1]) * ei + E[:, R["q"], 1:] * ej
    np.testing.assert_allclose(np.hypot(B[:, 0] - d, B[:, 1] - e), c, rtol=0, atol=1e-14)
    # and B is the rocker's tip at the angle beta + s
    b = kin[:, K["beta"]] + s
    np.testing.assert_allclose(B, np.stack([d + c * np.cos(b), e + c * np.sin(b)], -1), rtol=0, atol=1e-14)
    h = 1e-5
    q = lambda tt: _kinematics.end_map(case, *_trajectory(case, tt))[:, R["q"]]        # noqa: E731
    qd = lambda tt: _kinematics.end_map(case, *_trajectory(case, tt))[:, R["qd"]]      # noqa: E731
    np.testing.assert_allclose((q(t + h) - q(t - h)) / (2 * h), E[:, R["qd"]], rtol=0, atol=1e-9)
    np.testing.assert_allclose((qd(t + h) - qd(t - h)) / (2 * h), E[:, R["qdd"]], rtol=0, atol=1e-8)
    for row, wrt, derivative in (("q", 0, "g_s"), ("qd", 0, "dqd_ds"), ("qdd", 0, "dqdd_ds"),
                                 ("qdd", 1, "dqdd_dsd"), ("qd", 1, "g_s"), ("qdd", 2, "g_s"),
                                 ("g_s", 0, "g_ss")):
        args = [s, sd, sdd]
        plus, minus = list(args), list(args)
        plus[wrt], minus[wrt] = args[wrt] + h, args[wrt] - h
        at = lambda args: _kinematics.end_map(case, kin, *args)[:, R[row]]       # noqa: E731
        fd = (at(plus) - at(minus)) / (2 * h)
        np.testing.assert_allclose(fd, E[:, R[derivative]], rtol=0, atol=1e-9, err_msg=f"d{row}/d{wrt}")


def test_reduced_tangents_are_derivatives_of_the_reduced_residual():
    """The projected end element (d'Alembert, with the end map's curvature g_ss in K): the
    Newmark matrix's parts dR/da, dR/dv, dR/dd against central differences of the reduced residual,
    four-bar with a fluctuating crank, a state with the rocker off its rigid angle."""
    case = Case(guide="circle", a=0.3, c=0.9, d=1.1, offset=0.2, eps=0.05,
                motion=crankgen.Fluctuation(omega=0.9, amplitude=0.3, order=1), n_elements=3)
    model = Model(case)
    rng = np.random.default_rng(4)
    N = model.n_dofs
    scales = model.mesh.dof_scales(case.eps, _kinematics.end_scale(case))
    d, v, a = (2 * scales * rng.standard_normal(N) for _ in range(3))
    t = 1.7
    kin = model.kinematics(t)

    def dense(terms, c_v, c_d):
        return model.assembler.dense(terms.M + c_v * terms.C + c_d * terms.K)

    terms = model.element_terms(kin, d, v, a)
    M = dense(terms, 0.0, 0.0)
    parts = {"a": M, "v": dense(terms, 1.0, 0.0) - M, "d": dense(terms, 0.0, 1.0) - M}
    fds = {}
    for which, X in parts.items():
        fd = np.zeros((N, N))
        for j in range(N):
            h = 1e-4 * scales[j]
            plus, minus = {"d": d, "v": v, "a": a}, {"d": d, "v": v, "a": a}
            step = np.zeros(N)
            step[j] = h
            plus[which], minus[which] = plus[which] + step, minus[which] - step
            fd[:, j] = (model.residual(t, **plus) - model.residual(t, **minus)) / (2 * h)
        scale = np.max(np.abs(X), axis=0)
        err = np.max(np.abs(fd - X), axis=0) / scale
        assert np.all(err < 1e-6), (which, err)
        fds[which] = fd
    # the curvature term g_ss . r_end counts: without it, dR/dd of the end DOF is off
    _, E, r, K_, C_, M_ = model.unprojected_terms(kin, d, v, a)
    E = E.copy()
    E[schema.END_MAP_ROWS["g_ss"]] = 0.0
    from crankgen.discrete.constraints import project
    last = project(E, r[-1], K_[-1], C_[-1], M_[-1])
    K_[-1], C_[-1], M_[-1] = last[1], last[2], last[3]
    s = model.mesh.reduced_coordinates()[0]
    without = model.assembler.dense(K_)
    assert abs(without[s, s] - fds["d"][s, s]) > 1e-3 * np.max(np.abs(parts["d"][:, s]))


def test_a_linkage_whose_crank_cannot_turn_is_refused():
    # the rod and the rocker cannot reach each other when the crank points towards D
    with pytest.raises(ParameterError, match=r"full revolution.*\|1 - c\|.*got a = 0.3, offset = 0, c = 0.8, d = 0.4"):
        crankgen.Mechanism(guide="circle", a=0.3, c=0.8, d=0.4)
    # ... nor when it points away from D
    with pytest.raises(ParameterError, match=r"full revolution.*\|D\| \+ a\* < 1 \+ c"):
        crankgen.Mechanism(guide=crankgen.Circle(center=(1.6, 0.3), radius=0.8), a=0.3)
    with pytest.raises(ParameterError, match="full revolution"):
        Case(guide="circle", a=0.2, c=0.2, d=1.0)
    # a ground pivot on the crank's circle: the rod would have to reach |1 - c| at distance 0
    with pytest.raises(ParameterError, match="full revolution"):
        crankgen.Mechanism(guide="circle", a=0.3, c=0.8, d=0.3)
    crankgen.Mechanism(guide="circle", a=0.3, c=0.8, d=1.0)                 # a crank-rocker turns
    crankgen.Mechanism(guide="circle", a=0.5, c=0.8, d=0.1)                 # a drag link turns


def test_guide_parameters_given_to_the_line_guide_are_refused():
    for kw in (dict(c=0.5), dict(d=1.2), dict(branch=-1), dict(guide="line", c=0.5),
               dict(guide=crankgen.Line(offset=0.1), d=0.9)):
        name = next(k for k in kw if k != "guide")
        with pytest.raises(ParameterError, match=rf"{name} .*circle guide only.*'line'"):
            crankgen.Mechanism(**kw)
    with pytest.raises(ParameterError, match="c is given twice"):
        crankgen.Mechanism(guide=crankgen.Circle(center=(1.0, 0.0), radius=0.8), c=0.5)
    with pytest.raises(ParameterError, match="Line takes no argument 'radius'"):
        crankgen.Line(radius=0.8)
    r = crankgen.simulate(crankgen.Mechanism(), omega=0.5, n_elements=2, steps_per_rev=20, revolutions=0.2)
    with pytest.raises(ParameterError, match="rocker_angle exists for the circle guide only"):
        r.rocker_angle


def test_flat_and_record_forms_agree():
    m1 = crankgen.Mechanism(guide=crankgen.Circle(center=(1.1, 0.2), radius=0.9, branch=-1), a=0.3)
    m2 = crankgen.Mechanism(guide="circle", c=0.9, d=1.1, offset=0.2, branch=-1, a=0.3)
    assert m1 == m2 and m1.guide_record == crankgen.Circle(center=(1.1, 0.2), radius=0.9, branch=-1)


# ---- the stiff and the quasi-static limits ----------------------------------------------------

LINKAGE = dict(guide="circle", a=0.3, c=0.9, d=1.1, offset=0.2, branch=1)


def _steady(omega, eps, approach, mu=0.5, ms=0.5, spr=100):
    mech = crankgen.Mechanism(eps=eps, ms=ms, mu=mu, **LINKAGE)
    st = crankgen.steady_state(mech, omega=omega, approach=approach, n_elements=8, steps_per_rev=spr)
    assert st.ok, st.message
    return st


def _rigid(st):
    g = LINKAGE
    return fb.four_bar(st.theta, st.case.omega, 0 * st.theta, g["a"], g["c"], g["d"], g["offset"], g["branch"])


def test_stiff_limit_the_rocker_follows_the_rigid_four_bar_to_order_eps_squared():
    """Omega* = 0.5, steady revolutions.  In crankgen's units EI is fixed, so eps -> 0 stiffens the
    rod axially (EA = 1 / (pi^4 eps^2)) while its bending deflection v stays (v* = v / eps grows).
    Approach C (linear strain): the chord's length changes only by the axial strain, and the
    rocker's deviation from the rigid four-bar is O(eps^2): 1.73e-3 at eps = 0.01, 4.31e-4 at
    0.005, 1.07e-4 at 0.0025 (ratios 4.03, 4.01; deviation / eps^2 -> 17.2).  Approach A: the
    bent rod's chord is shorter by (1/2) int v_x^2 dx, which does not vanish with eps; the
    deviation tends to that of the inextensible bent rod (2.74e-2) with an O(eps^2) remainder
    (successive differences in the ratio 4), and the membrane extension delta* is O(eps^2)."""
    eps_values = (0.01, 0.005, 0.0025)
    dev = {}
    for approach in "CA":
        runs = [_steady(0.5, eps, approach) for eps in eps_values]
        dev[approach] = [st.rocker_angle - _rigid(st)["beta"] for st in runs]
        if approach == "A":
            ext = [np.max(np.abs(st.extension)) for st in runs]
    peak = [np.max(np.abs(x)) for x in dev["C"]]
    assert peak[0] < 2e-3
    for k in (0, 1):
        assert 3.8 < peak[k] / peak[k + 1] < 4.2, peak
    # the deviation's shape converges: dev / eps^2 differs by O(eps^2) between eps values
    shape = [x / eps**2 for x, eps in zip(dev["C"], eps_values)]
    assert np.max(np.abs(shape[1] - shape[2])) < 0.01 * np.max(np.abs(shape[2]))
    # approach A: an eps-independent limit, approached at O(eps^2)
    diff = [np.max(np.abs(dev["A"][k] - dev["A"][k + 1])) for k in (0, 1)]
    assert 3.5 < diff[0] / diff[1] < 4.5, diff
    assert np.max(np.abs(dev["A"][2])) > 10 * peak[0]        # the bending shortening dominates
    for k in (0, 1):
        assert 3.5 < ext[k] / ext[k + 1] < 4.5, ext


def test_quasi_static_limit_is_the_rigid_four_bar_inertia_loading():
    """Approach C, light damping mu* = 0.005, heavy end mass ms* = 2: v*(1/2) and u*(1) approach
    the static rod under the rigid four-bar's inertia loads (tests/four_bar.py: pinned at the
    crank, the end node moving along the rocker's tangent, in balance along it with the end mass)
    at O(Omega*^2): v* 7.7e-3 off at Omega* = 0.04, 1.9e-3 at 0.02 (ratio 4.0); u*(1) 5e-4 and
    2e-4 (the damping lag, O(mu* Omega*), weighs more there)."""
    errors = []
    for omega in (0.04, 0.02):
        st = _steady(omega, 0.01, "C", mu=0.005, ms=2.0, spr=200)
        vm, ue = fb.quasi_static(_rigid(st), LINKAGE["a"], 0.01, 2.0)
        errors.append([np.max(np.abs(got - want)) / np.max(np.abs(want))
                       for got, want in ((st.v_mid, vm), (st.u_end, ue))])
    errors = np.array(errors)
    assert np.all(errors[1] < 2.5e-3), errors
    assert errors[0, 0] / errors[1, 0] > 3.5, errors          # v*: O(Omega*^2)
    assert np.all(errors[:, 1] < 1e-3), errors


# ---- the compiled engine against the NumPy reference ----------------------------------------

STEP_OUTPUTS = ("torque", "crank_on_rod_x", "crank_on_rod_y", "guide_on_slider_x", "guide_on_slider_y",
                "rod_on_slider_x", "rod_on_slider_y", "rocker_on_tip_x", "rocker_on_tip_y", "rod_on_tip_x",
                "rod_on_tip_y", "crank_speed",
                "slider_position", "end_height", "chord_angle", "rocker_angle")


def compare_engines(mech, **kw):
    """Both engines' runs: the same numbers to 1e-11 of each signal's scale, the same iterations."""
    ref = crankgen.simulate(mech, engine="numpy", **kw)
    fast = crankgen.simulate(mech, engine="compiled", **kw)
    assert np.array_equal(fast.iterations, ref.iterations)
    outputs = ("v_mid", "u_end", "extension") + tuple(
        n for n in STEP_OUTPUTS if ref.case.guide in schema.OUTPUTS[n].guides)
    for name in outputs:
        x, y = getattr(ref, name), getattr(fast, name)
        # a force's components on one scale (the slider's guide_on_slider_x is zero)
        scale = (max(np.max(np.abs(getattr(ref, name[:-1] + k))) for k in "xy") if name.endswith(("_x", "_y"))
                 else np.max(np.abs(x)))
        assert scale > 0, name
        np.testing.assert_allclose(y, x, rtol=0, atol=1e-11 * scale, err_msg=name)
    x, y = ref.chord_deflection([0.25, 0.5]), fast.chord_deflection([0.25, 0.5])
    np.testing.assert_allclose(y, x, rtol=0, atol=1e-11 * np.max(np.abs(x)))
    return ref, fast


@pytest.mark.parametrize("integrator", ["newton", "full-newton", "one-pass"])
@pytest.mark.parametrize("formulation", ["lagrange", "paper"])
def test_compiled_engine_equals_numpy_reference_on_the_four_bar(formulation, integrator):
    """A long rocker (c = 2: the rocker angle's natural size eps^2 / c differs from a slider's)."""
    mech = crankgen.Mechanism(guide="circle", a=0.2, c=2.0, d=1.5, offset=0.1, eps=0.02, ms=0.7, mu=0.3)
    compare_engines(mech, omega=0.6, formulation=formulation, damping="kelvin-voigt",
                    integrator=integrator, n_elements=3, steps_per_rev=40, revolutions=1.5)


def test_kinematic_outputs_are_what_they_say():
    """slider_position / end_height, rocker_angle, chord_angle and chord_deflection(x) of a
    vibrating four-bar, against the same quantities computed here from the stored nodal values
    (the rod's points A + (x + u) e_i + v e_j, Hermite interpolation typed in energy_balance.py)."""
    from energy_balance import shapes
    g = dict(guide="circle", a=0.2, c=0.9, d=1.1, offset=0.2, branch=1)
    mech = crankgen.Mechanism(eps=0.05, **g)
    r = crankgen.simulate(mech, omega=0.9, n_elements=4, steps_per_rev=50, revolutions=1.5, store_nodes=True)
    kin = _kinematics.case_state(r.case, r.t)
    nodes = r.nodes.reshape(len(r.t), -1, 4)                            # (steps, n + 1, (u, v, psi, chi))
    ei = np.stack([np.cos(kin.phi), -np.sin(kin.phi)], -1)
    ej = np.stack([np.sin(kin.phi), np.cos(kin.phi)], -1)
    A = g["a"] * np.stack([np.cos(kin.theta), np.sin(kin.theta)], -1)
    un, vn = nodes[:, -1, 0], nodes[:, -1, 1]
    B = A + (1 + un)[:, None] * ei + vn[:, None] * ej
    np.testing.assert_allclose(r.slider_position, B[:, 0], rtol=0, atol=1e-13)
    np.testing.assert_allclose(r.end_height, B[:, 1], rtol=0, atol=1e-13)
    np.testing.assert_allclose(np.hypot(B[:, 0] - g["d"], B[:, 1] - g["offset"]), g["c"], rtol=0, atol=1e-13)
    np.testing.assert_allclose(_angle(r.rocker_angle - np.arctan2(B[:, 1] - g["offset"], B[:, 0] - g["d"])),
                               0, atol=1e-13)
    np.testing.assert_allclose(_angle(r.chord_angle - np.arctan2(*(B - A).T[::-1])), 0, atol=1e-13)
    assert np.ptp(r.rocker_angle - _rigid_beta(r, g)) > 1e-4              # the rocker does deviate
    # chord deflection: signed distance from the chord A -> B, counter-clockwise positive
    l = 0.25
    chord = np.stack([1 + un, vn], -1)
    for x in (0.0, 0.3, 0.5, 0.875, 1.0):
        e = min(int(x / l), 3)
        z = x / l - e
        Nu, _, Nv, _, _ = shapes(np.array([z]), l)
        q = np.concatenate([nodes[:, e], nodes[:, e + 1]], -1)           # (steps, 8)
        P = np.stack([x + q @ Nu[0], q @ Nv[0]], -1)
        want = (chord[:, 0] * P[:, 1] - chord[:, 1] * P[:, 0]) / np.hypot(*chord.T)
        got = r.chord_deflection(x)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 + 1e-10 * np.max(np.abs(want)))
    assert np.max(np.abs(r.chord_deflection(0.5))) > 1e-3


def _rigid_beta(r, g):
    k = _kinematics.case_state(r.case, r.t).vector
    return fb.four_bar(k[:, K["theta"]], k[:, K["thetad"]], k[:, K["thetadd"]], g["a"], g["c"], g["d"],
                       g["offset"], g["branch"])["beta"]
