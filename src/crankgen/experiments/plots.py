"""Plots of Figures 2-8 and of the convergence check: paper model | consistent model side by side.
Cases without a result are marked (never dropped): an 'x' on the axis where a sweep case or a
transient run failed, hollow markers for unstable orbits and non-periodic responses."""

import math

import numpy as np

from ..plotting import APPROACH_COLORS, mark_at_axis, panels, status_legend_handles
from . import findings as fd
from .config import APPROACHES, MODELS

_SPEED_STYLES = [("-", "o"), ("--", "s"), (":", "D"), ("-.", "v")]


def _title(ax, model, extra=""):
    ax.set_title(f"{model.label}{extra}", fontsize=9)


def _grid(ax):
    ax.grid(alpha=0.3)


def _transient(ax, curve, color, ls="-", label=None, lw=1.0):
    if curve.ok:
        ax.plot(curve.t, curve.v_mid, color=color, ls=ls, lw=lw, label=label)
    else:
        when = f"{curve.fail_time:.3g}" if math.isfinite(curve.fail_time) else "?"
        mark_at_axis(ax, [curve.fail_time if math.isfinite(curve.fail_time) else 0.0], color,
                     label=f"{label}: failed at t* = {when}")


_LINESTYLES = ["-", "--", "-.", ":", (0, (5, 1, 1, 1))]


def _ls(k):
    return _LINESTYLES[k % len(_LINESTYLES)]


def _colors(n):
    import matplotlib
    cmap = matplotlib.colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.85, max(n, 1))]


def plot_figure2(data, cfg, counts):
    fig, axes = panels(3, 2, width=6.2, height=2.6, sharex=True)
    for j, m in enumerate(MODELS):
        for i, ap in enumerate(APPROACHES):
            ax = axes[i, j]
            cs = [c for c in data["curves"] if c.spec.model == m.key and c.spec.approach == ap]
            for k, (c, col) in enumerate(zip(cs, _colors(len(cs)))):
                _transient(ax, c, col, ls=_ls(k), label=f"n = {c.spec.n_elements}")
            _title(ax, m, f"\napproach {ap}, Omega* = {cfg.fig2_omega:g}")
            ax.set_ylabel("v* at x* = 1/2")
            ax.legend(fontsize=7, loc="best")
            _grid(ax)
        axes[-1, j].set_xlabel("t*")
    fig.suptitle(f"Figure 2: transient v*, approaches A, B, C (eps = {cfg.eps:g}, ms* = {cfg.ms:g})",
                 fontsize=10)
    return fig


def plot_figure3(data, cfg, counts):
    fig, axes = panels(1, 2, width=6.2, height=3.8)
    for j, m in enumerate(MODELS):
        ax = axes[0, j]
        cs = [c for c in data["curves"] if c.spec.model == m.key]
        base = [c for c in cs if c.spec.steps_per_rev == cfg.fig3_steps[0]]
        for k, (c, col) in enumerate(zip(base, _colors(len(base)))):
            _transient(ax, c, col, ls=_ls(k), label=f"n = {c.spec.n_elements}, {c.spec.steps_per_rev} steps/rev")
        for c in cs:
            if c.spec.steps_per_rev != cfg.fig3_steps[0]:
                _transient(ax, c, "k", ls=(0, (1, 2)), lw=0.9,
                           label=f"n = {c.spec.n_elements}, {c.spec.steps_per_rev} steps/rev")
        _title(ax, m, f"\napproach A, Omega* = {cfg.fig3_omega:g}")
        ax.set_xlabel("t*")
        ax.set_ylabel("v* at x* = 1/2")
        ax.legend(fontsize=7)
        _grid(ax)
    fig.suptitle("Figure 3: convergence of approach A with the number of elements", fontsize=10)
    return fig


def plot_figure4(data, cfg, counts):
    fig, axes = panels(2, 2, width=6.2, height=3.4)
    for j, m in enumerate(MODELS):
        ax = axes[0, j]
        for ap in APPROACHES:
            for c in data["curves"]:
                if c.spec.model == m.key and c.spec.approach == ap and c.spec.ms == cfg.ms:
                    _transient(ax, c, APPROACH_COLORS[ap], label=f"{ap}, n = {c.spec.n_elements}")
        _title(ax, m, f"\nOmega* = {cfg.fig4_omega:g}, ms* = {cfg.ms:g}")
        ax.set_ylabel("v* at x* = 1/2")
        ax.legend(fontsize=7)
        _grid(ax)
        ax = axes[1, j]
        masses = sorted({c.spec.ms for c in data["curves"] if c.spec.approach != "A"})
        cols = dict(zip(masses, _colors(len(masses))))
        for ap, ls in (("B", "-"), ("C", "--")):
            for c in data["curves"]:
                if c.spec.model == m.key and c.spec.approach == ap:
                    _transient(ax, c, cols[c.spec.ms], ls=ls, label=f"{ap}, ms* = {c.spec.ms:g}")
        _title(ax, m, "\neffect of the slider mass on B (solid) and C (dashed)")
        ax.set_xlabel("t*")
        ax.set_ylabel("v* at x* = 1/2")
        ax.legend(fontsize=6, ncol=2)
        _grid(ax)
    fig.suptitle("Figure 4: transient v* at high speed", fontsize=10)
    return fig


def _sweep_series(ax, rows, xkey, color, ls, marker, label, mark_missing=True):
    """Line through the periodic points; markers for the other statuses (see module docstring)."""
    rows = sorted(rows, key=lambda r: r[xkey])
    x = np.array([r[xkey] for r in rows], dtype=float)
    y = np.array([r["amplitude"] for r in rows], dtype=float)
    ax.plot(x, y, ls=ls, marker=marker, ms=3, color=color, lw=1.1, label=label)
    unst = [r for r in rows if r["status"] == "unstable" and math.isfinite(r["orbit_amplitude"])]
    if unst:
        ax.scatter([r[xkey] for r in unst], [r["orbit_amplitude"] for r in unst], marker="o",
                   facecolors="none", edgecolors=color, s=22, zorder=4)
    env = [r for r in rows if r["status"] != "periodic" and math.isfinite(r["envelope"])]
    if env:
        ax.scatter([r[xkey] for r in env], [r["envelope"] for r in env], marker="^",
                   facecolors="none", edgecolors=color, s=26, zorder=4)
    if mark_missing:
        missing = [r[xkey] for r in rows if r["status"] != "periodic" and not math.isfinite(r["envelope"])]
        mark_at_axis(ax, missing, color)


def _limit_to_steady(ax, rows, margin=1.25):
    """Linear y axis scaled to the steady amplitudes (periodic and unstable orbits); non-periodic
    responses beyond it are drawn on the top edge with their value, so they never squash the curves."""
    vals = [r["amplitude"] for r in rows if math.isfinite(r["amplitude"])]
    vals += [r["orbit_amplitude"] for r in rows if r["status"] == "unstable"
             and math.isfinite(r["orbit_amplitude"])]
    if not vals:
        return
    top = margin * max(vals)
    ax.set_ylim(0.0, top)
    xkey = "omega" if ax.get_xlabel() == "Omega*" else "eps"
    off = [r[xkey] for r in rows
           if r["status"] != "periodic" and math.isfinite(r["envelope"]) and r["envelope"] > top]
    if off:
        ax.scatter(off, np.ones(len(off)), transform=ax.get_xaxis_transform(), marker="^",
                   clip_on=False, facecolors="none", edgecolors="k", s=26, zorder=5)


def _status_kinds(rows):
    kinds = []
    if any(r["status"] != "periodic" and not math.isfinite(r["envelope"]) for r in rows):
        kinds.append("failed")
    if any(r["status"] == "unstable" for r in rows):
        kinds.append("unstable")
    if any(math.isfinite(r["envelope"]) for r in rows):
        kinds.append("envelope")
    return kinds


def _legend_with_status(ax, rows, fontsize=7, below=False, ncol=1):
    handles, labels = ax.get_legend_handles_labels()
    extra = status_legend_handles(_status_kinds(rows))
    kwargs = dict(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=ncol) if below else {}
    ax.legend(handles + extra, labels + [h.get_label() for h in extra], fontsize=fontsize, **kwargs)


def plot_figure5(data, cfg, counts):
    fig, axes = panels(2, 2, width=6.2, height=4.0, space_below=0.9)
    for j, m in enumerate(MODELS):
        rows = [r for r in data["rows"] if r["model"] == m.key]
        for i, log in enumerate((False, True)):
            ax = axes[i, j]
            for k, om in enumerate(cfg.fig5_omegas):
                ls, mk = _SPEED_STYLES[k % len(_SPEED_STYLES)]
                for ap in APPROACHES:
                    sel = [r for r in rows if r["approach"] == ap and r["omega"] == om]
                    n = sel[0]["n_elements"] if sel else "?"
                    _sweep_series(ax, sel, "eps", APPROACH_COLORS[ap], ls, mk,
                                  f"{ap} (n = {n}), Omega* = {om:g}")
            if log:
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_ylabel("max |v*| (log scale)")
            else:
                ax.set_ylabel("steady amplitude max |v*|")
            ax.set_xlabel("eps")
            if not log:
                _limit_to_steady(ax, rows)
            _title(ax, m, " (log-log)" if log else "")
            if log:
                _legend_with_status(ax, rows, fontsize=6, below=True, ncol=2)
            _grid(ax)
    fig.suptitle("Figure 5: steady-state amplitude of v* against slenderness eps", fontsize=10)
    return fig


def plot_figure6(data, cfg, counts):
    fig, axes = panels(len(cfg.fig6_eps), 2, width=6.4, height=4.8, space_below=0.9)
    for j, m in enumerate(MODELS):
        for i, eps in enumerate(cfg.fig6_eps):
            ax = axes[i, j]
            rows = [r for r in data["rows"] if r["model"] == m.key and r["eps"] == eps]
            inset = ax.inset_axes([0.07, 0.52, 0.36, 0.42])
            for ap in APPROACHES:
                sel = [r for r in rows if r["approach"] == ap]
                n = sel[0]["n_elements"] if sel else "?"
                for a in (ax, inset):
                    _sweep_series(a, sel, "omega", APPROACH_COLORS[ap], "-", "o",
                                  f"{ap} (n = {n})" if a is ax else None, mark_missing=a is ax)
            inset.set_ylim(0, cfg.fig6_inset_ylim)
            lo = [r["omega"] for r in rows if r["status"] == "periodic"
                  and r["amplitude"] <= cfg.fig6_inset_ylim]
            if lo:
                inset.set_xlim(0, max(lo) * 1.15)
            inset.tick_params(labelsize=6)
            inset.set_title(f"v* from 0 to {cfg.fig6_inset_ylim:g}", fontsize=6)
            inset.grid(alpha=0.3)
            ax.set_xlabel("Omega*")
            _limit_to_steady(ax, rows)
            ax.set_ylabel("steady amplitude max |v*|")
            _title(ax, m, f", eps = {eps:g}")
            _legend_with_status(ax, rows, fontsize=6, below=True, ncol=2)
            _grid(ax)
    fig.suptitle("Figure 6: steady-state amplitude of v* against crank speed Omega*", fontsize=10)
    return fig


def plot_extension(data, cfg, counts):
    fig, axes = panels(1, 2, width=6.2, height=3.8)
    for j, m in enumerate(MODELS):
        ax = axes[0, j]
        cs = [c for c in data["curves"] if c["model"] == m.key]
        for c, col in zip(cs, _colors(len(cs))):
            label = f"ms* = {c['ms']:g}"
            if c["theta_deg"] is not None:
                ls = "-" if c["status"] == "periodic" else ":"
                if c["status"] != "periodic":
                    label += f" ({c['status']})"
                ax.plot(c["theta_deg"], c["extension"], color=col, ls=ls, lw=1.1, label=label)
            else:
                mark_at_axis(ax, [0.0], col, label=f"{label}: {c['status']}")
        stable = [c for c in cs if c["status"] == "periodic"]
        if len(stable) >= 2:
            for x in fd.extension_crossings(stable[0]["theta_deg"],
                                            np.stack([c["extension"] for c in stable]),
                                            cfg.crossing_rel_tol):
                ax.axvline(x["angle"], color="grey", ls=":", lw=0.8)
        n = cs[0]["n_elements"] if cs else "?"
        _title(ax, m, f"\napproach A, n = {n}, Omega* = {data['omega']:g}")
        ax.set_xlabel("crank angle theta (degrees)")
        ax.set_ylabel("extension delta*")
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 60))
        ax.legend(fontsize=7)
        _grid(ax)
    fig.suptitle(f"Figure {data['figure']}: extension of the neutral axis over a steady revolution "
                 "(dotted: common crossings)", fontsize=10)
    return fig


def plot_figure(data, cfg, counts):
    f = data["figure"]
    fn = {2: plot_figure2, 3: plot_figure3, 4: plot_figure4, 5: plot_figure5, 6: plot_figure6,
          7: plot_extension, 8: plot_extension}[f]
    return fn(data, cfg, counts)


def plot_convergence(conv, cfg):
    """Top: steady amplitude against n; bottom: relative change to the next count and the tolerance."""
    fig, axes = panels(2, 2, width=6.2, height=3.3)
    for j, m in enumerate(MODELS):
        top, bot = axes[0, j], axes[1, j]
        for k, om in enumerate(cfg.conv_omegas):
            ls, mk = _SPEED_STYLES[k % len(_SPEED_STYLES)]
            for ap in APPROACHES:
                rows = sorted([r for r in conv["rows"] if r["model"] == m.key and r["approach"] == ap
                               and r["omega"] == om], key=lambda r: r["n_elements"])
                x = [r["n_elements"] for r in rows]
                col = APPROACH_COLORS[ap]
                top.plot(x, [r["amplitude"] for r in rows], ls=ls, marker=mk, ms=3, color=col,
                         label=f"{ap}, Omega* = {om:g}")
                mark_at_axis(top, [r["n_elements"] for r in rows if r["status"] != "periodic"], col)
                ch = [(r["n_elements"], r["change_to_next"]) for r in rows
                      if math.isfinite(r.get("change_to_next", math.nan)) and r["change_to_next"] > 0]
                if ch:
                    bot.plot(*zip(*ch), ls=ls, marker=mk, ms=3, color=col, label=f"{ap}, Omega* = {om:g}")
        for ap in APPROACHES:
            for a in (top, bot):
                a.axvline(conv["counts"][(m.key, ap)], color=APPROACH_COLORS[ap], ls=":", lw=0.8)
        bot.axhline(cfg.conv_tol, color="k", lw=0.8, ls="--", label=f"tolerance {100 * cfg.conv_tol:g} %")
        for a in (top, bot):
            a.set_xscale("log", base=2)
            a.set_yscale("log")
            _grid(a)
            a.legend(fontsize=6)
        top.set_ylabel("steady amplitude max |v*|")
        bot.set_ylabel("|a(n) - a(next n)| / a(next n)")
        bot.set_xlabel("number of elements n")
        _title(top, m, "\n(dotted: count used; x on the axis: no periodic state)")
    fig.suptitle(f"Element-count convergence of the steady amplitude (eps = {cfg.eps:g})", fontsize=10)
    return fig
