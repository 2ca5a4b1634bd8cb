"""Plots of Figures 2-8 and of the convergence check: paper model | consistent model side by side.
Nothing is dropped: a transient that diverged (approach B: ill-posed) or failed is drawn up to
there, marked with a large 'X'; a sweep case whose run from rest diverged gets an 'x' inside the
frame at the bottom (a '+' for a run that failed otherwise or never settled), an off-scale value a
filled triangle inside the frame at the top (both in the series' colour); hollow markers for
unstable orbits and the settled transients of non-periodic responses; deflections beyond the
theory (|v|/L > 0.1) lie in a shaded band.  Curves that coincide keep distinct markers and line
styles, and the legend says so.  Legends sit below the axes, labels wrapped to the panel; the
layout is measured (crankgen.plots.figures.fit_panels); no text is smaller than 8 pt."""

import math

import numpy as np

from ..plots.figures import APPROACH_COLORS, fit_panels, mark_at_axis, panels, shade_beyond
from . import findings as fd

from .config import APPROACHES, MODELS
from .figures import DIVERGED, STRAIN_LIMIT, THEORY_LIMIT
from .plot_style import (APPROACH_STYLES, FONT, SPEED_STYLES, Line2D, coincide_note, legend_below, legend_room,
                         panel_grid, panel_title, theory_handle)
from .plots_sweeps import plot_figure5, plot_figure6, room_below


def _transient(ax, curve, color, ls="-", label=None, lw=1.0):
    """A transient curve; a run that diverged or failed up to there (its 'X' is drawn by
    _transient_axes)."""
    if curve.diverged:
        label = f"{label}: DIVERGED at t* = {curve.fail_time:.3g}"
    elif not curve.ok:
        label = f"{label}: FAILED at t* = {curve.fail_time:.3g}"
    if curve.has_history:
        ax.plot(curve.t, curve.v_mid, color=color, ls=ls, lw=lw, label=label)
    else:
        ax.plot([], [], color=color, ls=ls, lw=lw, label=label)
    curve._color = color


def _theory_band(ax, eps, data_max):
    """Shade |v*| > THEORY_LIMIT / eps (beyond the small-deflection theory) when the data reach it."""
    lim = THEORY_LIMIT / eps
    if not (math.isfinite(data_max) and data_max > lim):
        return False
    shade_beyond(ax, lim, "0.85")
    return True


def _curve_coincidences(curves, name):
    """coincide_note over all pairs of successful transient curves."""
    ok = [c for c in curves if c.ok]
    return coincide_note([(name(a), name(b), _curve_pair_diff(a, b))
                           for i, a in enumerate(ok) for b in ok[i + 1:]])


def _transient_axes(ax, curves, eps):
    """Finish a panel of transients: y range (a run that blows up beyond 5 times the other curves
    and the theory limit does not squash them: the range then fits the others and its failure is
    marked on the edge with its value), an 'X' where each failed run stopped, and the shaded band
    beyond the theory.  Returns extra legend handles."""
    lim = THEORY_LIMIT / eps
    ok = [c.max_abs for c in curves if c.ok and c.has_history]
    bad = [c for c in curves if not c.ok]
    base = max(ok + [lim]) if ok else None
    top = None
    if base is not None and any(c.has_history and c.max_abs > 5 * base for c in bad):
        top = 1.3 * base
        ax.set_ylim(-top, top)
    stacked = {}
    for c in bad:
        col = getattr(c, "_color", "k")
        if not c.has_history:
            mark_at_axis(ax, [c.fail_time if math.isfinite(c.fail_time) else 0.0], col)
            continue
        t, v = c.t[-1], c.v_mid[-1]
        if top is not None and abs(v) > top:
            y = math.copysign(0.9 * top, v)
            k = stacked.setdefault(v > 0, 0)
            stacked[v > 0] += 1
            ax.plot([t], [y], ls="none", marker="X", ms=9, color=col, markeredgecolor="k", zorder=6)
            x0, x1 = ax.get_xlim()
            right = t < (x0 + x1) / 2               # the label on the side with room
            ax.annotate(f"v* = {v:.3g}", (t, y), xytext=(8 if right else -8, (-2 - 10 * k) if v > 0 else (2 + 10 * k)),
                        textcoords="offset points", fontsize=FONT, color=col, ha="left" if right else "right",
                        va="top" if v > 0 else "bottom")
        else:
            ax.plot([t], [v], ls="none", marker="X", ms=9, color=col, markeredgecolor="k", zorder=6)
    vmax = max([c.max_abs for c in curves if c.has_history] or [math.nan])
    extra = []
    if any(c.diverged for c in bad):
        extra.append(Line2D([], [], ls="none", marker="X", ms=8, color="0.6", markeredgecolor="k",
                            label="X: the run diverged here (history kept; approach B is ill-posed: "
                                  "its strain energy is unbounded below)"))
    if any(not c.diverged for c in bad):
        extra.append(Line2D([], [], ls="none", marker="X", ms=8, color="0.6", markeredgecolor="k",
                            label="X: the run failed here (history kept)"))
    if _theory_band(ax, eps, vmax):
        extra.append(theory_handle())
    return extra


_LINESTYLES = ["-", "--", "-.", ":", (0, (5, 1, 1, 1))]


def _ls(k):
    return _LINESTYLES[k % len(_LINESTYLES)]


def _colors(n):
    import matplotlib
    cmap = matplotlib.colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.72, max(n, 1))]


def _curve_pair_diff(a, b):
    from .figures import transient_difference
    return transient_difference(a, b)


def plot_figure2(data, cfg, counts):
    n_max = max(len({c.spec.n_elements for c in data["curves"] if c.spec.model == m.key
                     and c.spec.approach == ap}) for m in MODELS for ap in APPROACHES)
    fig, axes = panels(3, 2, width=6.2, height=2.4, space_below=legend_room(n_max + 1, 3), top_margin=0.95)
    for j, m in enumerate(MODELS):
        for i, ap in enumerate(APPROACHES):
            ax = axes[i, j]
            cs = [c for c in data["curves"] if c.spec.model == m.key and c.spec.approach == ap]
            for k, (c, col) in enumerate(zip(cs, _colors(len(cs)))):
                _transient(ax, c, col, ls=_ls(k), label=f"n = {c.spec.n_elements}", lw=1.0 + 0.6 * (k == 0))
            extra = _transient_axes(ax, cs, cfg.eps)
            note = _curve_coincidences(cs, lambda c: f"n = {c.spec.n_elements}")
            panel_title(ax, m, f"\napproach {ap}, Omega* = {cfg.fig2_omega:g}")
            ax.set_ylabel("v* at x* = 1/2")
            ax.tick_params(labelbottom=True)
            ax.set_xlabel("t*")
            legend_below(ax, ncol=3, extra=extra + ([note] if note else []))
            panel_grid(ax)
    fig.suptitle(f"Figure 2: transient v*, approaches A, B, C (eps = {cfg.eps:g}, ms* = {cfg.ms:g})",
                 fontsize=10)
    return fig


def plot_figure3(data, cfg, counts):
    n = max(len([c for c in data["curves"] if c.spec.model == m.key]) for m in MODELS)
    fig, axes = panels(1, 2, width=6.2, height=3.4, space_below=legend_room(n + 1, 2), top_margin=0.95)
    for j, m in enumerate(MODELS):
        ax = axes[0, j]
        cs = [c for c in data["curves"] if c.spec.model == m.key]
        base = [c for c in cs if c.spec.steps_per_rev == cfg.fig3_steps[0]]
        for k, (c, col) in enumerate(zip(base, _colors(len(base)))):
            _transient(ax, c, col, ls=_ls(k), label=f"n = {c.spec.n_elements}, {c.spec.steps_per_rev} steps/rev")
        pairs = []
        for c in cs:
            if c.spec.steps_per_rev != cfg.fig3_steps[0]:
                _transient(ax, c, "k", ls=(0, (1, 2)), lw=1.4,
                           label=f"n = {c.spec.n_elements}, {c.spec.steps_per_rev} steps/rev")
                ref = [b for b in base if b.spec.n_elements == c.spec.n_elements]
                if ref:
                    pairs.append((f"{ref[0].spec.steps_per_rev} steps/rev", f"{c.spec.steps_per_rev} steps/rev "
                                  f"(n = {c.spec.n_elements})", _curve_pair_diff(ref[0], c)))
        extra = _transient_axes(ax, cs, cfg.eps)
        ok = [c for c in base if c.ok]
        pairs = [(f"n = {a.spec.n_elements}", f"n = {b.spec.n_elements}", _curve_pair_diff(a, b))
                 for i, a in enumerate(ok) for b in ok[i + 1:]] + pairs
        note = coincide_note(pairs)
        panel_title(ax, m, f"\napproach A, Omega* = {cfg.fig3_omega:g}")
        ax.set_xlabel("t*")
        ax.set_ylabel("v* at x* = 1/2")
        legend_below(ax, ncol=2, extra=extra + ([note] if note else []))
        panel_grid(ax)
    fig.suptitle("Figure 3: convergence of approach A with the number of elements", fontsize=10)
    return fig


def plot_figure4(data, cfg, counts):
    masses = sorted({c.spec.ms for c in data["curves"] if c.spec.approach != "A"})
    fig, axes = panels(2, 2, width=6.2, height=3.0, space_below=legend_room(2 * len(masses) + 4, 2), top_margin=0.95)
    for j, m in enumerate(MODELS):
        ax = axes[0, j]
        top = []
        for ap in APPROACHES:
            for c in data["curves"]:
                if c.spec.model == m.key and c.spec.approach == ap and c.spec.ms == cfg.ms:
                    ls, _, _ = APPROACH_STYLES[ap]
                    _transient(ax, c, APPROACH_COLORS[ap], ls=ls, label=f"{ap}, n = {c.spec.n_elements}")
                    top.append(c)
        extra = _transient_axes(ax, top, cfg.eps)
        note = _curve_coincidences(top, lambda c: c.spec.approach)
        extra += [note] if note else []
        panel_title(ax, m, f"\nOmega* = {cfg.fig4_omega:g}, ms* = {cfg.ms:g}")
        ax.set_ylabel("v* at x* = 1/2")
        ax.set_xlabel("t*")
        legend_below(ax, ncol=2, extra=extra)
        panel_grid(ax)
        ax = axes[1, j]
        cols = dict(zip(masses, _colors(len(masses))))
        bottom = []
        for ap, ls in (("B", "-"), ("C", "--")):
            for c in data["curves"]:
                if c.spec.model == m.key and c.spec.approach == ap:
                    _transient(ax, c, cols[c.spec.ms], ls=ls, label=f"{ap}, ms* = {c.spec.ms:g}")
                    bottom.append(c)
        extra = _transient_axes(ax, bottom, cfg.eps)
        note = _curve_coincidences(bottom, lambda c: f"{c.spec.approach} ms* = {c.spec.ms:g}")
        extra += [note] if note else []
        panel_title(ax, m, "\nslider mass: B (solid) and C (dashed)")
        ax.set_xlabel("t*")
        ax.set_ylabel("v* at x* = 1/2")
        legend_below(ax, ncol=2, extra=extra)
        panel_grid(ax)
    fig.suptitle(f"Figure 4: transient v* at high speed (eps = {cfg.eps:g}; X: where a run diverged)",
                 fontsize=10)
    return fig


def plot_extension(data, cfg, counts):
    cs_all = data["curves"]
    n_leg = max(len([c for c in cs_all if c["model"] == m.key]) for m in MODELS) + 2
    fig, axes = panels(1, 2, width=6.2, height=3.4, space_below=legend_room(n_leg, 2), top_margin=0.95)
    for j, m in enumerate(MODELS):
        ax = axes[0, j]
        cs = [c for c in cs_all if c["model"] == m.key]
        for k, (c, col) in enumerate(zip(cs, _colors(len(cs)))):
            label = f"ms* = {c['ms']:g}"
            if c["theta_deg"] is not None:
                ls = _ls(k) if c["status"] == "periodic" else ":"
                if c["status"] != "periodic":
                    label += f" ({c['status']})"
                ax.plot(c["theta_deg"], c["extension"], color=col, ls=ls, lw=1.2 + 0.5 * (k == 0), label=label)
            else:                   # nothing to draw: the legend says so, with no marker
                ax.plot([], [], ls="none", label=f"{label}: no periodic state ({c['status']}), no curve")
        stable = [c for c in cs if c["status"] == "periodic"]
        extra = []
        if len(stable) >= 2:
            xs = fd.extension_crossings(stable[0]["theta_deg"], np.stack([c["extension"] for c in stable]),
                                        cfg.crossing_rel_tol)
            for x in xs:
                ax.axvline(x["angle"], color="grey", ls=":", lw=1.0)
            if xs:
                extra.append(Line2D([], [], color="grey", ls=":", label="common crossings: "
                                    + ", ".join(f"{x['angle']:.1f}" for x in xs) + " deg"))
            spread = max(float(np.max(np.abs(c["extension"] - stable[0]["extension"]))) for c in stable[1:])
            scale = float(np.ptp(stable[0]["extension"]))
            if scale > 0 and spread < 0.01 * scale:
                extra.append(Line2D([], [], ls="none", label="all ms* coincide to 1 %"))
        flagged = [c for c in cs if c.get("beyond_theory") == "yes"]
        if flagged:
            extra.append(Line2D([], [], ls="none", label=f"beyond the theory (|v|/L > {THEORY_LIMIT:g} or axial "
                                f"strain > {STRAIN_LIMIT:g}): ms* = "
                                + ", ".join(f"{c['ms']:g}" for c in flagged)))
        n = cs[0]["n_elements"] if cs else "?"
        panel_title(ax, m, f"\napproach A, n = {n}, Omega* = {data['omega']:g}")
        ax.set_xlabel("crank angle theta (degrees)")
        ax.set_ylabel("extension delta*")
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 60))
        legend_below(ax, ncol=2, extra=extra)
        panel_grid(ax)
    fig.suptitle(f"Figure {data['figure']}: extension of the neutral axis over a steady revolution",
                 fontsize=10)
    return fig


def plot_figure(data, cfg, counts, bifurcations=None):
    """The figure of `data`, laid out from measurements (nothing clipped, no legend over a panel)."""
    f = data["figure"]
    if f == 6:
        return fit_panels(plot_figure6(data, cfg, counts, bifurcations))
    fn = {2: plot_figure2, 3: plot_figure3, 4: plot_figure4, 5: plot_figure5, 7: plot_extension,
          8: plot_extension}[f]
    return fit_panels(fn(data, cfg, counts))


def plot_convergence(conv, cfg):
    """Top: steady amplitude against n; bottom: relative change to the next count and the tolerance."""
    fig, axes = panels(2, 2, width=6.2, height=3.0, space_below=legend_room(3 * len(cfg.conv_omegas) + 2, 2),
                       top_margin=0.95)
    for j, m in enumerate(MODELS):
        top, bot = axes[0, j], axes[1, j]
        pairs = []
        for k, om in enumerate(cfg.conv_omegas):
            speed_ls = SPEED_STYLES[k % len(SPEED_STYLES)][0]
            amps = {}
            for ap in APPROACHES:
                _, mk, size = APPROACH_STYLES[ap]
                rows = sorted([r for r in conv["rows"] if r["model"] == m.key and r["approach"] == ap
                               and r["omega"] == om], key=lambda r: r["n_elements"])
                x = [r["n_elements"] for r in rows]
                col = APPROACH_COLORS[ap]
                style = dict(ls=speed_ls, marker=mk, ms=size + 1, color=col,
                             markerfacecolor="none" if ap == "B" else col, markeredgewidth=1.1)
                top.plot(x, [r["amplitude"] for r in rows], label=f"{ap}, Omega* = {om:g}", **style)
                amps[ap] = {r["n_elements"]: r["amplitude"] for r in rows}
                for kind, marker in ((True, "x"), (False, "+")):
                    bad = [r["n_elements"] for r in rows if r["status"] != "periodic"
                           and (r["status"] == DIVERGED) == kind]
                    if bad:
                        top.scatter(bad, np.full(len(bad), 0.04), transform=top.get_xaxis_transform(),
                                    marker=marker, color=col, s=40, zorder=5)
                ch = [(r["n_elements"], r["change_to_next"]) for r in rows
                      if math.isfinite(r.get("change_to_next", math.nan)) and r["change_to_next"] > 0]
                if ch:
                    bot.plot(*zip(*ch), label=f"{ap}, Omega* = {om:g}", **style)
            for a, b in (("A", "B"), ("A", "C"), ("B", "C")):
                common = [n for n in amps[a] if n in amps[b] and math.isfinite(amps[a][n])
                          and math.isfinite(amps[b][n]) and amps[a][n] != 0]
                d = max((abs(amps[b][n] / amps[a][n] - 1) for n in common), default=None)
                pairs.append((f"{a}@{om:g}", f"{b}@{om:g}", d))
        used = {}
        for ap in APPROACHES:
            used.setdefault(conv["counts"][(m.key, ap)], []).append(ap)
        bot.axhline(cfg.conv_tol, color="k", lw=0.8, ls="--", label=f"tolerance {100 * cfg.conv_tol:g} %")
        # the counts computed (the ladder stops where a series converged) and those used
        computed = {r["n_elements"] for r in conv["rows"] if r["model"] == m.key}
        ticks = sorted(computed | set(used))
        names = [str(n) + (f"\n{', '.join(used[n])}" if n in used else "") for n in ticks]
        for a in (top, bot):
            a.set_xscale("log", base=2)
            a.set_yscale("log")
            a.set_xticks(ticks, names)      # the approaches using a count are named under it
            a.minorticks_off()
            a.set_xlim(ticks[0] / 1.25, ticks[-1] * 1.25)
            for n in used:                  # one dotted line per count used
                a.axvline(n, color="0.45", ls=":", lw=1.0, zorder=1)
            panel_grid(a)
        if any(r["status"] != "periodic" for r in conv["rows"] if r["model"] == m.key):
            top.autoscale_view()
            room_below(top)
        note = coincide_note(pairs)
        extra = [Line2D([], [], color="0.45", ls=":", label="dotted: element count used, by the approaches named under it")]
        beyond = sorted(n for n in used if n not in computed)
        if beyond:
            extra.append(Line2D([], [], ls="none", label="; ".join(
                f"n = {n} ({', '.join(used[n])}): the paper's count, larger than the converged one "
                "(not on the ladder, which stopped once converged)" for n in beyond)))
        if any(r["status"] == DIVERGED for r in conv["rows"] if r["model"] == m.key):
            extra.append(Line2D([], [], ls="none", marker="x", color="0.4",
                                label="x at the bottom: the run from rest diverged (B is ill-posed)"))
        if any(r["status"] not in ("periodic", DIVERGED) for r in conv["rows"] if r["model"] == m.key):
            extra.append(Line2D([], [], ls="none", marker="+", color="0.4", label="+ at the bottom: no periodic state"))
        legend_below(top, ncol=2, extra=extra + ([note] if note else []))
        legend_below(bot, ncol=2)
        top.set_ylabel("steady amplitude max |v*|")
        top.set_xlabel("number of elements n")
        bot.set_ylabel("|a(n) - a(next n)| / a(next n)")
        bot.set_xlabel("number of elements n")
        panel_title(top, m, "\nsteady amplitude against n")
        panel_title(bot, m, "\nchange to the next count")
    fig.suptitle(f"Element-count convergence of the steady amplitude (eps = {cfg.eps:g})", fontsize=10)
    return fit_panels(fig)
