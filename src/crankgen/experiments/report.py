"""findings.md: tables of numbers computed from the runs and plain statements generated from them."""

import datetime as _dt
import math
from collections import OrderedDict

import numpy as np

from .. import __version__
from . import figures as F
from . import claims
from . import findings as fd
from .config import APPROACHES, MODELS

STABLE = "periodic"


# ----------------------------------------------------------------------------- formatting

def num(x, digits=4):
    if x is None:
        return "n/a"
    try:
        x = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(x):
        return "n/a"
    return f"{x:.{digits}g}"


def pct(x, digits=3):
    if x is None or not math.isfinite(float(x)):
        return "n/a"
    return f"{100 * float(x):.{digits}g} %"


def _cell(c):
    return " ".join(str(c).split()).replace("|", "\\|")


def table(headers, rows):
    out = ["| " + " | ".join(_cell(h) for h in headers) + " |", "|" + "---|" * len(headers)]
    for r in rows:
        out.append("| " + " | ".join(_cell(c) for c in r) + " |")
    return "\n".join(out)


def _short(message, limit=110):
    message = " ".join(str(message).split())
    return message if len(message) <= limit else message[: limit - 3] + "..."


def _mlabel(key):
    return next(m for m in MODELS if m.key == key).key


def _rows(data, **match):
    return [r for r in data["rows"] if all(r[k] == v for k, v in match.items())]


def _series(rows, xkey, ykey="amplitude"):
    rows = sorted(rows, key=lambda r: r[xkey])
    return (np.array([r[xkey] for r in rows], dtype=float),
            np.array([r[ykey] for r in rows], dtype=float), rows)


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
                 ["Figures 7, 8", f"Omega* = {cfg.fig7_omega:g}, {cfg.fig8_omega:g}; ms* = {', '.join(f'{m:g}' for m in cfg.ext_ms)}; approach A"],
                 ["steady state", "periodic orbit with the crank period (shooting); amplitude = max |v*(1/2)| over the steady revolution"],
                 ["cases without a stable periodic state", (f"transient of {cfg.envelope_revolutions} revolutions from zero initial conditions, max |v*| over the last {cfg.envelope_window}" if cfg.envelope_revolutions > 0 else "no transient computed")],
                 ["steady_states options", ", ".join(f"{k} = {v}" for k, v in cfg.steady_options.items()) or "defaults"],
             ]), "",
             "Models (every figure is computed for both):", "",
             table(["model", "formulation", "damping", "membrane", "description"],
                   [[m.key, m.formulation, m.damping, m.membrane, m.label] for m in MODELS]), ""]
    return lines


def _convergence(cfg, conv, refine):
    counts, series = conv["counts"], conv["series"]
    ladder = list(cfg.conv_ladder)
    lines = ["## Element counts (convergence check)", "",
             f"Steady amplitude max |v*| at eps = {cfg.eps:g} on the element ladder; a series stops "
             f"once two successive counts agree to {pct(cfg.conv_tol)} (the count is then the "
             "smaller of the two). A model uses, for each approach, the largest count required at "
             "the checked speeds and never fewer than the paper's count.", ""]
    rows = []
    for m in MODELS:
        for ap in APPROACHES:
            for om in cfg.conv_omegas:
                s = series[(m.key, ap, om)]
                byn = dict(zip(s["ns"], s["amplitudes"]))
                st = {r["n_elements"]: r["status"] for r in conv["rows"]
                      if r["model"] == m.key and r["approach"] == ap and r["omega"] == om}
                cells = [num(byn[n], 6) if n in byn and math.isfinite(byn[n]) else (st.get(n, "") if n in byn else "")
                         for n in ladder]
                rows.append([m.key, ap, f"{om:g}", *cells, s["n"] if s["kind"] == "converged" else s["kind"]])
    lines += [table(["model", "approach", "Omega*", *[f"n = {n}" for n in ladder], "converged n"], rows), ""]
    lines += [table(["model", "approach", "count used", "basis"],
                    [[m.key, ap, counts[(m.key, ap)], conv["notes"][(m.key, ap)]]
                     for m in MODELS for ap in APPROACHES]), ""]
    # statements
    om_ref = cfg.fig3_omega if cfg.fig3_omega in cfg.conv_omegas else cfg.conv_omegas[-1]
    for m in MODELS:
        s = series[(m.key, "A", om_ref)]
        if s["kind"] == "converged":
            txt = f"converges to {pct(cfg.conv_tol)} at n = {s['n']} elements"
        elif s["kind"] == "not-converged":
            txt = f"is {s['note']}"
        else:
            txt = f"could not be checked ({_short(s['note'], 90)})"
        lines.append(f"- Approach A at Omega* = {om_ref:g}, {m.key} model: {txt}.")
    for m in MODELS:
        enough, short = [], []
        for ap in APPROACHES:
            need = [series[(m.key, ap, om)] for om in cfg.conv_omegas]
            req = [s["n"] for s in need if s["kind"] == "converged"]
            unconv = [s for s in need if s["kind"] == "not-converged"]
            paper_n = cfg.paper_elements[ap]
            if unconv:
                short.append(f"{ap} (paper {paper_n}; not converged up to n = {unconv[0]['n']})")
            elif req and max(req) > paper_n:
                short.append(f"{ap} (paper {paper_n}, needs {max(req)})")
            elif req:
                enough.append(f"{ap} (paper {paper_n}, needs {max(req)})")
        txt = f"- {m.key} model: the paper's counts are sufficient for " + (", ".join(enough) or "none")
        txt += "; insufficient for " + (", ".join(short) or "none") + "."
        lines.append(txt)
    lines.append("")
    if refine is not None and refine["rows"]:
        rr = refine["rows"]
        lines += ["Refinement check: cases of Figures 5 and 6 away from the checked speed and eps, "
                  "recomputed with twice the count used.", "",
                  table(["model", "approach", "eps", "Omega*", "n", "max |v*|", "2 n", "max |v*| (2 n)", "change"],
                        [[r["model"], r["approach"], f"{r['eps']:g}", f"{r['omega']:g}", r["n_elements"],
                          num(r["amplitude"], 6) if math.isfinite(r["amplitude"]) else r["status"],
                          r["n_refined"],
                          num(r["amplitude_refined"], 6) if math.isfinite(r["amplitude_refined"]) else r["status_refined"],
                          pct(r["change"])] for r in rr]), ""]
        for m in MODELS:
            ch = [(r["change"], r) for r in rr if r["model"] == m.key and math.isfinite(r["change"])]
            mism = [r for r in rr if r["model"] == m.key and r["status"] != r["status_refined"]]
            if ch:
                c, r = max(ch, key=lambda t: t[0])
                verdict = "within" if c < cfg.conv_tol else "NOT within"
                lines.append(f"- {m.key} model: the largest change on doubling n is {pct(c)} "
                             f"({r['approach']}, eps = {r['eps']:g}, Omega* = {r['omega']:g}): "
                             f"{verdict} the {pct(cfg.conv_tol)} tolerance.")
            else:
                lines.append(f"- {m.key} model: no refinement pair with two periodic states.")
            if mism:
                lines.append(f"  Status changes on doubling n: " + "; ".join(
                    f"{r['approach']} eps = {r['eps']:g} Omega* = {r['omega']:g}: {r['status']} -> {r['status_refined']}"
                    for r in mism) + ".")
        lines.append("")
    return lines


def _transient_note(c):
    """Failure, deflection beyond the theory, and growth over the last two revolutions."""
    notes = []
    if not c.ok:
        notes.append(f"failed at t* = {num(c.fail_time)} (history up to there kept): {_short(c.message, 80)}")
    x = c.spec.eps * c.max_abs
    if math.isfinite(x) and x > F.THEORY_LIMIT:
        notes.append(f"beyond the theory: |v|/L up to {num(x, 3)}")
    k = c.spec.steps_per_rev
    if c.ok and c.has_history and len(c.v_mid) > 2 * k:
        last, before = np.max(np.abs(c.v_mid[-k:])), np.max(np.abs(c.v_mid[-2 * k:-k]))
        if last > 1.05 * before:
            notes.append(f"still growing: max |v*| {num(before)} then {num(last)} over the last two revolutions")
    return "; ".join(notes)


def _transients(cfg, data):
    lines = []
    titles = {2: f"Figure 2: transient v* at Omega* = {cfg.fig2_omega:g}",
              3: f"Figure 3: convergence of approach A at Omega* = {cfg.fig3_omega:g}",
              4: f"Figure 4: transient v* at Omega* = {cfg.fig4_omega:g}"}
    for f in (2, 3, 4):
        if f not in data:
            continue
        curves = data[f]["curves"]
        lines += [f"## {titles[f]}", "",
                  table(["model", "approach", "n", "steps/rev", "ms*", "status", "max |v*|", "note"],
                        [[c.spec.model, c.spec.approach, c.spec.n_elements, c.spec.steps_per_rev,
                          f"{c.spec.ms:g}", c.status, num(c.max_abs), _transient_note(c)]
                         for c in curves]), ""]
        if f == 3:
            for m in MODELS:
                cs = [c for c in curves if c.spec.model == m.key]
                base = [c for c in cs if c.spec.steps_per_rev == cfg.fig3_steps[0]]
                if not base:
                    continue
                ref = base[-1]
                diffs = [(c.spec.n_elements, F.transient_difference(c, ref)) for c in base[:-1]]
                txt = ", ".join(f"n = {n}: {pct(d)}" for n, d in diffs if d is not None)
                lines.append(f"- {m.key} model: max |v*(t) - v*_ref(t)| / max |v*_ref| against "
                             f"n = {ref.spec.n_elements}: {txt or 'n/a'}.")
                for c in cs:
                    if c.spec.steps_per_rev != cfg.fig3_steps[0] and c.spec.n_elements == ref.spec.n_elements:
                        d = F.transient_difference(ref, c)
                        lines.append(f"  Time step: {ref.spec.steps_per_rev} against {c.spec.steps_per_rev} "
                                     f"steps per revolution at n = {c.spec.n_elements} differ by {pct(d)} "
                                     "(same measure).")
            lines.append("")
        failed = [c for c in curves if not c.ok]
        for c in failed:
            lines.append(f"- {c.spec.model} model, approach {c.spec.approach} (n = {c.spec.n_elements}, "
                         f"ms* = {c.spec.ms:g}) diverges: the integration fails at t* = {num(c.fail_time)} "
                         f"({_short(c.message, 90)}).")
        if failed:
            lines.append("")
    return lines


def _ratios(cfg, data):
    lines = []
    if 5 in data:
        rows = []
        for m in MODELS:
            for om in cfg.fig5_omegas:
                amp = {ap: _rows(data[5], model=m.key, omega=om, eps=cfg.eps, approach=ap) for ap in APPROACHES}
                a = {ap: (amp[ap][0]["amplitude"] if amp[ap] else math.nan) for ap in APPROACHES}
                st = {ap: (amp[ap][0]["status"] if amp[ap] else "missing") for ap in APPROACHES}
                rb, rc = fd.ratio(a["B"], a["A"]), fd.ratio(a["C"], a["A"])
                rows.append([m.key, f"{om:g}", *(num(a[ap], 5) if math.isfinite(a[ap]) else st[ap] for ap in APPROACHES),
                             num(rb, 5), num(rc, 5)])
        lines += [f"## Ratios of the B and C amplitudes to A (eps = {cfg.eps:g}, from Figure 5)", "",
                  table(["model", "Omega*", "A: max |v*|", "B", "C", "B/A", "C/A"], rows), ""]
        for r in rows:
            rb, rc = r[5], r[6]
            verdicts = []
            for name, v in (("B", rb), ("C", rc)):
                try:
                    x = float(v)
                    verdicts.append(f"{name}/A = {v} ({'within' if abs(x - 1) <= cfg.differ_threshold else 'beyond'} "
                                    f"{pct(cfg.differ_threshold)})")
                except ValueError:
                    verdicts.append(f"{name}/A not available ({name} has no stable periodic state)")
            lines.append(f"- {r[0]} model, Omega* = {r[1]}: " + "; ".join(verdicts) + ".")
        lines.append("")
    if 6 in data:
        for eps in cfg.fig6_eps:
            head, rows = ["Omega*"], []
            for m in MODELS:
                head += [f"{m.key} A", f"{m.key} B/A", f"{m.key} C/A"]
            for om in cfg.fig6_omegas:
                row = [f"{om:g}"]
                for m in MODELS:
                    cell = {}
                    for ap in APPROACHES:
                        rr = _rows(data[6], model=m.key, omega=om, eps=eps, approach=ap)
                        cell[ap] = rr[0] if rr else None
                    a = cell["A"]
                    row.append(num(a["amplitude"]) if a and a["status"] == STABLE else (a["status"] if a else ""))
                    for ap in ("B", "C"):
                        c = cell[ap]
                        row.append(num(c["ratio_to_A"]) if c and math.isfinite(c["ratio_to_A"])
                                   else (c["status"] if c and c["status"] != STABLE else "n/a"))
                rows.append(row)
            lines += [f"### Amplitude ratios against Omega* (Figure 6, eps = {eps:g})", "",
                      table(head, rows), ""]
    return lines


def _threshold(cfg, data):
    if 6 not in data:
        return []
    thr = cfg.differ_threshold
    rows, lines = [], []
    for m in MODELS:
        for eps in cfg.fig6_eps:
            res = {}
            for ap in ("B", "C"):
                x, d, rr = _series(_rows(data[6], model=m.key, eps=eps, approach=ap), "omega", "ratio_to_A")
                cross = fd.first_exceedance(x, np.abs(d - 1.0), thr)
                a_rows = {r["omega"]: r for r in _rows(data[6], model=m.key, eps=eps, approach="A")}
                lost = fd.first_where(x, [r["status"] != STABLE and a_rows.get(r["omega"], {}).get("status") == STABLE
                                          for r in rr])
                res[ap] = (cross, lost)
            cands = [v for ap in ("B", "C") for v in res[ap] if v is not None]
            first = min(cands) if cands else None
            rows.append([m.key, f"{eps:g}",
                         *(num(res[ap][0]) if res[ap][0] is not None else "none" for ap in ("B", "C")),
                         *(num(res[ap][1]) if res[ap][1] is not None else "none" for ap in ("B", "C")),
                         num(first) if first is not None else "none"])
            start = min(cfg.fig6_omegas)
            for ap in ("B", "C"):
                cross, lost = res[ap]
                if cross is not None:
                    where = (f"already at the lowest speed of the sweep (Omega* = {start:g})"
                             if cross == start else f"from Omega* = {num(cross)} (interpolated)")
                    lines.append(f"- {m.key} model, eps = {eps:g}: {ap} differs from A by more than "
                                 f"{pct(thr)} {where}.")
                else:
                    lines.append(f"- {m.key} model, eps = {eps:g}: where both have stable periodic states, "
                                 f"{ap} stays within {pct(thr)} of A over the sweep.")
                if lost is not None:
                    lines.append(f"  {ap} has no stable periodic state (while A does) from Omega* = {num(lost)}.")
    head = ["model", "eps", f"B: |B/A - 1| > {pct(thr)} from", f"C: > {pct(thr)} from",
            "B: no stable state from", "C: no stable state from", "lowest speed (B or C)"]
    return (["## Lowest speed at which B or C differs from A (Figure 6)", "",
             f"Crossings of |ratio - 1| = {pct(thr)} are interpolated linearly between sweep points "
             f"(step {num(np.min(np.diff(sorted(cfg.fig6_omegas)))) if len(cfg.fig6_omegas) > 1 else 'n/a'}); "
             "speeds where B or C has no stable periodic state but A has are listed separately and "
             "count as a difference in the last column.", "",
             table(head, rows), ""] + lines + [""])


def _slopes(cfg, data):
    if 5 not in data:
        return []
    rows, fits = [], {}
    for m in MODELS:
        for ap in APPROACHES:
            for om in cfg.fig5_omegas:
                x, y, _ = _series(_rows(data[5], model=m.key, approach=ap, omega=om), "eps")
                f = fd.loglog_slope(x, y)
                fits[(m.key, ap, om)] = f
                rows.append([m.key, ap, f"{om:g}", num(f["slope"]) if f else "n/a",
                             f["points"] if f else 0, num(f["max_residual"], 2) if f else "n/a"])
    lines = ["## Slope of log v* against log eps (Figure 5)", "",
             "Least-squares fit of log(max |v*|) against log(eps) over the stable periodic points; "
             "'max residual' is the largest deviation from the fitted power law in log v*.", "",
             table(["model", "approach", "Omega*", "slope", "points", "max residual"], rows), ""]
    for m in MODELS:
        for om in cfg.fig5_omegas:
            f = fits[(m.key, "A", om)]
            if f:
                lines.append(f"- {m.key} model, Omega* = {om:g}: approach A gives v* ~ eps^{f['slope']:.3g} "
                             f"(power law {'holds' if f['max_residual'] < 0.05 else 'holds only roughly'}: "
                             f"max residual {f['max_residual']:.2g} in log v*).")
    lines.append("")
    return lines


def _extensions(cfg, data):
    figs = [f for f in (7, 8) if f in data]
    if not figs:
        return []
    zeros = fd.slider_acceleration_zeros(cfg.a)
    rows, lines = [], []
    crossings = {}
    for f in figs:
        for m in MODELS:
            xs = F.extension_crossings_of(data[f], m.key, cfg.crossing_rel_tol)
            crossings[(f, m.key)] = xs
            used = [f"{c['ms']:g}" for c in data[f]["curves"] if c["model"] == m.key and c["status"] == STABLE]
            if xs is None:
                rows.append([f, m.key, f"{data[f]['omega']:g}", ", ".join(used) or "none",
                             "fewer than two stable curves", ""])
            else:
                rows.append([f, m.key, f"{data[f]['omega']:g}", ", ".join(used),
                             ", ".join(f"{x['angle']:.1f}" for x in xs) or "none",
                             ", ".join(pct(x["relative_spread"], 2) for x in xs)])
    lines += ["## Crank angles where the extension does not depend on the slider mass (Figures 7, 8)", "",
              f"Angles where the spread of delta* across ms* = {', '.join(f'{m:g}' for m in cfg.ext_ms)} "
              f"has a local minimum below {pct(cfg.crossing_rel_tol)} of its largest value over the "
              "revolution (curves interpolated linearly, 0.01 degree resolution). For reference, the "
              f"rigid mechanism's slider acceleration vanishes at {', '.join(f'{z:.1f}' for z in zeros)} degrees.", "",
              table(["figure", "model", "Omega*", "ms* of the stable curves", "crossing angles (degrees)",
                     "spread there / largest spread"], rows), ""]
    for (f, mk), xs in crossings.items():
        if xs is not None and not xs:
            cs = [c for c in data[f]["curves"] if c["model"] == mk and c["status"] == STABLE]
            minima = fd.extension_crossings(cs[0]["theta_deg"], np.stack([c["extension"] for c in cs]),
                                            rel_tol=1.0)
            if minima:
                best = min(minima, key=lambda x: x["relative_spread"])
                lines.append(f"- Figure {f}, {mk} model (Omega* = {data[f]['omega']:g}): the stable curves "
                             f"have no common crossing; their spread comes closest to zero at "
                             f"{best['angle']:.1f} deg, where it is still {pct(best['relative_spread'], 2)} "
                             "of its largest value.")
            continue
        if not xs:
            continue
        near = []
        for x in xs:
            dz = min(abs((x["angle"] - z + 180) % 360 - 180) for z in zeros) if zeros else math.nan
            near.append(f"{x['angle']:.1f} deg ({dz:.1f} deg from a zero of the rigid slider acceleration)")
        lines.append(f"- Figure {f}, {mk} model (Omega* = {data[f]['omega']:g}): the curves for all slider "
                     f"masses cross at " + "; ".join(near) + ".")
    lines.append("")
    return lines


def _disagreement(cfg, conv, data):
    tol = cfg.agree_tol
    rows, lines = [], []
    p, c = MODELS[0].key, MODELS[1].key
    for ap in APPROACHES:
        rows.append([f"element count used, approach {ap}", conv["counts"][(p, ap)],
                     conv["counts"][(c, ap)], ""])

    def compare(label, x, a, b, xname):
        d = fd.max_relative_difference(x, b, a)
        onlyp = [xx for xx, aa, bb in zip(x, a, b) if math.isfinite(aa) and not math.isfinite(bb)]
        onlyc = [xx for xx, aa, bb in zip(x, a, b) if math.isfinite(bb) and not math.isfinite(aa)]
        note = []
        if onlyp:
            note.append(f"stable in {p} only at {xname} = {fd.ranges_text(onlyp)}")
        if onlyc:
            note.append(f"stable in {c} only at {xname} = {fd.ranges_text(onlyc)}")
        diff = (f"max {pct(d['value'])} at {xname} = {d['at']:g} ({d['points']} points)" if d else "no common points")
        rows.append([label, "", "", diff + ("; " + "; ".join(note) if note else "")])
        if d:
            verdict = (f"agree within {pct(tol)}" if d["value"] < tol else
                       f"differ by up to {pct(d['value'])} (at {xname} = {d['at']:g})")
            lines.append(f"- {label}: the models {verdict}" + ("; " + "; ".join(note) if note else "") + ".")
        elif note:
            lines.append(f"- {label}: " + "; ".join(note) + ".")

    if 4 in data:
        for ap in APPROACHES:
            cp = [x for x in data[4]["curves"] if x.spec.model == p and x.spec.approach == ap and x.spec.ms == cfg.ms]
            cc = [x for x in data[4]["curves"] if x.spec.model == c and x.spec.approach == ap and x.spec.ms == cfg.ms]
            if cp and cc:
                a, b = cp[0].max_abs, cc[0].max_abs
                rows.append([f"Figure 4 max |v*| (transient), {ap}", num(a) if cp[0].ok else "failed",
                             num(b) if cc[0].ok else f"failed at t* = {num(cc[0].fail_time)}",
                             pct(fd.relative_difference(b, a)) if cp[0].ok and cc[0].ok else "one model diverges"])
    if 5 in data:
        for ap in APPROACHES:
            for om in cfg.fig5_omegas:
                x, a, _ = _series(_rows(data[5], model=p, approach=ap, omega=om), "eps")
                _, b, _ = _series(_rows(data[5], model=c, approach=ap, omega=om), "eps")
                compare(f"Figure 5 amplitude, {ap}, Omega* = {om:g}", x, a, b, "eps")
        for ap in APPROACHES:
            for om in cfg.fig5_omegas:
                x, a, _ = _series(_rows(data[5], model=p, approach=ap, omega=om), "eps")
                _, b, _ = _series(_rows(data[5], model=c, approach=ap, omega=om), "eps")
                fa, fb = fd.loglog_slope(x, a), fd.loglog_slope(x, b)
                if fa and fb:
                    rows.append([f"Figure 5 slope, {ap}, Omega* = {om:g}", num(fa["slope"]), num(fb["slope"]),
                                 num(fb["slope"] - fa["slope"], 3)])
    if 6 in data:
        for ap in APPROACHES:
            for eps in cfg.fig6_eps:
                x, a, _ = _series(_rows(data[6], model=p, approach=ap, eps=eps), "omega")
                _, b, _ = _series(_rows(data[6], model=c, approach=ap, eps=eps), "omega")
                compare(f"Figure 6 amplitude, {ap}, eps = {eps:g}", x, a, b, "Omega*")
    for f in (7, 8):
        if f not in data:
            continue
        cp = {r["ms"]: r for r in data[f]["curves"] if r["model"] == p and r["status"] == STABLE}
        cc = {r["ms"]: r for r in data[f]["curves"] if r["model"] == c and r["status"] == STABLE}
        common = sorted(set(cp) & set(cc))
        if common:
            rng = max(np.ptp(cp[m]["extension"]) for m in common)
            dmax = max(fd.max_abs_difference(cp[m]["extension"], cc[m]["extension"]) for m in common)
            rel = dmax / rng if rng > 0 else math.nan
            rows.append([f"Figure {f} extension delta*", f"range {num(rng)}", "",
                         f"max |difference| {num(dmax)} = {pct(rel)} of the paper model's range"])
            lines.append(f"- Figure {f} extension: the models " +
                         (f"agree within {pct(tol)} of the range" if rel < tol else
                          f"differ by up to {pct(rel)} of the range of delta*") + ".")
        xp = F.extension_crossings_of(data[f], p, cfg.crossing_rel_tol) or []
        xc = F.extension_crossings_of(data[f], c, cfg.crossing_rel_tol) or []
        if xp or xc:
            shifts = [min(abs((a["angle"] - b["angle"] + 180) % 360 - 180) for b in xc) for a in xp] if xc else []
            rows.append([f"Figure {f} crossing angles (deg)", ", ".join(f"{x['angle']:.1f}" for x in xp) or "none",
                         ", ".join(f"{x['angle']:.1f}" for x in xc) or "none",
                         f"max shift {max(shifts):.2f} deg" if shifts else "not comparable"])
    return (["## Where the paper model and the consistent model disagree", "",
             f"Differences are relative to the paper model; 'agree' means within {pct(tol)}.", "",
             table(["quantity", p, c, "difference"], rows), ""] + lines + [""])


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


def findings_markdown(cfg, conv, refine, data, timings, total, files=(), missing=None):
    """The whole findings.md.  Deterministic for the same runs except the last section (Run:
    date and wall times)."""
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
    lines += _summary(cfg, conv, data)
    lines += _theory(cfg, data)
    lines += _settings(cfg, total, files)
    lines += _convergence(cfg, conv, refine)
    lines += _ratios(cfg, data)
    lines += _threshold(cfg, data)
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
