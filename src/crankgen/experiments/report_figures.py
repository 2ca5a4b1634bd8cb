"""findings.md, the sections of the figures' numbers: element counts and the refinement check,
transients (Figures 2-4), amplitude ratios and the speed where B or C departs from A (Figures 5, 6),
log-log slopes, extension crossings (Figures 7, 8), and where the two models disagree."""

import math

import numpy as np

from . import figures as F
from . import findings as fd
from .config import APPROACHES, MODELS
from .markdown import num, pct, table
from .markdown import rows_where as _rows, series as _series, short as _short

STABLE = "periodic"
KIND_WORDS = {"not-converged": "not converged", "no-result": "no periodic state",
              "diverged": "diverged (ill-posed)"}


def _status_word(status):
    """A status as a table cell: a run of an ill-posed approach that failed 'diverged (ill-posed)'."""
    return "diverged (ill-posed)" if status == F.DIVERGED else status


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
                cells = [num(byn[n], 6) if n in byn and math.isfinite(byn[n])
                         else (_status_word(st.get(n, "")) if n in byn else "") for n in ladder]
                rows.append([m.key, ap, f"{om:g}", *cells,
                             s["n"] if s["kind"] == "converged" else KIND_WORDS[s["kind"]]])
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
                          num(r["amplitude"], 6) if math.isfinite(r["amplitude"]) else _status_word(r["status"]),
                          r["n_refined"],
                          num(r["amplitude_refined"], 6) if math.isfinite(r["amplitude_refined"])
                          else _status_word(r["status_refined"]),
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
                lines.append("  Status changes on doubling n: " + "; ".join(
                    f"{r['approach']} eps = {r['eps']:g} Omega* = {r['omega']:g}: {r['status']} -> {r['status_refined']}"
                    for r in mism) + ".")
        lines.append("")
    return lines


def _transient_note(c):
    """Failure, deflection beyond the theory, and growth over the last two revolutions."""
    notes = []
    if c.diverged:
        notes.append(f"diverged at t* = {num(c.fail_time)} ({F.theory.ILL_POSED}; history up to there "
                     f"kept, no amplitude): {_short(c.message, 80)}")
    elif not c.ok:
        notes.append(f"failed at t* = {num(c.fail_time)} (history up to there kept): {_short(c.message, 80)}")
    x = c.spec.eps * c.max_abs
    if c.ok:
        why = F.theory.reasons(x, c.max_strain)
        if why:
            notes.append(f"beyond the theory: {why}")
    if c.ok and c.still_growing is not None:
        before, last = c.still_growing
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
                  table(["model", "approach", "n", "steps/rev", "ms*", "status", "max |v*|",
                         "max axial strain", "note"],
                        [[c.spec.model, c.spec.approach, c.spec.n_elements, c.spec.steps_per_rev,
                          f"{c.spec.ms:g}", _status_word(c.status),
                          num(c.max_abs) if c.ok else "none (no amplitude)",
                          num(c.max_strain, 3) if c.ok else "", _transient_note(c)]
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
            why = (f"; approach {c.spec.approach} is ill-posed (strain energy unbounded below), so this "
                   "is no instability and its numbers before the failure are no amplitude"
                   if c.diverged else "")
            lines.append(f"- {c.spec.model} model, approach {c.spec.approach} (n = {c.spec.n_elements}, "
                         f"ms* = {c.spec.ms:g}) {'diverges' if c.diverged else 'fails'}: the integration "
                         f"stops at t* = {num(c.fail_time)} ({_short(c.message, 90)}){why}.")
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
                rows.append([m.key, f"{om:g}", *(num(a[ap], 5) if math.isfinite(a[ap]) else _status_word(st[ap])
                                                   for ap in APPROACHES),
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
                    why = ("diverged: ill-posed, no amplitude" if "diverged" in str(r[3 if name == "B" else 4])
                           else "no stable periodic state")
                    verdicts.append(f"{name}/A not available ({name}: {why})")
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
                    row.append(num(a["amplitude"]) if a and a["status"] == STABLE
                               else (_status_word(a["status"]) if a else ""))
                    for ap in ("B", "C"):
                        c = cell[ap]
                        row.append(num(c["ratio_to_A"]) if c and math.isfinite(c["ratio_to_A"])
                                   else (_status_word(c["status"]) if c and c["status"] != STABLE else "n/a"))
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
                a_ok = [a_rows.get(r["omega"], {}).get("status") == STABLE for r in rr]
                lost = fd.first_where(x, [r["status"] not in (STABLE, F.DIVERGED) and ok
                                          for r, ok in zip(rr, a_ok)])
                div = fd.first_where(x, [r["status"] == F.DIVERGED and ok for r, ok in zip(rr, a_ok)])
                count = sum(r["status"] == F.DIVERGED for r in rr)
                res[ap] = (cross, lost, div, count, len(rr))
            cands = [v for ap in ("B", "C") for v in res[ap][:3] if v is not None]
            first = min(cands) if cands else None
            rows.append([m.key, f"{eps:g}",
                         *(num(res[ap][0]) if res[ap][0] is not None else "none" for ap in ("B", "C")),
                         *(num(res[ap][1]) if res[ap][1] is not None else "none" for ap in ("B", "C")),
                         *(f"{num(res[ap][2])} ({res[ap][3]} of {res[ap][4]} speeds)" if res[ap][2] is not None
                           else "none" for ap in ("B", "C")),
                         num(first) if first is not None else "none"])
            start = min(cfg.fig6_omegas)
            for ap in ("B", "C"):
                cross, lost, div, count, total = res[ap]
                if cross is not None:
                    where = (f"already at the lowest speed of the sweep (Omega* = {start:g})"
                             if cross == start else f"from Omega* = {num(cross)} (interpolated)")
                    lines.append(f"- {m.key} model, eps = {eps:g}: {ap} differs from A by more than "
                                 f"{pct(thr)} {where}.")
                else:
                    lines.append(f"- {m.key} model, eps = {eps:g}: where both have stable periodic states, "
                                 f"{ap} stays within {pct(thr)} of A over the sweep.")
                if lost is not None:
                    lines.append(f"  {ap} has no stable periodic state (an unstable orbit or no periodic "
                                 f"one, while A is stable) from Omega* = {num(lost)}.")
                if div is not None:
                    lines.append(f"  {ap} diverges from rest from Omega* = {num(div)} ({count} of {total} "
                                 f"speeds): approach {ap} is ill-posed (strain energy unbounded below), so "
                                 "these runs give neither an amplitude nor a stability verdict.")
    head = ["model", "eps", f"B: |B/A - 1| > {pct(thr)} from", f"C: > {pct(thr)} from",
            "B: unstable / not periodic from", "C: unstable / not periodic from",
            "B: diverges (ill-posed) from", "C: diverges from", "lowest speed (B or C)"]
    return (["## Lowest speed at which B or C differs from A (Figure 6)", "",
             f"Crossings of |ratio - 1| = {pct(thr)} are interpolated linearly between sweep points "
             f"(step {num(np.min(np.diff(sorted(cfg.fig6_omegas)))) if len(cfg.fig6_omegas) > 1 else 'n/a'}); "
             "speeds where A is stable and B or C is not are listed separately, those where B or C "
             "has an unstable orbit or no periodic one apart from those where its run from rest "
             "diverges (an ill-posed approach: no result at all). Each counts as a departure from A "
             "in the last column.", "",
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
    xname_key = {"eps": "eps", "Omega*": "omega"}
    for ap in APPROACHES:
        rows.append([f"element count used, approach {ap}", conv["counts"][(p, ap)],
                     conv["counts"][(c, ap)], ""])

    def compare(label, x, a, b, xname, ra=(), rb=()):
        d = fd.max_relative_difference(x, b, a)
        div = {p: [r[xname_key[xname]] for r in ra if r["status"] == F.DIVERGED],
               c: [r[xname_key[xname]] for r in rb if r["status"] == F.DIVERGED]}
        onlyp = [xx for xx, aa, bb in zip(x, a, b) if math.isfinite(aa) and not math.isfinite(bb)
                 and xx not in div[c]]
        onlyc = [xx for xx, aa, bb in zip(x, a, b) if math.isfinite(bb) and not math.isfinite(aa)
                 and xx not in div[p]]
        note = []
        if onlyp:
            note.append(f"stable in {p} only at {xname} = {fd.ranges_text(onlyp)}")
        if onlyc:
            note.append(f"stable in {c} only at {xname} = {fd.ranges_text(onlyc)}")
        for k, xs in div.items():
            if xs:
                note.append(f"{k} diverges (ill-posed, no amplitude) at {xname} = {fd.ranges_text(xs)}")
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
                def cell(x, v):
                    return num(v) if x.ok else f"{_status_word(x.status)} at t* = {num(x.fail_time)}"
                rows.append([f"Figure 4 max |v*| (transient), {ap}", cell(cp[0], a), cell(cc[0], b),
                             pct(fd.relative_difference(b, a)) if cp[0].ok and cc[0].ok
                             else "not comparable: a run has no result"])
    if 5 in data:
        for ap in APPROACHES:
            for om in cfg.fig5_omegas:
                x, a, ra = _series(_rows(data[5], model=p, approach=ap, omega=om), "eps")
                _, b, rb = _series(_rows(data[5], model=c, approach=ap, omega=om), "eps")
                compare(f"Figure 5 amplitude, {ap}, Omega* = {om:g}", x, a, b, "eps", ra, rb)
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
                x, a, ra = _series(_rows(data[6], model=p, approach=ap, eps=eps), "omega")
                _, b, rb = _series(_rows(data[6], model=c, approach=ap, eps=eps), "omega")
                compare(f"Figure 6 amplitude, {ap}, eps = {eps:g}", x, a, b, "Omega*", ra, rb)
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
