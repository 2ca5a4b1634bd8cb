"""Figures 5 and 6 (steady amplitude against eps and against Omega*): one series per approach,
with every case that has no stable periodic state marked (plots.py states the conventions), the
shaded range beyond the theory, the geometrically exact rod (black) beside both models' panels,
and on Figure 6 the continuation of approach A."""

EXACT_COLOR = "#17becf"      # teal: apart from the approaches and the periods of the continuation


def _exact_series(ax, rows, xkey, mark_missing=True, label_speed=None, ls="-"):
    """The exact rod's rows (model "exact") of a panel, in black over the panel's approaches."""
    if not rows:
        return
    n = rows[0]["n_elements"]
    label = f"exact rod (n = {n})" + (f", Omega* = {label_speed:g}" if label_speed is not None else "")
    _sweep_series(ax, rows, xkey, EXACT_COLOR, ls, ".", label, mark_missing=mark_missing, ms=3,
                  slot=len(APPROACHES))

import math

import numpy as np

from ..plots.figures import APPROACH_COLORS, panels
from . import plot_bifurcations as PB
from .config import APPROACHES, EXACT, MODELS
from . import figures as F
from .figures import DIVERGED, STRAIN_LIMIT, THEORY_LIMIT
from .plot_style import (APPROACH_STYLES, SPEED_STYLES, Line2D, coincide_note, legend_below, legend_room,
                         panel_grid, panel_title, theory_handle)


def _sweep_series(ax, rows, xkey, color, ls, marker, label, mark_missing=True, ms=4, slot=0):
    """Line through the periodic points; markers for the other statuses (plots.py); the markers
    of cases without a value sit in the bottom strip at a height of their own per series (slot),
    so that two approaches missing at the same speed stay apart."""
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
    strained = [(r[xkey], F.response_of(r)) for r in rows if _strained(r)]
    if strained:        # a grey ring: beyond the theory by its axial strain
        ax.scatter(*zip(*strained), marker="o", s=95, facecolors="none", edgecolors="0.55",
                   linewidths=0.9, zorder=2)
    if mark_missing:    # inside the frame, at the bottom
        for kind, marker in (("diverged", "x"), ("failed", "+")):
            xs = [r[xkey] for r in rows if _missing_kind(r) == kind]
            if xs:
                ax.scatter(xs, np.full(len(xs), 0.022 + 0.025 * slot), transform=ax.get_xaxis_transform(),
                           marker=marker, color=color, s=40, zorder=5, linewidths=1.5)


def _missing_kind(r):
    """Why a sweep case has no value to draw: "diverged" (its run from rest diverged: the steady
    state's march, or the transient of an unstable / non-periodic case), "failed" (another
    failure, or a transient that never settled), or None (it has a value)."""
    if r["status"] == "periodic" or math.isfinite(r["envelope"]):
        return None
    note = r.get("envelope_note", "")
    if r["status"] == DIVERGED or note.startswith("the transient from rest diverged"):
        return "diverged"
    if r["status"] in ("unstable", "not-periodic") and not note:
        return None                 # no transient was run (envelope_revolutions = 0)
    return "failed"


def room_below(ax):
    """Extend the y range downwards by a strip (about 10 % of the height) for the 'x' markers of
    cases without a value, so that they never hide under data points."""
    lo, hi = ax.get_ylim()
    if ax.get_yscale() == "log":
        ax.set_ylim(lo / (hi / lo) ** 0.12, hi)
    else:
        ax.set_ylim(lo - 0.1 * (hi - lo), hi)
        ax.axhline(0.0, color="0.5", lw=0.6)


def _has_missing(rows):
    return any(_missing_kind(r) for r in rows)


def _off_scale(ax, rows, top, xkey):
    """Values above the y range (envelopes of non-periodic responses): filled triangles inside the
    frame at the top, in the series' colour."""
    for ap in APPROACHES:
        off = [r[xkey] for r in rows if r["approach"] == ap and r["status"] != "periodic"
               and math.isfinite(r["envelope"]) and r["envelope"] > top]
        if off:
            ax.scatter(off, np.full(len(off), 0.93), transform=ax.get_xaxis_transform(), marker="^",
                       color=APPROACH_COLORS[ap], edgecolors="k", linewidths=0.5, s=40, zorder=5,
                       clip_on=False)


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
    # a response just above the top would be cut by the frame: raise the top over it, so that
    # every hollow marker is either whole inside or well outside (then a filled one at the top)
    env = sorted(r["envelope"] for r in rows if math.isfinite(r.get("envelope", math.nan)))
    for v in env:
        if 0.95 * top < v <= 1.15 * top:
            top = 1.08 * v
    ax.set_ylim(0.0, top)
    _off_scale(ax, rows, top, xkey)


def _strained(r):
    """Whether a row's response exists and its axial strain is beyond the theory (the paper's: the
    exact rod has limits of its own, findings.md)."""
    if r.get("model") == EXACT.key:
        return False
    e = r.get("axial_strain", math.nan)
    return math.isfinite(F.response_of(r)) and e is not None and math.isfinite(e) and e > STRAIN_LIMIT


def _ring_handles(rows):
    if not any(_strained(r) for r in rows):
        return []
    return [Line2D([], [], ls="none", marker="o", ms=9, color="0.55", markerfacecolor="none",
                   label=f"grey ring: axial strain > {STRAIN_LIMIT:g}, beyond the theory")]


def _status_handles(rows, off_scale=False):
    out = []
    kinds = {r["status"] for r in rows}
    out += _ring_handles(rows)
    if any(_missing_kind(r) == "diverged" for r in rows):
        out.append(Line2D([], [], ls="none", marker="x", color="0.4",
                          label="x at the bottom: the run from rest diverged, no amplitude (approach B "
                                "is ill-posed: its strain energy is unbounded below)"))
    if any(_missing_kind(r) == "failed" for r in rows):
        out.append(Line2D([], [], ls="none", marker="+", color="0.4",
                          label="+ at the bottom: the run from rest failed or never settled (see CSV)"))
    if "unstable" in kinds:
        out.append(Line2D([], [], ls="none", marker="o", color="0.4", markerfacecolor="none",
                          label="hollow o: unstable periodic orbit"))
    if any(math.isfinite(r["envelope"]) for r in rows):
        out.append(Line2D([], [], ls="none", marker="^", color="0.4", markerfacecolor="none",
                          label="hollow ^: no stable periodic state: max |v*| of the settled transient from rest"))
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
    return coincide_note(pairs)


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
    return [theory_handle()]


def plot_figure5(data, cfg, counts):
    oms = list(cfg.fig5_omegas)
    fig, axes = panels(len(oms) + 1, 2, width=6.2, height=2.9, space_below=legend_room(10, 2), top_margin=0.8)
    for j, m in enumerate(MODELS):
        rows = [r for r in data["rows"] if r["model"] == m.key]
        for i in range(len(oms) + 1):
            ax = axes[i, j]
            log = i == len(oms)
            shown = oms if log else [oms[i]]
            sel_rows = [r for r in rows if r["omega"] in shown]
            exact_rows = [r for r in data["rows"] if r["model"] == EXACT.key and r["omega"] in shown]
            for k, om in enumerate(shown):
                speed_ls = SPEED_STYLES[k % len(SPEED_STYLES)][0]
                for ap in APPROACHES:
                    ls, mk, size = APPROACH_STYLES[ap]
                    sel = [r for r in rows if r["approach"] == ap and r["omega"] == om]
                    n = sel[0]["n_elements"] if sel else "?"
                    _sweep_series(ax, sel, "eps", APPROACH_COLORS[ap], speed_ls if log else ls, mk,
                                  f"{ap} (n = {n})" + (f", Omega* = {om:g}" if log else ""), ms=size, slot=APPROACHES.index(ap))
                _exact_series(ax, [r for r in exact_rows if r["omega"] == om], "eps",
                              label_speed=om if log else None, ls=speed_ls if log else "-")
            sel_rows = sel_rows + exact_rows
            ax.set_xlabel("eps")
            if log:
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_ylabel("max |v*| (log scale)")
                panel_title(ax, m, f"\nlog-log, Omega* = {', '.join(f'{o:g}' for o in oms)} "
                       "(solid, dashed)")
            else:
                ax.set_ylabel("steady amplitude max |v*|")
                _limit_to_steady(ax, sel_rows, "eps")
                panel_title(ax, m, f"\nOmega* = {oms[i]:g}")
            if _has_missing(sel_rows):
                room_below(ax)
            extra = _theory_curve(ax, "eps", None, sel_rows)
            note = None if log else _approach_coincidences(sel_rows, "eps")
            extra += _status_handles(sel_rows, off_scale=not log and _has_off_scale(ax, sel_rows))
            legend_below(ax, ncol=2, extra=extra + ([note] if note else []))
            panel_grid(ax)
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
    fig, axes = panels(n_rows, 2, width=6.4, height=2.9, space_below=legend_room(8 + n_bif, 2),
                       top_margin=1.0 if runs else 0.8)
    oms = sorted(set(cfg.fig6_omegas))
    step = float(np.min(np.diff(oms))) if len(oms) > 1 else 0.05
    xs = oms + ([float(x) for r in runs.values() for br in r.get("branches", []) for x in br["omega"]]
                if runs else [])
    xlim = (max(0.0, min(xs) - step / 2), max(xs) + step / 2)     # no marker cut at the edges
    # the magnified panels of one eps share one range: up to where A (periodic) last stays within
    # the magnified amplitudes in either model, never beyond the sweep
    zooms = {eps: (0.0, min(xlim[1], _zoom_end([r for r in data["rows"] if r["eps"] == eps],
                                               cfg.fig6_inset_ylim, oms) * 1.1 + step / 2))
             for eps in cfg.fig6_eps}
    for j, m in enumerate(MODELS):
        for i, eps in enumerate(cfg.fig6_eps):
            zoom_xlim = zooms[eps]
            rows = [r for r in data["rows"] if r["model"] == m.key and r["eps"] == eps]
            exact_rows = [r for r in data["rows"] if r["model"] == EXACT.key and r["eps"] == eps]
            run = runs.get(eps) if m is MODELS[1] else None
            for zoom in (False, True):
                ax = axes[2 * i + zoom, j]
                for ap in APPROACHES:
                    ls, mk, size = APPROACH_STYLES[ap]
                    sel = [r for r in rows if r["approach"] == ap]
                    n = sel[0]["n_elements"] if sel else "?"
                    _sweep_series(ax, sel, "omega", APPROACH_COLORS[ap], ls, mk, f"{ap} (n = {n})",
                                  mark_missing=not zoom, ms=size, slot=APPROACHES.index(ap))
                _exact_series(ax, exact_rows, "omega", mark_missing=not zoom)
                ax.set_xlabel("Omega*")
                ax.set_ylabel("steady amplitude max |v*|")
                if zoom:
                    ax.set_ylim(0, cfg.fig6_inset_ylim)
                    ax.set_xlim(*zoom_xlim)
                    panel_title(ax, m, f", eps = {eps:g}\nmagnified: v* from 0 to {cfg.fig6_inset_ylim:g}, "
                           f"Omega* from 0 to {zoom_xlim[1]:.2g}")
                    extra = _ring_handles([r for r in rows if zoom_xlim[0] <= r["omega"] <= zoom_xlim[1]
                                           and F.response_of(r) <= cfg.fig6_inset_ylim])
                else:
                    ax.set_xlim(*xlim)
                    _limit_to_steady(ax, rows + exact_rows, "omega",
                                     extra=[PB.top(run, xlim) * 1.05 / 1.25] if run else ())
                    ax.set_xlim(*xlim)
                    if _has_missing(rows + exact_rows):
                        room_below(ax)
                    panel_title(ax, m, f", eps = {eps:g}" + ("\nswept points and the continuation of approach A"
                                                        if run else ""))
                    extra = _status_handles(rows + exact_rows, off_scale=_has_off_scale(ax, rows + exact_rows))
                if run is not None:
                    extra = PB.draw(ax, run) + extra
                extra = _theory_curve(ax, "omega", eps, rows) + extra
                note = _approach_coincidences(rows, "omega")
                legend_below(ax, ncol=2, extra=extra + ([note] if note else []))
                panel_grid(ax)
    fig.suptitle("Figure 6: steady-state amplitude of v* against crank speed Omega*", fontsize=10)
    return fig


def _zoom_end(rows, ylim, oms):
    """Largest speed up to which approach A's periodic amplitude stays within ylim, in any model
    and eps of `rows` (the end of a magnified panel of Figure 6)."""
    ends = []
    for key in {(r["model"], r["eps"]) for r in rows}:
        a = sorted((r for r in rows if (r["model"], r["eps"]) == key and r["approach"] == "A"),
                   key=lambda r: r["omega"])
        last = None
        for r in a:
            if r["status"] != "periodic" or r["amplitude"] > ylim:
                break
            last = r["omega"]
        if last is not None:
            ends.append(last)
    return max(ends) if ends else max(oms)
