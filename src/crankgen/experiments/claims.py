"""What the source paper states about its Figures 2-8 and in its conclusions, claim by claim (in
the project's words): the claims as data, each naming the function of claim_checks.py that
computes the same quantity from a model's runs and its verdict against a stated tolerance.

A claim is not a target: a model that does not reproduce it is a finding, reported with the
numbers.  `evaluate(claim, run, model)` returns an Outcome for one model; `assess(run)` gives the
row of the findings table (both models and the combined verdict).  `run` is a RunData: the
config, the convergence check and the data of the figures that were computed (a figure that is
absent makes the claims that need it "not computable", with the reason).
"""

from dataclasses import dataclass, field

from .claim_measures import (ANGLE, CLOSE, FACTOR, NOT_COMPUTABLE, NOT_REPRODUCED, NOTICEABLE,
                             PARTLY, REPRODUCED, SAME, SLOPE, SPEED, STABLE, VERDICTS, Missing,
                             Outcome, RunData)
from .claim_checks import (c2a, c2b, c3a, c3b, c3c, c4a, c4b, c4c, c5a, c5b, c5c, c5d, c6a, c6b,
                           c6c, c6d, c6e, c7a, c7b, c7c, c8a, c8b, k1, k2, k3, k4)

__all__ = ["ANGLE", "CLAIMS", "CLOSE", "Claim", "FACTOR", "IDS", "Missing", "NOT_COMPUTABLE",
           "NOT_REPRODUCED", "NOTICEABLE", "Outcome", "PARTLY", "REPRODUCED", "RunData", "SAME",
           "SLOPE", "SPEED", "STABLE", "VERDICTS", "assess", "combine", "evaluate"]


@dataclass(frozen=True)
class Claim:
    id: str
    figure: str
    statement: str
    paper_value: str
    tolerance: str
    needs: tuple                     # figures whose data the claim needs
    evaluate: object = field(repr=False, compare=False)


CLAIMS = (
    Claim("C2a", "2", "At Omega* = 0.1, 2 and 4 elements give almost the same transient in all three approaches.",
          "almost indistinguishable", f"max |v2 - v4| / max |v4| within {100 * CLOSE:g} %", (2,), c2a),
    Claim("C2b", "2", "At Omega* = 0.1, dropping the quartic term (B) or taking linear strain (C) changes the transient very little.",
          "almost no difference", f"within {100 * CLOSE:g} % of max |v*_A|", (2,), c2b),
    Claim("C3a", "3", "At Omega* = 0.8 approach A converges satisfactorily only with 16 elements.",
          "16 elements", "converged count of the steady amplitude equal to 16", (), c3a),
    Claim("C3b", "3", "With 16 elements, 100 and 200 time steps per crank period give the same transient.",
          "same result", f"within {100 * SAME:g} %", (3,), c3b),
    Claim("C3c", "3", "Approaches B and C need only 4 elements, even at Omega* = 0.8.",
          "4 elements", "converged count at most 4", (), c3c),
    Claim("C4a", "4", "At Omega* = 0.8 C departs noticeably from B, the more so with a heavier slider.",
          "noticeable, growing with ms*", f"above {100 * NOTICEABLE:g} %", (4,), c4a),
    Claim("C4b", "4", "In approach C the transverse deflection does not depend on the slider mass.",
          "no effect", f"within {100 * SAME:g} %", (4,), c4b),
    Claim("C4c", "4", "At Omega* = 0.8 approach A deflects about a tenth as much as B and C.",
          "A / B, A / C about 0.1", f"factor {FACTOR:g}", (4,), c4c),
    Claim("C5a", "5", "At Omega* = 0.1 the three approaches give nearly equal steady amplitudes for every eps.",
          "almost the same", f"within {100 * CLOSE:g} %", (5,), c5a),
    Claim("C5b", "5", "At Omega* = 0.8, eps = 0.01, dropping the quartic term overestimates the amplitude about tenfold.",
          "B / A about 10", f"factor {FACTOR:g}", (5,), c5b),
    Claim("C5c", "5", "B and C differ only negligibly, also at high speed.",
          "negligible", f"within {100 * CLOSE:g} %", (5,), c5c),
    Claim("C5d", "5", "The amplitude is nearly inversely proportional to eps (log-log slope near -1).",
          "slope about -1", f"-1 +- {SLOPE:g}", (5,), c5d),
    Claim("C6a", "6", "For eps = 0.01, B and C nearly coincide below Omega* = 0.7.",
          "almost the same below 0.7", f"within {100 * CLOSE:g} %", (6,), c6a),
    Claim("C6b", "6", "For eps = 0.01, B and C follow A closely only below Omega* = 0.2.",
          "Omega* = 0.2", f"0.2 +- {SPEED:g}", (6,), c6b),
    Claim("C6c", "6", "For eps = 0.01, B and C overestimate the amplitude tenfold at Omega* = 1.",
          "B / A, C / A about 10", f"factor {FACTOR:g}", (6,), c6c),
    Claim("C6d", "6", "B and C peak near Omega* = 1, while A keeps rising past Omega* = 1.",
          "maximum near 1; A rising", "peak within 1 +- 0.2", (6,), c6d),
    Claim("C6e", "6", "For eps = 0.1 the picture is the same with amplitudes about a tenth as large, and B, C follow A below Omega* = 0.4.",
          "ratio 0.1; Omega* = 0.4", f"factor {FACTOR:g}; 0.4 +- {SPEED:g}", (6,), c6e),
    Claim("C7a", "7", "At Omega* = 0.8 a heavier slider stretches and compresses the rod more.",
          "grows with ms*", "monotone in ms*", (7,), c7a),
    Claim("C7b", "7", "At Omega* = 0.8 the extension is independent of the slider mass at two crank angles.",
          "106.4 and 295.2 deg", f"+- {ANGLE:g} deg", (7,), c7b),
    Claim("C7c", "7", "At those two angles u*(1) and v*(1) vanish, so the extension is only the bending (slope) term.",
          "u*(1) = v*(1) = 0", f"{100 * CLOSE:g} % of the range of u*(1)", (7,), c7c),
    Claim("C8a", "8", "At Omega* = 0.1 the slope term is much smaller than the axial one and the extension is nearly symmetric about 180 deg.",
          "much smaller; symmetric", f"{100 * NOTICEABLE:g} %; {100 * CLOSE:g} %", (8,), c8a),
    Claim("C8b", "8", "At Omega* = 0.1 the mass-independent angles lie where the transmission angle is close to 90 deg.",
          "86.4 and 279 deg", f"+- {ANGLE:g} deg", (8,), c8b),
    Claim("K1", "conclusions", "Below Omega* = 0.2 the non-linear approach converges as fast as the simplified ones, which then make no significant error.",
          "Omega* < 0.2", f"error within {100 * 0.10:g} %", (6,), k1),
    Claim("K2", "conclusions", "Above Omega* = 0.2 the simplified approaches err noticeably, more so for smaller eps, and A needs more elements at higher speed.",
          "Omega* > 0.2", "errors above 10 %", (6,), k2),
    Claim("K3", "conclusions", "Extension and contraction grow strongly with speed, and two crank angles make the extension independent of the slider mass.",
          "two angles", "range ratio at least 2", (7, 8), k3),
    Claim("K4", "abstract", "The simplified approaches start to err at about a fifth of the fundamental bending frequency and, for eps = 0.01, overestimate about tenfold near Omega* = 1.",
          "Omega* = 0.2; 10-fold", f"0.2 +- {SPEED:g}; factor {FACTOR:g}", (6,), k4),
)

IDS = tuple(c.id for c in CLAIMS)


def evaluate(claim, run, model):
    """Outcome of one claim for one model; missing data -> not computable with the reason."""
    missing = [f for f in claim.needs if f not in run.data]
    if missing:
        f = missing[0]
        return Outcome(NOT_COMPUTABLE, "n/a", f"Figure {f} {run.missing.get(f, 'was not computed')}")
    try:
        out = claim.evaluate(run, model)
    except Missing as exc:
        return Outcome(NOT_COMPUTABLE, "n/a", str(exc))
    except (KeyError, ValueError, ZeroDivisionError, IndexError) as exc:
        return Outcome(NOT_COMPUTABLE, "n/a", f"cannot be computed from these runs ({type(exc).__name__}: {exc})")
    if out.verdict not in VERDICTS:
        raise ValueError(f"claim {claim.id}: verdict {out.verdict!r}")
    return out


def combine(paper, consistent):
    """One verdict for the two models: both the same -> that; otherwise partly (not computable only
    when neither model can be evaluated)."""
    if paper == consistent:
        return paper
    return PARTLY


def assess(run, models=("paper", "consistent")):
    """Rows: dict(claim, outcomes {model: Outcome}, verdict, reason)."""
    rows = []
    for c in CLAIMS:
        outs = {m: evaluate(c, run, m) for m in models}
        verdict = combine(*[outs[m].verdict for m in models])
        reasons = {o.reason for o in outs.values()}
        if len(reasons) == 1:
            reason = reasons.pop()
        else:
            reason = "; ".join(f"{m}: {o.reason}" for m, o in outs.items())
        rows.append(dict(claim=c, outcomes=outs, verdict=verdict, reason=reason))
    return rows
