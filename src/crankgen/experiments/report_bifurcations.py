"""findings.md, the bifurcations of approach A (data: bifurcations.py): every special point the
continuation found in each model at each eps, with kind, Omega*, amplitude, period and critical
multiplier; the stability of each branch along it; and what the response is beyond the last
special point."""

from . import figures as F
from .bifurcations import beyond_edge, multiplier_abs, stability_segments
from .config import MODELS
from .markdown import num, table
from .markdown import short as _short

LABELS = {"fold": "fold", "period-doubling": "period doubling", "neimark-sacker": "Neimark-Sacker"}


def _where(r):
    return f"{r['model']} model, eps = {r['eps']:g}"


def _segments(r, b):
    """Stability along branch b; a run shorter than the printed precision (the first point of a
    branch born at a period doubling, whose multiplier there is +1: marginal) is left out."""
    sps = [s for s in r["special_points"] if s["branch"] == b]
    segs = stability_segments(r["branches"][b], sps)
    shown = [g for g in segs if num(g[1], 5) != num(g[2], 5)] or segs
    return ", ".join(f"{'stable' if s else 'unstable'} {num(x, 5)} -> {num(y, 5)}" for s, x, y in shown)


def _point_text(s):
    return f"{LABELS[s['kind']]} at Omega* = {num(s['omega'], 7)} (period {s['period']})"


def summary_line(bif, missing=None):
    """One line for the Summary section."""
    if bif is None:
        return (f"- Bifurcations of approach A: not in this report (the bifurcations step "
                f"{missing or 'was not computed'}).")
    lo, hi = bif["range"]
    parts = []
    for r in bif["runs"]:
        if r["status"] != "ok":
            parts.append(f"{_where(r)}: continuation failed")
        elif not r["special_points"]:
            parts.append(f"{_where(r)}: none")
        else:
            parts.append(f"{_where(r)}: " + ", ".join(
                _point_text(s) for s in sorted(r["special_points"], key=lambda s: s["omega"])))
    return (f"- Bifurcations of approach A for {lo:g} <= Omega* <= {hi:g} (continuation): "
            + "; ".join(parts) + ".")


def _beyond_text(r, hi):
    b = r["beyond"]
    edge = beyond_edge(r, hi)
    if r["status"] != "ok":
        return "unknown (the continuation failed)"
    if b is None:
        if edge is not None:
            return "nothing: the last special point lies at the end of the range"
        b0 = r["branches"][0]
        if b0["stable"][-1]:
            return (f"no special point: the crank-period branch reaches Omega* = {hi:g} and is "
                    f"stable there (largest |multiplier| {num(b0['max_abs_multiplier'][-1], 4)})")
        return (f"no special point, but the crank-period branch is unstable at Omega* = {hi:g} "
                f"(largest |multiplier| {num(b0['max_abs_multiplier'][-1], 4)})")
    what = ("the last special point" if any(s["omega"] == edge for s in r["special_points"])
            else "where the crank-period branch stopped")
    head = (f"above Omega* = {num(edge, 5)} ({what}), a Poincare sweep up (first speed from rest, "
            f"each next from the previous state, {b['transient']} transient and {b['samples']} "
            "sampled revolutions): ")
    if b["status"] != "ok":
        return head + f"FAILED ({_short(b['message'], 100)})"
    out = []
    for q in b["points"]:
        ev = (f"repeat residual {num(q['repeat_residual'], 2)}" if q["period"] else
              f"Lyapunov exponent {num(q['lyapunov'], 3)} per revolution, {q['distinct']} distinct samples")
        if q["classification"] == "failed":
            ev = _short(q["message"], 90)
        out.append(f"{q['omega']:g}: {q['classification']} ({ev})")
    return head + "; ".join(out)


def _stable_at_end(r, hi):
    ends = [br for br in r["branches"] if abs(float(br["omega"][-1]) - hi) < 1e-9 and br["stable"][-1]]
    if not ends:
        periods = ", ".join(str(p) for p in sorted({br["period"] for br in r["branches"]}))
        return f"no branch followed (periods {periods}) is stable at Omega* = {hi:g}"
    return f"stable at Omega* = {hi:g}: " + ", ".join(
        f"period {br['period']} (max |v*| {num(br['amplitude'][-1], 4)})" for br in ends)


def section(cfg, bif, missing=None):
    """The findings section (a list of lines)."""
    head = ["## Bifurcations of approach A (continuation, drawn over Figure 6)", ""]
    if bif is None:
        return head + [f"Not in this report: the bifurcations step {missing or 'was not computed'} "
                       "(it runs with Figure 6: `crankgen reproduce --figures 6` with the same "
                       "options adds it).", ""]
    lo, hi = bif["range"]
    runs = bif["runs"]
    lines = head + [
        f"crankgen.continuation follows the crank-periodic response of approach A from Omega* = "
        f"{lo:g} to {hi:g}, in both models at each eps of Figure 6: pseudo-arclength continuation "
        "of the fixed points of the crank-revolution map, with all Floquet multipliers at every "
        "point (stable: all inside the unit circle). At each period doubling the branch of twice "
        f"the period is followed, up to period {bif['max_period']}. A special point is a fold (a real "
        "multiplier through +1), a period doubling (through -1) or a Neimark-Sacker point (a "
        "complex pair through the unit circle), located to about 1e-9 in its test function; the "
        "critical multiplier is given there. Beyond the last special point (or where the "
        "crank-period branch stopped short of the range), a Poincare sweep classifies the "
        "response (period-k, quasi-periodic, irregular or unsettled, with its evidence). The "
        "consistent model's branches are drawn over its panels of Figure 6; the numbers are in "
        "bifurcations.csv (special points), bifurcation_branches.csv (every point of every "
        "branch) and bifurcation_beyond.csv (the sweeps).", "",
        table(["model", "eps", "n", "steps/rev", "status", "branches", "special points"],
              [[r["model"], f"{r['eps']:g}", r["n_elements"], r["steps_per_rev"],
                "ok" if r["status"] == "ok" else "FAILED: " + _short(r["message"], 100),
                len(r["branches"]), len(r["special_points"])] for r in runs]), ""]
    rows = []
    for r in runs:
        for s in sorted(r["special_points"], key=lambda s: (s["omega"], s["period"])):
            x = r["eps"] * s["amplitude"]
            rows.append([r["model"], f"{r['eps']:g}", s["kind"], num(s["omega"], 7), s["period"],
                         num(s["amplitude"], 5), num(x, 3) + (" (beyond the theory)" if x > F.THEORY_LIMIT else ""),
                         f"{s['multiplier'][0]:+.6f} {s['multiplier'][1]:+.6f}i",
                         num(multiplier_abs(s), 10)])
    if rows:
        lines += ["Every special point found:", "",
                  table(["model", "eps", "kind", "Omega*", "period", "max |v*|", "max |v|/L",
                         "critical multiplier", "|multiplier|"], rows), ""]
    else:
        lines += [f"No special point was found for {lo:g} <= Omega* <= {hi:g} in either model.", ""]
    for m in MODELS:
        for r in (r for r in runs if r["model"] == m.key):
            where = f"- {_where(r)} (n = {r['n_elements']}, {r['steps_per_rev']} steps/rev): "
            if r["status"] != "ok":
                lines.append(where + f"the continuation FAILED ({_short(r['message'], 160)}); "
                             "nothing is known from it.")
                continue
            pts = sorted(r["special_points"], key=lambda s: s["omega"])
            lines.append(where + ("; ".join(_point_text(s) for s in pts) if pts else
                                  f"no fold, period doubling or Neimark-Sacker point for {lo:g} <= Omega* <= {hi:g}") + ".")
            for b, br in enumerate(r["branches"]):
                lines.append(f"  Period {br['period']} ({br['origin']}): {_segments(r, b)}; "
                             f"ends: {br['stop_reason']}.")
            lines.append(f"  {_stable_at_end(r, hi)[0].upper()}{_stable_at_end(r, hi)[1:]}.")
            lines.append(f"  Beyond: {_beyond_text(r, hi)}.")
    lines.append("")
    return lines
