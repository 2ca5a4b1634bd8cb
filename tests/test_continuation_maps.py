"""The continuation core and the brute-force sweeps on small maps with known answers."""

import math

import numpy as np
import pytest

from crankgen.analyses.bifurcation import FunctionMap, Settings, continue_map, sweep_map


def logistic():
    return FunctionMap(lambda x, r: (r * x * (1 - x), r * (1 - 2 * x), x * (1 - x)), 1, "r")


def delayed_logistic():
    # x_{n+1} = r x_n (1 - x_{n-1}) as the map (x_{n-1}, x_n) -> (x_n, x_{n+1})
    def f(x, r):
        return (np.array([x[1], r * x[1] * (1 - x[0])]),
                np.array([[0.0, 1.0], [-r * x[1], r * (1 - x[0])]]),
                np.array([0.0, x[1] * (1 - x[0])]))
    return FunctionMap(f, 2, "r")


def cubic(c=0.2):
    # fixed points p + x - x^3 = 0: folds at x = -+1/sqrt(3), p = +-2/(3 sqrt(3))
    return FunctionMap(lambda x, p: (x + c * (p + x - x**3), 1 + c * (1 - 3 * x**2), c * np.ones(1)), 1, "p")


def test_logistic_period_doubling_cascade():
    d = continue_map(logistic(), [0.6], 2.5, 3.56)
    pd = {s.period: s for s in d.special_points if s.kind == "period-doubling"}
    assert abs(pd[1].parameter - 3.0) < 1e-6
    assert abs(pd[2].parameter - (1 + math.sqrt(6))) < 1e-6
    assert 3.5 < pd[4].parameter < 3.56                   # the third doubling, r = 3.5441
    for s in pd.values():
        assert abs(s.multiplier + 1) < 1e-6
    assert sorted(b.period for b in d.branches) == [1, 2, 4]
    one = next(b for b in d.branches if b.period == 1)
    assert np.all(one.stable[one.parameter < 2.999]) and not np.any(one.stable[one.parameter > 3.001])
    assert np.allclose(one.amplitude, 1 - 1 / one.parameter, atol=1e-10)
    two = next(b for b in d.branches if b.period == 2)
    r = two.parameter
    upper = (r + 1 + np.sqrt((r - 3) * (r + 1))) / (2 * r)      # the period-2 points, closed form
    assert np.allclose(two.amplitude, upper, atol=1e-8)
    assert np.allclose(np.sort(two.section, axis=1)[:, 1], upper, atol=1e-8)
    inside = (r > 3.01) & (r < 1 + math.sqrt(6) - 0.01)
    assert inside.sum() > 3 and np.all(two.stable[inside])
    assert np.all(np.abs(two.multipliers[inside]) < 1)


def test_fold_of_the_normal_form():
    fold = FunctionMap(lambda x, p: (x + p - x**2, 1 - 2 * x, np.ones(1)), 1, "p")
    d = continue_map(fold, [0.5], 0.25, -0.5)
    (s,) = d.special_points
    assert s.kind == "fold" and abs(s.parameter) < 1e-6 and abs(s.multiplier - 1) < 1e-6
    (b,) = d.branches
    # turned at p = 0 and came back on the unstable branch x = -sqrt(p) to p = 0.25
    assert b.parameter.min() > -1e-6 and abs(b.parameter[-1] - 0.25) < 1e-12
    assert abs(b.states[-1, 0] + 0.5) < 1e-8 and not b.stable[-1] and b.stable[0]


def test_neimark_sacker_of_the_delayed_logistic_map():
    d = continue_map(delayed_logistic(), [0.5, 0.5], 1.5, 2.3)
    (s,) = d.special_points
    assert s.kind == "neimark-sacker" and abs(s.parameter - 2.0) < 1e-6
    assert abs(abs(s.multiplier) - 1) < 1e-6
    assert abs(s.multiplier - complex(0.5, math.sqrt(3) / 2)) < 1e-5      # e^{i pi/3} at r = 2


def test_hysteresis_of_the_sweeps_at_the_folds():
    m = cubic()
    d = continue_map(m, [-1.3], -1.0, 1.0, Settings(ds_max=0.05))
    folds = sorted(s.parameter for s in d.special_points if s.kind == "fold")
    assert np.allclose(folds, [-2 / (3 * math.sqrt(3)), 2 / (3 * math.sqrt(3))], atol=1e-6)
    values = np.linspace(-1, 1, 21)
    pc = sweep_map(m, values, [-1.3], "both", transient=200, samples=8)
    for direction, fold in (("up", folds[1]), ("down", folds[0])):
        pts = [q for q in pc.points if q.direction == direction]
        side = np.array([np.sign(q.samples[-1]) for q in pts])
        jump = np.flatnonzero(np.diff(side) != 0)
        assert len(jump) == 1                              # one jump per sweep
        before, after = pts[jump[0]].parameter, pts[jump[0] + 1].parameter
        assert min(before, after) < fold < max(before, after)
    assert all(q.classification == "period-1" for q in pc.points)


def test_poincare_classification_of_the_logistic_map():
    pc = sweep_map(logistic(), [3.2, 3.5, 3.83, 4.0], [0.3], "up", transient=400, samples=200)
    cls = {round(q.parameter, 2): q for q in pc.points}
    assert cls[3.2].classification == "period-2" and cls[3.2].distinct == 2
    assert cls[3.5].classification == "period-4"
    assert cls[3.83].classification == "period-3"          # the period-3 window
    assert cls[4.0].classification == "irregular"
    assert abs(cls[4.0].lyapunov - math.log(2)) < 0.1      # ln 2 at r = 4


def test_quasi_periodic_after_the_neimark_sacker_point():
    pc = sweep_map(delayed_logistic(), [1.9, 2.1], [0.5, 0.5], "up", transient=2000, samples=400)
    below, above = pc.points
    assert below.classification == "period-1"
    assert above.classification == "quasi-periodic" and abs(above.lyapunov) < 0.01
    assert above.distinct > 300


def test_settings_are_checked():
    from crankgen import ParameterError
    with pytest.raises(ParameterError, match="ds_min <= ds <= ds_max"):
        continue_map(logistic(), [0.6], 2.5, 3.0, Settings(ds=1.0, ds_max=0.5))
    with pytest.raises(ParameterError, match="direction"):
        sweep_map(logistic(), [3.0], [0.5], "sideways")


@pytest.mark.parametrize("corrector, predictor", [("newton", "tangent"), ("newton", "quadratic"),
                                                  ("broyden", "tangent"), ("broyden", "quadratic")])
def test_every_corrector_and_predictor_finds_the_known_points(corrector, predictor):
    s = Settings(corrector=corrector, predictor=predictor)
    pd = {p.period: p for p in continue_map(logistic(), [0.6], 2.5, 3.56, s).special_points
          if p.kind == "period-doubling"}
    assert abs(pd[1].parameter - 3.0) < 1e-6 and abs(pd[2].parameter - (1 + math.sqrt(6))) < 1e-6
    (fold,) = continue_map(FunctionMap(lambda x, p: (x + p - x**2, 1 - 2 * x, np.ones(1)), 1, "p"),
                           [0.5], 0.25, -0.5, s).special_points
    assert fold.kind == "fold" and abs(fold.parameter) < 1e-6
    (ns,) = continue_map(delayed_logistic(), [0.5, 0.5], 1.5, 2.3, s).special_points
    assert ns.kind == "neimark-sacker" and abs(ns.parameter - 2.0) < 1e-6


def test_broyden_corrector_evaluates_the_jacobians_less_often():
    """The quasi-Newton corrector iterates on the map's values (Map.value) and evaluates the
    Jacobians about once per point; Newton evaluates them at every iterate."""
    from crankgen.analyses.bifurcation.core import Continuer

    calls = {}

    class Counted(FunctionMap):
        def evaluate(self, x, p, period=1, dp=True):
            if dp:                          # (the orbits of accepted points are evaluated without)
                calls["jacobians"] = calls.get("jacobians", 0) + 1
            return super().evaluate(x, p, period, dp)

        def value(self, x, p, period=1):
            calls["values"] = calls.get("values", 0) + 1
            return FunctionMap.evaluate(self, x, p, period, False)[0]

    counts = {}
    for corrector in ("newton", "broyden"):
        calls.clear()
        fmap = Counted(lambda x, r: (r * x * (1 - x), r * (1 - 2 * x), x * (1 - x)), 1, "r")
        c = Continuer(fmap, 2.5, 3.4, Settings(corrector=corrector))
        d = c.diagram(np.array([0.6]), 2.5, 1.0)
        assert c.evaluations == calls.get("jacobians", 0) and c.values == calls.get("values", 0)
        counts[corrector] = (dict(calls), sum(len(b) for b in d.branches))
    (newton, points_n), (broyden, points_b) = counts["newton"], counts["broyden"]
    assert "values" not in newton and broyden["values"] > 0
    assert broyden["jacobians"] / points_b < 0.8 * newton["jacobians"] / points_n


def test_corrector_and_predictor_names_are_checked():
    from crankgen import ParameterError
    with pytest.raises(ParameterError, match="corrector"):
        Settings(corrector="secant").check()
    with pytest.raises(ParameterError, match="predictor"):
        Settings(predictor="cubic").check()
