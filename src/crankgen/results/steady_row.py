"""The row of a steady state (steady.csv, sweep.csv and a sweep's checkpoint): what every column is,
with its units, and the row in SI.

Columns, in order: the case's parameters (schema order; empty where the case's guide or crank
motion does not read them: a slider's row has no c, d, branch, a constant speed's no omega0, ramp,
fluctuation, order), the model (the preset its options match, empty for none), the model options
and the audit's switched-off groups, then the results (RESULTS: status, amplitude, half
peak-to-peak, the range of the theory, ...) with, after range_note, the peak over the orbit of
every load the case's guide declares (`peak_<output>`: the largest |value| of each declared step
output whose unit is a force or a moment: the driving torque, the joint forces' components), and
every declared reduction over the revolution (schema.REDUCTIONS: crankgen.results.reductions).
A number that does not exist is None (an empty CSV field).  The units of a column are crankgen's
declared units strings (crankgen.declaration.units); `in_si` turns a row into SI, each column then named with
its SI unit.
"""

import math

import numpy as np

from ..declaration import schema
from .motor_duty import duty_units
from ..declaration.units import Scales
from . import reductions
from ..declaration.ingredients import available

AMPLITUDE_UNITS = schema.OUTPUTS["v_mid"].units        # the amplitude is of v*(1/2), in its units

# the result columns of a row: (name, units or None for words, meaning); "peak_*" follow range_note
RESULTS = (
    ("status", None, "periodic (a stable periodic orbit), unstable (an orbit with a Floquet multiplier "
                     "outside the unit circle), not-periodic or failed; the message says why"),
    ("amplitude", AMPLITUDE_UNITS, "max |v*(1/2)| over the orbit: the largest mid-span deflection from the "
                                   "rigid rod, in units of the radius of gyration r"),
    ("half_peak_to_peak", AMPLITUDE_UNITS, "half the peak-to-peak of v*(1/2) over the orbit, (max - min) / 2"),
    ("deflection_over_L", "1", "the amplitude as a deflection over the rod's length, |v|/L = eps max|v*|: "
                               "beyond the theory above 0.1 (the paper's range; not a limit of the exact model)"),
    ("axial_strain", "1", "the largest axial strain of the neutral axis over the orbit (the approach's "
                          "membrane strain, nodes and element midpoints): beyond the theory above 0.01 "
                          "(the paper's range; not a limit of the exact model)"),
    ("fibre_strain", "1", "exact model only: the largest |strain| at the outer fibres of a rectangular "
                          "section (fiber = +-sqrt(3) r) over the orbit: beyond its limits above 0.005"),
    ("section_rotation_deg", None, "exact model only: the largest section rotation from the chord over the "
                                   "orbit in degrees, asin(|v_x| / lambda) at the element ends: beyond its "
                                   "limits above 60"),
    ("beyond_theory", None, "yes when deflection_over_L or axial_strain exceeds its limit (the numbers are "
                            "then the equations' output, not a prediction of the rod), no when neither does; "
                            "for the exact model by its own limits: eps > 0.05, fibre_strain, "
                            "section_rotation_deg"),
    ("range_note", None, "when beyond: the limits exceeded and what to use (model=\"exact\" beyond the "
                         "paper's range; for the exact model what its limits leave out); empty otherwise"),
    ("model_error", "1", "the estimated relative difference of the orbit from the exact rod's (largest |v| of "
                         "the first-order correction over the largest |v|: crankgen.analyses.model_error; 0 for the "
                         "exact model; empty for a motor-driven crank); accurate near 1 %, an overestimate "
                         "where large"),
    ("verdict", None, "which model to trust here: 'trust this model here' (model_error <= 1 % within the exact "
                      "rod's limits), 'use the exact rod' (model_error > 1 %), 'beyond both' (beyond the exact "
                      "rod's own limits: slenderness, outer-fibre strain, section rotation)"),
    ("periods", "rev", "crank revolutions marched: the warm-up from rest and any marching fallback"),
    ("iterations", "1", "Newton iterations of shooting"),
    ("residual", "1", "the scaled change |P(x) - x| of the returned state over one revolution"),
    ("multiplier", "1", "the largest |Floquet multiplier| of the orbit (1 or more: unstable)"),
    ("wall_time", None, "wall-clock seconds (s) the computer spent on the case (for a batch: its wall "
                        "time shared equally by its cases)"),
    ("message", None, "why a case is not periodic, failed or is marked; empty otherwise"),
)
# a motor-driven crank's steady motion (crankgen.analyses.steady, on the section map) adds, before `periods`:
_DUTY = duty_units()                   # what sizes its motor (results/motor_duty.py)
MOTOR_RESULTS = (
    ("revolution_time", "1/omega_b", "a motor-driven crank's steady revolution time T (its period)"),
    ("mean_speed", "omega_b", "a motor-driven crank's mean speed 2 pi / T over the steady revolution"),
    ("speed_fluctuation", "1", "a motor-driven crank's speed fluctuation over the steady revolution, "
                               "(max - min crank speed) / mean speed"),
    ("peak_motor_torque", _DUTY["peak_motor_torque"], "the motor's torque T_m(thetad) of largest magnitude over "
                                                      "the steady revolution, signed (on its torque-speed curve)"),
    ("rms_motor_torque", _DUTY["rms_motor_torque"], "the RMS of the motor's torque over the steady revolution "
                                                    "(what a motor's thermal rating is sized by)"),
    ("mean_motor_power", _DUTY["mean_motor_power"], "the motor's mean power T_m thetad over the steady revolution"),
)
PEAK = "peak_"
_RESULT_UNITS = {name: units for name, units, _ in RESULTS + MOTOR_RESULTS}
CLOCK = {"wall_time": "s"}             # quantities of the computer, not of the mechanism: SI always


def is_load(units):
    """True for a force or a moment (SI unit N or N m)."""
    return Scales.si_name(units) in ("N", "N m")


def load_outputs(guide):
    """The declared step outputs of a guide that are loads (a force or a moment), schema order."""
    return [name for name, o in schema.OUTPUTS.items()       # (a flexible body's: not a column of every row)
            if o.kind == "step" and not o.engine and guide in o.guides and is_load(o.units) and not o.flexible]


def _number(x):
    x = None if x is None else float(x)
    return x if x is not None and math.isfinite(x) else None


def row(state):
    """The row of a crankgen.SteadyState (module docstring)."""
    from ..analyses import theory
    from ..declaration.units import in_L
    case = state.case
    values = case.parameters()
    guide, motion = case.guide_record.name, case.motion_record.name
    out = {}
    for name, p in schema.PARAMETERS.items():
        value = values[name] if p.read_by(guide, motion) else None
        out[name] = list(value) if isinstance(value, tuple) else value
    out["model"] = case.model
    out.update(case.options)
    out["groups_off"] = case.groups_off
    has_orbit = getattr(state, "states", None) is not None
    deflection = (None if state.amplitude is None
                  else _number(theory.deflection_over_L(in_L(AMPLITUDE_UNITS, values), state.amplitude)))
    strain = _number(theory.axial_strain(state)) if has_orbit else None
    if theory.is_exact(case):
        fibre, rotation = theory.exact_measures(state) if has_orbit else (math.nan, math.nan)
        fibre, rotation = _number(fibre), _number(rotation)
        exact = theory.exact_range_flag(case.eps, math.nan if fibre is None else fibre,
                                        math.nan if rotation is None else rotation)
        flag, note = (exact.label if has_orbit else ""), exact.note
    else:
        fibre = rotation = None
        flag = theory.beyond(math.nan if deflection is None else deflection, math.nan if strain is None else strain)
        note = theory.range_flag(math.nan if deflection is None else deflection,
                                 math.nan if strain is None else strain).note
    results = dict(status=state.status, amplitude=state.amplitude, half_peak_to_peak=state.half_peak_to_peak,
                   deflection_over_L=deflection, axial_strain=strain, fibre_strain=fibre,
                   section_rotation_deg=rotation, beyond_theory=flag or None, range_note=note or None)
    judged = state.verdict if has_orbit else None
    results.update(model_error=None if judged is None else _number(judged.error),
                   verdict=(judged.words or None) if judged is not None else None)
    for name in load_outputs(guide):
        results[PEAK + name] = (_number(np.max(np.abs(np.asarray(state.quantity(name), dtype=float))))
                                if has_orbit and available(name, case) else None)
    for r in reductions.declared(case):              # the declared reductions over the revolution
        results[r.name] = _number(reductions.value(state, r)) if has_orbit else None
    from ..analyses import rod_loads                    # the rod's axial force, buckling margin, bearing loads
    peaks = rod_loads.peaks(state) if has_orbit else {}
    results.update({name: _number(peaks.get(name)) for name in rod_loads.peak_columns(guide)})
    if getattr(state, "period", None) is not None:
        results.update(revolution_time=state.period, mean_speed=state.mean_speed,
                       speed_fluctuation=state.speed_fluctuation, **(state.motor_duty or {}))
    results.update(periods=state.periods, iterations=state.iterations, residual=state.residual,
                   multiplier=state.multiplier, wall_time=state.wall_time, message=state.message)
    out.update(results)
    return out


def units_of(column):
    """The declared units of a row's column (None for words: status, the choices, the options)."""
    from ..analyses import rod_loads
    if column in schema.PARAMETERS:
        p = schema.PARAMETERS[column]
        return p.units if p.kind in ("real", "pair") else None
    if column in _RESULT_UNITS:
        return _RESULT_UNITS[column]
    design = rod_loads.units_of(column)
    if design is not False:
        return design
    if column.startswith(PEAK) and column[len(PEAK):] in schema.OUTPUTS:
        return schema.OUTPUTS[column[len(PEAK):]].units
    return reductions.units(column)


def meaning(column):
    """What a row's column is, in words."""
    if column in schema.PARAMETERS:
        p = schema.PARAMETERS[column]
        readers = f" [{' and '.join(p.readers)} {p.owner} only: empty otherwise]" if p.owner in ("guide", "motion") \
            and set(p.readers) != set(schema.GUIDES if p.owner == "guide" else schema.MOTIONS) else ""
        return p.doc + readers
    if column in schema.OPTIONS:
        return "model option: " + schema.OPTIONS[column].doc
    if column == "model":
        return ("the named model whose options the case has (" + ", ".join(schema.PRESETS)
                + "); empty when the options match none")
    if column == "groups_off":
        return "the audit's switched-off term groups (empty: none)"
    for name, _, text in RESULTS + MOTOR_RESULTS:
        if name == column:
            return text
    from ..analyses import rod_loads
    design = rod_loads.meaning(column)
    if design:
        return design
    if column.startswith(PEAK) and column[len(PEAK):] in schema.OUTPUTS:
        return "the largest |value| over the orbit of: " + schema.OUTPUTS[column[len(PEAK):]].doc
    return reductions.meaning(column)


def describe(columns, si=False):
    """[{column, units, meaning}] of a table's columns (crankgen's declared units, or SI;
    "dimensionless" for a number, empty for words); a pair's two columns (gravity_x, gravity_y: crankgen.results.tables.PAIRS) are its components."""
    from .tables import PAIRS
    parts = {c: (name, k) for name, pair in PAIRS.items() for k, c in enumerate(pair)}
    out = []
    for c in columns:
        name, k = parts.get(c, (c, None))
        units = units_of(name)
        text = CLOCK.get(name, "" if units is None else (Scales.si_name(units) if si else units))
        text = "dimensionless" if text == "1" else text
        what = meaning(name) + ("" if k is None else f" ({'XY'[k]} component)")
        out.append({"column": c, "units": text, "meaning": what})
    return out
