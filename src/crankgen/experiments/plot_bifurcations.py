"""The continuation of approach A drawn over Figure 6 (data: bifurcations.py): each branch in the
colour of its period, stable solid, unstable dashed; special points marked (square fold, circle
period doubling, diamond Neimark-Sacker) and labelled with their kind and Omega*."""

import math

import numpy as np

LABELS = {"fold": "F", "period-doubling": "PD", "neimark-sacker": "NS"}
MARKERS = {"fold": "s", "period-doubling": "o", "neimark-sacker": "D"}
from ..analyses.bifurcation.diagram import PERIOD_COLORS  # noqa: E402  (one colour per period, everywhere)
FONT = 8


def _color(period):
    return PERIOD_COLORS.get(period, "0.4")


def top(run, xlim=None):
    """Largest branch amplitude (within xlim), for the y range; nan without branches."""
    vals = []
    for br in run["branches"]:
        om, amp = br["omega"], br["amplitude"]
        sel = np.ones(len(om), bool) if xlim is None else (om >= xlim[0]) & (om <= xlim[1])
        vals += list(amp[sel & np.isfinite(amp)])
    return max(vals) if vals else math.nan


def legend_handles(run, ax=None):
    """Legend entries of one continuation record (periods, stable / unstable, special points);
    with ax, only those of what lies within its limits."""
    from matplotlib.lines import Line2D

    if run["status"] != "ok":
        return [Line2D([], [], ls="none", label="continuation of A failed (see findings.md)")]
    inside = (lambda x, y: True) if ax is None else _inside(ax)
    branches = [br for br in run["branches"]
                if any(inside(x, y) for x, y in zip(br["omega"], br["amplitude"]))]
    n = run["n_elements"]
    out = [Line2D([], [], color=_color(k), lw=1.3, label=f"continuation of A (n = {n}), period {k}")
           for k in sorted({br["period"] for br in branches})]
    if branches:
        out += [Line2D([], [], color="0.3", lw=1.3, label="continuation: stable"),
                Line2D([], [], color="0.3", lw=1.0, ls=(0, (4, 2)), label="continuation: unstable")]
    kinds = {s["kind"] for s in run["special_points"] if inside(s["omega"], s["amplitude"])}
    out += [Line2D([], [], ls="none", marker=m, markerfacecolor="white", color="black",
                   label=f"{LABELS[kind]}: {kind}") for kind, m in MARKERS.items() if kind in kinds]
    return out


def _inside(ax):
    (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
    return lambda x, y: x0 <= x <= x1 and y0 <= y <= y1


def draw(ax, run, label_points=True):
    """Branches and special points of one continuation record on ax (axis limits already set);
    returns the legend handles of what is visible."""
    if run["status"] != "ok":
        return legend_handles(run)
    for br in run["branches"]:
        c = _color(br["period"])
        om, amp, st = br["omega"], br["amplitude"], br["stable"]
        start = 0
        for i in range(1, len(om) + 1):
            if i == len(om) or st[i] != st[start]:
                j = min(i + 1, len(om))          # join each run to the next point: no gap
                ax.plot(om[start:j], amp[start:j], color=c, ls="-" if st[start] else (0, (4, 2)),
                        lw=1.3 if st[start] else 1.0, zorder=3.5)
                start = i
    pts = sorted(run["special_points"], key=lambda s: s["omega"])
    for kind, m in MARKERS.items():
        sel = [s for s in pts if s["kind"] == kind]
        if sel:
            ax.scatter([s["omega"] for s in sel], [s["amplitude"] for s in sel], marker=m, s=34,
                       facecolor="white", edgecolor=[_color(s["period"]) for s in sel],
                       linewidths=1.3, zorder=6)
    if label_points:
        _labels(ax, [s for s in pts if _inside(ax)(s["omega"], s["amplitude"])])
    return legend_handles(run, ax)


def _labels(ax, pts):
    """Kind and Omega* beside each special point, where the text covers no drawn point or line,
    no other label, and stays inside the frame (crankgen.plots.figures.place_labels)."""
    from ..plots.figures import place_labels
    place_labels(ax, [(s["omega"], s["amplitude"], f"{LABELS[s['kind']]} {s['omega']:.4g}",
                       _color(s["period"])) for s in pts], fontsize=FONT)
