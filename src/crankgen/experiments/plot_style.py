"""The look shared by the reproduce figures (crankgen.experiments.plots, plots_sweeps): text sizes,
per-approach and per-speed line styles, panel titles and grids, legends below the axes with the
room they take, and the legend entry of series that coincide."""

import math

from ..plots.figures import beyond_patch

FONT = 8                                   # legends, insets, annotations (pt)
# per approach: line style and marker, so that coinciding curves stay visible
APPROACH_STYLES = {"A": ("-", "o", 4), "B": ("--", "s", 6), "C": (":", "^", 4)}
# per crank speed: line style and marker
SPEED_STYLES = [("-", "o"), ("--", "s"), (":", "D"), ("-.", "v")]


def panel_title(ax, model, extra=""):
    ax.set_title(f"{model.label}{extra}", fontsize=9)


def panel_grid(ax):
    ax.grid(alpha=0.3)


def theory_handle():
    return beyond_patch("0.85")


def legend_below(ax, handles=None, labels=None, ncol=1, extra=()):
    """Legend below the axes (outside them, so that it covers no data), 8 pt."""
    import textwrap
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    handles, labels = list(handles) + list(extra), list(labels) + [h.get_label() for h in extra]
    if not handles:
        return
    fig = ax.figure
    h_in = ax.get_position().height * fig.get_figheight()
    w_in = ax.get_position().width * fig.get_figwidth()
    # characters per column (8 pt text is about 0.5 em wide; handle and spacing take 3.8 em)
    width = max(20, int((w_in * 72 / ncol - 3.8 * FONT) / (0.52 * FONT)))
    def wrap(text):
        lines = textwrap.wrap(str(text), width, break_on_hyphens=False)
        if len(lines) > 1 and len(lines[-1]) < 6:          # no orphan word on a line of its own
            lines = textwrap.wrap(str(text), width + 6, break_on_hyphens=False)
        return "\n".join(lines)
    labels = [wrap(t) for t in labels]
    leg = ax.legend(handles, labels, fontsize=FONT, loc="upper center", ncol=ncol, frameon=False,
                    bbox_to_anchor=(0.5, -0.55 / h_in), handlelength=2.6, columnspacing=1.2)
    leg._crankgen_outside = True


def coincide_note(pairs):
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


def Line2D(*a, **k):
    from matplotlib.lines import Line2D as L
    return L(*a, **k)


def legend_room(n_entries, ncol):
    """Inches of legend room below a panel for n_entries in ncol columns (plus the x label)."""
    return 0.3 + 0.17 * math.ceil(max(n_entries, 1) / ncol)
