"""The bifurcations step of `crankgen reproduce` on constructed data with known answers: stability
segments, the findings section (special points, failures, nothing found), the CSV tables, and a
continuation that fails inside the step."""

import math

import numpy as np

from crankgen.errors import CrankgenError
from crankgen.experiments import ReproduceConfig
from crankgen.experiments import bifurcations as BF
from crankgen.experiments import report_bifurcations as RB
from crankgen.experiments.runner import Context


def _branch(period, omega, stable, amp=None, origin="start", reason="reached omega = 1.6"):
    omega = np.asarray(omega, dtype=float)
    return dict(period=period, origin=origin, stop_reason=reason, omega=omega,
                amplitude=np.asarray(amp if amp is not None else omega, dtype=float),
                stable=np.asarray(stable, dtype=bool), max_abs_multiplier=np.full(len(omega), 0.5))


def _run(model, eps, status="ok", message="", branches=(), points=(), beyond=None):
    return dict(model=model, formulation="f", damping="d", membrane="m", eps=eps, n_elements=16,
                steps_per_rev=100, status=status, message=message, branches=list(branches),
                special_points=list(points), beyond=beyond)


def _data(runs):
    return dict(range=(0.1, 1.6), max_period=4, runs=runs)


def test_stability_segments_end_at_the_special_point():
    br = _branch(1, [0.1, 0.5, 1.0, 1.05, 1.1, 1.6], [1, 1, 1, 1, 0, 0])
    pd = dict(kind="period-doubling", omega=1.07, amplitude=1.0, period=1, branch=0, multiplier=(-1.0, 0.0))
    assert BF.stability_segments(br, [pd]) == [(True, 0.1, 1.07), (False, 1.07, 1.6)]
    # a folding branch: order of the continuation, not of Omega*
    br2 = _branch(2, [1.05, 0.9, 0.87, 0.95, 1.13], [0, 0, 1, 1, 1])
    fold = dict(kind="fold", omega=0.87, amplitude=1.0, period=2, branch=1, multiplier=(1.0, 0.0))
    assert BF.stability_segments(br2, [fold]) == [(False, 1.05, 0.87), (True, 0.87, 1.13)]


def test_section_lists_points_failures_and_empty_runs():
    pd = dict(kind="period-doubling", omega=1.0549949, amplitude=13.88, period=1, branch=0,
              multiplier=(-1.0, 0.0))
    ns = dict(kind="neimark-sacker", omega=1.4, amplitude=2.0, period=2, branch=1,
              multiplier=(0.6, 0.8))
    beyond = dict(start=1.4, values=[1.5, 1.6], transient=100, samples=32, status="ok", message="",
                  points=[dict(omega=1.5, classification="period-2", period=2, repeat_residual=1e-10,
                               lyapunov=math.nan, distinct=2, message=""),
                          dict(omega=1.6, classification="irregular", period=0, repeat_residual=0.3,
                               lyapunov=0.12, distinct=32, message="")])
    runs = [_run("paper", 0.01, branches=[_branch(1, [0.1, 0.8, 1.6], [1, 1, 1])]),
            _run("paper", 0.1, status="failed", message="CrankgenError: no periodic orbit near the start"),
            _run("consistent", 0.01, branches=[_branch(1, [0.1, 1.0, 1.1, 1.6], [1, 1, 0, 0]),
                                               _branch(2, [1.055, 1.0550001, 1.3, 1.6], [0, 1, 0, 0])],
                 points=[pd, ns], beyond=beyond),
            _run("consistent", 0.1, branches=[_branch(1, [0.1, 1.6], [1, 0])])]
    text = "\n".join(RB.section(ReproduceConfig.full(), _data(runs)))
    assert "| consistent | 0.01 | period-doubling | 1.054995 | 1 |" in text
    assert "| consistent | 0.01 | neimark-sacker | 1.4 | 2 |" in text
    assert "+0.600000 +0.800000i" in text
    assert "(beyond the theory)" in text                  # 0.01 * 13.88 > 0.1
    assert "the continuation FAILED (CrankgenError: no periodic orbit near the start)" in text
    assert "| paper | 0.1 | 16 | 100 | FAILED: CrankgenError" in text
    assert "- paper model, eps = 0.01 (n = 16, 100 steps/rev): no fold, period doubling or " \
           "Neimark-Sacker point for 0.1 <= Omega* <= 1.6." in text
    assert "stable there" in text                           # paper 0.01: stable at the end
    assert "no special point, but the crank-period branch is unstable at Omega* = 1.6" in text
    assert "Period 1 (start): stable 0.1 -> 1.055, unstable 1.055 -> 1.6" in text
    # a run shorter than the printed precision (marginal first point of a born branch) is left out
    assert "Period 2 (start): stable 1.055 -> 1.3, unstable 1.3 -> 1.6" in text
    assert "above Omega* = 1.4 (the last special point)" in text
    assert "1.5: period-2" in text and "1.6: irregular (Lyapunov exponent 0.12 per revolution" in text
    assert "No branch followed (periods 1, 2) is stable at Omega* = 1.6." in text
    line = RB.summary_line(_data(runs))
    assert "paper model, eps = 0.1: continuation failed" in line and "paper model, eps = 0.01: none" in line
    assert "period doubling at Omega* = 1.054995 (period 1)" in line
    missing = "\n".join(RB.section(ReproduceConfig.full(), None, "not computed in this folder"))
    assert "Not in this report: the bifurcations step not computed in this folder" in missing


def test_tables_keep_every_run():
    runs = [_run("paper", 0.01, branches=[_branch(1, [0.1, 1.6], [1, 1])]),
            _run("paper", 0.1, status="failed", message="boom")]
    t = BF.tables(_data(runs))
    cols, rows = t["bifurcations.csv"]
    assert [r["kind"] for r in rows] == ["none", "failed"] and rows[1]["message"] == "boom"
    assert len(t["bifurcation_branches.csv"][1]) == 2 and t["bifurcation_beyond.csv"][1] == []


class _Ctx(Context):
    """The runner's context, its log lines kept."""

    def __init__(self, cfg):
        super().__init__(cfg, quiet=True)
        self.lines = []

    def log(self, text):
        super().log(text)
        self.lines.append(text)


def test_a_continuation_that_fails_is_recorded_not_raised(monkeypatch):
    import crankgen.analyses.bifurcation as B

    def fails(*a, **k):
        raise CrankgenError("no periodic response to start from")
    monkeypatch.setattr(B, "continuation", fails)
    cfg = ReproduceConfig.tiny()
    ctx = _Ctx(cfg)
    data = BF.bifurcations(ctx, {("paper", "A"): 2, ("consistent", "A"): 2})
    assert [r["status"] for r in data["runs"]] == ["failed"] * 2 * len(cfg.fig6_eps)
    assert all("no periodic response" in r["message"] for r in data["runs"])
    assert any("continuation FAILED" in line for line in ctx.lines)
