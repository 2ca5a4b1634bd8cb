"""Two-parameter continuation on small maps whose curves and codimension-two points are known in
closed form (bifurcation/codim2.py, defining.py, curve.py)."""

import csv
import math

import numpy as np
import pytest

from crankgen.analyses.bifurcation.curve import Curve
from crankgen.analyses.bifurcation.follow import follow_map
from crankgen.analyses.bifurcation.plane_maps import FunctionPlaneMap


def cusp_map(c=0.3):
    """x -> x + c (a + b x - x^3): folds where b = 3 x^2, a = x^3 - b x; the cusp at a = b = 0."""
    def f(x, p):
        a, b = p
        return x + c * (a + b * x - x**3), np.array([[1 + c * (b - 3 * x[0] ** 2)]]), np.array([[c, c * x[0]]])
    return FunctionPlaneMap(f, 1, ("a", "b"))


def flip_fold_map(swap=False):
    """(X, Y) -> (X + a - X^2, (b - 1) Y + X Y): fixed points X = +-sqrt(a), Y = 0, multipliers
    1 - 2 X and X + b - 1.  Period doubling where b = -X (a = b^2); on it the other multiplier is
    -1 at X = 1 (1:2 resonance, a = 1, b = -1) and +1 at X = 0 (fold-flip, a = b = 0); the folds
    lie on a = 0, and the fold-flip again at b = 0."""
    def f(x, p):
        a, b = (p[1], p[0]) if swap else p
        X, Y = x
        F = np.array([X + a - X * X, (b - 1) * Y + X * Y])
        J = np.array([[1 - 2 * X, 0.0], [Y, b - 1 + X]])
        P = np.array([[1.0, 0.0], [0.0, Y]])
        return F, J, (P[:, ::-1] if swap else P)
    return FunctionPlaneMap(f, 2, ("b", "a") if swap else ("a", "b"))


def rotation_map():
    """rho R(b) x + (X^2, X Y), rho = 1 + a - b^2 / 4: the fixed point 0 has the multipliers rho
    e^{+-i b}: Neimark-Sacker on a = b^2 / 4 with theta = b; 1:4 and 1:3 resonances at b = pi/2,
    2 pi/3; 1:1 at b = 0."""
    def f(x, p):
        a, b = p
        X, Y = x
        rho = 1 + a - b * b / 4
        c, s = math.cos(b), math.sin(b)
        Rx = np.array([c * X - s * Y, s * X + c * Y])
        F = rho * Rx + np.array([X * X, X * Y])
        J = rho * np.array([[c, -s], [s, c]]) + np.array([[2 * X, 0.0], [Y, X]])
        dR = np.array([-s * X - c * Y, c * X - s * Y])
        return F, J, np.column_stack([Rx, -b / 2 * Rx + rho * dR])
    return FunctionPlaneMap(f, 2, ("a", "b"))


def test_fold_curve_through_the_cusp():
    b0 = 1.0
    x0 = math.sqrt(b0 / 3)
    curve = follow_map(cusp_map(), "fold", [x0], [x0**3 - b0 * x0, b0], [-1, -0.5], [1, 1.5])
    a, b, x = curve["a"], curve["b"], curve.states[:, 0]
    assert np.max(np.abs(b - 3 * x**2)) < 1e-7 and np.max(np.abs(a - (x**3 - b * x))) < 1e-7
    # both folds: the curve passes through the cusp and comes back on the other one
    assert x.min() < -0.6 and x.max() > 0.6 and curve.stop_reasons == ("reached b = 1.5", "reached b = 1.5")
    (cp,) = curve.codim2
    assert cp.kind == "cusp" and cp.label == "CP"
    assert abs(cp["a"]) < 1e-6 and abs(cp["b"]) < 1e-6 and abs(cp.state[0]) < 1e-6
    assert abs(cp.multipliers[0] - 1) < 1e-6 and cp.curve_kind == "fold"
    assert np.allclose(curve["critical"], 1.0, atol=1e-7)


def test_period_doubling_curve_with_a_state_that_moves():
    """x -> r x (1 - x) + s: period doubling where r (1 - 2 x) = -1, x = (1 + 1/r) / 2."""
    def f(x, p):
        r, s = p
        return r * x * (1 - x) + s, np.array([[r * (1 - 2 * x[0])]]), np.array([[x[0] * (1 - x[0]), 1.0]])
    r0 = 3.0
    x0 = (1 + 1 / r0) / 2
    curve = follow_map(FunctionPlaneMap(f, 1, ("r", "s")), "period-doubling", [x0],
                       [r0, x0 - r0 * x0 * (1 - x0)], [2, -0.5], [4, 0.5])
    r, s, x = curve["r"], curve["s"], curve.states[:, 0]
    xs = (1 + 1 / r) / 2
    assert np.max(np.abs(x - xs)) < 1e-8 and np.max(np.abs(s - (xs - r * xs * (1 - xs)))) < 1e-8
    assert set(curve.stop_reasons) == {"reached r = 2", "reached r = 4"}
    assert np.allclose(curve["critical"], -1.0, atol=1e-7)
    assert not curve.codim2


def test_resonance_and_fold_flip_on_a_period_doubling_curve():
    curve = follow_map(flip_fold_map(), "period-doubling", [0.5, 0.0], [0.25, -0.5], [-1, -1], [1, 1])
    assert np.max(np.abs(curve["a"] - curve["b"] ** 2)) < 1e-7
    got = {p.kind: p for p in curve.codim2}
    assert set(got) == {"1:2 resonance", "fold-flip"}
    r2, lppd = got["1:2 resonance"], got["fold-flip"]
    assert abs(r2["a"] - 1) < 1e-6 and abs(r2["b"] + 1) < 1e-6 and r2.label == "R2"
    assert np.allclose(np.sort(r2.multipliers.real), [-1, -1], atol=1e-6)
    assert abs(lppd["a"]) < 1e-6 and abs(lppd["b"]) < 1e-6 and lppd.label == "LPPD"
    assert np.allclose(np.sort(lppd.multipliers.real), [-1, 1], atol=1e-6)


def test_fold_flip_on_a_fold_curve():
    curve = follow_map(flip_fold_map(swap=True), "fold", [0.0, 0.0], [0.5, 0.0], [-1, -1], [1, 1])
    assert np.max(np.abs(curve["a"])) < 1e-8
    (p,) = curve.codim2
    assert p.kind == "fold-flip" and abs(p["b"]) < 1e-6 and p.curve_kind == "fold"


def test_neimark_sacker_curve_and_its_resonances():
    curve = follow_map(rotation_map(), "neimark-sacker", [0.0, 0.0], [0.25, 1.0], [-1, -0.5], [3, 2.5],
                       theta=1.0)
    assert np.max(np.abs(curve["a"] - curve["b"] ** 2 / 4)) < 1e-7
    assert np.max(np.abs(curve["theta"] - curve["b"])) < 1e-7
    got = {p.kind: p for p in curve.codim2}
    assert abs(got["1:4 resonance"]["b"] - math.pi / 2) < 1e-6
    assert abs(got["1:3 resonance"]["b"] - 2 * math.pi / 3) < 1e-6
    assert abs(got["1:1 resonance"]["b"]) < 1e-4
    # the curve ends at the 1:1 resonance (the pair leaves the circle as a real pair)
    assert any(r.startswith("1:1 resonance") for r in curve.stop_reasons)
    assert np.allclose(np.abs(curve["critical"]), 1.0, atol=1e-7)


def test_curve_files_round_trip(tmp_path):
    b0 = 1.0
    x0 = math.sqrt(b0 / 3)
    curve = follow_map(cusp_map(), "fold", [x0], [x0**3 - b0 * x0, b0], [-1, -0.5], [1, 1.5],
                       info={"note": "cusp map"})
    back = Curve.from_json(curve.to_json(tmp_path / "curve.json"))
    assert back.kind == curve.kind and back.period == curve.period and back.names == curve.names
    for name in ("a", "b", "amplitude"):
        assert np.array_equal(back[name], curve[name])
    assert np.array_equal(back.multipliers, curve.multipliers) and np.array_equal(back.states, curve.states)
    assert back.stop_reasons == curve.stop_reasons and back.info == {"note": "cusp map"}
    (cp,), (cq,) = curve.codim2, back.codim2
    assert (cq.kind, cq.parameters, cq.amplitude, cq.index) == (cp.kind, cp.parameters, cp.amplitude, cp.index)
    assert np.array_equal(cq.multipliers, cp.multipliers)
    paths = curve.to_csv(tmp_path / "csv")
    with open(paths[0], newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(curve)
    assert [float(r["a"]) for r in rows] == list(curve["a"])
    with open(paths[1], newline="") as fh:
        (row,) = list(csv.DictReader(fh))
    assert row["kind"] == "cusp" and float(row["b"]) == cp["b"] and row["multipliers"]
    with open(paths[2], newline="") as fh:
        assert len(list(csv.DictReader(fh))) == len(curve) * curve.multipliers.shape[1]


def test_bad_kind_is_refused():
    with pytest.raises(ValueError, match="kind must be one of"):
        follow_map(cusp_map(), "hopf", [0.5], [0, 1], [-1, 0], [1, 2])
