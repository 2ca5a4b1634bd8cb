"""Plots of Figures 2-8 and of the convergence check: paper model | consistent model side by side.
Nothing is dropped: a failed transient is drawn up to its failure, marked with a large 'x' there;
sweep cases without a value get an 'x' inside the frame at the bottom, off-scale values a
triangle inside the frame at the top (both in the series' colour); hollow markers for unstable
orbits and non-periodic responses; deflections beyond the theory (|v|/L > 0.1) lie in a shaded
band.  Curves that coincide keep distinct markers and line styles, and the legend says so.
Legends sit outside the axes; no text is smaller than 8 pt."""

import math

import numpy as np

from ..plotting import APPROACH_COLORS, mark_at_axis, panels
from . import findings as fd
from . import plot_bifurcations as PB
from .config import APPROACHES, MODELS
from .figures import THEORY_LIMIT

FONT = 8                                   # legends, insets, annotations (pt)
# per approach: line style and marker, so that coinciding curves stay visible
APPROACH_STYLES = {"A": ("-", "o", 4), "B": ("--", "s", 6), "C": (":", "^", 4)}

_SPEED_STYLES = [("-", "o"), ("--", "s"), (":", "D"), ("-.", "v")]


def _title(ax, model, extra=""):
    ax.set_title(f"{model.label}{extra}", fontsize=9)


def _grid(ax):
    ax.grid(alpha=0.3)


def _transient(ax, curve, color, ls="-", label=None, lw=1.0):
    """A transient curve; a failed run up to its failure (its 'X' is drawn by _transient_axes)."""
    if not curve.ok:
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
    lo, hi = ax.get_ylim()
    for a, b in ((lim, max(hi, lim)), (min(lo, -lim), -lim)):
        if b > a:
            ax.axhspan(a, b, color="0.85", zorder=0, lw=0)
    ax.set_ylim(lo, hi)
    return True


def _theory_handle():
    from matplotlib.patches import Patch
    return Patch(color="0.85", label=f"|v|/L > {THEORY_LIMIT:g}: beyond the theory")


def _legend(ax, handles=None, labels=None, ncol=1, extra=()):
    """Legend below the axes (outside them, so that it covers no data), 8 pt."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    handles, labels = list(handles) + list(extra), list(labels) + [h.get_label() for h in extra]
    if not handles:
        return
    fig = ax.figure
    h_in = ax.get_position().height * fig.get_figheight()
    ax.legend(handles, labels, fontsize=FONT, loc="upper center", ncol=ncol, frameon=False,
              bbox_to_anchor=(0.5, -0.55 / h_in), handlelength=2.6, columnspacing=1.2)


def _coincide_note(pairs):
    """Legend entry for series that coincide: pairs of (name_a, name_b, max relative difference);
    names joined in groups (connected by differences below 1 %)."""
    groups = []
    for a, b, d in pairs:
        if d is None or not math.isfinite(d) or d >= 0.01:
            continue
        hit = [g for g in groups if a in g or b in g]
        merged = [a, b] + [x for g in hit for x in g]
        groups = [g for g in groups if g not in hit] + [list(dict.fromkeys(merged))]
    if not groups:
        return None
    order = list(dict.fromkeys(x for a, b, _ in pairs for x in (a, b)))
    text = "; ".join(_compact(sorted(g, key=order.index)) for g in groups)
    return Line2D([], [], ls="none", label=f"{text}: coincide to 1 %")


def _compact(names):
    """"C ms* = 0", "C ms* = 1" -> "C ms* = 0, 1" (names sharing the text before their last '= ')."""
    heads = {n.rpartition("= ")[0] for n in names}
    if len(heads) == 1 and all("= " in n for n in names):
        return heads.pop() + "= " + ", ".join(n.rpartition("= ")[2] for n in names)
    return ", ".join(names)


def _curve_coincidences(curves, name):
    """_coincide_note over all pairs of successful transient curves."""
    ok = [c for c in curves if c.ok]
    return _coincide_note([(name(a), name(b), _curve_pair_diff(a, b))
                           for i, a in enumerate(ok) for b in ok[i + 1:]])


def Line2D(*a, **k):
    from matplotlib.lines import Line2D as L
    return L(*a, **k)


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
            ax.annotate(f"v* = {v:.3g}", (t, y), xytext=(8, (-2 - 10 * k) if v > 0 else (2 + 10 * k)),
                        textcoords="offset points", fontsize=FONT, color=col,
                        va="top" if v > 0 else "bottom")
        else:
            ax.plot([t], [v], ls="none", marker="X", ms=9, color=col, markeredgecolor="k", zorder=6)
    vmax = max([c.max_abs for c in curves if c.has_history] or [math.nan])
    extra = []
    if bad:
        extra.append(Line2D([], [], ls="none", marker="X", ms=8, color="0.6", markeredgecolor="k",
                            label="X: run failed here (history kept)"))
    if _theory_band(ax, eps, vmax):
        extra.append(_theory_handle())
    return extra


_LINESTYLES = ["-", "--", "-.", ":", (0, (5, 1, 1, 1))]


def _ls(k):
    return _LINESTYLES[k % len(_LINESTYLES)]


def _colors(n):
    import matplotlib
    cmap = matplotlib.colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.72, max(n, 1))]


def _below(n_entries, ncol):
    """Inches of legend room below a panel for n_entries in ncol columns (plus the x label)."""
    return 0.3 + 0.17 * math.ceil(max(n_entries, 1) / ncol)


def _curve_pair_diff(a, b):
    from .figures import transient_difference
    return transient_difference(a, b)


def plot_figure2(data, cfg, counts):
    n_max = max(len({c.spec.n_elements for c in data["curves"] if c.spec.model == m.key
                     and c.spec.approach == ap}) for m in MODELS for ap in APPROACHES)
    fig, axes = panels(3, 2, width=6.2, height=2.4, space_below=_below(n_max + 1, 3), top_margin=0.95)
    for j, m in enumerate(MODELS):
        for i, ap in enumerate(APPROACHES):
            ax = axes[i, j]
            cs = [c for c in data["curves"] if c.spec.model == m.key and c.spec.approach == ap]
            for k, (c, col) in enumerate(zip(cs, _colors(len(cs)))):
                _transient(ax, c, col, ls=_ls(k), label=f"n = {c.spec.n_elements}", lw=1.0 + 0.6 * (k == 0))
            extra = _transient_axes(ax, cs, cfg.eps)
            note = _curve_coincidences(cs, lambda c: f"n = {c.spec.n_elements}")
            _title(ax, m, f"\napproach {ap}, Omega* = {cfg.fig2_omega:g}")
            ax.set_ylabel("v* at x* = 1/2")
            ax.tick_params(labelbottom=True)
            ax.set_xlabel("t*")
            _legend(ax, ncol=3, extra=extra + ([note] if note else []))
            _grid(ax)
    fig.suptitle(f"Figure 2: transient v*, approaches A, B, C (eps = {cfg.eps:g}, ms* = {cfg.ms:g})",
                 fontsize=10)
    return fig


def plot_figure3(data, cfg, counts):
    n = max(len([c for c in data["curves"] if c.spec.model == m.key]) for m in MODELS)
    fig, axes = panels(1, 2, width=6.2, height=3.4, space_below=_below(n + 1, 2), top_margin=0.95)
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
        note = _coincide_note(pairs)
        _title(ax, m, f"\napproach A, Omega* = {cfg.fig3_omega:g}")
        ax.set_xlabel("t*")
        ax.set_ylabel("v* at x* = 1/2")
        _legend(ax, ncol=2, extra=extra + ([note] if note else []))
        _grid(ax)
    fig.suptitle("Figure 3: convergence of approach A with the number of elements", fontsize=10)
    return fig


def plot_figure4(data, cfg, counts):
    masses = sorted({c.spec.ms for c in data["curves"] if c.spec.approach != "A"})
    fig, axes = panels(2, 2, width=6.2, height=3.0, space_below=_below(2 * len(masses) + 4, 2), top_margin=0.95)
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
        _title(ax, m, f"\nOmega* = {cfg.fig4_omega:g}, ms* = {cfg.ms:g}")
        ax.set_ylabel("v* at x* = 1/2")
        ax.set_xlabel("t*")
        _legend(ax, ncol=2, extra=extra)
        _grid(ax)
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
        _title(ax, m, "\nslider mass: B (solid) and C (dashed)")
        ax.set_xlabel("t*")
        ax.set_ylabel("v* at x* = 1/2")
        _legend(ax, ncol=2, extra=extra)
        _grid(ax)
    fig.suptitle(f"Figure 4: transient v* at high speed (eps = {cfg.eps:g}; X: where a run failed)",
                 fontsize=10)
    return fig


def _sweep_series(ax, rows, xkey, color, ls, marker, label, mark_missing=True, ms=4):
    """Line through the periodic points; markers for the other statuses (see module docstring)."""
    rows = sorted(rows, key=lambda r: r[xkey])
    x = np.array([r[xkey] for r in rows], dtype=float)
    y = np.array([r["amplitude"] for r in rows], dtype=float)
    hollow = marker in ("s", "D")
    ax.plot(x, y, ls=ls, marker=marker, ms=ms, color=color, lw=1.2, label=label,
            markerfacecolor="none" if hollow else color, markeredgewidth=1.1)
    unst = [r for r in rows if r["status"] == "unstable" and math.isfinite(r["orbit_amplitude"])]
    if unst:
        ax.scatter([r[xkey] for r in unst], [r["orbit_amplitude"] for r in unst], marker="o",
                   facecolors="none", edgecolors=color, s=30, zorder=4)
    env = [r for r in rows if r["status"] != "periodic" and math.isfinite(r["envelope"])]
    if env:
        ax.scatter([r[xkey] for r in env], [r["envelope"] for r in env], marker="^",
                   facecolors="none", edgecolors=color, s=34, zorder=4)
    if mark_missing:
        missing = [r[xkey] for r in rows if r["status"] != "periodic" and not math.isfinite(r["envelope"])]
        if missing:     # inside the frame, at the bottom
            ax.scatter(missing, np.full(len(missing), 0.04), transform=ax.get_xaxis_transform(),
                       marker="x", color=color, s=40, zorder=5, linewidths=1.5)


def _room_below(ax):
    """Extend the y range downwards by a strip (about 10 % of the height) for the 'x' markers of
    cases without a value, so that they never hide under data points."""
    lo, hi = ax.get_ylim()
    if ax.get_yscale() == "log":
        ax.set_ylim(lo / (hi / lo) ** 0.12, hi)
    else:
        ax.set_ylim(lo - 0.1 * (hi - lo), hi)
        ax.axhline(0.0, color="0.5", lw=0.6)


def _has_missing(rows):
    return any(r["status"] != "periodic" and not math.isfinite(r["envelope"]) for r in rows)


def _off_scale(ax, rows, top, xkey):
    """Values above the y range (envelopes of non-periodic responses): filled triangles inside the
    frame at the top, in the series' colour."""
    for ap in APPROACHES:
        off = [r[xkey] for r in rows if r["approach"] == ap and r["status"] != "periodic"
               and math.isfinite(r["envelope"]) and r["envelope"] > top]
        if off:
            ax.scatter(off, np.full(len(off), 0.95), transform=ax.get_xaxis_transform(), marker="^",
                       color=APPROACH_COLORS[ap], edgecolors="k", linewidths=0.5, s=40, zorder=5)


def _limit_to_steady(ax, rows, xkey, margin=1.25, extra=()):
    """Linear y axis scaled to the steady amplitudes (periodic and unstable orbits, and the
    `extra` values: continuation branches); responses beyond it are marked at the top inside the
    frame, so they never squash the curves."""
    vals = [r["amplitude"] for r in rows if math.isfinite(r["amplitude"])]
    vals += [r["orbit_amplitude"] for r in rows if r["status"] == "unstable"
             and math.isfinite(r["orbit_amplitude"])]
    vals += [v for v in extra if math.isfinite(v)]
    if not vals:
        return
    top = margin * max(vals)
    ax.set_ylim(0.0, top)
    _off_scale(ax, rows, top, xkey)


def _status_handles(rows, off_scale=False):
    out = []
    kinds = {r["status"] for r in rows}
    if any(r["status"] != "periodic" and not math.isfinite(r["envelope"]) for r in rows):
        out.append(Line2D([], [], ls="none", marker="x", color="0.4", label="x at the bottom: no steady response (run failed)"))
    if "unstable" in kinds:
        out.append(Line2D([], [], ls="none", marker="o", color="0.4", markerfacecolor="none",
                          label="hollow o: unstable periodic orbit"))
    if any(math.isfinite(r["envelope"]) for r in rows):
        out.append(Line2D([], [], ls="none", marker="^", color="0.4", markerfacecolor="none",
                          label="hollow ^: non-periodic, max |v*| of a transient"))
    if off_scale:
        out.append(Line2D([], [], ls="none", marker="^", color="0.4", markeredgecolor="k",
                          label="filled ^ at the top: off scale (value in the CSV)"))
    return out


def _has_off_scale(ax, rows):
    top = ax.get_ylim()[1]
    return any(r["status"] != "periodic" and math.isfinite(r["envelope"]) and r["envelope"] > top for r in rows)


def _approach_coincidences(rows, xkey):
    """Pairs of approaches whose amplitudes agree within 1 % at every common point."""
    by = {ap: {r[xkey]: r["amplitude"] for r in rows if r["approach"] == ap} for ap in APPROACHES}
    pairs = []
    for i, a in enumerate(APPROACHES):
        for b in APPROACHES[i + 1:]:
            xs = [x for x in by[a] if x in by[b] and math.isfinite(by[a][x]) and math.isfinite(by[b][x])]
            d = max((abs(by[b][x] / by[a][x] - 1) for x in xs if by[a][x] != 0), default=None)
            pairs.append((a, b, d))
    return _coincide_note(pairs)


def _theory_curve(ax, xkey, eps_fixed, rows):
    """Shade |v|/L > THEORY_LIMIT (v* > THEORY_LIMIT / eps) where the data reach it."""
    vals = [r["deflection_over_L"] for r in rows if math.isfinite(r.get("deflection_over_L", math.nan))]
    if not vals or max(vals) <= THEORY_LIMIT:
        return []
    lo, hi = ax.get_ylim()
    if xkey == "eps":
        x = np.geomspace(*sorted(ax.get_xlim()), 200) if ax.get_xscale() == "log" else np.linspace(*sorted(ax.get_xlim()), 200)
        lim = THEORY_LIMIT / x
        ax.fill_between(x, lim, max(hi, lim.max()), color="0.85", zorder=0, lw=0)
        ax.set_xlim(x[0], x[-1])
    else:
        lim = THEORY_LIMIT / eps_fixed
        if lim >= hi:
            return []
        ax.axhspan(lim, hi, color="0.85", zorder=0, lw=0)
    ax.set_ylim(lo, hi)
    return [_theory_handle()]


def plot_figure5(data, cfg, counts):
    oms = list(cfg.fig5_omegas)
    fig, axes = panels(len(oms) + 1, 2, width=6.2, height=2.9, space_below=_below(8, 2), top_margin=0.8)
    for j, m in enumerate(MODELS):
        rows = [r for r in data["rows"] if r["model"] == m.key]
        for i in range(len(oms) + 1):
            ax = axes[i, j]
            log = i == len(oms)
            shown = oms if log else [oms[i]]
            sel_rows = [r for r in rows if r["omega"] in shown]
            for k, om in enumerate(shown):
                speed_ls = _SPEED_STYLES[k % len(_SPEED_STYLES)][0]
                for ap in APPROACHES:
                    ls, mk, size = APPROACH_STYLES[ap]
                    sel = [r for r in rows if r["approach"] == ap and r["omega"] == om]
                    n = sel[0]["n_elements"] if sel else "?"
                    _sweep_series(ax, sel, "eps", APPROACH_COLORS[ap], speed_ls if log else ls, mk,
                                  f"{ap} (n = {n})" + (f", Omega* = {om:g}" if log else ""), ms=size)
            ax.set_xlabel("eps")
            if log:
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_ylabel("max |v*| (log scale)")
                _title(ax, m, f"\nlog-log, Omega* = {', '.join(f'{o:g}' for o in oms)} "
                       "(solid, dashed)")
            else:
                ax.set_ylabel("steady amplitude max |v*|")
                _limit_to_steady(ax, sel_rows, "eps")
                _title(ax, m, f"\nOmega* = {oms[i]:g}")
            if _has_missing(sel_rows):
                _room_below(ax)
            extra = _theory_curve(ax, "eps", None, sel_rows)
            note = None if log else _approach_coincidences(sel_rows, "eps")
            extra += _status_handles(sel_rows, off_scale=not log and _has_off_scale(ax, sel_rows))
            _legend(ax, ncol=2, extra=extra + ([note] if note else []))
            _grid(ax)
    fig.suptitle("Figure 5: steady-state amplitude of v* against slenderness eps", fontsize=10)
    return fig


def plot_figure6(data, cfg, counts, bifurcations=None):
    """Steady amplitude against Omega*; with `bifurcations` (bifurcations.py), the continuation
    of approach A drawn over the consistent model's panels."""
    n_rows = 2 * len(cfg.fig6_eps)
    runs = {}
    for r in (bifurcations or {}).get("runs", []):
        if r["model"] == MODELS[1].key:
            runs[r["eps"]] = r
    n_bif = max((len(PB.legend_handles(r)) for r in runs.values()), default=0)
    fig, axes = panels(n_rows, 2, width=6.4, height=2.9, space_below=_below(7 + n_bif, 2),
                       top_margin=1.0 if runs else 0.8)
    for j, m in enumerate(MODELS):
        for i, eps in enumerate(cfg.fig6_eps):
            rows = [r for r in data["rows"] if r["model"] == m.key and r["eps"] == eps]
            run = runs.get(eps) if m is MODELS[1] else None
            for zoom in (False, True):
                ax = axes[2 * i + zoom, j]
                for ap in APPROACHES:
                    ls, mk, size = APPROACH_STYLES[ap]
                    sel = [r for r in rows if r["approach"] == ap]
                    n = sel[0]["n_elements"] if sel else "?"
                    _sweep_series(ax, sel, "omega", APPROACH_COLORS[ap], ls, mk, f"{ap} (n = {n})",
                                  mark_missing=not zoom, ms=size)
                ax.set_xlabel("Omega*")
                ax.set_ylabel("steady amplitude max |v*|")
                if zoom:
                    ax.set_ylim(0, cfg.fig6_inset_ylim)
                    lo = [r["omega"] for r in rows if r["status"] == "periodic"
                          and r["amplitude"] <= cfg.fig6_inset_ylim]
                    if lo:
                        ax.set_xlim(0, max(lo) * 1.15)
                    _title(ax, m, f", eps = {eps:g}\nmagnified: v* from 0 to {cfg.fig6_inset_ylim:g}")
                    extra = []
                else:
                    xlim = ax.get_xlim()
                    _limit_to_steady(ax, rows, "omega",
                                     extra=[PB.top(run, xlim) * 1.05 / 1.25] if run else ())
                    ax.set_xlim(*xlim)
                    if _has_missing(rows):
                        _room_below(ax)
                    _title(ax, m, f", eps = {eps:g}" + ("\nswept points and the continuation of approach A"
                                                        if run else ""))
                    extra = _status_handles(rows, off_scale=_has_off_scale(ax, rows))
                if run is not None:
                    extra = PB.draw(ax, run) + extra
                extra = _theory_curve(ax, "omega", eps, rows) + extra
                note = _approach_coincidences(rows, "omega")
                _legend(ax, ncol=2, extra=extra + ([note] if note else []))
                _grid(ax)
    fig.suptitle("Figure 6: steady-state amplitude of v* against crank speed Omega*", fontsize=10)
    return fig


def plot_extension(data, cfg, counts):
    cs_all = data["curves"]
    n_leg = max(len([c for c in cs_all if c["model"] == m.key]) for m in MODELS) + 2
    fig, axes = panels(1, 2, width=6.2, height=3.4, space_below=_below(n_leg, 2), top_margin=0.95)
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
            else:
                ax.plot([], [], ls="none", marker="x", color=col, label=f"{label}: no periodic state ({c['status']})")
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
            extra.append(Line2D([], [], ls="none", label="beyond the theory (|v|/L > 0.1): ms* = "
                                + ", ".join(f"{c['ms']:g}" for c in flagged)))
        n = cs[0]["n_elements"] if cs else "?"
        _title(ax, m, f"\napproach A, n = {n}, Omega* = {data['omega']:g}")
        ax.set_xlabel("crank angle theta (degrees)")
        ax.set_ylabel("extension delta*")
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 60))
        _legend(ax, ncol=2, extra=extra)
        _grid(ax)
    fig.suptitle(f"Figure {data['figure']}: extension of the neutral axis over a steady revolution",
                 fontsize=10)
    return fig


def plot_figure(data, cfg, counts, bifurcations=None):
    f = data["figure"]
    if f == 6:
        return plot_figure6(data, cfg, counts, bifurcations)
    fn = {2: plot_figure2, 3: plot_figure3, 4: plot_figure4, 5: plot_figure5, 7: plot_extension,
          8: plot_extension}[f]
    return fn(data, cfg, counts)


def plot_convergence(conv, cfg):
    """Top: steady amplitude against n; bottom: relative change to the next count and the tolerance."""
    fig, axes = panels(2, 2, width=6.2, height=3.0, space_below=_below(3 * len(cfg.conv_omegas) + 2, 2),
                       top_margin=0.95)
    for j, m in enumerate(MODELS):
        top, bot = axes[0, j], axes[1, j]
        pairs = []
        for k, om in enumerate(cfg.conv_omegas):
            speed_ls = _SPEED_STYLES[k % len(_SPEED_STYLES)][0]
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
                bad = [r["n_elements"] for r in rows if r["status"] != "periodic"]
                if bad:
                    top.scatter(bad, np.full(len(bad), 0.04), transform=top.get_xaxis_transform(),
                                marker="x", color=col, s=40, zorder=5)
                ch = [(r["n_elements"], r["change_to_next"]) for r in rows
                      if math.isfinite(r.get("change_to_next", math.nan)) and r["change_to_next"] > 0]
                if ch:
                    bot.plot(*zip(*ch), label=f"{ap}, Omega* = {om:g}", **style)
            for a, b in (("A", "B"), ("A", "C"), ("B", "C")):
                common = [n for n in amps[a] if n in amps[b] and math.isfinite(amps[a][n])
                          and math.isfinite(amps[b][n]) and amps[a][n] != 0]
                d = max((abs(amps[b][n] / amps[a][n] - 1) for n in common), default=None)
                pairs.append((f"{a}@{om:g}", f"{b}@{om:g}", d))
        for ap in APPROACHES:
            for a in (top, bot):
                a.axvline(conv["counts"][(m.key, ap)], color=APPROACH_COLORS[ap], ls=":", lw=1.0)
        bot.axhline(cfg.conv_tol, color="k", lw=0.8, ls="--", label=f"tolerance {100 * cfg.conv_tol:g} %")
        for a in (top, bot):
            a.set_xscale("log", base=2)
            a.set_yscale("log")
            _grid(a)
        if any(r["status"] != "periodic" for r in conv["rows"] if r["model"] == m.key):
            top.autoscale_view()
            _room_below(top)
        note = _coincide_note(pairs)
        extra = [Line2D([], [], color="0.4", ls=":", label="vertical dotted: count used")]
        if any(r["status"] != "periodic" for r in conv["rows"] if r["model"] == m.key):
            extra.append(Line2D([], [], ls="none", marker="x", color="0.4", label="x at the bottom: no periodic state"))
        _legend(top, ncol=2, extra=extra + ([note] if note else []))
        _legend(bot, ncol=2)
        top.set_ylabel("steady amplitude max |v*|")
        top.set_xlabel("number of elements n")
        bot.set_ylabel("|a(n) - a(next n)| / a(next n)")
        bot.set_xlabel("number of elements n")
        _title(top, m, "\nsteady amplitude against n")
        _title(bot, m, "\nchange to the next count")
    fig.suptitle(f"Element-count convergence of the steady amplitude (eps = {cfg.eps:g})", fontsize=10)
    return fig
