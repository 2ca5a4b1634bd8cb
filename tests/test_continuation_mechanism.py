"""Continuation and Poincare sweeps of the mechanism (consistent model, eps = 0.01, coarse mesh)."""

import numpy as np
import pytest

import crankgen
from crankgen import engine
from crankgen.cases import Case
from crankgen.steady import _scaled_change

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


def test_branch_points_agree_with_steady_state(diagram):
    one = next(b for b in diagram.branches if b.period == 1)
    pd = next(s for s in diagram.special_points if s.kind == "period-doubling")
    picks = [np.argmin(np.abs(one.parameter - w)) for w in (0.9, pd.parameter, 1.15)]
    for i in picks:
        st = crankgen.steady_state(case=_case(one.parameter[i]), tol=1e-11)
        assert st.status == ("periodic" if one.stable[i] else "unstable") or abs(one.parameter[i] - pd.parameter) < 1e-9
        assert abs(st.amplitude - one.amplitude[i]) < 1e-6
        assert abs(st.multiplier - np.abs(one.multipliers[i]).max()) < 1e-6


def test_period_two_orbit_repeats_every_two_revolutions(diagram):
    two = next(b for b in diagram.branches if b.period == 2)
    stable = np.flatnonzero(two.stable & (two.parameter > 1.08) & (two.parameter < 1.12))
    i = stable[len(stable) // 2]
    batch = engine.Batch([_case(two.parameter[i])])
    N = batch.N
    X0 = two.states[i][None]
    res = engine.march(batch, 2 * batch.steps_per_rev, D0=X0[:, :N], V0=X0[:, N:], keep_history=True)
    assert res.status[0] == engine.OK
    S = np.concatenate([batch.scales, batch.scales], axis=1)
    spr = batch.steps_per_rev
    X1 = np.concatenate([res.D_history[:, spr], res.V_history[:, spr]], axis=1)
    X2 = np.concatenate([res.D, res.V], axis=1)
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
