"""findings.md: tables of numbers computed from the runs and plain statements generated from them.
This module assembles the document and writes its overview sections (claims, summary, results
beyond the theory, settings, cases without a stable state, run); report_figures.py writes the
sections of each figure's numbers."""

import datetime as _dt
import math
from collections import OrderedDict

import numpy as np

from .. import __version__
from . import figures as F
from . import claims
from . import findings as fd
from . import report_bifurcations as RB
from .config import APPROACHES, MODELS
from .markdown import num, pct, table
from .markdown import rows_where as _rows, series as _series, short as _short
from .report_figures import (_convergence, _disagreement, _extensions, _ratios, _slopes,
                             _threshold, _transients)

STABLE = "periodic"


# ----------------------------------------------------------------------------- sections

def _settings(cfg, total, files):
    lines = ["## Settings", "",
             table(["setting", "value"], [
                 ["preset", cfg.preset],
                 ["a*, eps (base), ms* (base), mu*", f"{cfg.a:g}, {cfg.eps:g}, {cfg.ms:g}, {cfg.mu:g}"],
                 ["initial conditions", "zero (rod undeformed, at rest in the moving frame at theta = 0)"],
                 ["time integration", f"Newmark beta = 1/4, gamma = 1/2, Newton iterations, {cfg.steps_per_rev} steps per crank revolution"],
                 ["paper's element counts", ", ".join(f"{a} {n}" for a, n in cfg.paper_elements.items())],
                 ["element ladder (convergence check)", ", ".join(map(str, cfg.conv_ladder)) + f" at Omega* = {', '.join(f'{o:g}' for o in cfg.conv_omegas)}, tolerance {pct(cfg.conv_tol)}"],
                 ["refinement check (2 n elements)", ", ".join(f"Omega* {o:g} eps {e:g}" for o, e in F.refinement_points(cfg)) or "not run"],
                 ["Figure 2", f"Omega* = {cfg.fig2_omega:g}, n = {', '.join(map(str, cfg.fig2_elements))} and the count used, {cfg.fig2_revolutions:g} revolutions"],
                 ["Figure 3", f"Omega* = {cfg.fig3_omega:g}, n = {', '.join(map(str, cfg.fig3_elements))} and the count used, steps/rev {', '.join(map(str, cfg.fig3_steps))}, {cfg.fig3_revolutions:g} revolutions"],
                 ["Figure 4", f"Omega* = {cfg.fig4_omega:g}, ms* = {', '.join(f'{m:g}' for m in cfg.fig4_ms)} (B, C), {cfg.fig4_revolutions:g} revolutions"],
                 ["Figure 5", f"Omega* = {', '.join(f'{o:g}' for o in cfg.fig5_omegas)}; eps = {', '.join(f'{e:g}' for e in cfg.fig5_eps)}"],
                 ["Figure 6", f"eps = {', '.join(f'{e:g}' for e in cfg.fig6_eps)}; Omega* = {fd.ranges_text(cfg.fig6_omegas)}"],
                 ["bifurcations (approach A)", f"continuation over Omega* = {cfg.bif_range[0]:g} to {cfg.bif_range[1]:g}, eps = {', '.join(f'{e:g}' for e in cfg.fig6_eps)}, "
                  + (f"n = {cfg.bif_elements}" if cfg.bif_elements else "n = the count used for A")
                  + f", {cfg.bif_steps_per_rev or cfg.steps_per_rev} steps/rev, periods up to {cfg.bif_max_period}, Omega* steps up to {cfg.bif_dp_max:g}, points converged to {cfg.bif_tol:g}; "
                  f"beyond the last special point a Poincare sweep over {cfg.bif_beyond_values} speeds ({cfg.bif_transient} transient + {cfg.bif_samples} sampled revolutions each)"],
                 ["Figures 7, 8", f"Omega* = {cfg.fig7_omega:g}, {cfg.fig8_omega:g}; ms* = {', '.join(f'{m:g}' for m in cfg.ext_ms)}; approach A"],
                 ["steady state", "periodic orbit with the crank period (shooting); amplitude = max |v*(1/2)| over the steady revolution"],
                 ["cases without a stable periodic state", (f"transient of {cfg.envelope_revolutions} revolutions from zero initial conditions, max |v*| over the last {cfg.envelope_window}" if cfg.envelope_revolutions > 0 else "no transient computed")],
                 ["steady_states options", ", ".join(f"{k} = {v}" for k, v in cfg.steady_options.items()) or "defaults"],
             ]), "",
             "Models (every figure is computed for both):", "",
             table(["model", "formulation", "damping", "membrane", "description"],
                   [[m.key, m.formulation, m.damping, m.membrane, m.label] for m in MODELS]), ""]
    return lines


def _failures(cfg, conv, data):
    groups = OrderedDict()

    def add(fig, r, xkey):
        if r["status"] == STABLE:
            return
        key = (fig, r["model"], r["approach"], r["eps"] if xkey != "eps" else None, r["ms"], r["status"])
        g = groups.setdefault(key, dict(x=[], message=r["message"], env=[], diverged=[], defl=[]))
        g["x"].append(r[xkey])
        if math.isfinite(r.get("deflection_over_L", math.nan)):
            g["defl"].append(r["deflection_over_L"])
        if math.isfinite(r.get("envelope", math.nan)):
            g["env"].append(r["envelope"])
        elif r.get("envelope_note", "").startswith("transient failed"):
            g["diverged"].append(r[xkey])

    for r in conv["rows"]:
        add("convergence", dict(r), "n_elements")
    if 5 in data:
        for r in data[5]["rows"]:
            add("5", r, "eps")
    if 6 in data:
        for r in data[6]["rows"]:
            add("6", r, "omega")
    for f in (7, 8):
        if f in data:
            for r in data[f]["curves"]:
                add(str(f), r, "omega")
    rows = []
    for (fig, model, ap, eps, ms, status), g in groups.items():
        xname = {"convergence": "n", "5": "eps", "6": "Omega*"}.get(fig, "Omega*")
        env = []
        if g["env"]:
            lo, hi = min(g["env"]), max(g["env"])
            env.append(f"max |v*| {num(lo)}" + (f" to {num(hi)}" if hi != lo else ""))
        if g["defl"] and max(g["defl"]) > F.THEORY_LIMIT:
            env.append(f"up to |v|/L = {num(max(g['defl']), 3)}: beyond the theory")
        if g["diverged"]:
            env.append(f"transient diverges at {xname} = {fd.ranges_text(g['diverged'])}")
        env = "; ".join(env)
        rows.append([fig, model, ap, "" if eps is None else f"{eps:g}", f"{ms:g}", status,
                     f"{xname} = {fd.ranges_text(g['x'])}", _short(g["message"], 100), env])
    lines = ["## Cases without a stable periodic steady state", "",
             "Every such case is kept in the CSV tables (status, message) and marked in the figures "
             "('x' inside the frame at the bottom, hollow markers for unstable orbits and non-periodic "
             "responses, filled triangles at the top for values off the scale). "
             "Grouped by figure, model, approach and status; the reason is that of the first case "
             "of the group; 'response' is max |v*| over the last revolutions of a transient from zero "
             "initial conditions (cases whose integration itself failed have none).", ""]
    if rows:
        lines += [table(["figure", "model", "approach", "eps", "ms*", "status", "cases", "reason (first case)", "response"],
                        rows), ""]
    else:
        lines += ["None: every steady-state case reached a stable periodic state.", ""]
    return lines


def _summary(cfg, conv, data):
    """Headline numbers, recomputed with the same functions as the sections below."""
    out = ["## Summary", ""]
    counts, series = conv["counts"], conv["series"]
    om_ref = cfg.fig3_omega if cfg.fig3_omega in cfg.conv_omegas else cfg.conv_omegas[-1]
    conv_a = []
    for m in MODELS:
        s = series[(m.key, "A", om_ref)]
        if s["kind"] == "converged":
            conv_a.append(f"n = {s['n']} ({m.key})")
        elif s["kind"] == "not-converged":
            conv_a.append(f"not reached up to n = {s['n']} ({m.key})")
        else:
            conv_a.append(f"not determinable ({m.key})")
    out.append("- Element counts used: " + "; ".join(
        f"{m.key} " + ", ".join(f"{ap} {counts[(m.key, ap)]}" for ap in APPROACHES) for m in MODELS)
        + f". Approach A at Omega* = {om_ref:g}, {pct(cfg.conv_tol)} convergence: " + "; ".join(conv_a) + ".")
    if 5 in data:
        parts = []
        for m in MODELS:
            for om in cfg.fig5_omegas:
                a = {ap: _rows(data[5], model=m.key, omega=om, eps=cfg.eps, approach=ap) for ap in APPROACHES}
                amp = {ap: (a[ap][0]["amplitude"] if a[ap] else math.nan) for ap in APPROACHES}
                parts.append(f"{m.key}, Omega* = {om:g}: B/A {num(fd.ratio(amp['B'], amp['A']), 4)}, "
                             f"C/A {num(fd.ratio(amp['C'], amp['A']), 4)}")
        out.append(f"- Amplitude ratios at eps = {cfg.eps:g} (n/a: no stable periodic state): " + "; ".join(parts) + ".")
    if 6 in data:
        parts = []
        for m in MODELS:
            for eps in cfg.fig6_eps:
                first = []
                for ap in ("B", "C"):
                    x, d, rr = _series(_rows(data[6], model=m.key, eps=eps, approach=ap), "omega", "ratio_to_A")
                    c = fd.first_exceedance(x, np.abs(d - 1.0), cfg.differ_threshold)
                    a_ok = {r["omega"]: r["status"] == STABLE for r in _rows(data[6], model=m.key, eps=eps, approach="A")}
                    lost = fd.first_where(x, [r["status"] != STABLE and a_ok.get(r["omega"], False) for r in rr])
                    first += [v for v in (c, lost) if v is not None]
                parts.append(f"{m.key}, eps = {eps:g}: " + (f"Omega* = {num(min(first))}" if first else "never"))
        out.append(f"- Lowest speed at which B or C differs from A by more than {pct(cfg.differ_threshold)} "
                   "(or loses its stable periodic state): " + "; ".join(parts) + ".")
    if 5 in data:
        parts = []
        for m in MODELS:
            for om in cfg.fig5_omegas:
                x, y, _ = _series(_rows(data[5], model=m.key, approach="A", omega=om), "eps")
                f = fd.loglog_slope(x, y)
                parts.append(f"{m.key}, Omega* = {om:g}: {num(f['slope'], 3) if f else 'n/a'}")
        out.append("- Slope of log v* against log eps, approach A: " + "; ".join(parts) + ".")
    parts = []
    for f in (7, 8):
        if f in data:
            for m in MODELS:
                xs = F.extension_crossings_of(data[f], m.key, cfg.crossing_rel_tol)
                txt = "n/a" if xs is None else (", ".join(f"{x['angle']:.1f}" for x in xs) or "none")
                parts.append(f"Figure {f} {m.key}: {txt}")
    if parts:
        out.append("- Crank angles (degrees) where the extension does not depend on ms*: " + "; ".join(parts) + ".")
    if 6 in data:
        worst, mism = None, 0
        p, c = MODELS[0].key, MODELS[1].key
        for ap in APPROACHES:
            for eps in cfg.fig6_eps:
                x, a, _ = _series(_rows(data[6], model=p, approach=ap, eps=eps), "omega")
                _, b, _ = _series(_rows(data[6], model=c, approach=ap, eps=eps), "omega")
                d = fd.max_relative_difference(x, b, a)
                if d and (worst is None or d["value"] > worst[0]["value"]):
                    worst = (d, ap, eps)
                mism += int(np.sum(np.isfinite(a) != np.isfinite(b)))
        if worst:
            d, ap, eps = worst
            out.append(f"- Paper model against consistent model (Figure 6): largest amplitude difference "
                       f"{pct(d['value'])} (approach {ap}, eps = {eps:g}, Omega* = {d['at']:g}); "
                       f"{mism} of the sweep's cases have a stable periodic state in one model only.")
    return out + [""]


def _missing_note(missing):
    if not missing:
        return []
    return ["**Not in this report:** " + "; ".join(
        f"Figure {f} ({why}; `crankgen reproduce --figures {f}` with the same options adds it)"
        for f, why in sorted(missing.items())) + ". Everything below that needs these figures says so.", ""]


def _claims(cfg, conv, data, missing):
    run = claims.RunData(cfg, conv, data, missing or {})
    rows = claims.assess(run)
    p, c = MODELS[0].key, MODELS[1].key
    counts = {v: sum(r["verdict"] == v for r in rows) for v in claims.VERDICTS}
    lines = ["## The paper's claims beside both models", "",
             "Each statement the paper makes about its Figures 2-8 and in its conclusions, restated, "
             "with the same quantity computed from both models' runs. Per model, the claim is "
             "reproduced when the computed value meets the tolerance given in the reason, partly when "
             "only some of its parts (or some of its points) do, not reproduced when none do, and not "
             "computable when the runs it needs are absent. The verdict column combines the two "
             "models: the common verdict when they agree, partly when they do not. Tolerances: "
             f"'almost the same' {pct(claims.CLOSE)}, 'the same' / 'no effect' {pct(claims.SAME)}, "
             f"'noticeable' above {pct(claims.NOTICEABLE)}, 'about N-fold' a factor {claims.FACTOR:g}, "
             f"speeds +- {claims.SPEED:g}, crank angles +- {claims.ANGLE:g} deg. "
             f"Verdicts: {', '.join(f'{n} {v}' for v, n in counts.items())}.", "",
             table(["id", "figure", "claim", "paper's value", f"{p} model", f"{c} model", "verdict", "reason"],
                   [[r["claim"].id, r["claim"].figure, r["claim"].statement, r["claim"].paper_value,
                     f"{r['outcomes'][p].value} ({r['outcomes'][p].verdict})",
                     f"{r['outcomes'][c].value} ({r['outcomes'][c].verdict})",
                     r["verdict"], r["reason"]] for r in rows]), ""]
    return lines


def _theory(cfg, data):
    """Results whose deflection leaves the range of the theory (|v|/L above THEORY_LIMIT)."""
    lim = F.THEORY_LIMIT
    rows = []
    for f in (2, 3, 4):
        for c in data.get(f, {}).get("curves", []):
            x = c.spec.eps * c.max_abs
            if math.isfinite(x) and x > lim:
                rows.append([f, c.spec.model, c.spec.approach, f"n = {c.spec.n_elements}, ms* = {c.spec.ms:g}, "
                             f"{c.spec.steps_per_rev} steps/rev", "transient" + (" (failed)" if not c.ok else ""),
                             num(c.max_abs), num(x, 3)])
    for f in (5, 6):
        groups = OrderedDict()
        for r in data.get(f, {}).get("rows", []):
            if r.get("beyond_theory") == "yes":
                key = (r["model"], r["approach"], r["eps"] if f == 6 else r["omega"], r["status"])
                groups.setdefault(key, []).append(r)
        for (m, ap, fixed, st), rr in groups.items():
            xkey = "omega" if f == 6 else "eps"
            where = (f"eps = {fixed:g}, Omega* = " if f == 6 else f"Omega* = {fixed:g}, eps = ") + \
                fd.ranges_text([r[xkey] for r in rr])
            top = max(rr, key=lambda r: r["deflection_over_L"])
            rows.append([f, m, ap, where, st, num(top["deflection_over_L"] / top["eps"]),
                         num(top["deflection_over_L"], 3)])
    for f in (7, 8):
        for r in data.get(f, {}).get("curves", []):
            if r.get("beyond_theory") == "yes":
                rows.append([f, r["model"], "A", f"ms* = {r['ms']:g}", r["status"],
                             num(r["deflection_over_L"] / r["eps"]), num(r["deflection_over_L"], 3)])
    lines = ["## Results beyond the range of the theory", "",
             f"The models assume small transverse deflections. A result is flagged when its largest "
             f"deflection |v| / L = eps max |v*| exceeds {lim:g} (steady or unstable orbit, envelope of a "
             "non-periodic response, or a transient's history up to its end or failure); the CSV files "
             "carry the same flag (columns deflection_over_L, beyond_theory) and the figures shade the "
             "region. Such numbers are outputs of the equations, not predictions of a real rod.", ""]
    if rows:
        lines += [table(["figure", "model", "approach", "cases", "status", "max |v*|", "max |v|/L"], rows), ""]
    else:
        lines += ["None: every computed deflection stays within the range.", ""]
    return lines


def findings_markdown(cfg, conv, refine, data, timings, total, files=(), missing=None,
                      bifurcations=None, bifurcations_missing=None):
    """The whole findings.md.  Deterministic for the same runs except the last section (Run:
    date and wall times).  bifurcations: the data of the bifurcations step (None: absent, for the
    reason bifurcations_missing)."""
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    figs = sorted(data)
    title = "Figures 2-8" if not missing else "Figures " + ", ".join(map(str, figs)) + \
        " of 2-8 (" + ", ".join(map(str, sorted(missing))) + " missing)"
    lines = [f"# Findings: {title} recomputed", "",
             f"Generated by `crankgen reproduce` (crankgen {__version__}, preset `{cfg.preset}`). "
             f"Figures in this report: {', '.join(map(str, figs)) or 'none'}. Every number below is "
             "computed from the runs recorded beside this file (one CSV per figure, convergence.csv, "
             "data/*.json); the statements and verdicts are generated from those numbers.", ""]
    lines += _missing_note(missing)
    lines += _claims(cfg, conv, data, missing)
    lines += _summary(cfg, conv, data)[:-1] + [RB.summary_line(bifurcations, bifurcations_missing), ""]
    lines += _theory(cfg, data)
    lines += _settings(cfg, total, files)
    lines += _convergence(cfg, conv, refine)
    lines += _ratios(cfg, data)
    lines += _threshold(cfg, data)
    lines += RB.section(cfg, bifurcations, bifurcations_missing)
    lines += _slopes(cfg, data)
    lines += _extensions(cfg, data)
    lines += _transients(cfg, data)
    lines += _disagreement(cfg, conv, data)
    lines += _failures(cfg, conv, data)
    lines += ["## Run", "", f"Written {now}. Wall time of each step when it was computed (a rerun "
              "keeps complete, current steps without recomputing them):", "",
              table(["step", "wall time (s)"], [[k, "n/a" if v is None else f"{v:.1f}"] for k, v in timings.items()]
                    + [["total", f"{total:.1f}"]]), "",
              "Files: " + ", ".join(f"`{f}`" for f in files) + ".", ""]
    return "\n".join(lines)
