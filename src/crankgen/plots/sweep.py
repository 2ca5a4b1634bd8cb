"""The figure of a sweep: the steady amplitude and the peak driving torque against the swept
parameter, one series per combination of the other swept values (crankgen sweep's sweep.png).

x is the swept parameter (the numeric parameter column with the most values along the table,
unless given), every other varying column (a second parameter, the model, the approach, ...) makes a
series.  Top: the amplitude max |v*(1/2)| (in crankgen's units: units of r, with the limit of
the theory |v|/L = 0.1 as a dotted line per series; in SI: mm); bottom: the peak over the orbit of
each declared load that is a moment (the driving torque; N m in SI).  A periodic (stable) orbit is
a filled marker joined by a line, an unstable orbit a hollow marker, a case beyond the theory is
ringed in grey, and a case with no orbit (not periodic, failed) a cross at the bottom of the panel.
Layout by crankgen.plots.figures (panels, fit_panels): measured, nothing clipped.
"""

import math

import numpy as np

from ..declaration import schema
from ..results.steady_row import PEAK, is_load

MAX_SERIES = 10
DPI = 120
HANDLED = {"status", "message", "groups_off"}


def _number(x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        return math.nan
    return x


def varying(rows, columns):
    """The columns (parameters, the model, options) whose values differ between rows."""
    out = []
    for c in columns:
        if c in schema.PARAMETERS or c in schema.OPTIONS or c == "model":
            values = {repr(r.get(c)) for r in rows}
            if len(values) > 1:
                out.append(c)
    return out


def independent(rows, columns):
    """The columns of `columns` that name a series: each dropped whose value follows from those
    kept before it (a rocker's length from the guide, a fluctuation from the crank motion, the
    options and a preset's run settings, rho_inf, from the model)."""
    by_model = set(schema.OPTIONS) | {k for p in schema.PRESETS.values() for k in getattr(p, "settings", {})}
    order = [c for c in columns if c not in by_model and c != "model"]
    order += (["model"] if "model" in columns else []) + [c for c in columns if c in by_model]
    kept = []
    for c in order:
        seen = {}
        for r in rows:
            seen.setdefault(tuple(repr(r.get(k)) for k in kept), set()).add(repr(r.get(c)))
        if any(len(v) > 1 for v in seen.values()):
            kept.append(c)
    return [c for c in columns if c in kept]


def moments(columns):
    """The peak columns of loads that are moments (the driving torque)."""
    from ..declaration.units import Scales
    out = []
    for c in columns:
        spec = schema.OUTPUTS.get(c[len(PEAK):]) if c.startswith(PEAK) else None
        if spec is not None and is_load(spec.units) and Scales.si_name(spec.units) == "N m":
            out.append(c)
    return out


def sweep_figure(table, x=None, si=None):
    """The figure (module docstring) of a crankgen.SweepTable; si: the crankgen.SIMechanism of the
    rows (amplitude in mm, torque in N m, the swept parameter in its SI unit), or None."""
    from ..results.exports import column
    from .figures import fit_panels, panels
    rows = list(table.rows if si is None else table.si_view(si).rows)
    columns = list(table.columns)
    swept = varying(rows, columns)
    numeric = [c for c in swept if c in schema.PARAMETERS and schema.PARAMETERS[c].kind in ("real", "count")]
    if x is None:                       # the numeric parameter with the most values
        x = max(numeric, key=lambda c: len({repr(r.get(c)) for r in rows}), default=None)
    if x is None:
        raise ValueError("the sweep varies no numeric parameter to draw against")
    p = schema.PARAMETERS[x]
    if si is not None and p.kind == "real" and column(p.si or p.name, p.units, True) in rows[0]:
        xcol, xlabel = column(p.si or p.name, p.units, True), f"{(p.si or p.name).replace('_', ' ')} ({_si(p.units)})"
    else:
        xcol, xlabel = x, (p.axis or p.name)
    others = independent(rows, [c for c in swept if c != x])
    loads = moments(columns)
    amp_col = "amplitude" if si is None else column("amplitude", _amplitude_units(), True)
    groups = {}
    for r in rows:
        groups.setdefault(tuple(repr(r.get(c)) for c in others), []).append(r)
    keys = list(groups)[:MAX_SERIES]
    n_panels = 1 + bool(loads)
    fig, axes = panels(n_panels, 1, width=6.4, height=3.0, space_below=0.0, top_margin=0.95)
    fig.set_dpi(DPI)                          # laid out at the resolution it is written with
    a_amp = axes[0, 0]
    a_load = axes[1, 0] if loads else None
    scale = 1e3 if si is not None else 1.0                # metres -> mm
    handles, limits = [], {}
    ringed = False
    missing_any = False
    for k, key in enumerate(keys):
        color = f"C{k % 10}"
        label = ", ".join(_describe(c, groups[key][0].get(c)) for c in others) or None
        group = sorted(groups[key], key=lambda r: _number(r.get(xcol)))
        xs = np.array([_number(r.get(xcol)) for r in group])
        amp = np.array([_number(r.get(amp_col)) for r in group]) * scale
        status = [r.get("status") for r in group]
        stable = np.array([s == "periodic" for s in status])
        unstable = np.array([s == "unstable" for s in status])
        line_y = np.where(stable, amp, np.nan)
        h, = a_amp.plot(xs, line_y, "-o", color=color, ms=4, lw=1.2, label=label)
        handles.append(h)
        if unstable.any():
            a_amp.scatter(xs[unstable], amp[unstable], marker="o", facecolors="none", edgecolors=color, s=30,
                          zorder=4)
        beyond = np.array([r.get("beyond_theory") == "yes" for r in group])
        if beyond.any():
            ringed = True
            a_amp.scatter(xs[beyond], amp[beyond], marker="o", s=95, facecolors="none", edgecolors="0.55",
                          linewidths=0.9, zorder=2)
        missing = ~(stable | unstable)
        if missing.any():
            missing_any = True
            for ax in (a_amp, a_load) if a_load is not None else (a_amp,):
                ax.scatter(xs[missing], np.full(int(missing.sum()), 0.03 + 0.025 * (k % 4)),
                           transform=ax.get_xaxis_transform(), marker="x", color=color, s=36, zorder=5)
        from ..analyses.theory import DEFLECTION_LIMIT
        eps = {_number(r.get(u)) for r in group for u in schema.UNIT_PARAMETERS.values()}
        limit = DEFLECTION_LIMIT * si.scales.L * scale if si is not None else \
            DEFLECTION_LIMIT / eps.pop() if len(eps) == 1 else None          # in the amplitude's unit drawn
        if limit is not None and np.nanmax(np.append(amp, 0.0)) > 0.5 * limit:
            limits.setdefault(limit, set()).add(color)
        for j, load in enumerate(loads):
            col = load if si is None else column(load, schema.OUTPUTS[load[len(PEAK):]].units, True)
            y = np.array([_number(r.get(col)) for r in group])
            a_load.plot(xs, np.where(stable, y, np.nan), marker="o", color=color, ms=4, lw=1.2,
                        ls=("-", "--", ":")[j % 3])
            if unstable.any():
                a_load.scatter(xs[unstable], y[unstable], marker="o", facecolors="none", edgecolors=color, s=30)
    every = [x for key in keys for x in (_number(r.get(xcol)) for r in groups[key]) if np.isfinite(x)]
    if every:                                 # the crosses (axes' y) do not extend the data limits
        lo, hi = min(every), max(every)
        pad = 0.05 * (hi - lo) if hi > lo else 0.05 * max(abs(lo), 1.0)
        for ax in axes[:, 0]:
            ax.set_xlim(lo - pad, hi + pad)
    for limit, colors in limits.items():      # one line per limit, in its series' colour when it has one
        a_amp.axhline(limit, color=colors.pop() if len(colors) == 1 else "0.4", ls=":", lw=0.9)
    a_amp.set_ylabel("amplitude |v(L/2)| (mm)" if si is not None else "amplitude |v*(1/2)| (units of r)")
    a_amp.set_ylim(bottom=0.0)
    if a_load is not None:
        names = ", ".join(c[len(PEAK):].replace("_", " ") for c in loads)
        a_load.set_ylabel(f"peak {names} (N m)" if si is not None else f"peak {names}\n({_units(loads[0])})")
        a_load.set_ylim(bottom=0.0)
    axes[-1, 0].set_xlabel(xlabel)
    for ax in axes[:, 0]:
        ax.grid(alpha=0.3)
        if ax is not axes[-1, 0]:
            ax.tick_params(labelbottom=False)
    import textwrap
    title = _title(rows[0], swept, len(groups), len(keys), si)
    fig.suptitle("\n".join(textwrap.fill(line, 95) for line in title.split("\n")), fontsize=8.5)
    from matplotlib.lines import Line2D
    extra = []
    if any(r.get("status") == "unstable" for r in rows):
        extra.append(Line2D([], [], ls="none", marker="o", color="0.3", markerfacecolor="none",
                            label="unstable orbit"))
    if missing_any:
        extra.append(Line2D([], [], ls="none", marker="x", color="0.3", label="no periodic orbit (see status)"))
    if ringed:
        extra.append(Line2D([], [], ls="none", marker="o", ms=9, color="0.55", markerfacecolor="none",
                            label="beyond the theory"))
    if any(line.get_linestyle() == ":" for line in a_amp.get_lines()):
        from ..analyses.theory import DEFLECTION_LIMIT
        extra.append(Line2D([], [], ls=":", color="0.3", label=f"|v|/L = {DEFLECTION_LIMIT:g}, limit of the theory"))
    labelled = [h for h in handles if h.get_label() and not h.get_label().startswith("_")]
    if not labelled + extra:
        return fit_panels(fig)
    leg = axes[-1, 0].legend(handles=labelled + extra, loc="upper center", bbox_to_anchor=(0.5, -0.22),
                             ncol=2, fontsize=7.5, frameon=False)
    leg._crankgen_outside = True
    return fit_panels(fig)


def _si(units):
    from ..declaration.units import Scales
    return Scales.si_name(units)


def _units(peak):
    return schema.OUTPUTS[peak[len(PEAK):]].units


def _amplitude_units():
    from ..results.steady_row import AMPLITUDE_UNITS
    return AMPLITUDE_UNITS


def _describe(c, v):
    """A series' value of a column as a legend names it: a guide or motion by its record's label
    (slider, four-bar, run-up, ...), an option or the model by its value, a number with its axis."""
    if c in schema.PARAMETERS:
        p = schema.PARAMETERS[c]
        if p.selects:
            record = (schema.GUIDES if p.selects == "guide" else schema.MOTIONS)[v]
            return record.label or record.name
        return f"{p.axis or p.name} = {v:g}" if isinstance(v, (int, float)) else f"{p.axis or p.name} = {v}"
    return f"{v} {c}"


def _title(row, swept, n_groups, shown, si=None):
    """What the sweep holds fixed: the model options and the parameters that are not swept (in SI
    with their SI names and units, and the rod, for an SI sweep)."""
    values = {k: (tuple(v) if isinstance(v, list) else v) for k, v in row.items() if v is not None}
    options = [f"{row[o]} {o}" if o != "approach" else f"approach {row[o]}" for o in schema.OPTIONS
               if o not in swept and o != "rotary_inertia"]
    if si is None:
        main, other = schema.describe(values, skip=swept)
    else:
        from ..declaration.si import describe_si
        from ..declaration.units import ROD
        main = [f"{n} = {getattr(si, n):g} {u}" for n, u, _ in ROD]
        other = describe_si(values, si.scales, skip=swept)
    if "n_elements" not in swept:
        options.append(f"n = {row['n_elements']}")
    more = f"; {n_groups - shown} more series not drawn" if n_groups > shown else ""
    from .figures import listed
    return ("steady states of a sweep: " + ", ".join(options) + "\n" + listed(main)
            + ("\n" + listed(other) if other else "") + more)


def plot_sweep(table, path, x=None, si=None):
    """Write the sweep figure (sweep_figure) to path atomically; returns path."""
    from ..results.io import save_figure
    return save_figure(sweep_figure(table, x, si), path, dpi=DPI)
