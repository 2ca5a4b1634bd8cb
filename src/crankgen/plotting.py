"""Plots (matplotlib, Agg backend, imported only when a figure is written)."""


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _title(s):
    extra = ""
    gravity = tuple(s.get("gravity", (0.0, 0.0)))
    if any(gravity):
        extra += f", gravity ({gravity[0]:g}, {gravity[1]:g})"
    if s.get("offset", 0.0):
        extra += f", offset {s['offset']:g}"
    if not s.get("rotary_inertia", True):
        extra += ", no rotary inertia"
    return (f"approach {s['approach']}, {s['formulation']} formulation, {s['damping']} damping, "
            f"{s.get('membrane', 'pointwise')} membrane\nOmega* = {s['omega']:g}, eps = {s['eps']:g}, "
            f"ms* = {s['ms']:g}, mu* = {s['mu']:g}, n = {s['n_elements']}{extra}")


def plot_deflection(result, path, failure=None, si=None):
    """v* at x* = 1/2 against t*, written atomically to path (returned).  failure: the
    ConvergenceError of a run that stopped, whose time is marked on the plot.  si: the result's SI
    view (crankgen.outputs.SIView): v in mm against t in s."""
    from .io import save_figure
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 3.8), constrained_layout=True)
    if si is None:
        t, v, tf, unit = result.t, result.v_mid, None if failure is None else failure.time, "t*"
    else:
        t, v, unit = si.t, si.v_mid * 1e3, "t (s)"
        tf = None if failure is None else failure.time * si.scales.factor("1/omega_b")
    ax.plot(t, v, lw=1, color="C0", label="v* (x* = 1/2)" if si is None else "v (x = L/2), mm")
    if failure is not None:
        ax.axvline(tf, color="C3", ls="--", lw=1,
                   label=f"run failed at {unit.split()[0]} = {tf:.4g} (step {failure.step})")
        if len(t):
            ax.plot(t[-1:], v[-1:], "x", color="C3", ms=9, mew=2,
                    label="last computed state")
        ax.legend(fontsize=8, loc="best")
    ax.set_xlabel(unit)
    ax.set_ylabel("v* at x* = 1/2" if si is None else "v at x = L/2 in the moving frame (mm)")
    ax.set_title(_title(result.settings), fontsize=9)
    ax.grid(alpha=0.3)
    return save_figure(fig, path)


def plot_orbit(state, path):
    """A steady revolution (crankgen.SteadyState): v* at x* = 1/2 and the extension delta*
    against the crank angle, written atomically to path (returned)."""
    import numpy as np

    from .io import save_figure
    plt = _pyplot()
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 5.2), sharex=True, constrained_layout=True)
    deg = np.degrees(state.theta)
    a1.plot(deg, state.v_mid, lw=1.2, color="C0")
    a1.set_ylabel("v* at x* = 1/2")
    a2.plot(deg, state.extension, lw=1.2, color="C2")
    a2.set_ylabel("extension delta*")
    a2.set_xlabel("crank angle theta (degrees)")
    a2.set_xticks(np.arange(0, 361, 60))
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
    s = dict(state.case.as_dict())
    mult = (f", largest |multiplier| {state.multiplier:.4f}"
            if state.multiplier is not None and np.isfinite(state.multiplier) else "")
    a1.set_title(f"steady state: {state.status}{mult}\n" + _title(s), fontsize=9)
    return save_figure(fig, path)


# --- helpers for multi-panel figures (crankgen reproduce) -------------------------------------

APPROACH_COLORS = {"A": "C0", "B": "C1", "C": "C3"}


def pyplot():
    """matplotlib.pyplot with the Agg backend."""
    return _pyplot()


def panels(rows, cols, width=6.0, height=3.4, space_below=0.0, top_margin=0.6, **kwargs):
    """Figure with a rows x cols grid of axes (always a 2-D array), panels of width x height
    inches plus space_below inches under each row (for a legend placed below the axes) and
    top_margin inches above the first row (suptitle and panel titles).  Fixed
    margins instead of a layout engine: constrained layout cost about a third of the wall time of
    `crankgen reproduce --quick`."""
    plt = _pyplot()
    h_row = height + space_below
    fig, axes = plt.subplots(rows, cols, figsize=(width * cols, h_row * rows), squeeze=False,
                             **kwargs)
    w, h = width * cols, h_row * rows
    gap = 0.75 + space_below + (top_margin - 0.6)    # inches: axis labels + (taller) titles
    axes_h = (h - top_margin - 0.6 - space_below - gap * (rows - 1)) / rows
    left, right, between = 0.9, 0.25, 1.15           # inches: y tick labels and axis label
    fig.subplots_adjust(left=left / w, right=1 - right / w, bottom=(0.6 + space_below) / h,
                        top=1 - top_margin / h,
                        wspace=between / ((w - left - right - between * (cols - 1)) / cols),
                        hspace=gap / axes_h)
    return fig, axes


def mark_at_axis(ax, x, color, marker="x", label=None, size=50):
    """Markers on the horizontal axis (y at the bottom of the axes, whatever the y scale) at
    abscissae x: for points of a curve that have no value (failed or diverged cases)."""
    import numpy as np
    x = np.atleast_1d(np.asarray(x, dtype=float))
    if x.size == 0:
        return None
    return ax.scatter(x, np.zeros_like(x), transform=ax.get_xaxis_transform(), clip_on=False,
                      marker=marker, color=color, s=size, label=label, zorder=5)


def status_legend_handles(kinds=("failed", "unstable", "envelope")):
    """Grey proxy artists explaining the status markers of steady-state sweep plots."""
    from matplotlib.lines import Line2D
    text = {
        "failed": ("x", "x on the axis: no steady response (run failed / diverged)"),
        "unstable": ("o", "hollow o: unstable periodic orbit"),
        "envelope": ("^", "hollow ^: non-periodic response, max |v*| of a transient (on the top edge: off scale, see CSV)"),
    }
    out = []
    for k in kinds:
        m, label = text[k]
        face = "none" if k != "failed" else "grey"
        out.append(Line2D([], [], ls="none", marker=m, color="grey", markerfacecolor=face, label=label))
    return out
