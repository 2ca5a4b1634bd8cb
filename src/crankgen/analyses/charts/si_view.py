"""A stability chart of a mechanism given in SI (crankgen chart --si): its axes taken and shown in
the parameters' SI units (a crank speed in rad/s, or rpm; a length in m; ...), its curves written
in SI beside crankgen's units.  The chart itself is computed in crankgen's units (chart.json reads
back as before); this module converts at its edges, from the declaration's units
(crankgen.units.Scales), naming nothing itself."""

import math

import numpy as np

from ...declaration import schema
from ...declaration.si import rad_per_s, si_unit, to_crankgen, to_si

RPM = "rpm"


def unit_text(name, rpm=False):
    """The SI unit an axis is shown in ("rad/s", "rpm" for a crank speed with rpm, "m", ...)."""
    return RPM if rpm and si_unit(name) == "rad/s" else si_unit(name)


def to_model(axis, scales, rpm=False):
    """(name, low, high) given in SI (a speed in rpm with rpm) -> the same in crankgen's units; the
    slenderness, the rod's section, is refused."""
    from ...errors import ParameterError
    name, lo, hi = axis
    if name in schema.UNIT_PARAMETERS.values():
        raise ParameterError(f"with --si, {schema.PARAMETERS[name].label} is the rod's section (sqrt(I/A)/L): "
                             "chart it without --si, or give the file's I and A")
    convert = rad_per_s if rpm and si_unit(name) == "rad/s" else float
    return name, to_crankgen(name, convert(lo), scales), to_crankgen(name, convert(hi), scales)


def from_model(name, value, scales, rpm=False):
    """A value of an axis in crankgen's units -> in the unit it is shown in (unit_text)."""
    out = to_si(name, value, scales)
    return out * 60.0 / (2.0 * math.pi) if rpm and si_unit(name) == "rad/s" else out


def describe(chart, scales, rpm=False):
    """Lines of text: the box and each curve's range in SI."""
    lines = []
    for axis in (chart.x, chart.y):
        name, lo, hi = axis
        lines.append(f"  in SI: {schema.PARAMETERS[name].si or name} {from_model(name, lo, scales, rpm):.5g}.."
                     f"{from_model(name, hi, scales, rpm):.5g} {unit_text(name, rpm)}")
    xn, yn = chart.x[0], chart.y[0]
    for c in chart.curves:
        xs, ys = (np.asarray([from_model(n, v, scales, rpm) for v in c[n]]) for n in (xn, yn))
        lines.append(f"  {c.label}: {schema.PARAMETERS[xn].si or xn} {xs.min():.5g}..{xs.max():.5g} "
                     f"{unit_text(xn, rpm)}, {schema.PARAMETERS[yn].si or yn} {ys.min():.5g}..{ys.max():.5g} "
                     f"{unit_text(yn, rpm)}")
    return lines


def to_csv(chart, path, scales, rpm=False):
    """curves_si.csv: every point of every curve with both parameters in SI and its amplitude in m."""
    from ...results.exports import suffix
    from ...results.io import write_csv
    xn, yn = chart.x[0], chart.y[0]
    cols = {n: f"{schema.PARAMETERS[n].si or n}_{suffix(unit_text(n, rpm))}".rstrip("_") for n in (xn, yn)}
    r = scales.base["r"]
    rows = []
    for k, c in enumerate(chart.curves):
        for i in range(len(c[xn])):
            rows.append({"curve": k, "kind": c.kind, "period": c.period, cols[xn]: from_model(xn, c[xn][i], scales, rpm),
                         cols[yn]: from_model(yn, c[yn][i], scales, rpm),
                         "amplitude_m": float(c["amplitude"][i]) * r})
    return write_csv(path, ["curve", "kind", "period", cols[xn], cols[yn], "amplitude_m"], rows)


def label(name):
    """An axis' words from its parameter's label, without crankgen's symbols: 'crank speed',
    'crank length', 'end mass', ..."""
    p = schema.PARAMETERS[name]
    text = p.label.split("(", 1)[1].rsplit(")", 1)[0] if "(" in p.label else p.label
    words = []
    for word in text.split():
        if any(c in word for c in "*=/"):
            break
        words.append(word)
    return " ".join(words) or name


def figure(chart, scales, rpm=False):
    """The chart's figure with its axes' ticks (at round SI values) and labels in SI, and its
    title's mechanism in SI (the two axes' parameters left out)."""
    from matplotlib.ticker import MaxNLocator

    from ...declaration.si import describe_si
    from .plot import chart_figure
    xn, yn = chart.x[0], chart.y[0]
    info = chart.info
    values = {k: v for k, v in info.items() if k in schema.PARAMETERS}
    model = ", ".join(str(info[k]) for k in ("approach", "formulation", "damping", "membrane") if k in info)
    import textwrap
    title = (f"stability chart in ({label(xn)}, {label(yn)}): {model}, n = {info.get('n_elements')}\n"
             + textwrap.fill(f"L = {scales.L:g} m, omega_b = {scales.omega_b:.5g} rad/s, rho A = {scales.rhoA:.4g} "
                             f"kg/m, r = {scales.base['r']:.4g} m, "
                             + ", ".join(describe_si(values, scales, skip=(xn, yn))), 100, break_on_hyphens=False))
    fig = chart_figure(chart, title)
    ax = fig.axes[0]
    for axis, which, setter in ((chart.x, ax.xaxis, ax.set_xticks), (chart.y, ax.yaxis, ax.set_yticks)):
        name, lo, hi = axis
        lo_si, hi_si = from_model(name, lo, scales, rpm), from_model(name, hi, scales, rpm)
        ticks = [t for t in MaxNLocator(6).tick_values(lo_si, hi_si) if lo_si - 1e-12 <= t <= hi_si + 1e-12]
        factor = (hi - lo) / (hi_si - lo_si)                          # the conversion is linear
        setter([lo + (t - lo_si) * factor for t in ticks], [f"{t:.0f}" if abs(t) >= 1000 else f"{t:.4g}" for t in ticks])
        which.set_label_text(f"{label(name)} ({unit_text(name, rpm)})")
    return fig


def plot(chart, path, scales, rpm=False):
    from ...results.io import save_figure
    save_figure(figure(chart, scales, rpm), path, dpi=130)
    return path
