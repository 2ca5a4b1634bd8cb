"""exact_rod.png: the continuation of the consistent model (left) and of the geometrically exact
rod (right), one row per mechanism, on the same axes (data: exact_rod.py).  Branches in the colour
of their period, stable solid, unstable dashed; special points marked and labelled with their kind
and Omega* (plot_bifurcations.py); an exact-rod branch that ends before the range's end is marked
(x) where it ends (where the continuation stopped: the element has no rotation limit), its sections'
largest rotation from the chord there in the legend.  On the exact rod's panels the response marched
from rest at exact_character_omegas (a star at its max |v*|, its class and Lyapunov exponent in the
legend) where it is not one of the drawn orbits."""

import math

from ..plots.figures import panels
from . import plot_bifurcations as PB
from .plot_style import legend_below, panel_grid

TITLES = {"consistent": "consistent model (approach A)", "exact": "exact rod"}


def plot_exact_rod(data, cfg):
    runs = {(r["mechanism"], r["model"]): r for r in data["runs"]}
    names = list(dict.fromkeys(r["mechanism"] for r in data["runs"]))
    fig, axes = panels(len(names), 2, width=6.2, height=3.2, space_below=0.9, top_margin=0.9)
    lo, hi = data["settings"]["range"]
    for i, name in enumerate(names):
        tops = [PB.top(r) for r in (runs.get((name, "consistent")), runs.get((name, "exact")))
                if r is not None and r["status"] == "ok"]
        ymax = 1.08 * max([t for t in tops if math.isfinite(t)] or [1.0])
        for j, key in enumerate(("consistent", "exact")):
            ax = axes[i, j]
            run = runs.get((name, key))
            ax.set_xlim(lo - 0.02, hi + 0.02)
            ax.set_ylim(0, ymax)
            extra = []
            if run is not None:
                PB.draw(ax, run)
                extra = _handles(run)
                for br in run["branches"]:
                    end = br.get("end")
                    if end and math.isfinite(end.get("section_rotation_deg", math.nan)):
                        ax.plot([end["omega"]], [end["amplitude"]], "x", color="k", ms=8, mew=1.6, zorder=7)
                        extra.append(_end_handle(br["period"], end))
                if key == "exact":
                    extra += _characters(ax, data, name)
            n = run["n_elements"] if run else "?"
            ax.set_title(f"{name}, {TITLES[key]}, eps = {data['settings']['eps']:g}, n = {n}", fontsize=9)
            ax.set_xlabel("Omega*")
            ax.set_ylabel("max |v*| over the orbit")
            legend_below(ax, ncol=3, extra=extra)
            panel_grid(ax)
    fig.suptitle("The consistent model's branches and special points, and the exact rod's", fontsize=10)
    return fig


def _handles(run):
    from matplotlib.lines import Line2D
    if run["status"] != "ok":
        return [Line2D([], [], ls="none", label="continuation failed (see findings.md)")]
    out = [Line2D([], [], color=PB._color(k), lw=1.3, label=f"period {k}")
           for k in sorted({br["period"] for br in run["branches"]})]
    out += [Line2D([], [], color="0.3", lw=1.3, label="stable"),
            Line2D([], [], color="0.3", lw=1.0, ls=(0, (4, 2)), label="unstable")]
    kinds = {s["kind"] for s in run["special_points"]}
    out += [Line2D([], [], ls="none", marker=m, markerfacecolor="white", color="black",
                   label=f"{PB.LABELS[kind]}: {kind}") for kind, m in PB.MARKERS.items() if kind in kinds]
    return out


def _end_handle(period, end):
    from matplotlib.lines import Line2D
    return Line2D([], [], ls="none", marker="x", color="k",
                  label=f"period-{period} branch ends at Omega* = {end['omega']:.4g}: sections turned "
                        f"{end['section_rotation_deg']:.1f} deg from the chord (where the continuation stopped)")


def _characters(ax, data, name):
    """Stars at the exact rod's marched responses that are not period-k orbits (classified by
    exact_rod.py's character step), with a legend entry each."""
    from matplotlib.lines import Line2D
    out = []
    for c in data.get("characters", []):
        if c["mechanism"] != name or c["status"] != "ok":
            continue
        for q in c["points"]:
            if str(q["classification"]).startswith("period-") or q.get("amplitude") is None:
                continue
            ax.plot([q["omega"]], [q["amplitude"]], "*", color="0.25", ms=10, zorder=8)
            lyap = q.get("lyapunov")
            out.append(Line2D([], [], ls="none", marker="*", color="0.25", ms=9,
                              label=f"march from rest: {q['classification']}"
                                    + (f", Lyapunov {lyap:+.2f}" if lyap is not None else "")))
    return out
