"""What a designer sizes the rod and its bearings by, from a result that stores its states.

- **Along the rod** (`along_rod`): the axial force N at every node, and with a
  crankgen.sections.Section the normal stress at both outer fibres, sigma = N/A - M y/I
  (crankgen.analyses.stresses), per step: columns of the per-step table (simulation.csv, orbit.csv).
- **The bearing loads** (`joint_columns`): every joint force the guide declares as X and Y
  components (crank_on_rod at the crank pin A, rod_on_slider or rod_on_tip at B, the guide's or
  rocker's force) also as magnitude |F| and direction atan2(F_Y, F_X) in the inertial frame
  (counter-clockwise from the X axis, the guide's direction), per step.
- **The peaks** (`peaks`): the largest compression and tension in the rod (axial force, with where
  along the rod and at which crank angle), the Euler buckling margin of the rod under the largest
  compression, and each joint force's largest magnitude with its direction and crank angle; with
  a section the largest tension and compression stress (`stress_peaks`).  One row: steady.csv
  (crankgen.results.steady_row), simulate's summary.csv (crankgen.cli.runs).

**The buckling margin** is the pinned-pinned rod's Euler load pi^2 EI / L^2 over the largest
compressive axial force anywhere along the rod over the result (in crankgen's units the Euler
load is N* = pi^2: N* = N L^2 / EI).  It treats that largest force as acting along the whole rod
(the rod's own inertia makes the compression vary along it: the margin is conservative by the
variation), and the rod as a straight pinned-pinned strut (its deflection under the inertia loads
lowers the load a real rod carries: a margin near 1 is a rod near buckling, as the modes'
divergent frozen states and the range of the theory say too).  Below 1 the compression exceeded
the Euler load: the rod buckles in that state.
"""

import math

import numpy as np

from ..declaration import schema
from ..declaration.ingredients import available

EULER_LOAD = math.pi ** 2          # the pinned-pinned Euler load in units of EI/L^2 (N* = pi^2)
AXIAL = "axial_force"


def joints(guide):
    """[(joint, x output, y output)] of the joint forces a guide declares by components (schema
    order): crank_on_rod, rod_on_slider, guide_on_slider on a slider; rod_on_tip, rocker_on_tip on
    a four-bar."""
    out = []
    for name, spec in schema.OUTPUTS.items():
        if not name.endswith("_x") or spec.kind != "step" or guide not in spec.guides or spec.flexible:
            continue                   # (a flexible body's joint force: not a column of every case of the guide)
        base = name[:-2]
        twin = schema.OUTPUTS.get(base + "_y")
        if twin is not None and guide in twin.guides and spec.units == twin.units \
                and spec.units == schema.OUTPUTS["crank_on_rod_x"].units:
            out.append((base, name, base + "_y"))
    return out


def _nodes(case):
    return np.arange(case.n_elements + 1) / case.n_elements


def _points(case):
    """The nodes and the element midpoints (x*), where the peaks are sought."""
    return np.arange(2 * case.n_elements + 1) / (2 * case.n_elements)


def joint_columns(result, si=None):
    """[(name, units, array)]: each joint force's magnitude (its components' declared units; the
    column is named with them, crankgen.results.exports.column) and direction (units None: the name
    is complete; degrees in crankgen's units, rad in SI, as the crank angle's column), per step."""
    view = result if si is None else si
    out = []
    for base, x, y in joints(result.case.guide_record.name):
        if not available(x, result.case):         # a flexible rocker's tip and pivot forces (not yet)
            continue
        fx, fy = (np.asarray(view.quantity(name), dtype=float) for name in (x, y))
        angle = np.arctan2(fy + 0.0, fx)        # + 0.0: a Y of -0 points at 180 deg, not -180
        out += [(f"{base}_magnitude", schema.OUTPUTS[x].units, np.hypot(fx, fy)),
                (f"{base}_angle_" + ("rad" if si is not None else "deg"), None,
                 angle if si is not None else np.degrees(angle))]
    return out


def along_rod(result, si=None, section=None):
    """[(name, units, array)]: the axial force at every node (x* = i/n, or x in m in SI; its declared
    units) per step, and with a Section the stress at its top and bottom outer fibres there (units
    None: the name is complete, _E for units of E, _Pa in SI)."""
    from .stresses import stress
    case = result.case
    xs = _nodes(case)
    view = result if si is None else si
    length = 1.0 if si is None else si.scales.L
    where = [f"{x * length:g}" + ("m" if si is not None else "") for x in xs]
    units = schema.OUTPUTS[AXIAL].units
    N = np.asarray(view.quantity(AXIAL, xs * length), dtype=float).reshape(len(result.t), -1)
    out = [(f"{AXIAL}_at_{w}", units, N[:, j]) for j, w in enumerate(where)]
    if section is not None:
        history = stress(result, section, x=xs * length, scales=None if si is None else si.scales)
        unit = "Pa" if si is not None else "E"
        for fibre, array in (("top", history.top), ("bottom", history.bottom)):
            out += [(f"stress_{fibre}_at_{w}_{unit}", None, array[:, j]) for j, w in enumerate(where)]
    return out


def _crank_degrees(theta):
    from .stresses import crank_degrees
    return float(crank_degrees(theta))


def peaks(result):
    """{column: value} in crankgen's units (module docstring): peak_compression and peak_tension
    (EI/L^2, positive magnitudes; None when the rod is never in compression or tension) with their
    _x (x*) and _crank_angle_deg, buckling_margin, and per joint peak_<joint> (its unit),
    peak_<joint>_angle_deg (the force's direction) and peak_<joint>_crank_angle_deg."""
    case = result.case
    xs = _points(case)
    theta = np.asarray(result.theta, dtype=float)
    N = np.asarray(result.quantity(AXIAL, xs), dtype=float).reshape(len(theta), -1)
    out = {}
    for name, sign in (("compression", -1.0), ("tension", 1.0)):
        signed = sign * N
        k, j = np.unravel_index(int(np.nanargmax(signed)), signed.shape)
        there = float(signed[k, j]) > 0
        out[f"peak_{name}"] = float(signed[k, j]) if there else None
        out[f"peak_{name}_x"] = float(xs[j]) if there else None
        out[f"peak_{name}_crank_angle_deg"] = _crank_degrees(theta[k]) if there else None
    compression = out["peak_compression"]
    out["buckling_margin"] = None if compression is None else EULER_LOAD / compression
    for base, x, y in joints(case.guide_record.name):
        if not available(x, case):                 # a flexible rocker's tip and pivot forces (not yet)
            out.update({f"peak_{base}": None, f"peak_{base}_angle_deg": None, f"peak_{base}_crank_angle_deg": None})
            continue
        fx, fy = (np.asarray(result.quantity(name), dtype=float) for name in (x, y))
        magnitude = np.hypot(fx, fy)
        k = int(np.nanargmax(magnitude))
        out[f"peak_{base}"] = float(magnitude[k])
        out[f"peak_{base}_angle_deg"] = float(math.degrees(math.atan2(fy[k] + 0.0, fx[k])))
        out[f"peak_{base}_crank_angle_deg"] = _crank_degrees(theta[k])
    return out


def peak_columns(guide):
    """The columns of `peaks` for a guide, in order."""
    out = []
    for name in ("compression", "tension"):
        out += [f"peak_{name}", f"peak_{name}_x", f"peak_{name}_crank_angle_deg"]
    out.append("buckling_margin")
    for base, _, _ in joints(guide):
        out += [f"peak_{base}", f"peak_{base}_angle_deg", f"peak_{base}_crank_angle_deg"]
    return out


def units_of(name):
    """The declared units of a column of `peaks` (None for degrees and words), or False when the
    column is not one of them."""
    if name in ("peak_compression", "peak_tension"):
        return schema.OUTPUTS[AXIAL].units
    if name in ("peak_compression_x", "peak_tension_x"):
        return "L"
    if name == "buckling_margin":
        return "1"
    if name.endswith("_deg") and name.startswith("peak_"):
        return None
    if name.startswith("peak_") and name[5:] + "_x" in schema.OUTPUTS and name[5:] + "_y" in schema.OUTPUTS:
        return schema.OUTPUTS[name[5:] + "_x"].units
    return False


def meaning(name):
    """What a column of `peaks` is, in words ('' when it is not one)."""
    fixed = {
        "peak_compression": "the largest compressive axial force in the rod over the response (a positive "
                            "magnitude; empty when the rod is never compressed), nodes and element midpoints",
        "peak_compression_x": "where along the rod (from the crank pin) the largest compression acts",
        "peak_compression_crank_angle_deg": "the crank angle (degrees, 0-360) at which the largest compression acts",
        "peak_tension": "the largest tensile axial force in the rod over the response (empty when never in tension)",
        "peak_tension_x": "where along the rod (from the crank pin) the largest tension acts",
        "peak_tension_crank_angle_deg": "the crank angle (degrees, 0-360) at which the largest tension acts",
        "buckling_margin": "the pinned-pinned rod's Euler load pi^2 EI/L^2 over the largest compression "
                           "(below 1: the compression exceeds it; conservative: the largest compression "
                           "taken along the whole rod)",
    }
    if name in fixed:
        return fixed[name]
    for suffix, text in (("_crank_angle_deg", "the crank angle (degrees, 0-360) at which the largest {} acts"),
                         ("_angle_deg", "the direction of the {} at its largest (degrees from the X axis, "
                                        "counter-clockwise, inertial frame)"), ("", "the largest magnitude of the {}")):
        if name.startswith("peak_") and name.endswith(suffix):
            base = name[5:len(name) - len(suffix)] if suffix else name[5:]
            spec = schema.OUTPUTS.get(base + "_x")
            if spec is not None:
                what = spec.doc.split(" (")[0].replace("X component of the ", "")
                return text.format(what)
    return ""


def stress_peaks(result, section, si=None):
    """{column: value} of the outer-fibre stresses of a result: peak_stress (largest tension),
    min_stress (largest compression), each with _x, _fibre, _crank_angle_deg, and stress_range (the
    largest range over a complete revolution; None without one); in units of E (sigma / E), or in
    Pa with si (the crankgen.SIMechanism of the result: columns named _Pa, positions _m)."""
    from .stresses import stress
    history = stress(result, section, si=si)
    unit, length = ("_Pa", "_m") if si is not None else ("", "")
    out = {}
    for name, point in (("peak_stress", history.maximum), ("min_stress", history.minimum)):
        out[name + unit] = point.value
        out[f"{name}_x{length}"] = point.x
        out[f"{name}_fibre"] = point.fibre
        out[f"{name}_crank_angle_deg"] = _crank_degrees(point.theta)
    out["stress_range" + unit] = history.range
    return out


def summary_line(values, si=False):
    """One line of the peaks for a command's output: the largest compression with where and when,
    the buckling margin, and the bearing loads' peaks with their direction (values: `peaks`, in SI
    with si: the SI columns of crankgen.results.si_row.row_in_si beside them)."""
    force = "N" if si else "EI/L^2"

    def x_text(name):
        return f"x = {values[name + '_x_m']:.4g} m" if si else f"x* = {values[name + '_x']:.4g}"
    parts = []
    c = values.get("peak_compression_N" if si else "peak_compression")
    if c is not None:
        parts.append(f"largest compression {c:.4g} {force} at {x_text('peak_compression')}, crank angle "
                     f"{values['peak_compression_crank_angle_deg']:.1f} deg; Euler buckling margin "
                     f"{values['buckling_margin']:.3g} (pi^2 EI/L^2 over it)")
    t = values.get("peak_tension_N" if si else "peak_tension")
    if t is not None:
        parts.append(f"largest tension {t:.4g} {force} at {x_text('peak_tension')}, crank angle "
                     f"{values['peak_tension_crank_angle_deg']:.1f} deg")
    return "axial force: " + ("; ".join(parts) if parts else "none")
