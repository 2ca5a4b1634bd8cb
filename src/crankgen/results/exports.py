"""A result's per-step table: every declared output, each column named with its unit, in
crankgen's units or in SI, and the range of the theory per step.

A column is the quantity's name and its unit (`column`): in SI the SI unit (t_s, theta_rad, v_mid_m,
torque_N_m, crank_on_rod_x_N, crank_speed_rad_per_s), in crankgen's units the declared units string
(t_per_omega_b, v_mid_r, u_end_r2_per_L, slider_position_L, torque_rhoA_L3_omega_b2); a
dimensionless quantity is its name alone (extension), the crank angle is in degrees in crankgen's
units (theta_deg).  The outputs are those the result gives per step (`output_names`: the engine's,
and with stored states every step and reduction output of the case's guide), fields at the
positions asked (default the mid-span), then the measures of the range of the theory per step
(deflection_over_L, axial_strain, beyond_theory: crankgen.analyses.theory; for the exact model also
fibre_strain and section_rotation_deg, beyond_theory by its own limits, and range_note).
"""

import numpy as np

from ..declaration import schema
from ..declaration.units import Scales
from ..declaration.ingredients import available

# the result's own per-step arrays beside the declared outputs, and their units
BASE = {"t": "1/omega_b", "theta": "rad"}


def unit_text(units, si=False):
    """A unit as a column's suffix: the SI unit (N_m, rad_per_s, m_per_s2) or crankgen's declared
    units (rhoA_L3_omega_b2, per_omega_b, r2_per_L); '' for a dimensionless one."""
    return suffix(Scales.si_name(units) if si else units)


def suffix(text):
    """A unit's text as a column's suffix (kg/m^3 -> kg_per_m3, N m -> N_m; '1' -> '')."""
    if text == "1":
        return ""
    text = text.replace("^", "").replace(" / ", "/").replace("/", " per ").split()
    if text[:1] == ["1"]:
        text = text[1:]
    return "_".join(text)


def column(name, units, si=False):
    """The column of a quantity: its name and its unit (crank_speed_rad_per_s, v_mid_r,
    extension)."""
    text = unit_text(units, si)
    return f"{name}_{text}" if text else name


def output_names(result):
    """The declared outputs a result gives per step, in the schema's order: the engine's (every
    result), then, for a result with stored states, every step and reduction output of the case's
    guide."""
    names = [name for name, spec in schema.OUTPUTS.items() if spec.engine]
    if getattr(result, "states", None) is not None:
        guide = result.case.guide_record.name
        names += [name for name, spec in schema.OUTPUTS.items()
                  if not spec.engine and spec.kind in ("step", "reduction") and guide in spec.guides
                  and available(name, result.case)]
    return names


def field_names(result, fiber=None):
    """The field outputs of the case's guide a table can hold: those taking no argument but the
    position, and those taking `fiber` when it is given."""
    if getattr(result, "states", None) is None:
        return []
    guide = result.case.guide_record.name
    return [name for name, spec in schema.OUTPUTS.items()
            if spec.kind == "field" and guide in spec.guides and available(name, result.case)
            and all(a == "fiber" and fiber is not None for a in spec.arguments)]


def per_step(result, si=None, x=(0.5,), fiber=None, theory=True, along=False, section=None):
    """(columns, arrays) of a result's per-step table: t, theta, every output of output_names, each
    joint force's magnitude and direction (crankgen.analyses.rod_loads.joint_columns), the fields at x (x* in
    [0, 1]; metres in SI) with `fiber` where a field takes it, (along, or a section) the axial force
    at every node and with a crankgen.sections.Section the outer-fibre stresses there
    (crankgen.analyses.rod_loads.along_rod), and (theory) the range of the theory per step.  si: the
    result's SI view (crankgen.outputs.SIView), or None."""
    view = result if si is None else si
    x = tuple(np.atleast_1d(np.asarray(x, dtype=float))) if x is not None else ()
    if si is None:
        columns, values = ["theta_deg"], [np.degrees(np.asarray(result.theta, dtype=float))]
    else:
        columns, values = [column("theta", BASE["theta"], True)], [np.asarray(si.theta, dtype=float)]
    columns.insert(0, column("t", BASE["t"], si is not None))
    values.insert(0, np.asarray(view.t, dtype=float))
    for name in output_names(result):
        columns.append(column(name, schema.OUTPUTS[name].units, si is not None))
        values.append(np.asarray(view.quantity(name), dtype=float))
    coordinates = getattr(result, "coordinates", None) or {}
    for c in result.case.motion_record.coordinates if coordinates else ():
        if c.crank:                             # the crank's angle and speed are outputs already
            continue
        # another declared co-ordinate (a rotor's angle): its value and rate (an angle's: rad, omega_b)
        for k, (label, units) in enumerate(((c.name, c.units), (c.name + "_rate", "omega_b"))):
            factor = 1.0 if si is None else si.scales.factor(units)
            columns.append(column(label, units, si is not None))
            values.append(np.asarray(coordinates[c.name][:, k], dtype=float) * factor)
    motor = getattr(result, "motor_torque", None)
    if motor is not None:                      # a motor-driven crank: the motor's torque on its curve
        units = schema.OUTPUTS["torque"].units
        columns.append(column("motor_torque", units, si is not None))
        values.append(np.asarray(motor, dtype=float) * (1.0 if si is None else si.scales.factor(units)))
    stored = getattr(result, "states", None) is not None
    if stored:                                 # the bearing loads as magnitude and direction too
        from ..analyses.rod_loads import joint_columns
        for name, units, value in joint_columns(result, si):
            columns.append(name if units is None else column(name, units, si is not None))
            values.append(value)
    for name in field_names(result, fiber):
        spec = schema.OUTPUTS[name]
        arguments = {"fiber": fiber} if "fiber" in spec.arguments else {}
        for xj in x:
            where = f"{xj:g}" + ("" if si is None else "m")
            label = name + (f"_fiber_{fiber:g}" if arguments else "")
            columns.append(column(f"{label}_at_{where}", spec.units, si is not None))
            values.append(np.asarray(view.quantity(name, float(xj), **arguments), dtype=float))
    if stored and (along or section is not None):       # the axial force and stresses along the rod
        from ..analyses.rod_loads import along_rod
        for name, units, value in along_rod(result, si, section):
            name = name if units is None else column(name, units, si is not None)
            if name not in columns:            # the mid-span field, when x* = 1/2 is a node, once
                columns.append(name)
                values.append(value)
    if theory and getattr(result, "case", None) is not None:      # the range needs the case's eps
        from ..analyses import theory as _theory
        from ..declaration.units import in_L
        deflection = np.abs(np.asarray(result.v_mid, dtype=float)) * in_L(schema.OUTPUTS["v_mid"].units,
                                                                          result.case.parameters())
        strain = _theory.axial_strain(result, per_step=True)
        if strain.size != deflection.size:               # no states: the strain is unknown
            strain = np.full(deflection.shape, np.nan)
        if _theory.is_exact(result.case):          # the exact rod: its own limits (crankgen.analyses.theory)
            fibre, rotation = _theory.exact_measures(result, per_step=True)
            if fibre.size != deflection.size:
                fibre = rotation = np.full(deflection.shape, np.nan)
            flags = [_theory.exact_range_flag(result.case.eps, f, r) for f, r in zip(fibre, rotation)]
            columns += ["deflection_over_L", "axial_strain", "fibre_strain", "section_rotation_deg",
                        "beyond_theory", "range_note"]
            values += [deflection, strain, fibre, rotation, np.array([f.label for f in flags], dtype=object),
                       np.array([f.note for f in flags], dtype=object)]
        else:
            columns += ["deflection_over_L", "axial_strain", "beyond_theory"]
            values += [deflection, strain, np.array([_theory.beyond(d, s) for d, s in zip(deflection, strain)],
                                                    dtype=object)]
    return columns, values


def write(path, columns, values):
    """Write the table's columns (arrays of one length) as CSV (crankgen.results.io.write_csv: full
    precision, a number that does not exist an empty field), atomically."""
    from .io import write_csv
    return write_csv(path, columns, (dict(zip(columns, row)) for row in zip(*values)))
