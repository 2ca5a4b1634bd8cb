"""crankgen.follow on the slider-crank: the two-parameter curves against one-parameter
continuations at fixed values of the second parameter (brute force), and the exports."""

import numpy as np
import pytest

import crankgen
from crankgen.errors import ParameterError

SMALL = dict(n_elements=4, steps_per_rev=50)


@pytest.fixture(scope="module")
def diagram():
    return crankgen.continuation(crankgen.Mechanism(eps=0.01), "omega", 0.6, 1.6, max_period=2, **SMALL)


def _special(d, kind, period, near):
    return min((s for s in d.special_points if s.kind == kind and s.period == period),
               key=lambda s: abs(s.parameter - near))


@pytest.mark.slow
def test_curves_hold_the_special_points_of_continuations_at_fixed_eps(diagram):
    """The period doubling of the period-1 orbits and the fold of the period-2 orbits continued in
    eps to 0.03: each curve ends exactly at eps = 0.03 (the box's edge), where a continuation in
    Omega* at eps = 0.03 finds the same point, to the continuations' tolerances."""
    pd = _special(diagram, "period-doubling", 1, 1.05)
    fold = _special(diagram, "fold", 2, 0.87)
    at = crankgen.continuation(crankgen.Mechanism(eps=0.03), "omega", 0.6, 1.6, max_period=2, **SMALL)
    for point, near in ((pd, None), (fold, None)):
        curve = crankgen.follow(point, "eps", 0.01, 0.03)
        assert curve.kind == point.kind and curve.period == point.period
        assert abs(curve["eps"][0] - 0.01) < 1e-12 and abs(curve["omega"][0] - point.parameter) < 1e-7
        end = int(np.argmax(curve["eps"]))
        assert abs(curve["eps"][end] - 0.03) < 1e-12 and "reached eps = 0.03" in curve.stop_reasons
        same = _special(at, point.kind, point.period, curve["omega"][end])
        assert abs(same.parameter - curve["omega"][end]) < 1e-6, (same.parameter, curve["omega"][end])
        assert abs(same.amplitude - curve["amplitude"][end]) < 1e-4 * same.amplitude
        assert abs(curve["critical"][end] - same.multiplier) < 1e-6


@pytest.mark.slow
def test_the_fold_curve_of_the_period_two_orbits_turns_at_a_cusp(diagram):
    """The two folds of the period-2 branch at eps = 0.01 are one curve in (Omega*, eps): followed
    from the lower one, it rises to a cusp, where the hysteresis between the folds vanishes, and
    comes back to eps = 0.01 at the upper fold the one-parameter continuation found."""
    lower = _special(diagram, "fold", 2, 0.87)
    upper = _special(diagram, "fold", 2, 1.13)
    curve = crankgen.follow(lower, "eps", 0.01, 0.1)
    assert curve.stop_reasons == ("reached eps = 0.01", "reached eps = 0.01")
    ends = sorted([curve["omega"][0], curve["omega"][-1]])
    assert abs(ends[0] - lower.parameter) < 1e-7 and abs(ends[1] - upper.parameter) < 1e-6
    (cp,) = curve.codim2
    assert cp.kind == "cusp" and set(cp.parameters) == {"omega", "eps"}
    # the cusp is the curve's highest eps; there the fold's quadratic coefficient vanishes
    assert abs(cp["eps"] - curve["eps"].max()) < 1e-6
    assert 0.03 < cp["eps"] < 0.1 and 0.9 < cp["omega"] < 1.3
    assert len(cp.multipliers) == curve.multipliers.shape[1] and abs(np.max(np.abs(cp.multipliers)) - 1) < 1e-6


def test_follow_refuses_bad_input(diagram):
    pd = _special(diagram, "period-doubling", 1, 1.05)
    with pytest.raises(ParameterError, match="must differ from the diagram's"):
        crankgen.follow(pd, "omega", 0.5, 1.5)
    with pytest.raises(ParameterError, match="outside"):
        crankgen.follow(pd, "eps", 0.02, 0.05)
    with pytest.raises(ParameterError, match="parameter must be one of"):
        crankgen.follow(pd, "steps_per_rev", 10, 20)
    with pytest.raises(ParameterError, match="special point of a mechanism"):
        crankgen.follow(diagram, "eps", 0.005, 0.05)
    with pytest.raises(ParameterError, match="c"):
        crankgen.follow(pd, "c", 1.0, 2.0)
