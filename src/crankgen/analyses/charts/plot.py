"""The stability chart as a figure: the regions filled and named in words, the curves (fold,
period doubling, Neimark-Sacker; solid for the crank-period orbits, dashed for period 2), the
codimension-two points marked, the lines of constant y that named the regions, and the range beyond
the theory hatched.  Axes in the parameters as the schema names them."""

import numpy as np

from ...declaration import schema
from ..bifurcation.curve import LABELS
from ...results.io import save_figure

KIND_COLORS = {"fold": "#1f3b73", "period-doubling": "#9b1c1c", "neimark-sacker": "#1b6e3a"}
PERIOD_STYLES = {1: "-", 2: "--", 4: ":"}
FILL = {"period-1": "#e3f1dc", "period-2": "#e9dcf2", "period-4": "#d6ece8", "coexist": "#fbe3c0",
        "coexist-2": "#f6cfa6", "none": "#ececec", "unknown": "#ffffff"}
BEYOND_HATCH = "////"
MIN_NAMED = 0.005         # pieces smaller than this (share of the box) are named in the legend only
ROOM = 1.3                # raster cells from a piece's middle to its edge per character of its name


def axis_text(name):
    """The axis text of a parameter from its schema record: its description and units."""
    p = schema.PARAMETERS[name]
    text = p.label.split("(", 1)[1].rsplit(")", 1)[0] if "(" in p.label else p.label
    return text + ("" if p.units in ("1", "") else f" (units of {p.units})")


def fill_color(region):
    if region.key is None:
        return FILL["unknown"]
    total = sum(n for _, n in region.key)
    if total == 0:
        return FILL["none"]
    if total >= 2:
        return FILL["coexist"] if len(region.key) > 1 else FILL["coexist-2"]
    return FILL.get(f"period-{region.key[0][0]}", "#dde3ea")


def _rgb(color):
    from matplotlib.colors import to_rgb
    return to_rgb(color)


def chart_title(chart):
    """Two lines: the plane and the model; every other parameter that sets the response (both axes
    left out)."""
    from ..bifurcation.diagram import axis
    info, xn, yn = chart.info, chart.x[0], chart.y[0]
    from ...plots.figures import model_parts
    parts = model_parts(info)
    main, other = schema.describe({k: v for k, v in info.items() if k in schema.PARAMETERS}, skip=(xn, yn))
    return (f"stability chart in ({axis(xn)}, {axis(yn)}): " + ", ".join(p for p in parts if p)
            + "\n" + ", ".join(main + other))


def plot_chart(chart, path, title=None):
    """chart_figure written atomically to path (returned)."""
    from ...results.io import output_path
    path = output_path(path)
    save_figure(chart_figure(chart, title), path, dpi=130)
    return path


def chart_figure(chart, title=None):
    """The chart's figure (module docstring), laid out from measurements."""
    from matplotlib import rc_context
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    from ...plots.figures import fit_panels, panels, place_labels

    xn, x_lo, x_hi = chart.x
    yn, y_lo, y_hi = chart.y
    fig, axes = panels(1, 1, width=7.8, height=5.2)
    ax = axes[0, 0]
    # regions
    colors = {0: (0.35, 0.35, 0.35)}
    for g in chart.regions:
        colors[g.index] = _rgb(fill_color(g))
    img = np.array([[colors.get(int(v), (1, 1, 1)) for v in row] for row in chart.labels])
    ax.imshow(img, origin="lower", extent=(x_lo, x_hi, y_lo, y_hi), aspect="auto", interpolation="nearest",
              zorder=0)
    # each verdict once in the legend, with a letter for the pieces too narrow for its words
    handles, letters = [], {}
    for g in sorted(chart.regions, key=lambda g: -g.area):
        if g.words not in letters and (g.key is not None or g.area >= MIN_NAMED):
            letters[g.words] = "abcdefghijklmnopqrstuvwxyz"[len(letters) % 26]
            handles.append(Patch(facecolor=fill_color(g), edgecolor="0.6", lw=0.5,
                                 label=f"{letters[g.words]}: {g.words}"))
    # beyond the theory
    beyond = np.nan_to_num(chart.deflection, nan=0.0) > 0.1
    if beyond.any():
        xs, ys = chart.raster.xs, chart.raster.ys
        with rc_context({"hatch.color": "0.6", "hatch.linewidth": 0.5}):
            ax.contourf(xs, ys, beyond.astype(float), levels=[0.5, 1.5], colors="none", hatches=[BEYOND_HATCH],
                        zorder=1)
        ax.contour(xs, ys, beyond.astype(float), levels=[0.5], colors="0.45", linewidths=0.6, zorder=1)
        handles.append(Patch(facecolor="white", edgecolor="0.6", hatch=BEYOND_HATCH,
                             label="a stable orbit beyond the theory (deflection > 0.1 L)"))
    # the lines that named the regions
    for ln in chart.lines:
        ax.axhline(ln.level, color="0.55", lw=0.5, ls=(0, (1, 3)), zorder=2)
    handles.append(Line2D([], [], color="0.55", lw=0.6, ls=(0, (1, 3)),
                          label=f"continuations in {xn} at fixed {yn} (they name the regions)"))
    # curves
    kinds = set()
    labels = []
    for c in chart.curves:
        color = KIND_COLORS[c.kind]
        ax.plot(c[xn], c[yn], color=color, ls=PERIOD_STYLES.get(c.period, "-."), lw=1.8, zorder=4)
        kinds.add((c.kind, c.period))
        inside = np.flatnonzero((c[xn] > x_lo) & (c[xn] < x_hi) & (c[yn] > y_lo) & (c[yn] < y_hi))
        if inside.size:
            i = int(inside[len(inside) // 2])
            labels.append((float(c[xn][i]), float(c[yn][i]), c.label, color))
    # a curve that ends inside the box (its stop reason is not an edge): its end marked
    ends = [(c[xn][k], c[yn][k]) for c in chart.curves
            for k, reason in ((0, c.stop_reasons[0]), (-1, c.stop_reasons[-1])) if not reason.startswith("reached")]
    if ends:
        ax.scatter([e[0] for e in ends], [e[1] for e in ends], marker="x", s=40, color="black", lw=1.2, zorder=6)
        handles.append(Line2D([], [], ls="none", marker="x", color="black",
                              label="a curve ends here (why: the summary, chart.json)"))
    for kind, period in sorted(kinds, key=lambda k: (k[1], k[0])):
        handles.append(Line2D([], [], color=KIND_COLORS[kind], ls=PERIOD_STYLES.get(period, "-."), lw=1.8,
                              label=f"{LABELS[kind]}{period}: {kind} of the period-{period} orbits"))
    points = chart.codim2
    if points:
        ax.scatter([p[xn] for p in points], [p[yn] for p in points], marker="*", s=140, color="black",
                   edgecolor="white", lw=0.6, zorder=6)
        labels += [(p[xn], p[yn], f"{p.label} ({p.kind})", "black") for p in points]
        handles.append(Line2D([], [], ls="none", marker="*", markersize=10, color="black",
                              label="codimension-two point"))
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(y_lo, y_hi)
    ax.set_xlabel(axis_text(xn))
    ax.set_ylabel(axis_text(yn))
    # region names: the words inside a piece with room for them, else the verdict's letter
    for g in chart.regions:
        if g.key is None or g.area < MIN_NAMED:
            continue
        text = g.words.replace(" and ", "\nand ").replace(" orbits coexist", "\norbits coexist")
        wide = g.room >= ROOM * max(len(t) for t in text.split("\n"))
        ax.text(g.x, g.y, text if wide else letters[g.words], ha="center", va="center",
                fontsize=7.5 if wide else 8.5, fontweight="normal" if wide else "bold", zorder=5, color="0.1",
                bbox=dict(boxstyle="round,pad=0.2", facecolor="white", alpha=0.75, lw=0))
    place_labels(ax, labels)
    leg = ax.legend(handles=handles, fontsize=7.5, loc="upper center", ncol=2, frameon=False,
                    bbox_to_anchor=(0.5, -0.12))
    leg._crankgen_outside = True
    ax.set_title(title or chart_title(chart), fontsize=9)
    return fit_panels(fig)
