"""What the claim checks (claim_checks.py) share: the verdict vocabulary, the tolerances, the run
data a check reads (RunData; Missing when a quantity is not in the runs; Outcome, a check's result)
and the measures computed from the runs (amplitudes and statuses of the figures' rows, differences
of curves, limit speeds, crossings, the words a value is given in)."""

import math
from dataclasses import dataclass, field

import numpy as np

from ..analyses import theory
from . import findings as fd
from .figures import DIVERGED    # a run of an ill-posed approach that failed

REPRODUCED, PARTLY, NOT_REPRODUCED, NOT_COMPUTABLE = (
    "reproduced", "partly", "not reproduced", "not computable")
VERDICTS = (REPRODUCED, PARTLY, NOT_REPRODUCED, NOT_COMPUTABLE)
STABLE = "periodic"
ILL = f"diverged ({theory.ILL_POSED})"

# tolerances (stated in findings.md beside the table)
CLOSE = 0.05          # "almost the same", "negligible", "almost indistinguishable": within 5 %
SAME = 0.02           # "the same result", "no effect": within 2 %
NOTICEABLE = 0.10     # "noticeable" difference: above 10 %
FACTOR = 1.5          # "about N-fold": within a factor 1.5 of N
SPEED = 0.1           # a speed limit "about Omega*": within +- 0.1
ANGLE = 3.0           # crank angles: within 3 degrees
SLOPE = 0.15          # "slope about -1": within +- 0.15, and the power law holding to 0.1 in log v*


@dataclass
class Outcome:
    verdict: str
    value: str = ""
    reason: str = ""


@dataclass
class RunData:
    cfg: object
    conv: dict
    data: dict                       # figure number -> figure data (as figures.py returns it)
    missing: dict = field(default_factory=dict)   # figure number -> why it is absent


class Missing(Exception):
    """A quantity a claim needs is not available (the message says why)."""


# ----------------------------------------------------------------------------- helpers

def _num(x, d=3):
    return "n/a" if x is None or not math.isfinite(x) else f"{x:.{d}g}"


def _pct(x):
    if x is not None and x == math.inf:
        return "not comparable (a run failed)"
    return "n/a" if x is None or not math.isfinite(x) else f"{100 * x:.3g} %"


def _pct_or(x, why):
    """A percentage, or why there is none (a part that cannot be computed)."""
    return why if x is None else _pct(x)


def _fig(run, f):
    if f not in run.data:
        raise Missing(f"Figure {f} {run.missing.get(f, 'was not computed')}")
    return run.data[f]


def _rows(run, f, **match):
    return [r for r in _fig(run, f)["rows"] if all(r[k] == v for k, v in match.items())]


def _amp(run, f, **match):
    rr = _rows(run, f, **match)
    return rr[0]["amplitude"] if rr else math.nan


def _status(run, f, **match):
    rr = _rows(run, f, **match)
    return rr[0]["status"] if rr else "missing"


def _compare_points(pairs):
    """pairs: (point, amplitude a, amplitude b, status a, status b).  Relative differences |b/a - 1|
    where both are periodic; points where either diverged are not computable (ill-posed); points
    where either has no stable periodic state otherwise are a qualitative difference (inf).
    Returns (differences by point, the points that diverged)."""
    diffs, diverged = {}, []
    for x, a, b, sa, sb in pairs:
        if DIVERGED in (sa, sb):
            diverged.append(x)
        elif math.isfinite(a) and math.isfinite(b) and a != 0:
            diffs[x] = abs(b / a - 1)
        else:
            diffs[x] = math.inf
    return diffs, diverged


def _held_text(diffs, diverged, what):
    """'max |C/B - 1| = 3 % at ...; holds at 5 of 8 points; not computable at 2 (B diverged: ...)'."""
    finite = {x: d for x, d in diffs.items() if math.isfinite(d)}
    lost = [x for x, d in diffs.items() if not math.isfinite(d)]
    held = sum(d <= CLOSE for d in diffs.values())
    parts = []
    if finite:
        x, d = max(finite.items(), key=lambda t: t[1])
        parts.append(f"max {what} = {_pct(d)} at {x}")
    parts.append(f"holds at {held} of {len(diffs)} comparable points")
    if lost:
        parts.append(f"no stable periodic state in one of them at {len(lost)}")
    if diverged:
        parts.append(f"not computable at {len(diverged)} ({ILL})")
    return "; ".join(parts)


def _held_verdict(diffs, diverged=()):
    """Reproduced when the claim holds at every point; points that cannot be computed (a run
    that diverged) leave at most partly."""
    if not diffs:
        return NOT_COMPUTABLE
    held = sum(d <= CLOSE for d in diffs.values())
    if held == 0:
        return NOT_REPRODUCED
    return REPRODUCED if held == len(diffs) and not diverged else PARTLY


def _curves(run, f, model, **match):
    return [c for c in _fig(run, f)["curves"] if c.spec.model == model
            and all(getattr(c.spec, k) == v for k, v in match.items())]


def _diff(a, b):
    """Transient difference max |v_a - v_b| / max |v_b| over their common history; None when
    either run diverged (an ill-posed approach: no result to compare), inf when either failed
    otherwise."""
    if a.diverged or b.diverged:
        return None
    if not (a.ok and b.ok):
        return math.inf
    ka, kb = a.spec.steps_per_rev, b.spec.steps_per_rev
    va, vb = a.v_mid, b.v_mid
    if kb % ka == 0:
        vb = vb[:: kb // ka]
    elif ka % kb == 0:
        va = va[:: ka // kb]
    k = min(len(va), len(vb))
    scale = float(np.max(np.abs(vb[:k])))
    return float(np.max(np.abs(va[:k] - vb[:k])) / scale) if scale > 0 else math.nan


def _by_parts(parts):
    """Verdict from sub-statements (bool each, None for a part that cannot be computed, e.g. of a
    run that diverged): all true -> reproduced, none true -> not reproduced, otherwise partly;
    not computable when no part can be."""
    known = [p for p in parts if p is not None]
    if not known:
        return NOT_COMPUTABLE
    n = sum(bool(p) for p in known)
    if n == len(parts):
        return REPRODUCED
    return NOT_REPRODUCED if n == 0 else PARTLY


def _near(x, target, tol, partly_tol=None):
    if x is None or not math.isfinite(x):
        return NOT_REPRODUCED
    if abs(x - target) <= tol:
        return REPRODUCED
    if partly_tol is not None and abs(x - target) <= partly_tol:
        return PARTLY
    return NOT_REPRODUCED


def _fold(x, target):
    """"About target-fold": within FACTOR reproduced, beyond 2 at least (a large overestimate)
    partly, otherwise not reproduced."""
    if x is None or not math.isfinite(x):
        return NOT_REPRODUCED
    if target / FACTOR <= x <= target * FACTOR:
        return REPRODUCED
    return PARTLY if x >= 2.0 else NOT_REPRODUCED


def _at_speed(run, f, model, ap, eps, omega, tol=0.026):
    """Row of Figure f nearest to omega (None if no sweep point within tol)."""
    rr = _rows(run, f, model=model, approach=ap, eps=eps)
    if not rr:
        return None
    r = min(rr, key=lambda r: abs(r["omega"] - omega))
    return r if abs(r["omega"] - omega) <= tol else None


def _limit_speed(run, model, eps):
    """Lowest Omega* (Figure 6) where B or C differs from A by more than the config's threshold or
    loses its stable periodic state while A has one (as findings.md's threshold table)."""
    thr = run.cfg.differ_threshold
    first = []
    a_ok = {r["omega"]: r["status"] == STABLE for r in _rows(run, 6, model=model, eps=eps, approach="A")}
    if not a_ok:
        raise Missing(f"Figure 6 has no eps = {eps:g}")
    for ap in ("B", "C"):
        rr = sorted(_rows(run, 6, model=model, eps=eps, approach=ap), key=lambda r: r["omega"])
        x = [r["omega"] for r in rr]
        d = np.abs(np.array([r["ratio_to_A"] for r in rr], dtype=float) - 1.0)
        c = fd.first_exceedance(x, d, thr)
        lost = fd.first_where(x, [r["status"] != STABLE and a_ok.get(r["omega"], False) for r in rr])
        first += [v for v in (c, lost) if v is not None]
    return min(first) if first else None


def _first_divergence(run, model, eps):
    """Lowest Omega* of Figure 6 where B or C diverged (None if nowhere)."""
    xs = [r["omega"] for ap in "BC" for r in _rows(run, 6, model=model, eps=eps, approach=ap)
          if r["status"] == DIVERGED]
    return min(xs) if xs else None


def _conv_series(run, model, ap, omega):
    s = run.conv["series"].get((model, ap, omega))
    if s is None:
        raise Missing(f"the convergence check did not run at Omega* = {omega:g}")
    return s


def _crossings(run, f, model):
    from .figures import extension_crossings_of
    xs = extension_crossings_of(_fig(run, f), model, run.cfg.crossing_rel_tol)
    if xs is None:
        raise Missing(f"Figure {f} has fewer than two stable extension curves")
    return [x["angle"] for x in xs]


def _angle_match(found, expected):
    d = [min(abs((e - a + 180) % 360 - 180) for a in found) if found else math.inf for e in expected]
    return d


def _offsets_text(found, expected, d):
    """'off by 0.8, 0.5 deg', or which of the paper's angles have no crossing near them."""
    if not found:
        return "no common crossing at all"
    near = [f"{x:.1f}" for x in d if x <= 90]
    far = [f"{e:g}" for e, x in zip(expected, d) if x > 90]
    text = "off by " + ", ".join(f"{x:.1f}" for x in d) + " deg" if not far else \
        (f"off by {', '.join(near)} deg; " if near else "") + \
        f"no crossing within 90 deg of the paper's {', '.join(far)} deg"
    return f"{len(found)} crossing(s) found; {text}"


def _ext_curves(run, f, model):
    cs = [c for c in _fig(run, f)["curves"] if c["model"] == model and c["status"] == STABLE]
    if not cs:
        raise Missing(f"Figure {f} has no stable extension curve")
    return sorted(cs, key=lambda c: c["ms"])
