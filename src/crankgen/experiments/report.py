"""findings.md: tables of numbers computed from the runs and plain statements generated from them.
This module assembles the document and writes its overview sections (claims, summary, results
beyond the theory, settings, cases without a stable state, run); report_figures.py writes the
sections of each figure's numbers."""

import datetime as _dt
import math
from collections import OrderedDict

import numpy as np

from .. import __version__
from ..analyses import theory
from . import figures as F
from . import claims
from . import findings as fd
from . import report_bifurcations as RB
from . import report_exact_rod as RX
from .config import APPROACHES, EXACT, MODELS
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
        g = groups.setdefault(key, dict(x=[], message=r["message"], env=[], diverged=[], growing=[],
                                        defl=[]))
        g["x"].append(r[xkey])
        note = r.get("envelope_note", "")
        if math.isfinite(r.get("envelope", math.nan)):
            g["env"].append(r["envelope"])
            if math.isfinite(r["envelope"] * r["eps"]):
                g["defl"].append(r["envelope"] * r["eps"])
        elif note.startswith("the transient from rest diverged") or note.startswith("the transient from rest failed"):
            g["diverged"].append(r[xkey])
        elif note.startswith("the transient from rest is still growing"):
            g["growing"].append(r[xkey])

    for r in conv["rows"]:
        add("convergence", dict(r), "n_elements")
    for f, xkey in ((5, "eps"), (6, "omega")):        # the exact rod's rows: its own section
        for r in data.get(f, {}).get("rows", []):
            if r["model"] != EXACT.key:
                add(str(f), r, xkey)
    for f in (7, 8):
        if f in data:
            for r in data[f]["curves"]:
                add(str(f), r, "omega")
    rows = []
    for (fig, model, ap, eps, ms, status), g in groups.items():
        xname = {"convergence": "n", "5": "eps", "6": "Omega*"}.get(fig, "Omega*")
        env = []
        if status == F.DIVERGED:
            env.append(f"none: the run from rest diverges ({theory.ILL_POSED})")
        if g["env"]:
            lo, hi = min(g["env"]), max(g["env"])
            env.append(f"the transient from rest settles at max |v*| {num(lo)}" + (f" to {num(hi)}" if hi != lo else ""))
        if g["defl"] and max(g["defl"]) > F.THEORY_LIMIT:
            env.append(f"up to |v|/L = {num(max(g['defl']), 3)}: beyond the theory")
        if g["diverged"]:
            ill = f" ({theory.ILL_POSED})" if theory.ill_posed(ap) else ""
            env.append(f"the transient from rest diverges{ill} at {xname} = {fd.ranges_text(g['diverged'])}")
        if g["growing"]:
            env.append(f"the transient from rest is still growing at {xname} = {fd.ranges_text(g['growing'])}")
        env = "; ".join(env)
        rows.append([fig, model, ap, "" if eps is None else f"{eps:g}", f"{ms:g}",
                     "diverged (ill-posed)" if status == F.DIVERGED else status,
                     f"{xname} = {fd.ranges_text(g['x'])}", _short(g["message"], 100), env])
    lines = ["## Cases without a stable periodic steady state", "",
             "Every such case is kept in the CSV tables (status, message) and marked in the figures "
             "(hollow o: an unstable periodic orbit; hollow triangle: the response of a transient from "
             "rest where there is no stable periodic state, a filled one at the top when it is off the "
             "scale; x at the bottom: the run from rest diverged, so there is no amplitude). Status "
             "'diverged (ill-posed)': the run of approach B from rest diverged; B's strain energy is "
             "unbounded below, so this is no instability and there is no amplitude (see 'Approach B "
             "is ill-posed'). Grouped by figure, model, approach and status; the reason is that of the "
             "first case of the group; 'response' is what a transient from zero initial conditions "
             "does (max |v*| over its last revolutions, or that it diverges).", ""]
    if rows:
        lines += [table(["figure", "model", "approach", "eps", "ms*", "status", "cases", "reason (first case)", "response"],
                        rows), ""]
    else:
        lines += ["None: every steady-state case reached a stable periodic state.", ""]
    return lines


def _ill_posed(cfg, conv, data):
    """Where the approaches whose strain energy is unbounded below diverged, counted from the runs."""
    lines = ["## Approach B is ill-posed (its strain energy is unbounded below)", "",
             "Approach B drops the quartic term (EA/8) v_x^4 from eq. (2). The membrane part of eq. (2) "
             "is a full square, (EA/2)(u_x + v_x^2/2)^2; without its quartic term it is (EA/2)(u_x^2 + "
             "u_x v_x^2), whose minimum over u_x, at u_x = -v_x^2/2, is -(EA/8) v_x^4: the strain "
             "energy of B is unbounded below in v_x (the audit derives it, section 1.1). The "
             "equations of B are therefore ill-posed: a motion can run off to ever larger deflections "
             "at ever lower energy. A B run from rest that diverges (Newton stops, residuals up to "
             "1e40) is this, not an instability of a periodic state: such cases are 'diverged "
             "(ill-posed)' in every table, marked x in the figures, and have no amplitude, no "
             "stability verdict and no place in a ratio; a claim that needs them is not computable "
             "there. Approaches A (a full square) and C (quadratic) have energies bounded below by "
             "zero" + ("; none of their runs failed." if not _diverged_other(conv, data) else
                       "; where one of their runs failed, the tables say 'failed', a numerical failure."),
             ""]
    rows = []

    def count(label, model, rr, xkey):
        name = {"omega": "Omega*", "n_elements": "n"}.get(xkey, xkey)
        div = [r for r in rr if r["status"] == F.DIVERGED]
        if div:
            rows.append([label, model, f"{len(div)} of {len(rr)}",
                         f"{name} = {fd.ranges_text([r[xkey] for r in div])}",
                         _short(min(div, key=lambda r: r[xkey])["message"], 90)])
        # an unstable orbit exists, but the transient from rest (its response) diverged
        env = [r for r in rr if r["status"] == "unstable"
               and r.get("envelope_note", "").startswith("the transient from rest diverged")]
        if env:
            rows.append([label + ": the transient from rest where the orbit is unstable", model,
                         f"{len(env)} of {len(rr)}", f"{name} = {fd.ranges_text([r[xkey] for r in env])}",
                         _short(env[0]["envelope_note"].rsplit("no amplitude): ", 1)[-1], 90)])
    for m in MODELS:
        for om in cfg.conv_omegas:
            count(f"convergence check, Omega* = {om:g}", m.key,
                  [r for r in conv["rows"] if r["model"] == m.key and r["approach"] == "B" and r["omega"] == om],
                  "n_elements")
        if 4 in data:
            cs = [c for c in data[4]["curves"] if c.spec.model == m.key and c.spec.approach == "B"]
            div = [c for c in cs if c.diverged]
            if div:
                rows.append([f"Figure 4 (transients, Omega* = {cfg.fig4_omega:g})", m.key, f"{len(div)} of {len(cs)}",
                             "ms* = " + ", ".join(f"{c.spec.ms:g}" for c in div),
                             _short(div[0].message, 90)])
        if 5 in data:
            for om in cfg.fig5_omegas:
                count(f"Figure 5, Omega* = {om:g}", m.key,
                      _rows(data[5], model=m.key, approach="B", omega=om), "eps")
        if 6 in data:
            for eps in cfg.fig6_eps:
                count(f"Figure 6, eps = {eps:g}", m.key, _rows(data[6], model=m.key, approach="B", eps=eps),
                      "omega")
    if rows:
        lines += ["Where approach B diverged in these runs:", "",
                  table(["where", "model", "diverged cases", "at", "first reason"], rows), ""]
    else:
        lines += ["No run of approach B diverged in these runs.", ""]
    far = [(r, r["envelope"] * r["eps"]) for f in (5, 6) for r in data.get(f, {}).get("rows", [])
           if r["approach"] == "B" and math.isfinite(r.get("envelope", math.nan))
           and r["envelope"] * r["eps"] > 1.0]
    if far:
        r, x = max(far, key=lambda t: t[1])
        lines += [f"Where B's transient from rest neither diverges nor finds the unstable orbit, it can "
                  f"settle far outside the range of the theory ({len(far)} case(s), up to |v|/L = "
                  f"{num(x, 3)}: {r['model']} model, eps = {r['eps']:g}, Omega* = {r['omega']:g}): a "
                  "response of the ill-posed equations, listed with the results beyond the theory, "
                  "not an amplitude of the mechanism.", ""]
    return lines


def _diverged_other(conv, data):
    """Whether a run of a bounded approach (A, C) diverged (it would be a numerical failure)."""
    rows = list(conv["rows"]) + [r for f in (5, 6) for r in data.get(f, {}).get("rows", [])]
    return any(r["status"] == "failed" for r in rows) or any(
        not c.ok for f in (2, 3, 4) for c in data.get(f, {}).get("curves", []) if not c.diverged)


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

                def ratio(ap):
                    if a[ap] and a[ap][0]["status"] == F.DIVERGED:
                        return "diverged (ill-posed)"
                    return num(fd.ratio(amp[ap], amp["A"]), 4)
                parts.append(f"{m.key}, Omega* = {om:g}: B/A {ratio('B')}, C/A {ratio('C')}")
        out.append(f"- Amplitude ratios at eps = {cfg.eps:g} (n/a: no stable periodic state; diverged: "
                   "the run from rest of the ill-posed approach B diverged, no amplitude): "
                   + "; ".join(parts) + ".")
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
                   "(or has no stable periodic state, or diverges, where A is stable): " + "; ".join(parts) + ".")
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
        worst, mism, mism_div = None, 0, 0
        p, c = MODELS[0].key, MODELS[1].key
        for ap in APPROACHES:
            for eps in cfg.fig6_eps:
                x, a, _ = _series(_rows(data[6], model=p, approach=ap, eps=eps), "omega")
                _, b, _ = _series(_rows(data[6], model=c, approach=ap, eps=eps), "omega")
                d = fd.max_relative_difference(x, b, a)
                if d and (worst is None or d["value"] > worst[0]["value"]):
                    worst = (d, ap, eps)
                rows_p, rows_c = (_rows(data[6], model=k, approach=ap, eps=eps) for k in (p, c))
                div = {r["omega"] for r in rows_p + rows_c if r["status"] == F.DIVERGED}
                one = [xx for xx, aa, bb in zip(x, a, b) if np.isfinite(aa) != np.isfinite(bb)]
                mism += len(one)
                mism_div += sum(xx in div for xx in one)
        if worst:
            d, ap, eps = worst
            out.append(f"- Paper model against consistent model (Figure 6): largest amplitude difference "
                       f"{pct(d['value'])} (approach {ap}, eps = {eps:g}, Omega* = {d['at']:g}); "
                       f"{mism} of the sweep's cases have a stable periodic state in one model only"
                       + (f" ({mism_div} of them where the other model's run diverged: approach B, "
                          "ill-posed)." if mism_div else "."))
    div = _divergence_summary(conv, data)
    if div:
        out.append(f"- Approach B is ill-posed (its strain energy is unbounded below); its runs from rest "
                   f"diverged in {div} (no amplitude, no stability verdict: see 'Approach B is ill-posed').")
    return out + [""]


def _divergence_summary(conv, data):
    parts = []
    for m in MODELS:
        n = sum(r["status"] == F.DIVERGED for r in conv["rows"] if r["model"] == m.key)
        for f in (5, 6):
            n += sum(r["status"] == F.DIVERGED or (theory.ill_posed(r["approach"]) and r.get(
                "envelope_note", "").startswith("the transient from rest diverged"))
                for r in data.get(f, {}).get("rows", []) if r["model"] == m.key)
        for f in (2, 3, 4):
            n += sum(c.diverged for c in data.get(f, {}).get("curves", []) if c.spec.model == m.key)
        if n:
            parts.append(f"{n} case(s) of the {m.key} model")
    return " and ".join(parts)


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
    """Results that leave the range of the theory (crankgen.analyses.theory: deflection or axial strain);
    a run that diverged has no result and is only counted."""
    rows, diverged = [], []

    def strain_cell(x):
        return num(x, 3) if x is not None and math.isfinite(x) else "n/a"
    for f in (2, 3, 4):
        for c in data.get(f, {}).get("curves", []):
            if not c.ok:
                diverged.append(f"Figure {f} {c.spec.model} {c.spec.approach} (ms* = {c.spec.ms:g})")
                continue
            x = c.spec.eps * c.max_abs
            growing = c.still_growing is not None
            if theory.beyond(x, c.max_strain) == "yes":
                rows.append([f, c.spec.model, c.spec.approach, f"n = {c.spec.n_elements}, ms* = {c.spec.ms:g}, "
                             f"{c.spec.steps_per_rev} steps/rev", "transient from rest (largest over the run"
                             + ("; still growing at its end)" if growing else ")"),
                             num(c.max_abs), num(x, 3), strain_cell(c.max_strain)])
    kinds = {STABLE: "periodic orbit", "unstable": "unstable periodic orbit",
             "not-periodic": "no periodic orbit: settled transient from rest"}
    for f in (5, 6):
        groups = OrderedDict()
        for r in data.get(f, {}).get("rows", []):
            fixed = r["eps"] if f == 6 else r["omega"]
            if r["status"] == F.DIVERGED or r["model"] == EXACT.key:   # the exact rod: its own limits
                continue
            if r.get("beyond_theory") == "yes":
                groups.setdefault((r["model"], r["approach"], fixed, kinds.get(r["status"], r["status"])), []).append(
                    (r, F.response_of(r), r.get("axial_strain", math.nan)))
            env = r.get("envelope", math.nan)
            if r["status"] == "unstable" and math.isfinite(env) and env * r["eps"] > F.THEORY_LIMIT:
                groups.setdefault((r["model"], r["approach"], fixed,
                                   "the transient from rest, where the orbit is unstable"), []).append(
                    (r, env, math.nan))
        for (m, ap, fixed, kind), rr in groups.items():
            xkey = "omega" if f == 6 else "eps"
            where = (f"eps = {fixed:g}, Omega* = " if f == 6 else f"Omega* = {fixed:g}, eps = ") + \
                fd.ranges_text([r[xkey] for r, _, _ in rr])
            top = max(rr, key=lambda t: t[1] * t[0]["eps"])
            strains = [e for _, _, e in rr if math.isfinite(e)]
            rows.append([f, m, ap, where, kind, num(top[1]), num(top[1] * top[0]["eps"], 3),
                         strain_cell(max(strains) if strains else math.nan)])
    for f in (7, 8):
        for r in data.get(f, {}).get("curves", []):
            if r.get("beyond_theory") == "yes":
                rows.append([f, r["model"], "A", f"ms* = {r['ms']:g}", kinds.get(r["status"], r["status"]),
                             num(F.response_of(r)), num(r["deflection_over_L"], 3),
                             strain_cell(r.get("axial_strain"))])
    lines = ["## Results beyond the range of the theory", "",
             f"The models assume moderate deflections and small strains. A result is flagged when "
             f"{theory.CRITERION} (the approach's own membrane strain u_x + v_x^2/2, or u_x for C, at "
             "the element ends and midpoints), for the response it stands for: a periodic or unstable "
             "orbit, the settled transient from rest of a non-periodic case, or a transient's whole "
             "history. The CSV files carry the same flag (columns deflection_over_L, axial_strain, "
             "beyond_theory) and the figures shade |v|/L > 0.1. Such numbers are outputs of the "
             "equations, not predictions of a real rod. Where an orbit is unstable, the transient "
             "from rest goes elsewhere; its response is a row of its own.", ""]
    if rows:
        lines += [table(["figure", "model", "approach", "cases", "response", "max |v*|", "max |v|/L",
                         "max axial strain"], rows), ""]
    else:
        lines += ["None: every computed deflection and strain stays within the range.", ""]
    if diverged:
        lines += ["Not listed, because they have no result: the runs that diverged (" +
                  "; ".join(diverged) + ") and every case of status 'diverged (ill-posed)' in the "
                  "tables; their histories up to the divergence are in the CSV files.", ""]
    return lines


def _figures_text(figs):
    """'Figure 5', 'Figures 2 and 3', 'Figures 2, 3 and 4'."""
    figs = [str(f) for f in figs]
    if len(figs) == 1:
        return f"Figure {figs[0]}"
    return "Figures " + ", ".join(figs[:-1]) + " and " + figs[-1]


def findings_markdown(cfg, conv, refine, data, timings, total, files=(), missing=None,
                      bifurcations=None, bifurcations_missing=None, engine=None, exact=None,
                      exact_missing=None):
    """The whole findings.md.  Deterministic for the same runs except the last section (Run:
    date and wall times).  bifurcations: the data of the bifurcations step (None: absent, for the
    reason bifurcations_missing); exact: the data of the exact rod step (None: absent, for the
    reason exact_missing)."""
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    figs = sorted(data)
    title = "Figures 2-8 recomputed" if not missing else (
        f"{_figures_text(figs) if figs else 'no figure'} recomputed ({_figures_text(sorted(missing))} "
        f"{'is' if len(missing) == 1 else 'are'} not in this report)")
    lines = [f"# Findings: {title}", "",
             f"Generated by `crankgen reproduce` (crankgen {__version__}, preset `{cfg.preset}`). "
             f"Figures in this report: {', '.join(map(str, figs)) or 'none'}. Every number below is "
             "computed from the runs recorded beside this file (one CSV per figure, convergence.csv, "
             "data/*.json); the statements and verdicts are generated from those numbers.", ""]
    lines += _missing_note(missing)
    lines += _claims(cfg, conv, data, missing)
    lines += _summary(cfg, conv, data)[:-1] + [RB.summary_line(bifurcations, bifurcations_missing),
                                               RX.summary_line(exact, exact_missing), ""]
    lines += _ill_posed(cfg, conv, data)
    lines += _theory(cfg, data)
    lines += _settings(cfg, total, files)
    lines += _convergence(cfg, conv, refine)
    lines += _ratios(cfg, data)
    lines += _threshold(cfg, data)
    lines += RB.section(cfg, bifurcations, bifurcations_missing)
    lines += RX.section(cfg, data, exact, exact_missing)
    lines += _slopes(cfg, data)
    lines += _extensions(cfg, data)
    lines += _transients(cfg, data)
    lines += _disagreement(cfg, conv, data)
    lines += _failures(cfg, conv, data)
    start = ([] if engine is None else
             [[("engine start-up in this run: compiling it for this machine (once)" if engine[1] else
                "engine start-up in this run: loading the compiled engine"), f"{engine[0]:.1f}"]])
    lines += ["## Run", "", f"Written {now}. Wall time of each step when it was computed (a rerun "
              "keeps complete, current steps without recomputing them); the start-up of the compiled "
              "engine is timed on its own, before the first step that needs it:", "",
              table(["step", "wall time (s)"], start + [[k, "n/a" if v is None else f"{v:.1f}"]
                                                         for k, v in timings.items()]
                    + [["total of the steps", f"{total:.1f}"]]), "",
              "Files: " + ", ".join(f"`{f}`" for f in files) + ".", ""]
    return "\n".join(lines)
