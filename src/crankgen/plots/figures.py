"""Plots (matplotlib, Agg backend, imported only when a figure is written), and their layout:
measured, so that nothing is clipped and no legend or label covers data or another panel."""

import textwrap

import numpy as np

from ..declaration import schema
from ..declaration.units import in_L


_FIGURE_KEYS = ("figsize", "dpi", "constrained_layout", "layout", "facecolor")


def subplots(nrows=1, ncols=1, **kwargs):
    """pyplot.subplots without pyplot: a matplotlib Figure on the Agg canvas (no GUI backend, no
    global registry of figures to close); figure keywords go to the Figure, the rest to its grid."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(**{k: kwargs.pop(k) for k in _FIGURE_KEYS if k in kwargs})
    FigureCanvasAgg(fig)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def membrane_applies(s):
    """Whether the membrane option of a case's options (as_dict, or a result's info) makes a
    difference to its model (declaration.ingredients.applies: not on approach C nor the exact rod,
    whose strain is pointwise whatever it says)."""
    from ..declaration.ingredients import applies
    return "membrane" in s and applies("membrane", s)


def membrane_words(s):
    """", <membrane> membrane" of a case's options (as_dict), "" where the option does not apply."""
    return f", {s['membrane']} membrane" if membrane_applies(s) else ""


def model_parts(info):
    """The model of a result's info in a title: ["approach A", "lagrange / kelvin-voigt / averaged",
    "n = 16"], the membrane option only where it applies, None for what info does not hold."""
    return [f"approach {info['approach']}" if "approach" in info else None,
            " / ".join(str(info[k]) for k in ("formulation", "damping", "membrane") if k in info
                       and (k != "membrane" or membrane_applies(info))) or None,
            f"n = {info['n_elements']}" if "n_elements" in info else None]


def _title(s):
    """Two lines naming the model and the case (the mechanism's parameters and the crank's, from
    their records); a third for the rest that differs from the defaults (gravity, a guide offset,
    a four-bar's circle guide, rotary inertia off)."""
    from ..declaration import schema
    main, other = schema.describe(s)
    if not s.get("rotary_inertia", True):
        other.append("no rotary inertia")
    return (f"approach {s['approach']}, {s['formulation']} formulation, {s['damping']} damping"
            f"{membrane_words(s)}\n"
            + textwrap.fill(listed(main + [f"n = {s['n_elements']}"]), 95, break_on_hyphens=False)
            + ("\n" + ", ".join(other) if other else ""))


def listed(parts):
    """Items joined with ", " for a title that is wrapped (textwrap): the spaces inside an item
    non-breaking, so that a line breaks between items, never between a value and its unit."""
    return ", ".join(p.replace(" ", "\u00a0") for p in parts)


def shade_beyond(ax, limit, color):
    """Shade |y| > limit on ax (above limit and below -limit, within the current y limits, which
    stay as they are): the deflections beyond the range of the theory."""
    lo, hi = ax.get_ylim()
    for a, b in ((limit, max(hi, limit)), (min(lo, -limit), -limit)):
        if b > a:
            ax.axhspan(a, b, color=color, zorder=0, lw=0)
    ax.set_ylim(lo, hi)


def beyond_patch(color):
    """The legend entry of shade_beyond's band at theory.DEFLECTION_LIMIT."""
    from matplotlib.patches import Patch

    from ..analyses.theory import DEFLECTION_LIMIT
    return Patch(color=color, label=f"|v|/L > {DEFLECTION_LIMIT:g}: beyond the theory")


def _beyond_theory(ax, eps, v, strain, result=None):
    """Shade |v*| beyond the theory's deflection limit where the data reach it; returns the note
    for the title ('' when the response stays in the range of the theory).  An exact-model result
    is judged by the exact rod's own limits (crankgen.analyses.theory: no band, the note names them)."""
    from ..analyses import theory
    case = getattr(result, "case", None)
    if case is not None and theory.is_exact(case):
        flag = result.beyond_theory
        return f"\nBEYOND THE EXACT ROD'S LIMITS: {flag.reason}" if flag else ""

    v = np.asarray(v, dtype=float)
    v = v[np.isfinite(v)]
    vmax = float(np.max(np.abs(v))) if v.size else float("nan")
    smax = float(np.nanmax(strain)) if strain is not None and np.size(strain) and np.any(np.isfinite(strain)) else float("nan")
    lim = theory.DEFLECTION_LIMIT / eps
    if np.isfinite(vmax) and vmax > lim:
        shade_beyond(ax, lim, "0.88")
    why = theory.reasons(eps * vmax, smax)
    return f"\nBEYOND THE THEORY: {why} (shaded: |v|/L > {theory.DEFLECTION_LIMIT:g})" if why else ""


def plot_deflection(result, path, failure=None, si=None, against="t", strain=None):
    """v* at x* = 1/2 against t* (against="t") or against the instantaneous crank speed Omega*
    (against="crank_speed": a run-up's passage through resonance), written atomically to path
    (returned).  failure: the ConvergenceError of a run that stopped, marked on the plot; a
    response beyond the range of the theory (crankgen.analyses.theory) is shaded and named in the title.
    si: the result's SI view (crankgen.results.outputs.SIView): v in mm against t in s (or rad/s).
    strain: theory.axial_strain(result, per_step=True) when the caller has it already."""
    from ..analyses import theory
    from ..results.io import output_path, save_figure
    path = output_path(path)
    if against not in ("t", "crank_speed"):
        raise ValueError(f"against must be 't' or 'crank_speed', got {against!r}")
    fig, ax = subplots(figsize=(7, 3.8), constrained_layout=True)
    view = result if si is None else si
    v = result.v_mid if si is None else si.v_mid * 1e3
    if against == "t":
        x = view.t
        unit = "t*" if si is None else "t (s)"
        xf = None if failure is None else (failure.time if si is None else
                                           failure.time * si.scales.factor("1/omega_b"))
    else:
        x = view.crank_speed
        unit = ("instantaneous crank speed Omega*" if si is None
                else "instantaneous crank speed (rad/s)")
        xf = None if failure is None or not len(x) else x[-1]
    ax.plot(x, v, lw=1, color="C0", label="v* (x* = 1/2)" if si is None else "v (x = L/2), mm")
    if against == "t" and result.case.motion_record.driven and len(x):
        _crank_speed_axis(ax, x, view.crank_speed, si)
    if failure is not None:
        approach = result.settings.get("approach")
        word = (f"run diverged (approach {approach} is ill-posed: strain energy unbounded below)"
                if theory.ill_posed(approach) else "run failed")
        where = (f"{unit.split()[0]} = {xf:.4g}" if against == "t"
                 else f"crank speed {xf:.4g}")
        ax.axvline(xf, color="C3", ls="--", lw=1, label=f"{word} at {where} (step {failure.step})")
        if len(x):
            ax.plot(x[-1:], v[-1:], "x", color="C3", ms=9, mew=2, label="last computed state")
        ax.legend(fontsize=8, loc="best")
    ax.set_xlabel(unit)
    ax.set_ylabel("v* at x* = 1/2" if si is None else "v at x = L/2 in the moving frame (mm)")
    # the range of the theory in the scale drawn: |v*| eps = |v| / L (v* in units of r = eps L)
    eps = in_L(schema.OUTPUTS["v_mid"].units, result.settings) if si is None else 1e-3 / si.scales.L
    if strain is None:
        strain = theory.axial_strain(result, per_step=True)
    note = _beyond_theory(ax, eps, v, strain, result)
    ax.set_title(_title(result.settings) + note, fontsize=9)
    ax.grid(alpha=0.3)
    return save_figure(fig, path)


def plot_runup(result, path, ramp_end, failure=None, si=None, strain=None):
    """runup_figure written atomically to path (returned)."""
    from ..results.io import output_path, save_figure
    path = output_path(path)
    return save_figure(runup_figure(result, ramp_end, failure, si, strain), path)


def runup_figure(result, ramp_end, failure=None, si=None, strain=None):
    """A run-up in two panels: v* at x* = 1/2 against the
    instantaneous crank speed while it rises (the passage through the rod's resonances), and
    against the crank revolutions over the whole run, with the crank speed on the right-hand axis
    and the end of the ramp marked (after it the speed is constant, so the revolutions there have
    one speed and cannot be told apart against it).  ramp_end: the time (t*) at which the ramp
    completes; a run that ends before it says so in the title.  failure, si, strain: as
    plot_deflection."""
    from ..analyses import theory
    fig, (a1, a2) = subplots(2, 1, figsize=(7, 6.4), constrained_layout=True)
    view = result if si is None else si
    v = np.asarray(result.v_mid if si is None else si.v_mid * 1e3, dtype=float)
    t = np.asarray(result.t, dtype=float)
    speed = np.asarray(view.crank_speed, dtype=float)
    revs = (np.asarray(result.theta, dtype=float) - float(result.theta[0])) / (2 * np.pi)
    ramp = t <= ramp_end * (1 + 1e-12)
    speed_unit = "Omega*" if si is None else "(rad/s)"
    ylabel = "v* at x* = 1/2" if si is None else "v at x = L/2 (mm)"
    a1.plot(speed[ramp], v[ramp], lw=1, color="C0")
    a1.set_xlabel(f"instantaneous crank speed {speed_unit} (during the ramp)")
    a1.set_ylabel(ylabel)
    a2.plot(revs, v, lw=0.8, color="C0")
    a2.set_xlabel("crank revolutions")
    a2.set_ylabel(ylabel)
    right = a2.twinx()
    right.plot(revs, speed, color="C1", lw=1.2)
    right.set_ylabel(f"crank speed {speed_unit}", color="C1")
    right.tick_params(axis="y", colors="C1")
    complete = t[-1] >= ramp_end * (1 - 1e-12)
    if complete:
        end_rev = float(np.interp(ramp_end, t, revs))
        a2.axvline(end_rev, color="0.3", ls=":", lw=1)
        a2.annotate(f"ramp ends (revolution {end_rev:.4g})", (end_rev, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(0, 2), textcoords="offset points", ha="center", va="bottom", fontsize=8,
                    color="0.3")
    if failure is not None and len(revs):
        approach = result.settings.get("approach")
        word = (f"run diverged (approach {approach} is ill-posed)" if theory.ill_posed(approach)
                else "run failed")
        for ax, x in ((a1, speed), (a2, revs)):
            if ax is a1 and not ramp[-1]:
                continue
            ax.plot(x[-1:], v[-1:], "x", color="C3", ms=9, mew=2,
                    label=f"{word} (step {failure.step})")
            ax.legend(fontsize=8, loc="best")
    eps = in_L(schema.OUTPUTS["v_mid"].units, result.settings) if si is None else 1e-3 / si.scales.L
    if strain is None:
        strain = theory.axial_strain(result, per_step=True)
    _beyond_theory(a1, eps, v[ramp], None if strain is None else np.asarray(strain)[ramp], result)
    note = _beyond_theory(a2, eps, v, strain, result)
    where = ("" if complete else
             f"\nthe run ends at crank speed {speed[-1]:.4g}, before the ramp completes "
             f"(revolution {revs[-1]:.4g} of {result.settings.get(result.case.motion_record.transient, float('nan')):g})")
    a1.set_title(_title(result.settings) + where + note, fontsize=9)
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
    return fig


def plot_orbit(state, path, strain=None, si=None):
    """orbit_figure written atomically to path (returned)."""
    from ..results.io import output_path, save_figure
    path = output_path(path)
    return save_figure(orbit_figure(state, strain, si), path)


def orbit_figure(state, strain=None, si=None):
    """A steady revolution (crankgen.SteadyState) against the crank angle: v* at x* = 1/2, the
    extension delta* and the driving torque (the declared output `torque`, which a motor and its
    bearings are sized from); beyond the range of the theory: shaded and named in the title.
    strain: theory.axial_strain(state, per_step=True) when the caller has it already.  si: the
    state's SI view (crankgen.results.outputs.SIView): v in mm, the torque in N m."""
    from ..analyses import theory
    fig, (a1, a2, a3) = subplots(3, 1, figsize=(7, 7.0), sharex=True, constrained_layout=True)
    deg = np.degrees(state.theta)
    v = state.v_mid if si is None else si.v_mid * 1e3
    a1.plot(deg, v, lw=1.2, color="C0")
    a1.set_ylabel("v* at x* = 1/2" if si is None else "v at x = L/2 (mm)")
    a2.plot(deg, state.extension, lw=1.2, color="C2")
    a2.set_ylabel("extension delta*")
    torque = state.torque if si is None else si.torque
    a3.plot(deg, torque, lw=1.2, color="C3")
    a3.axhline(0.0, color="0.5", lw=0.6)
    a3.set_ylabel("driving torque (N m)" if si is not None else
                  f"driving torque\n({schema.OUTPUTS['torque'].units})")
    if state.case.motion_record.driven:
        _crank_speed_axis(a3, deg, (state if si is None else si).crank_speed, si)
    a3.set_xlabel("crank angle theta (degrees)")
    a3.set_xticks(np.arange(0, 361, 60))
    for ax in (a1, a2, a3):
        ax.grid(alpha=0.3)
    s = dict(state.case.as_dict())
    mult = (f", largest |multiplier| {state.multiplier:.4g}"
            if state.multiplier is not None and np.isfinite(state.multiplier) else "")
    if getattr(state, "period", None) is not None:          # a motor-driven crank's steady motion
        if si is None:
            mult += (f"\nrevolution time T* = {state.period:.5g}, mean crank speed Omega* = {state.mean_speed:.5g}, "
                     f"fluctuation {state.speed_fluctuation:.3g}")
        else:
            mult += (f"\nrevolution time {state.period / si.scales.omega_b:.5g} s, mean speed "
                     f"{state.mean_speed * si.scales.omega_b:.5g} rad/s "
                     f"({state.mean_speed * si.scales.omega_b * 30 / np.pi:.5g} rpm), fluctuation "
                     f"{100 * state.speed_fluctuation:.2g} %")
    if strain is None:
        strain = theory.axial_strain(state, per_step=True)
    eps = in_L(schema.OUTPUTS["v_mid"].units, state.case.parameters()) if si is None else 1e-3 / si.scales.L
    note = _beyond_theory(a1, eps, v, strain, state)
    a1.set_title(f"steady state: {state.status}{mult}\n" + (_title(s) if si is None else _si_title(state, si))
                 + note, fontsize=9)
    return fig


def _crank_speed_axis(ax, x, speed, si):
    """The crank speed of a motor-driven crank (its angle a degree of freedom) on a right-hand axis
    of ax, against the same abscissa x."""
    right = ax.twinx()
    right.plot(x, speed, lw=1.0, color="C1")
    right.set_ylabel("crank speed (rad/s)" if si is not None else "crank speed Omega*", color="C1")
    right.tick_params(axis="y", colors="C1")
    return right


def _si_title(result, si):
    """The model, the rod and the case's parameters in SI (crankgen.declaration.si.describe_si), for a
    title.  si: the result's SI view, or the crankgen.Scales it converts by."""
    from ..declaration.si import describe_si
    s, sc = result.case.as_dict(), getattr(si, "scales", si)
    return (f"approach {s['approach']}, {s['formulation']} formulation, {s['damping']} damping"
            f"{membrane_words(s)}, n = {s['n_elements']}\n"
            f"L = {sc.L:g} m, omega_b = {sc.omega_b:.5g} rad/s, rho A = {sc.rhoA:.4g} kg/m, r = {sc.base['r']:.4g} m\n"
            + textwrap.fill(listed(describe_si(result.case.parameters(), sc)), 88))


# --- helpers for multi-panel figures (crankgen reproduce) -------------------------------------

APPROACH_COLORS = {"A": "C0", "B": "C1", "C": "C3"}


def panels(rows, cols, width=6.0, height=3.4, space_below=0.0, top_margin=0.6, **kwargs):
    """Figure with a rows x cols grid of axes (always a 2-D array), panels of width x height
    inches plus space_below inches under each row (for a legend placed below the axes) and
    top_margin inches above the first row (suptitle and panel titles).  Fixed
    margins instead of a layout engine: constrained layout cost about a third of the wall time of
    `crankgen reproduce --quick`."""
    h_row = height + space_below
    fig, axes = subplots(rows, cols, figsize=(width * cols, h_row * rows), squeeze=False, **kwargs)
    w, h = width * cols, h_row * rows
    gap = 0.75 + space_below + (top_margin - 0.6)    # inches: axis labels + (taller) titles
    axes_h = (h - top_margin - 0.6 - space_below - gap * (rows - 1)) / rows
    left, right, between = 0.9, 0.25, 1.15           # inches: y tick labels and axis label
    fig.subplots_adjust(left=left / w, right=1 - right / w, bottom=(0.6 + space_below) / h,
                        top=1 - top_margin / h,
                        wspace=between / ((w - left - right - between * (cols - 1)) / cols),
                        hspace=gap / axes_h)
    fig._crankgen_grid = dict(axes=axes, axes_w=(w - left - right - between * (cols - 1)) / cols,
                              axes_h=axes_h)         # fit_panels lays it out from measurements
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


# --- layout: measured, so that nothing is clipped and no legend covers another panel -----------

def fit_panels(fig, pad=0.12):
    """Lay out the grid of `panels` from the measured extents of every panel (title, tick and
    axis labels, a legend below it): the axes keep their size in inches, the gaps, margins and
    the figure grow to what the text needs.  One layout pass without rasterizing (cheaper than a
    layout engine); returns fig."""
    grid = getattr(fig, "_crankgen_grid", None)
    if grid is None:
        return fig
    axes = grid["axes"]
    rows, cols = axes.shape
    renderer = fig.canvas.get_renderer()
    dpi = fig.dpi
    for ax in axes.flat:        # a legend below its panel starts just under the x axis' labels
        leg = ax.get_legend()
        if leg is not None and _legend_outside(ax):
            box, below = ax.get_window_extent(renderer), ax.xaxis.get_tightbbox(renderer)
            y = (below.y0 - box.y0 - 0.06 * dpi) / box.height
            leg.set_bbox_to_anchor((0.5, y), transform=ax.transAxes)
    ax_w, ax_h = grid["axes_w"], grid["axes_h"]
    ext = np.zeros((rows, cols, 4))             # inches beyond the axes: left, right, below, above
    for i in range(rows):
        for j in range(cols):
            ax = axes[i, j]
            box, tight = ax.get_window_extent(renderer), ax.get_tightbbox(renderer)
            if tight is None:                   # a hidden panel (an odd count on a grid) needs no room
                continue
            ext[i, j] = [(box.x0 - tight.x0) / dpi, (tight.x1 - box.x1) / dpi,
                         (box.y0 - tight.y0) / dpi, (tight.y1 - box.y1) / dpi]
    ext = np.maximum(ext, 0.0)
    sup = fig._suptitle
    sup_h = (sup.get_window_extent(renderer).height / dpi + pad) if sup is not None else 0.0
    left = ext[:, 0, 0].max() + pad
    between = [ext[:, j, 1].max() + ext[:, j + 1, 0].max() + pad for j in range(cols - 1)]
    right = ext[:, -1, 1].max() + pad
    top = sup_h + ext[0, :, 3].max() + pad
    gaps = [ext[i, :, 2].max() + ext[i + 1, :, 3].max() + pad for i in range(rows - 1)]
    bottom = ext[-1, :, 2].max() + pad
    W = left + cols * ax_w + sum(between) + right
    H = top + rows * ax_h + sum(gaps) + bottom
    fig.set_size_inches(W, H)
    y = H - top
    for i in range(rows):
        x = left
        for j in range(cols):
            axes[i, j].set_position([x / W, (y - ax_h) / H, ax_w / W, ax_h / H])
            x += ax_w + (between[j] if j < cols - 1 else 0.0)
        y -= ax_h + (gaps[i] if i < rows - 1 else 0.0)
    if sup is not None:
        sup.set_y(1.0 - (pad / 2) / H)
        sup.set_va("top")
    return fig


def layout_problems(fig):
    """What a reader would see as broken, measured on the drawn figure: text or a legend outside
    the figure, a legend over an axes, panels whose titles, labels or legends overlap each other,
    and annotations overlapping one another or leaving their axes.  [] when none."""
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    frame = fig.bbox
    out = []

    def inside(bb, what):
        if bb.x0 < frame.x0 - 1 or bb.y0 < frame.y0 - 1 or bb.x1 > frame.x1 + 1 or bb.y1 > frame.y1 + 1:
            out.append(f"{what} extends beyond the figure")
    axes = [a for a in fig.axes if a.get_visible()]
    tights = [a.get_tightbbox(r) for a in axes]
    for a, t in zip(axes, tights):
        inside(t, f"panel {a.get_title()!r}")
        leg = a.get_legend()
        if leg is not None:
            lb = leg.get_window_extent(r)
            for b in axes:
                if lb.overlaps(b.get_window_extent(r)) and (b is not a or _legend_outside(a)):
                    out.append(f"the legend of {a.get_title()!r} covers panel {b.get_title()!r}")
    for i in range(len(axes)):
        for j in range(i + 1, len(axes)):
            if tights[i].overlaps(tights[j]):
                out.append(f"panels {axes[i].get_title()!r} and {axes[j].get_title()!r} overlap")
    if fig._suptitle is not None:
        sb = fig._suptitle.get_window_extent(r)
        inside(sb, "the title")
        out += [f"the title overlaps panel {a.get_title()!r}" for a, t in zip(axes, tights) if sb.overlaps(t)]
    for a in axes:
        points = None
        for t in a.texts:
            if getattr(t, "_crankgen_label", False):
                points = drawn_points(a) if points is None else points
                bb = _text_box(t, r)
                hits = np.sum((points[:, 0] >= bb.x0) & (points[:, 0] <= bb.x1)
                              & (points[:, 1] >= bb.y0) & (points[:, 1] <= bb.y1)) if points.size else 0
                if hits:
                    out.append(f"label {t.get_text()!r} covers {hits} drawn point(s) of {a.get_title()!r}")
        boxes = [_text_box(t, r) for t in a.texts if t.get_visible() and t.get_text()]
        abox = a.get_window_extent(r)
        for k, b in enumerate(boxes):
            if b.x0 < abox.x0 - 1 or b.x1 > abox.x1 + 1 or b.y0 < abox.y0 - 1 or b.y1 > abox.y1 + 1:
                out.append(f"annotation {a.texts[k].get_text()!r} leaves panel {a.get_title()!r}")
            out += [f"annotations {a.texts[k].get_text()!r} and {a.texts[m].get_text()!r} overlap"
                    for m in range(k + 1, len(boxes)) if b.overlaps(boxes[m])]
    return out


def _text_box(text, renderer):
    """Display box of a text or annotation's text alone (an annotation's own extent includes its
    leader line, which runs to the point it labels)."""
    from matplotlib.text import Text
    if hasattr(text, "update_positions"):
        text.update_positions(renderer)
    return Text.get_window_extent(text, renderer)


def _legend_outside(ax):
    """Whether the axes' legend was placed outside the axes (below it), so that covering the
    axes itself is a fault too."""
    leg = ax.get_legend()
    return getattr(leg, "_crankgen_outside", False)


def drawn_points(ax, spacing=2.0):
    """Display coordinates of everything drawn in the panel: its lines (densified every
    `spacing` pixels) and the markers of every collection, whatever their transform."""
    out = []
    for line in ax.get_lines():
        xy = np.asarray(line.get_xydata(), dtype=float)
        if len(xy) == 0 or not line.get_visible():
            continue
        d = line.get_transform().transform(xy)
        d = d[np.all(np.isfinite(d), axis=1)]
        if line.get_linestyle() in ("None", "none", " ", ""):
            out.append(d)
            continue
        for a, b in zip(d[:-1], d[1:]):
            k = min(2000, max(2, int(np.hypot(*(b - a)) / spacing) + 1))
            out.append(a + (b - a) * np.linspace(0, 1, k)[:, None])
        out.append(d)
    for col in ax.collections:
        off = np.asarray(col.get_offsets(), dtype=float)
        if len(off) and col.get_visible():
            d = col.get_offset_transform().transform(off)
            out.append(d[np.all(np.isfinite(d), axis=1)])
    return np.concatenate(out) if out else np.zeros((0, 2))


# offsets (points) tried for a label, nearest first: right / left of the point, above / below,
# then rings further out (a leader line joins a label placed away from its point)
LABEL_OFFSETS = [(6, 5), (-6, 5), (6, -13), (-6, -13), (8, 16), (-8, 16), (8, -24), (-8, -24)] + [
    (round(r * np.cos(a)) or 4, round(r * np.sin(a)))
    for r in (30, 45, 60, 80, 100) for a in np.radians(np.arange(15, 360, 30))]


def place_labels(ax, items, fontsize=8, margin=4.0):
    """items: (x, y, text, colour) in data coordinates.  Each text goes beside its point at the
    first of LABEL_OFFSETS where it covers no drawn point or line of the panel (with `margin`
    pixels for the markers' size), no other label, and stays inside the frame; an arrow joins
    a label placed away from its point.  A label that fits nowhere goes where it covers the
    fewest drawn points."""
    renderer = ax.figure.canvas.get_renderer()
    box = ax.get_window_extent(renderer)
    obstacles = drawn_points(ax)
    placed = []
    for x, y, text, color in items:
        best, best_cost = None, None
        for dx, dy in LABEL_OFFSETS:
            far = abs(dy) > 14 or abs(dx) > 14        # beyond the four adjacent places: a leader
            a = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy),
                            ha="left" if dx > 0 else "right", va="center", fontsize=fontsize,
                            zorder=7, color=color,
                            arrowprops=dict(arrowstyle="-", color=color, lw=0.6, shrinkA=0, shrinkB=3)
                            if far else None)
            bb = _text_box(a, renderer)        # the text, not its leader line
            bb = bb.from_extents(bb.x0 - margin, bb.y0 - margin, bb.x1 + margin, bb.y1 + margin)
            inside = box.contains(bb.x0, bb.y0) and box.contains(bb.x1, bb.y1)
            hits = int(np.sum((obstacles[:, 0] >= bb.x0) & (obstacles[:, 0] <= bb.x1)
                              & (obstacles[:, 1] >= bb.y0) & (obstacles[:, 1] <= bb.y1))) if obstacles.size else 0
            clash = any(bb.overlaps(p) for p in placed)
            cost = (not inside, clash, hits)
            a._crankgen_label = True
            if best_cost is None or cost < best_cost:
                if best is not None:
                    best[0].remove()
                best, best_cost = (a, bb), cost
                if cost == (False, False, 0):
                    break
            else:
                a.remove()
        placed.append(best[1])
