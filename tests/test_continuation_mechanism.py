"""Continuation and Poincare sweeps of the mechanism (consistent model, eps = 0.01, coarse mesh)."""

import numpy as np
import pytest

import crankgen
from crankgen import engine
from crankgen.analyses.bifurcation.mechanism import orbit_peak
from crankgen.declaration.cases import Case
from crankgen.analyses.steady import _scaled_change

MODEL = dict(formulation="lagrange", damping="kelvin-voigt", membrane="averaged", n_elements=4,
             steps_per_rev=50)


@pytest.fixture(scope="module")
def diagram():
    return crankgen.continuation(crankgen.Mechanism(eps=0.01), "omega", 0.8, 1.2, max_period=2, **MODEL)


def _case(omega):
    return Case(eps=0.01, omega=float(omega), **MODEL)


def test_special_points_have_their_critical_multipliers(diagram):
    kinds = sorted((s.period, s.kind) for s in diagram.special_points)
    # the rod starts snapping between sides on alternate revolutions a little above Omega* = 1;
    # the period-2 branch folds twice (the snap-through orbit and its hysteresis)
    assert kinds == [(1, "period-doubling"), (2, "fold"), (2, "fold")]
    for s in diagram.special_points:
        target = {"fold": 1.0, "period-doubling": -1.0}[s.kind]
        assert abs(s.multiplier - target) < 1e-6
    pd = next(s for s in diagram.special_points if s.kind == "period-doubling")
    assert 1.0 < pd.parameter < 1.1


def test_the_orbit_peak_is_the_maximum_between_the_samples():
    """A continuation point's amplitude is the orbit's maximum, not its largest sample: for a
    sampled cosine of any phase the largest sample falls short by up to (pi/50)^2/2 = 2e-3 and
    jumps as the phase moves (the kinks of an amplitude curve); the parabola through the largest
    sample and its neighbours is within 1e-5 and moves smoothly."""
    phases = np.linspace(0, 2 * np.pi / 50, 41)
    theta = np.linspace(0, 2 * np.pi, 51)
    sampled = np.array([np.max(np.abs(2.5 * np.cos(theta + p))) for p in phases])
    peak = np.array([orbit_peak(2.5 * np.cos(theta + p)) for p in phases])
    assert np.max(2.5 - sampled) > 1e-3 * 2.5
    assert np.max(np.abs(peak - 2.5)) < 1e-5 * 2.5
    assert orbit_peak(-3 * np.cos(theta)) == pytest.approx(3.0, rel=1e-12)       # a sample on the peak
    assert orbit_peak([0.0, 1.0, 0.0]) == 1.0                                      # too few samples


def test_branch_points_agree_with_steady_state(diagram):
    one = next(b for b in diagram.branches if b.period == 1)
    pd = next(s for s in diagram.special_points if s.kind == "period-doubling")
    picks = [np.argmin(np.abs(one.parameter - w)) for w in (0.9, pd.parameter, 1.15)]
    for i in picks:
        st = crankgen.steady_state(case=_case(one.parameter[i]), tol=1e-11)
        assert st.status == ("periodic" if one.stable[i] else "unstable") or abs(one.parameter[i] - pd.parameter) < 1e-9
        assert abs(orbit_peak(st.v_mid) - one.amplitude[i]) < 1e-6     # the same orbit, the same peak
        assert abs(st.multiplier - np.abs(one.multipliers[i]).max()) < 1e-6


def test_period_two_orbit_repeats_every_two_revolutions(diagram):
    two = next(b for b in diagram.branches if b.period == 2)
    stable = np.flatnonzero(two.stable & (two.parameter > 1.08) & (two.parameter < 1.12))
    i = stable[len(stable) // 2]
    batch = engine.Batch([_case(two.parameter[i])])
    X0 = two.states[i][None]                     # (d, v, a): generalized-alpha's state
    assert X0.shape[1] == batch.state_size == 3 * batch.N
    res = engine.march_state(batch, 2 * batch.steps_per_rev, X0, keep_history=True)
    assert res.status[0] == engine.OK
    S = np.concatenate([batch.scales] * 3, axis=1)
    spr = batch.steps_per_rev
    X1 = engine.join_state(res, True, [spr])
    X2 = engine.join_state(res, True)
    assert _scaled_change(X0, X2, S)[0] < 1e-8
    assert _scaled_change(X0, X1, S)[0] > 1e-2


def test_sweeps_jump_at_the_folds(diagram):
    folds = sorted(s.parameter for s in diagram.special_points if s.kind == "fold")
    values = np.round(np.arange(0.80, 1.2001, 0.02), 2)
    pc = crankgen.poincare(crankgen.Mechanism(eps=0.01), "omega", values, "both", transient=60,
                           samples=8, **MODEL)
    for direction, fold in (("up", folds[1]), ("down", folds[0])):
        pts = [q for q in pc.points if q.direction == direction and q.classification != "failed"]
        big = np.array([np.max(np.abs(q.samples)) > 30 for q in pts])      # the snap-through orbit
        change = np.flatnonzero(np.diff(big))
        assert len(change) == 1
        a, b = pts[change[0]].parameter, pts[change[0] + 1].parameter
        assert min(a, b) < fold < max(a, b)
    classes = {q.classification for q in pc.points}
    assert "period-1" in classes and "period-2" in classes


def test_parameter_errors():
    with pytest.raises(crankgen.ParameterError, match="parameter"):
        crankgen.continuation(parameter="length", start=0.2, stop=1.0)
    with pytest.raises(crankgen.ParameterError, match="eps"):
        crankgen.continuation(parameter="eps", start=-0.1, stop=0.1, n_elements=2)
    with pytest.raises(crankgen.ParameterError, match="direction"):
        crankgen.poincare(parameter="omega", values=[0.5, 0.6], direction="sideways", n_elements=2)


def test_command_line(tmp_path):
    from crankgen.cli import main

    common = ["--elements", "2", "--steps-per-rev", "24", "--damping", "kelvin-voigt", "--quiet"]
    assert main(["continue", "--from", "0.4", "--to", "0.6", "--out", str(tmp_path / "c")] + common) == 0
    for name in ("branches.csv", "special_points.csv", "multipliers.csv", "continuation.png"):
        assert (tmp_path / "c" / name).stat().st_size > 0
    rows = (tmp_path / "c" / "branches.csv").read_text().splitlines()
    assert rows[0].startswith("branch,period,point,omega,amplitude,stable") and len(rows) > 5
    assert main(["poincare", "--from", "0.4", "--to", "0.6", "--values", "3", "--transient", "5",
                 "--samples", "4", "--out", str(tmp_path / "p")] + common) == 0
    rows = (tmp_path / "p" / "poincare_summary.csv").read_text().splitlines()
    assert len(rows) == 1 + 2 * 3                          # both directions by default
    assert (tmp_path / "p" / "poincare.png").stat().st_size > 0


@pytest.mark.parametrize("parameter, value", [("omega", 0.9), ("eps", 0.02), ("offset", 0.05), ("mu", 0.3)])
def test_exact_parameter_derivative_matches_central_differences(parameter, value):
    """dP^2/dp of the map (the sensitivity column of the linearized steps) against a Richardson-
    extrapolated central difference of the map itself (marched with Newton to 1e-14)."""
    from dataclasses import replace

    from crankgen.analyses.bifurcation import MechanismMap

    case = Case(**{**MODEL, "n_elements": 3, "steps_per_rev": 30}, **{parameter: value})
    fmap = MechanismMap(case, parameter)
    warm = engine.march(engine.Batch([case]), 60)
    X = engine.join_state(warm, fmap.generalized)[0]
    P, jy, jp = fmap.evaluate(X / fmap.s, value, 2)
    fd = []
    for h in (4e-4 * abs(value), 2e-4 * abs(value)):
        Y = [engine.shoot(engine.Batch([replace(case, **{parameter: q})]), X[None], revolutions=2, tol=1e-14,
                          max_iter=60, jacobian=False).X1[0] / fmap.s for q in (value - h, value + h)]
        fd.append((Y[1] - Y[0]) / (2 * h))
    richardson = (4 * fd[1] - fd[0]) / 3
    scale = np.max(np.abs(richardson))
    assert scale > 0 and np.max(np.abs(jp - richardson)) < 1e-6 * scale


def test_the_parameter_derivative_at_a_bound_of_the_range_stays_inside_it():
    """At mu = 0 (the lower bound of the damping) dP/dmu comes from the cases at 0 and 2h, never
    from a damping of -h (refused): it matches the second-order one-sided difference of the map
    (-3 P(0) + 4 P(h) - P(2h)) / 2h, Richardson-extrapolated, marched with Newton to 1e-14."""
    from dataclasses import replace

    from crankgen.analyses.bifurcation import MechanismMap
    from crankgen.analyses.bifurcation.mechanism import difference_pair

    assert difference_pair("mu", 0.0, 1e-7) == (0.0, 2e-7)
    assert difference_pair("mu", 0.3, 1e-7) == (0.3 - 1e-7, 0.3 + 1e-7)
    case = Case(**{**MODEL, "n_elements": 3, "steps_per_rev": 30}, mu=0.0)
    fmap = MechanismMap(case, "mu")
    warm = engine.march(engine.Batch([case]), 60)
    X = engine.join_state(warm, fmap.generalized)[0]
    P, jy, jp = fmap.evaluate(X / fmap.s, 0.0, 1)
    Y = {q: engine.shoot(engine.Batch([replace(case, mu=q)]), X[None], revolutions=1, tol=1e-14,
                         max_iter=60, jacobian=False).X1[0] / fmap.s for q in (0.0, 5e-5, 1e-4, 2e-4)}
    fd = [(-3 * Y[0.0] + 4 * Y[h] - Y[2 * h]) / (2 * h) for h in (1e-4, 5e-5)]
    one_sided = (4 * fd[1] - fd[0]) / 3          # Richardson: the h^2 error of each removed
    scale = np.max(np.abs(one_sided))
    assert scale > 0 and np.max(np.abs(jp - one_sided)) < 1e-5 * scale


@pytest.mark.parametrize("rho_inf", [1.0, 0.8])
def test_shooting_marches_the_same_steps_as_march(rho_inf):
    """engine.shoot (with and without its linearization) takes the very steps of engine.march: the
    same states and outputs, so the orbit of a map evaluation is the marched orbit (Newmark's
    state (d, v); generalized-alpha's (d, v, a))."""
    from dataclasses import replace
    case = replace(_case(0.95), rho_inf=rho_inf)
    b = engine.Batch([case])
    generalized = rho_inf < 1
    warm = engine.march(b, 80)
    X0 = engine.join_state(warm, generalized)
    assert X0.shape[1] == b.state_size == (3 if generalized else 2) * b.N
    spr = b.steps_per_rev
    m = engine.march_state(b, 2 * spr, X0, keep_history=True)
    for jacobian in (False, True):
        r = engine.shoot(b, X0, revolutions=2, jacobian=jacobian)
        assert np.array_equal(r.y, m.y)
        assert np.array_equal(r.X1, engine.join_state(m, generalized))
        assert np.array_equal(r.states[0], engine.join_state(m, generalized, np.arange(3) * spr))


def test_former_corrector_and_derivative_find_the_same_special_points(diagram):
    """Newton with the Jacobians at every iterate, the tangent predictor and dP/dp by differences of
    marches (the former method) find the special points of the default method."""
    old = crankgen.continuation(crankgen.Mechanism(eps=0.01), "omega", 0.8, 1.2, max_period=2, corrector="newton",
                                predictor="tangent", derivative="central", **MODEL)
    assert old.info["map_values"] == 0 and diagram.info["map_values"] > 0
    assert [(s.kind, s.period) for s in old.special_points] == [(s.kind, s.period) for s in diagram.special_points]
    for a, b in zip(old.special_points, diagram.special_points):
        assert abs(a.parameter - b.parameter) < 1e-6
        assert abs(a.amplitude - b.amplitude) < 1e-6 * abs(a.amplitude)
        target = {"fold": 1.0, "period-doubling": -1.0}[a.kind]
        assert abs(a.multiplier - target) < 1e-6 and abs(b.multiplier - target) < 1e-6
