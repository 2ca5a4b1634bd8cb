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


# ---- ill-posed is not unstable: a diverged B run is neither an amplitude nor a verdict ---------

def _fig5_diverged(status_b):
    """Figure 5 with every B run of the consistent model in status_b (no amplitude)."""
    data = _fig5({"paper": 10.0, "consistent": 10.0})
    for r in data["rows"]:
        if r["model"] == "consistent" and r["approach"] == "B":
            r.update(amplitude=math.nan, ratio_to_A=math.nan, status=status_b)
    return data


def test_a_diverged_b_makes_its_claims_not_computable_not_false():
    run = _run({5: _fig5_diverged("diverged")})
    b = C.evaluate(_claim("C5b"), run, "consistent")
    assert b.verdict == C.NOT_COMPUTABLE and "diverged" in b.value and "unbounded below" in b.value
    # a genuinely unstable B (an orbit exists, with a multiplier outside the unit circle) is a result
    assert C.evaluate(_claim("C5b"), _run({5: _fig5_diverged("unstable")}), "consistent").verdict \
        == C.NOT_REPRODUCED
    # B against C: the diverged points are not computable; C against A still holds at Omega* 0.1
    c5c = C.evaluate(_claim("C5c"), run, "consistent")
    assert c5c.verdict == C.NOT_COMPUTABLE and "not computable at" in c5c.value
    slopes = C.evaluate(_claim("C5d"), run, "consistent")
    assert "B@0.8: diverged" in slopes.value and "n/a" not in slopes.value


def _fig6(b_status_from, b_peak_at=None):
    """Figure 6 rows at eps 0.01: A rising, C peaking at 1.0, B periodic below b_status_from and
    diverged from there (its largest stable amplitude at its last stable speed)."""
    rows = []
    for om in np.round(np.arange(0.2, 1.61, 0.1), 10):
        a = om
        c = 10 * om if om <= 1.0 + 1e-9 else 10 * (2 - om)
        bval = 5 * om if om < b_status_from - 1e-9 else math.nan
        for ap, amp in (("A", a), ("B", bval), ("C", c)):
            st = "periodic" if math.isfinite(amp) else "diverged"
            rows.append(dict(model="consistent", approach=ap, omega=float(om), eps=0.01, ms=0.5,
                             amplitude=amp, status=st, ratio_to_A=amp / a if math.isfinite(amp) else math.nan))
    return dict(figure=6, rows=rows)


def test_the_last_point_before_a_divergence_is_not_a_peak():
    run = _run({6: _fig6(b_status_from=0.35)})
    out = C.evaluate(_claim("C6d"), run, "consistent")
    assert "B: no peak can be read (its runs from rest diverge from Omega* = 0.4" in out.value
    assert "B max at" not in out.value
    assert out.verdict == C.PARTLY              # C peaks at 1 and A rises; B's part is unknown
    k4 = C.evaluate(_claim("K4"), run, "consistent")
    assert "B/A diverged" in k4.value


def test_crossings_are_described_in_words_when_there_are_none():
    data = _extension((106.4, 295.2))
    for c in data["curves"]:                    # parallel curves: no common crossing anywhere
        c["extension"] = 1e-3 * np.cos(np.radians(c["theta_deg"])) + c["ms"] * 1e-3
    out = C.evaluate(_claim("C7b"), _run({7: data}), "paper")
    assert out.verdict == C.NOT_REPRODUCED
    assert "inf" not in out.reason and "no common crossing at all" in out.reason
