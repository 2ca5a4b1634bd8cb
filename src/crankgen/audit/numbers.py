"""Numerical sections of the audit report (4: group weights, 5: quartic term, 6: element
convergence), computed from runs of the compiled engine; Markdown out, no SymPy."""

import math

from ..declaration.cases import Case
from ..declaration.ingredients import SWITCHABLE_GROUPS
from ..analyses.steady import steady_states
from .backbone import backbone
from .term_weights import (DAMPING_GROUPS, ELASTIC_GROUPS, KINETIC_GROUPS, switch_off_table,
                           weights_table)

EPS = (0.01, 0.1)
OMEGAS = (0.1, 0.2, 0.4, 0.6, 0.8, 1.0)
N_AUDIT = 8                      # elements of the consistent model (averaged membrane: converged)


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n" + "\n".join(lines) + "\n"


def _num(x, fmt="{:.3g}"):
    return "—" if x is None or not math.isfinite(x) else fmt.format(x)


# The RMS weights of section 4 come in three narrower tables instead of one of 16 columns.
WEIGHT_TABLES = (("inertia and kinematic terms", KINETIC_GROUPS),
                 ("elastic terms", ELASTIC_GROUPS),
                 ("damping terms, and the sum of all groups", DAMPING_GROUPS))


def section4(titles, facts=None):
    """Section 4; facts (a dict), if given, receives the weights and the switch-off runs."""
    weights, skipped = weights_table(EPS, OMEGAS, N_AUDIT)
    out = [
        "The consistent model (lagrange formulation, approach A, Kelvin-Voigt damping, element-mean "
        f"membrane strain, {N_AUDIT} elements, 100 steps per revolution) is marched to its periodic "
        "steady state (shooting, `crankgen.steady_state`) for each slenderness and speed. Along that "
        "revolution every group of section 2 is evaluated with its generated kernel, assembled on the "
        "reduced DOFs (pin and slider constraint applied) and its RMS over the revolution divided by "
        "the RMS of the total elastic force $\\partial U/\\partial q$. Axial DOFs ($u$ of every node and the "
        "slider co-ordinate $s$) and transverse DOFs ($v$, $\\psi$) are reported apart, because $EA$ "
        "makes axial forces much larger. The last column of each third table checks the split: the RMS "
        "of the sum of all groups (the residual of the equations of motion) over the same reference.\n"]
    for side in ("transverse", "axial"):
        out.append(f"\n### 4.{1 if side == 'transverse' else 2} RMS force relative to the elastic "
                   f"force, {side} DOFs\n")
        for k, (what, groups) in enumerate(WEIGHT_TABLES):
            last = k == len(WEIGHT_TABLES) - 1
            header = ["eps", "Omega*", "v* amplitude"] + [titles.get(g, g) for g in groups] \
                + (["sum of all"] if last else [])
            rows = []
            for w in weights:
                ratios = getattr(w, side)
                rows.append([f"{w.case.eps:g}", f"{w.case.omega:g}", f"{w.amplitude:.4g}"]
                            + [_num(ratios[g]) for g in groups] + ([_num(w.balance, "{:.1e}")] if last else []))
            out.append(f"\n{what.capitalize()}, {side} DOFs:\n")
            out.append(_table(header, rows))
    if skipped:
        out.append("\nNot periodic with the crank period (no weights computed): "
                   + "; ".join(f"eps = {c.eps:g}, Omega* = {c.omega:g}: {st} ({msg})" for c, st, msg in skipped)
                   + "\n")
    out.append(_observations(weights))

    table = switch_off_table(EPS, OMEGAS, N_AUDIT)
    if facts is not None:
        facts.update(weights=weights, switch_off=table)
    out.append("\n### 4.3 Change of the steady amplitude when one group is switched off\n\n"
               "Each switchable group is removed alone (rod and slider terms of that kind, forces and "
               "tangents) and the steady state recomputed; the table gives the relative change of the "
               "steady amplitude of $v^*(x^*=1/2)$, or the status when no periodic state is reached. "
               "Inertia, linear stiffness, forcing and damping are the structure of the model and are "
               "not switched off.\n")
    header = ["eps", "Omega*", "full model v*"] + [titles.get(g, g) for g in SWITCHABLE_GROUPS]
    rows = []
    for (eps, omega), runs in sorted(table.items()):
        base = runs[""]
        row = [f"{eps:g}", f"{omega:g}", f"{base.amplitude:.4g}" if base.ok else base.status]
        for g in SWITCHABLE_GROUPS:
            r = runs[g]
            if r.ok and base.ok:
                row.append(f"{(r.amplitude - base.amplitude) / base.amplitude:+.2%}")
            else:
                row.append(r.status)
        rows.append(row)
    out.append(_table(header, rows))
    return "".join(out)


def _observations(weights):
    """Plain statements read off the numbers (no conclusion is assumed)."""
    if not weights:
        return ""
    lines = ["\nRead off the tables:\n"]
    for w in weights:
        t, a = w.transverse, w.axial
        pair_t, pair_a = (t["cubic_transverse"], t["quartic"]), (a["stiffness"], a["cubic_axial"])
        if min(pair_t) > 2.0 and min(pair_t) / max(pair_t) > 0.9 and min(pair_a) / max(pair_a) > 0.9:
            lines.append(f"- eps = {w.case.eps:g}, Omega* = {w.case.omega:g}: in the transverse equations "
                         f"the cubic and quartic groups are each {t['cubic_transverse']:.3g} and "
                         f"{t['quartic']:.3g} times the total elastic force, so they nearly cancel (the "
                         f"membrane strain $u_{{,x}} + v_{{,x}}^2/2$ stays small while the rod bends); in the "
                         f"axial equations the linear stiffness ({a['stiffness']:.3g}) and the cubic axial "
                         f"force ({a['cubic_axial']:.3g}) cancel the same way.\n")
    kin = max(weights, key=lambda w: w.transverse["gyroscopic"])
    lines.append(f"- The gyroscopic group reaches at most {kin.transverse['gyroscopic']:.3g} of the "
                 f"transverse elastic force (eps = {kin.case.eps:g}, Omega* = {kin.case.omega:g}); the "
                 f"largest $\\ddot\\phi$ weight is {max(w.transverse['phidd'] for w in weights):.3g}.\n")
    return "".join(lines)


def section5(titles, facts=None):
    """Section 5; facts (a dict), if given, receives the A/B runs and the backbone curves."""
    out = ["### 5.1 Steady amplitude with and without the quartic term\n\n"
           "Approach A against B (B drops the quartic term) for the paper's model (printed form, "
           "eq. 24 damping, 16 elements) and the consistent model (lagrange, Kelvin-Voigt, "
           f"element-mean membrane strain, {N_AUDIT} elements); ratio B/A of the steady amplitude "
           "of $v^*(x^*=1/2)$, or the status of B when it has no periodic state.\n"]
    models = {"paper": dict(model="paper", n_elements=16),
              "consistent": dict(model="consistent", n_elements=N_AUDIT)}
    cases = [Case(eps=e, omega=w, approach=ap, **kw)
             for kw in models.values() for e in EPS for w in OMEGAS for ap in "AB"]
    res = iter(steady_states(cases))
    rows, pairs = [], []
    for name in models:
        for e in EPS:
            for w in OMEGAS:
                a, b = next(res), next(res)
                pairs.append((name, e, w, a, b))
                ratio = f"{b.amplitude / a.amplitude:.3f}" if a.ok and b.ok else (b.status if a.ok else a.status)
                rows.append([name, f"{e:g}", f"{w:g}", f"{a.amplitude:.4g}" if a.ok else a.status,
                             f"{b.amplitude:.4g}" if b.ok else b.status, ratio])
    out.append(_table(["model", "eps", "Omega*", "A", "B", "B / A"], rows))

    amplitudes = (0.1, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
    out.append("\n### 5.2 Backbone curve of the free rod\n\n"
               "First bending frequency of the free rod (crank at rest, no damping, eps = 0.01, "
               "ms* = 0.5) against the initial mid-span amplitude $v^*$ of a first-mode shape, in "
               "units of $\\omega_b$ (the small-amplitude value is $1/\\sqrt{1+\\pi^2\\varepsilon^2}$ "
               "with rotary inertia). Measured from zero crossings over 6 periods, 800 steps per "
               "period, corrected for the trapezoidal rule's period elongation; the slider end slides "
               "freely along the rod axis.\n")
    variants = [("consistent A", dict(approach="A", formulation="lagrange", membrane="averaged")),
                ("consistent B", dict(approach="B", formulation="lagrange", membrane="averaged")),
                ("C (linear)", dict(approach="C", formulation="lagrange")),
                ("paper A", dict(approach="A", formulation="paper")),
                ("paper B", dict(approach="B", formulation="paper"))]
    rows, curves = [], []
    for label, kw in variants:
        pts = backbone(amplitudes, eps=0.01, n_elements=N_AUDIT, steps_per_period=800, periods=6, **kw)
        rows.append([label] + [f"{p.frequency:.4f}" if p.status == "ok" else p.status for p in pts])
        curves.append((label, amplitudes, pts))
    if facts is not None:
        facts.update(quartic=pairs, backbone=curves)
    out.append(_table(["model"] + [f"v* = {a:g}" for a in amplitudes], rows))
    out.append("\nIn the printed form the axial force of the quartic term is never relieved by the "
               "slider (the axial equation lacks $\\frac{EA}{2}\\int v_{,x}^2 B_u$, section 3), so the "
               "quartic term acts as a string tension that grows with the amplitude; in the exact "
               "equations the slider end moves in and the membrane strain stays small. The numbers above "
               "show how much each model's frequency moves with amplitude.\n")
    return "".join(out)


def section6():
    ns = (2, 4, 8, 16, 32, 64)
    variants = [("paper", "paper", "pointwise"), ("paper", "kelvin-voigt", "pointwise"),
                ("lagrange", "paper", "pointwise"), ("lagrange", "kelvin-voigt", "pointwise"),
                ("lagrange", "paper", "averaged"), ("lagrange", "kelvin-voigt", "averaged")]
    cases = [Case(omega=0.8, eps=0.01, approach="A", formulation=f, damping=d, membrane=m, n_elements=n)
             for f, d, m in variants for n in ns]
    res = steady_states(cases)
    finest = {(f, d, m): res[k * len(ns) + len(ns) - 1] for k, (f, d, m) in enumerate(variants)}
    rows = []
    for k, (f, d, m) in enumerate(variants):
        runs = res[k * len(ns):(k + 1) * len(ns)]
        amps = [r.amplitude if r.ok else math.nan for r in runs]
        best = finest.get((f, d, "averaged"), finest[(f, d, m)])
        ref = best.amplitude if best.ok else math.nan
        conv = next((n for n, x in zip(ns, amps) if math.isfinite(x) and all(
            abs(y - ref) <= 0.01 * abs(ref) for y in amps[ns.index(n):])), None)
        rows.append([f, d, m] + [f"{x:.4f}" if math.isfinite(x) else r.status for x, r in zip(amps, runs)]
                    + [str(conv) if conv else "> 64"])
    text = ["Steady amplitude of $v^*(x^*=1/2)$ of approach A at Omega* = 0.8, eps = 0.01 "
            "(a* = 0.1, ms* = 0.5, mu* = 0.5, 100 steps per revolution) against the number of "
            "elements; last column: the smallest n from which every finer mesh stays within 1 % of "
            "the best estimate (the n = 64 value of the averaged element where the formulation has "
            "one, else the row's own n = 64 value).\n",
            _table(["formulation", "damping", "membrane", *(f"n = {n}" for n in ns), "1 % from n ="], rows)]
    text.append(
        "\n**Diagnosis.** With linear $u$ and cubic $v$ in an element, $u_{,x}$ is constant while "
        "$v_{,x}^2/2$ is a quartic polynomial in $x$: for an inextensional bending shape the element "
        "cannot make the membrane strain $u_{,x} + v_{,x}^2/2$ vanish, so it stores (and, with "
        "strain-rate damping, dissipates) spurious membrane energy when it bends: membrane locking. "
        "It shows wherever the exact membrane coupling acts (the lagrange formulation); the printed "
        "form never feeds $v_{,x}^2$ back into the axial equation and is not affected in the same way. "
        "Strain-rate damping of the locked membrane strain is the worst case: the rows with "
        "Kelvin-Voigt damping converge slowest.\n\n"
        "**Remedy.** `membrane=\"averaged\"` (derived in `derive/energies.py`, generated like every "
        "kernel) replaces $v_{,x}^2$ in the membrane strain by its element mean "
        "$\\langle v_{,x}^2\\rangle = \\frac1l\\int_0^l v_{,x}^2\\,dx$, which the linear $u$ can balance; "
        "bending is unchanged and the element converges to the same limit as the plain one "
        "(tests/test_membrane_averaged.py checks both as n grows).\n")
    return "".join(text)


# ---- the summary that opens the report -------------------------------------------------------
def _speeds(values):
    return ", ".join(f"{w:g}" for w in values)


def _quartic_summary(facts):
    pairs = facts.get("quartic")
    if pairs is None:
        return ["- (Section 5 is not part of this run: no numbers.)\n"]
    lines = []
    for model, what in (("paper", "paper model (printed form, eq. 24 damping)"),
                        ("consistent", "consistent model (exact equations, Kelvin-Voigt, averaged membrane)")):
        sel = [p for p in pairs if p[0] == model]
        parts = []
        for e in EPS:
            both = [(w, b.amplitude / a.amplitude) for m, ee, w, a, b in sel if ee == e and a.ok and b.ok]
            lost = [(w, b.status) for m, ee, w, a, b in sel if ee == e and a.ok and not b.ok]
            text = f"eps = {e:g}: "
            if both:
                lo, hi = min(both, key=lambda x: x[1]), max(both, key=lambda x: x[1])
                text += (f"B/A from {lo[1]:.3f} (Omega* = {lo[0]:g}) to {hi[1]:.3f} (Omega* = {hi[0]:g})"
                         if len(both) > 1 else f"B/A {hi[1]:.3f} at Omega* = {hi[0]:g}")
            if lost:
                statuses = sorted({st for _, st in lost})
                text += ("; " if both else "") + (f"B has no periodic state ({', '.join(statuses)}) "
                                                  f"at Omega* = {_speeds(w for w, _ in lost)}")
            parts.append(text)
        n_ok = sum(1 for p in sel if p[3].ok and p[4].ok)
        lines.append(f"- Steady amplitude, {what}: B periodic in {n_ok} of {len(sel)} cases; "
                     + "; ".join(parts) + " (5.1).\n")
    table = facts.get("switch_off")
    if table is not None:
        runs = [(k, r) for k, r in sorted(table.items())]
        gone = [(e, w) for (e, w), r in runs if r[""].ok and not r["quartic"].ok]
        kept = [abs(r["quartic"].amplitude - r[""].amplitude) / r[""].amplitude
                for (e, w), r in runs if r[""].ok and r["quartic"].ok]
        lines.append(f"- Switched off alone in the consistent model (4.3): no periodic state in "
                     f"{len(gone)} of {len(runs)} cases"
                     + (" (" + "; ".join(f"eps = {e:g}, Omega* = {w:g}" for e, w in gone) + ")" if gone else "")
                     + (f"; elsewhere the amplitude changes by at most {max(kept):.1%}" if kept else "")
                     + ".\n")
    curves = facts.get("backbone")
    if curves is not None:
        descr = []
        for label, amps, pts in curves:
            ok = [(a, p.frequency) for a, p in zip(amps, pts) if p.status == "ok"]
            bad = [a for a, p in zip(amps, pts) if p.status != "ok"]
            if not ok:
                descr.append(f"{label}: no frequency measured")
                continue
            f0 = ok[0][1]
            far = max(ok, key=lambda x: abs(x[1] - f0))
            text = (f"{label}: {f0:.4f} at v* = {ok[0][0]:g}, {ok[-1][1]:.4f} at v* = {ok[-1][0]:g}, "
                    f"largest change {(far[1] - f0) / f0:+.1%}"
                    + (f" (at v* = {far[0]:g})" if abs(far[1] - f0) >= 5e-4 * f0 else ""))
            if bad:
                text += f", no solution from v* = {bad[0]:g} on"
            descr.append(text)
        lines.append("- Free-rod frequency against amplitude, in units of omega_b (5.2): "
                     + "; ".join(descr) + ".\n")
    return lines


def _printed_summary(facts, titles, differences):
    lines = []
    if differences is None:
        lines.append("- (Section 3 is not part of this run: the list of differences is in it.)\n")
    else:
        exact = [d for d in differences if d.formulation == "paper"]
        text = [d for d in differences if d.formulation != "paper"]
        lines.append(f"- Where (3.3): {len(exact)} groups of terms of the exact equations are missing "
                     "from the printed form: " + "; ".join(
                         f"{d.component}, {titles.get(d.group, d.group)} (approach{'es' if len(d.approaches) > 1 else ''} "
                         f"{', '.join(d.approaches)})" for d in exact)
                     + f". The text as printed adds {len(text)} more, which are transcription problems "
                     "corrected in crankgen's `paper` formulation (3.5). Besides, the printed damping, "
                     "eq. (24), is a modelling choice with an indefinite dissipation, and the iteration "
                     "matrix of eq. (37) is a secant, not the tangent (3.4).\n")
    table, weights = facts.get("switch_off"), facts.get("weights")
    if table is not None:
        runs = sorted(table.items())
        parts, effects = [], []
        for g in ("gyroscopic", "phidd", "cubic_axial"):
            changes = [((e, w), (r[g].amplitude - r[""].amplitude) / r[""].amplitude)
                       for (e, w), r in runs if r[""].ok and r[g].ok]
            lost = [(e, w) for (e, w), r in runs if r[""].ok and not r[g].ok]
            text = titles.get(g, g)
            if changes:
                (e, w), c = max(changes, key=lambda x: abs(x[1]))
                text += f": at most {c:+.1%} (eps = {e:g}, Omega* = {w:g})"
                if weights is not None:
                    side = max(("transverse", "axial"),
                               key=lambda sd: max(getattr(x, sd)[g] for x in weights))
                    text += (f", RMS force at most {max(getattr(x, side)[g] for x in weights):.3g} of "
                             f"the elastic force on the {side} DOFs (4.{1 if side == 'transverse' else 2})")
            if lost:
                text += f"; no periodic state without it in {len(lost)} of {len(runs)} cases"
            parts.append(text)
            if changes:
                effects.append((max(abs(c) for _, c in changes), len(lost), titles.get(g, g)))
        ranked = sorted(effects, key=lambda x: (x[1], x[0]), reverse=True)
        lines.append("- How much (4.3): each missing group switched off alone in the consistent model, "
                     "largest change of the steady amplitude over the runs: " + "; ".join(parts)
                     + (f". Ranked by effect: {', '.join(t for _, _, t in ranked)}" if ranked else "")
                     + ".\n")
    pairs = facts.get("quartic")
    if pairs is not None:
        amp = {(m, e, w): a for m, e, w, a, b in pairs}
        parts = []
        for e in EPS:
            r = [(w, amp[("paper", e, w)].amplitude / amp[("consistent", e, w)].amplitude)
                 for w in OMEGAS if amp[("paper", e, w)].ok and amp[("consistent", e, w)].ok]
            if r:
                lo, hi = min(r, key=lambda x: x[1]), max(r, key=lambda x: x[1])
                parts.append(f"eps = {e:g}: from {lo[1]:.3f} (Omega* = {lo[0]:g}) to {hi[1]:.3f} "
                             f"(Omega* = {hi[0]:g})")
        if parts:
            lines.append("- Together with the models' other choices (damping, membrane strain), approach "
                         "A: steady amplitude of the paper model over the consistent model's, "
                         + "; ".join(parts) + " (5.1).\n")
    return lines


def summary(facts, titles, differences=None):
    """The report's opening summary, every number taken from this run's sections (facts: filled by
    section4 and section5; differences: crankgen._derive.audit.differences(), or None)."""
    out = ["## Summary\n\n",
           "Every number below is computed in this run (sections in brackets).\n\n",
           "**What does dropping the quartic term do?** Approach B drops "
           "$\\frac{EA}{8}v_{,x}^4$ from eq. (2); its strain energy is then not bounded below (1.1).\n\n"]
    out += _quartic_summary(facts)
    out.append("\n**Where does the printed form differ from the exact Lagrange equations, and how much "
               "does it matter?**\n\n")
    out += _printed_summary(facts, titles, differences)
    out += _exact_summary(facts)
    return "".join(out) + "\n"


def _exact_summary(facts):
    """What approach A drops relative to the exact rod (section 7), in numbers of this run."""
    weights, pairs = facts.get("exact_weights"), facts.get("exact_pairs")
    if not weights:
        return []
    lines = ["\n**What does approach A drop relative to the exact strain?** Terms of relative order "
             "$\\delta^2$, the square of the slopes (7.1). Along the consistent model's steady revolutions (7.2):\n\n"]
    for w in weights:
        if w.case.omega in (0.6, 0.8, 1.0):
            _, st_x = pairs[(w.case.eps, w.case.omega)]
            change = (f"{(st_x.amplitude - w.amplitude) / w.amplitude:+.1%}" if st_x.ok else st_x.status)
            lines.append(f"- eps = {w.case.eps:g}, Omega* = {w.case.omega:g} (slopes up to {w.slope:.2g}): the "
                         f"exact membrane strain differs from A's by {w.membrane:.2g} of it (RMS), the curvature "
                         f"by {w.curvature:.2g}, the transverse elastic force by {w.transverse:.2g}; the exact "
                         f"rod's steady amplitude is {change} from the consistent model's.\n")
    return lines
