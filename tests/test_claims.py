"""The paper's claims as data: every verdict from constructed figure data with known answers."""

import math

import numpy as np

from crankgen.experiments import ReproduceConfig
from crankgen.experiments import claims as C


def _fig5(ratio_b, ratio_c=None, models=("paper", "consistent")):
    """Figure 5 rows: A amplitude 1/eps, B and C ratio_b, ratio_c times it (per model)."""
    cfg = ReproduceConfig.full()
    rows = []
    for m in models:
        for om in cfg.fig5_omegas:
            for eps in cfg.fig5_eps:
                a = 0.05 / eps
                for ap, r in (("A", 1.0), ("B", ratio_b[m]), ("C", (ratio_c or ratio_b)[m])):
                    amp = a * r if math.isfinite(r) else math.nan
                    rows.append(dict(model=m, approach=ap, omega=om, eps=eps, ms=0.5, amplitude=amp,
                                     status="periodic" if math.isfinite(amp) else "failed",
                                     ratio_to_A=r))
    return dict(figure=5, rows=rows)


def _run(figs):
    return C.RunData(ReproduceConfig.full(), dict(series={}, counts={}), figs, {})


def _claim(cid):
    return next(c for c in C.CLAIMS if c.id == cid)


def test_every_claim_id_once_with_statement_and_tolerance():
    ids = [c.id for c in C.CLAIMS]
    assert ids == ["C2a", "C2b", "C3a", "C3b", "C3c", "C4a", "C4b", "C4c", "C5a", "C5b", "C5c",
                   "C5d", "C6a", "C6b", "C6c", "C6d", "C6e", "C7a", "C7b", "C7c", "C8a", "C8b",
                   "K1", "K2", "K3", "K4"]
    assert all(c.statement and c.paper_value and c.tolerance for c in C.CLAIMS)


def test_tenfold_overestimate_verdicts():
    run = _run({5: _fig5({"paper": 10.5, "consistent": 1.0})})
    out = {m: C.evaluate(_claim("C5b"), run, m) for m in ("paper", "consistent")}
    assert out["paper"].verdict == C.REPRODUCED and "10.5" in out["paper"].value
    assert out["consistent"].verdict == C.NOT_REPRODUCED
    assert C.evaluate(_claim("C5b"), _run({5: _fig5({"paper": 3.0, "consistent": 3.0})}), "paper").verdict == C.PARTLY
    # a case without a stable periodic state is a result, not a reason to skip the claim
    assert C.evaluate(_claim("C5b"), _run({5: _fig5({"paper": math.nan, "consistent": 1})}), "paper").verdict == C.NOT_REPRODUCED


def test_power_law_and_negligible_difference():
    run = _run({5: _fig5({"paper": 1.0, "consistent": 1.0}, {"paper": 1.01, "consistent": 1.2})})
    assert C.evaluate(_claim("C5d"), run, "paper").verdict == C.REPRODUCED       # amplitude 0.05/eps
    assert C.evaluate(_claim("C5c"), run, "paper").verdict == C.REPRODUCED
    assert C.evaluate(_claim("C5c"), run, "consistent").verdict == C.NOT_REPRODUCED
    assert C.evaluate(_claim("C5a"), run, "consistent").verdict == C.NOT_REPRODUCED


def test_missing_figure_is_not_computable_with_the_reason():
    run = C.RunData(ReproduceConfig.full(), dict(series={}, counts={}), {}, {5: "not computed in this folder"})
    out = C.evaluate(_claim("C5b"), run, "paper")
    assert out.verdict == C.NOT_COMPUTABLE and out.reason == "Figure 5 not computed in this folder"
    rows = C.assess(run)
    assert [r["claim"].id for r in rows] == list(C.IDS)
    assert all(r["verdict"] in C.VERDICTS for r in rows)


def _extension(crossings, ms_values=(0.0, 0.5, 1.0, 2.0), model="paper"):
    theta = np.linspace(0.0, 360.0, 721)
    # vanishes at both crossings: the curves for all masses meet there
    g = np.sin(np.radians(theta - crossings[0]) / 2) * np.sin(np.radians(theta - crossings[1]) / 2)
    curves = []
    for ms in ms_values:
        e = 1e-3 * np.cos(np.radians(theta)) + ms * 1e-3 * g
        curves.append(dict(model=model, ms=ms, status="periodic", theta_deg=theta, extension=e,
                           u_end=e / 0.01 ** 2))
    return dict(figure=7, omega=0.8, curves=curves)


def test_mass_independent_angles():
    run = _run({7: _extension((106.4, 295.2))})
    out = C.evaluate(_claim("C7b"), run, "paper")
    assert out.verdict == C.REPRODUCED and "106.4" in out.value and "295.2" in out.value
    run = _run({7: _extension((100.0, 295.2))})
    assert C.evaluate(_claim("C7b"), run, "paper").verdict == C.PARTLY
    assert C.evaluate(_claim("C7b"), run, "consistent").verdict == C.NOT_COMPUTABLE


def test_combined_verdict():
    assert C.combine(C.REPRODUCED, C.REPRODUCED) == C.REPRODUCED
    assert C.combine(C.NOT_COMPUTABLE, C.NOT_COMPUTABLE) == C.NOT_COMPUTABLE
    assert C.combine(C.REPRODUCED, C.NOT_REPRODUCED) == C.PARTLY
