"""findings.md, the geometrically exact rod beside the two models: its amplitudes in Figures 5 and
6 against the consistent model's and the paper's (approach A), its own range (crankgen.analyses.theory:
slenderness, outer-fibre strain, section rotation), and the consistent model's special points
re-read on it (data: exact_rod.py): which survive, move or vanish, the hysteresis loop, the
snap-through orbit, where the exact rod's branches end, and the character of its response at
exact_character_omegas (period-k, quasi-periodic, irregular)."""

import math

from ..analyses import theory
from . import figures as F
from . import exact_rod as XR
from .config import EXACT, MODELS
from .markdown import num, table

LABELS = {"fold": "fold", "period-doubling": "period doubling", "neimark-sacker": "Neimark-Sacker"}
DIFFER = 0.01          # the exact rod and the consistent model "differ" above 1 %


def _amp(r):
    return r["amplitude"] if r["status"] == F.STABLE else math.nan


def _sweep_table(data, f, cfg):
    """Rows of one figure: (fixed, x, paper A, consistent A, exact, exact / consistent - 1, the
    exact rod's range)."""
    rows = data.get(f, {}).get("rows", [])
    exact = [r for r in rows if r["model"] == EXACT.key]
    if not exact:
        return None, []
    ref = {(r["model"], r["omega"], r["eps"]): r for r in rows if r["approach"] == "A"}
    out, diffs = [], []
    for r in sorted(exact, key=lambda r: (r["eps"], r["omega"]) if f == 6 else (r["omega"], r["eps"])):
        c = ref.get((MODELS[1].key, r["omega"], r["eps"]))
        p = ref.get((MODELS[0].key, r["omega"], r["eps"]))
        ca, xa = (_amp(c) if c else math.nan), _amp(r)
        d = xa / ca - 1 if math.isfinite(ca) and math.isfinite(xa) and ca else math.nan
        if math.isfinite(d):
            diffs.append((abs(d), d, r))
        status = "" if r["status"] == F.STABLE else f" ({r['status']})"
        out.append([f"{r['eps']:g}", f"{r['omega']:g}", num(_amp(p)) if p else "n/a",
                    num(ca), num(xa) + status, "n/a" if not math.isfinite(d) else f"{100 * d:+.2f} %",
                    num(r.get("fibre_strain"), 3), num(r.get("section_rotation_deg"), 3),
                    r.get("beyond_theory") or "n/a"])
    return out, diffs


def _amplitudes(cfg, data):
    lines = []
    for f, what in ((6, "against Omega* (Figure 6)"), (5, "against eps (Figure 5)")):
        rows, diffs = _sweep_table(data, f, cfg)
        if rows is None:
            continue
        lines += [f"Steady amplitude max |v*| {what}: approach A of the paper's model and of the consistent "
                  "model, the exact rod (its own rows of the figure, drawn in teal in both models' panels), "
                  "the exact rod's amplitude relative to the consistent model's, and the exact rod's own "
                  "range: its largest outer-fibre strain and section rotation (degrees) over the orbit and "
                  "whether it leaves its limits (beyond).", "",
                  table(["eps", "Omega*", "paper A", "consistent A", "exact rod", "exact / consistent",
                         "outer-fibre strain", "section rotation", "beyond its limits"], rows), ""]
        failed = [r for r in data[f]["rows"] if r["model"] == EXACT.key and r["status"] == "failed"]
        if failed:
            lines += [f"The exact rod has no result in Figure {f} at " + "; ".join(
                f"eps = {e:g}, Omega* = " + ", ".join(f"{r['omega']:g}" for r in failed if r["eps"] == e)
                for e in sorted({r["eps"] for r in failed})) + ": its runs fail (the CSV's message says how; "
                "the element itself has no rotation limit).", ""]
        if diffs:
            within = [r for a, _, r in diffs if a <= DIFFER]
            big = max(diffs, key=lambda t: t[0])
            lines += [f"In Figure {f} the exact rod and the consistent model agree within "
                      f"{100 * DIFFER:g} % at {len(within)} of {len(diffs)} cases where both are periodic; "
                      f"the largest difference is {100 * big[1]:+.2f} % (eps = {big[2]['eps']:g}, Omega* = "
                      f"{big[2]['omega']:g}).", ""]
    return lines


def _point(s):
    return f"{LABELS.get(s['kind'], s['kind'])} (period {s['period']})"


def _special_points(exact):
    lines = []
    settings = exact["settings"]
    lo, hi = settings["range"]
    runs = {(r["mechanism"], r["model"]): r for r in exact["runs"]}
    for name, comp in exact["comparisons"].items():
        cons, ex = runs.get((name, "consistent")), runs.get((name, "exact"))
        lines += [f"### {name.capitalize()}", ""]
        if comp.get("status") != "ok":
            why = "; ".join(f"{r['model']}: {r['message']}" for r in (cons, ex) if r and r["status"] != "ok")
            lines += [f"A continuation failed ({why}): no comparison.", ""]
            continue
        rows = [[_point(p["consistent"]), num(p["consistent"]["omega"], 5), num(p["consistent"]["amplitude"]),
                 num(p["exact"]["omega"], 5) if p["exact"] else "—",
                 num(p["exact"]["amplitude"]) if p["exact"] else "—",
                 f"{p['exact']['omega'] - p['consistent']['omega']:+.4f}" if p["exact"] else "—", p["fate"]]
                for p in comp["pairs"]]
        rows += [[_point(e), "—", "—", num(e["omega"], 5), num(e["amplitude"]), "—", "new"] for e in comp["new"]]
        lines += [table(["special point", "consistent Omega*", "its max abs v*", "exact rod Omega*",
                         "its max abs v*", "shift", "on the exact rod"], rows), ""]
        facts = []
        h_c, h_x = XR.hysteresis(cons), XR.hysteresis(ex)
        if h_c:
            facts.append(f"the hysteresis loop of the consistent model spans Omega* = {num(h_c[0], 5)} (the "
                         f"period-2 branch's lowest fold, where its large orbit ends sweeping down) to "
                         f"{num(h_c[1], 5)} (its fold of smallest amplitude, where the small period-2 orbit "
                         "jumps sweeping up); on the exact rod "
                         + (f"{num(h_x[0], 5)} to {num(h_x[1], 5)}" if h_x else
                            "no such pair of folds is found (no loop)"))
        for model, run in (("consistent model", cons), ("exact rod", ex)):
            big = XR.largest(run, 2)
            if big:
                facts.append(f"the {model}'s largest period-2 orbit reaches max |v*| = {num(big[0])} (Omega* = "
                             f"{num(big[1], 4)}, |v|/L = {num(big[0] * settings['eps'], 3)})")
        for b, br in enumerate(ex["branches"]):
            end = br.get("end")
            if end:
                rot = end.get("section_rotation_deg")
                facts.append(f"the exact rod's period-{br['period']} branch ends at Omega* = {num(end['omega'], 5)} "
                             f"(max |v*| {num(end['amplitude'])}): {br['stop_reason']}; its orbit there turns "
                             f"sections by up to {num(rot, 3)} degrees from the chord (outer-fibre strain "
                             f"{num(end.get('fibre_strain'), 3)}); the element has no rotation limit, so the "
                             "branch ends where the continuation stops, not at an end of the rod's model"
                             if rot is not None else
                             f"the exact rod's period-{br['period']} branch ends at Omega* = {num(end['omega'], 5)}: "
                             f"{br['stop_reason']} ({end.get('message', '')})")
        stops = [f"{r['model']} period {br['period']}: {br['stop_reason']}" for r in (cons, ex)
                 for br in r["branches"] if not str(br["stop_reason"]).startswith("reached")]
        lines += [f"- {x}." for x in facts]
        if stops and not any(br.get("end") for br in ex["branches"]):
            lines += ["- Branches that end before the range's end: " + "; ".join(stops) + "."]
        lines += [""]
    return lines


def _snaps(exact):
    snaps = exact.get("snaps") or []
    if not snaps:
        return []
    lines = [f"Marched from rest at Omega* = {snaps[0]['omega']:g} (slider-crank, "
             f"{snaps[0]['revolutions']} revolutions):", ""]
    for s in snaps:
        peaks = s.get("peaks") or []
        last = ", ".join(num(p) for p in peaks[-4:])
        who = "exact rod" if s["model"] == EXACT.key else f"{s['model']} model"
        if s["status"] == "ok":
            lines.append(f"- the {who} runs all {s['revolutions']} revolutions; the per-revolution "
                         f"peaks of |v*| over the last {min(4, len(peaks))}: {last} (|v|/L up to "
                         f"{num(max(peaks[-4:]) * exact['settings']['eps'], 3)}).")
        else:
            lines.append(f"- the {who} stops at t* = {num(s.get('time'), 4)} (max |v*| "
                         f"{num(s.get('max_abs_v'))}, sections turned up to {num(s.get('section_rotation_deg'), 3)} "
                         f"degrees before): {s.get('reason', s['message'])}.")
    return lines + [""]


def _characters(exact):
    chars = exact.get("characters") or []
    if not chars:
        return []
    st = exact["settings"]
    lines = [f"The exact rod's response, classified by crankgen.poincare (from rest, {st['character_steps']} "
             f"steps per revolution, {st['character_transient']} revolutions, then {st['character_samples']} "
             "sampled once per revolution at theta = 0; the largest "
             "Lyapunov exponent per revolution from the exact Jacobians of the revolution map; "
             "`exact_rod_character.csv`):", ""]
    for c in chars:
        if c["status"] != "ok":
            lines.append(f"- {c['mechanism']}: failed ({c['message']}).")
            continue
        for q in c["points"]:
            lyap = q.get("lyapunov")
            lines.append(f"- {c['mechanism']}, Omega* = {q['omega']:g}: {q['classification']}"
                         + (f", largest Lyapunov exponent {lyap:+.3f} per revolution" if lyap is not None else "")
                         + f", {q['distinct']} distinct samples of v* in {num(q.get('sample_min'))} to "
                         f"{num(q.get('sample_max'))}, max |v*| {num(q.get('amplitude'))} (|v|/L "
                         f"{num((q.get('amplitude') or math.nan) * st['eps'], 3)})."
                         + (f" {q['message']}" if q.get("message") else "")
                         + "".join(_beside(q["classification"], k, a, st["steps_per_rev"])
                                   for k, a in _stable_orbits_at(exact, c["mechanism"], q["omega"])
                                   if q["classification"] != f"period-{k}"))
    return lines + ["", "(irregular: a positive exponent above 0.01, chaos; unsettled: a negative one, still "
                    "converging after the transient. Near a period doubling the step decides which attractor a march "
                    "from rest ends on: docs/theory/exact-rod.md reads the response at 100 to 400 steps per "
                    "revolution and 16 and 32 elements, with its periodic orbits and basins, by "
                    "examples/large_orbit.py.)", ""]


def _beside(classification, period, amplitude, steps):
    """What the continuation's stable period-`period` orbit at the same speed adds to a marched
    response: a second attractor, unless the march is still converging (unsettled), maybe to it."""
    where = f"(max |v*| {num(amplitude)}, {steps} steps per revolution)"
    if classification == "unsettled":
        return (f" The continuation's period-{period} orbit is stable here {where}: the march may still be "
                "converging to it.")
    return f" Beside it the continuation's stable period-{period} orbit {where}: two attractors at this speed."


def _stable_orbits_at(exact, mechanism, omega):
    """[(period, max |v*|)] of the exact rod's continued orbits that are stable at Omega* = omega
    (both neighbouring points of a branch stable, the amplitude interpolated between them)."""
    run = next((r for r in exact.get("runs", []) if r["mechanism"] == mechanism and r["model"] == EXACT.key
                and r["status"] == "ok"), None)
    out = []
    for br in (run or {}).get("branches", []):
        w, a, ok = (list(br[k]) for k in ("omega", "amplitude", "stable"))
        for i in range(len(w) - 1):
            lo, hi = sorted((w[i], w[i + 1]))
            if ok[i] and ok[i + 1] and lo <= omega <= hi and hi > lo:
                t = (omega - w[i]) / (w[i + 1] - w[i])
                out.append((int(br["period"]), a[i] + t * (a[i + 1] - a[i])))
    return out


def _range(data):
    rows = [r for f in (5, 6) for r in data.get(f, {}).get("rows", []) if r["model"] == EXACT.key]
    if not rows:
        return []
    flags = [theory.exact_range_flag(r["eps"], r.get("fibre_strain", math.nan),
                                     r.get("section_rotation_deg", math.nan)) for r in rows]
    known = [f for f in flags if f.known]
    count = {}
    for f in known:
        for m in f.tripped:
            count[m.name] = count.get(m.name, 0) + 1
    paper = sum(1 for r in rows if r["deflection_over_L"] > F.THEORY_LIMIT)
    return [f"The exact rod's own range (crankgen.analyses.theory, README): of its {len(known)} steady rows in "
            f"Figures 5 and 6, {sum(1 for f in known if f)} leave its limits ("
            + (", ".join(f"{n}: {k}" for n, k in count.items()) or "none")
            + f"); rows with |v|/L above the paper's limit of {F.THEORY_LIMIT:g}, which does not apply "
            f"to it: {paper}. At eps = 0.01 the outer fibres strain sqrt(3) eps pi^2 |v|/L about, so most of these "
            "orbits would yield a real metal rod: read them as the elastic rod's, as the models' own are.", ""]


def section(cfg, data, exact, missing=None):
    lines = ["## The geometrically exact rod beside the two models", "",
             "The exact rod (`model=\"exact\"`: the exact stretch |r'| - 1 at every quadrature point and "
             "the exact curvature of the deformed axis, with no limit on the section rotation; Lagrange "
             "equations, Kelvin-Voigt damping, rotary inertia) drops none of the terms of the paper's "
             "strain; where it differs from the consistent model, the difference is what approach A drops "
             "(`crankgen audit`, section 7).", ""]
    lines += _amplitudes(cfg, data)
    lines += _range(data)
    if exact is None:
        return lines + [f"The continuation of the exact rod is not in this report (the exact rod step "
                        f"{missing or 'was not computed'}; it runs with Figure 6).", ""]
    st = exact["settings"]
    lines += ["### Special points on the exact rod", "",
              f"crankgen.continuation over {st['range'][0]:g} <= Omega* <= {st['range'][1]:g} of the consistent "
              f"model and of the exact rod, eps = {st['eps']:g}, {st['n_elements']} elements, "
              f"{st['steps_per_rev']} steps per revolution, periods up to {st['max_period']} ("
              + " and ".join("the slider-crank" if n == "slider-crank" else f"a four-bar with a rocker of radius "
                             f"{st['rocker']:g} pivoted at (1, 0)" for n in st["mechanisms"])
              + f"). A consistent special "
              f"point and an exact one of the same kind and period within {st['match']:g} in Omega* are paired, "
              f"nearest first: it survives (shift below {XR.MOVED:g}), moves, or vanishes (no partner); an exact "
              "point without a partner is new. Files: exact_rod.png, exact_rod_points.csv, "
              "exact_rod_branches.csv. The same runs from the API: `crankgen.continuation(mech, \"omega\", "
              f"{st['range'][0]:g}, {st['range'][1]:g}, max_period={st['max_period']}, model=\"exact\", "
              f"n_elements={st['n_elements']}, steps_per_rev={st['steps_per_rev']})`, or `crankgen continue "
              f"--model exact --from {st['range'][0]:g} --to {st['range'][1]:g} --max-period {st['max_period']} "
              f"--elements {st['n_elements']} --steps-per-rev {st['steps_per_rev']}` (the four-bar: add "
              f"`--guide circle --rocker {st['rocker']:g} --ground 1`).", ""]
    lines += _special_points(exact)
    lines += _snaps(exact)
    lines += _characters(exact)
    return lines


def summary_line(exact, missing=None):
    if exact is None:
        return f"- The exact rod's special points: not in this report ({missing or 'not computed'})."
    parts = []
    for name, comp in exact["comparisons"].items():
        if comp.get("status") != "ok":
            parts.append(f"{name}: a continuation failed")
            continue
        moved = [f"{LABELS.get(p['consistent']['kind'])} {num(p['consistent']['omega'], 5)} -> "
                 f"{num(p['exact']['omega'], 5)}" for p in comp["pairs"] if p["exact"]]
        gone = [f"{LABELS.get(p['consistent']['kind'])} {num(p['consistent']['omega'], 5)}"
                for p in comp["pairs"] if not p["exact"]]
        parts.append(f"{name}: " + ", ".join(moved) + ("; vanish: " + ", ".join(gone) if gone else ""))
    return "- The consistent model's special points on the exact rod: " + "; ".join(parts) + "."
