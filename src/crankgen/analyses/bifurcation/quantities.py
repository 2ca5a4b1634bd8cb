"""The physical quantities of the orbits along a mechanism's branches.

Every point of a branch of a BifurcationDiagram (crankgen.continuation) is an orbit: its state at
theta0 and its period.  Marched for its period from that state (the points of a branch in engine
batches), its declared outputs (outputs.StateHistory, every one from the generated kernels) give,
over the orbit:
- peak_v: max |v*(1/2)| over the steps (the branch's amplitude is the same refined between steps);
- peak_torque: the driving torque of largest magnitude, signed;
- peak_pin_force_A, peak_pin_force_B, peak_support_force: the largest magnitude of the joint
  forces (outputs.py): the crank's on the rod at A (crank_on_rod), the rod's on the slider or the
  rocker's tip at B (rod_on_slider, rod_on_tip), the support's: the guide's on the slider or the
  ground's on the rocker at its pivot (guide_on_slider, ground_on_rocker: the rocker's force on its
  tip when the rocker is massless);
- peak_axial_force: the axial force N* of largest magnitude along the rod, signed (tension > 0);
- peak_strain: the largest |surface_strain| at the outer fibres, fiber = +-sqrt(3) radii of
  gyration (a rectangular section's outer fibres) or, with a section, its own;
- peak_stress (with a crankgen.sections.Section): the stress of largest magnitude at the outer
  fibres, sigma = N/A - M y/I (crankgen.stress), in units of E (or Pa with si, the
  crankgen.SIMechanism of the diagram).
Fields are read at the nodes and the element midpoints.  Units: those the outputs declare
(crankgen's units), listed by units(); a point whose orbit cannot be marched has NaN and its reason
in the branch's quantity_notes.

A motor-driven crank's point (motor_branch_quantities) is its section state on theta = theta0
(mod 2 pi); its orbit is the autonomous motion from there over its `period` revolutions, marched
by the continuation's own section map (analyses/section.py CrankSection: each
revolution's last step lands on the section), the crank's angle, speed and acceleration per step
from that run (the declared outputs read the kinematics of them, as a motor simulation's do).
Beside the quantities above (peak_torque: the torque T_rod the rod demands of the crank), it
carries, in motor_units():
- mean_speed = 2 pi k / T and revolution_time = T / k over the k revolutions of time T;
- min_crank_speed, max_crank_speed: the extremes of thetad over the orbit's steps;
- peak_motor_torque: the motor's torque T_m(thetad) of largest magnitude over the steps, signed
  (on the case's torque-speed curve, crankgen.torque_curve; T_m = J thetadd + T_load + T_rod along
  the orbit);
- rms_motor_torque = sqrt(<T_m^2>) (the torque a motor's thermal rating is sized by) and
  mean_motor_power = <T_m thetad>, <.> the time mean over the orbit by the trapezoidal rule on its
  steps (the last one shorter: it lands on the section).  Over a periodic orbit the motor's work
  T <T_m thetad> is the load's, 2 pi k T_load, and the damping's.
"""

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ... import engine
from ...declaration import schema
from ...discrete import kinematics as _kinematics
from ...declaration.ingredients import available
from ...results import motor_duty, reductions
from ...results.outputs import DeclaredOutputs
from ..marching import coordinate_histories, crank_of
from .maps import MapError
from .mechanism import V_MID

QUANTITIES = ("peak_v", "peak_torque", "peak_pin_force_A", "peak_pin_force_B", "peak_support_force",
              "peak_axial_force", "peak_strain", "peak_stress")
# the joint forces each quantity reads, the first whose output the case's guide declares
JOINTS = {"peak_pin_force_A": ("crank_on_rod",), "peak_pin_force_B": ("rod_on_slider", "rod_on_tip"),
          "peak_support_force": ("guide_on_slider", "ground_on_rocker")}
RECTANGLE_FIBRE = math.sqrt(3.0)        # outer fibre of a rectangle, in radii of gyration
CHUNK = 64                              # orbits marched in one batch
# a motor-driven crank's own quantities (module docstring), before the others in motor_units()
MOTOR_QUANTITIES = ("mean_speed", "revolution_time", "min_crank_speed", "max_crank_speed", "peak_motor_torque",
                    "rms_motor_torque", "mean_motor_power")


def units(section=None, si=None, case=None):
    """{quantity: units text} (crankgen's units, or SI with si); with the case, its declared
    reductions over the orbit too (crankgen.results.reductions)."""
    out = {"peak_v": "r (v* = v/r)", "peak_torque": schema.OUTPUTS["torque"].units,
           "peak_pin_force_A": schema.OUTPUTS["crank_on_rod_x"].units,
           "peak_pin_force_B": schema.OUTPUTS["rod_on_slider_x"].units,
           "peak_support_force": schema.OUTPUTS["guide_on_slider_x"].units,
           "peak_axial_force": schema.OUTPUTS["axial_force"].units, "peak_strain": "1"}
    if section is not None:
        out["peak_stress"] = "Pa" if si is not None else "E"
    for r in ([] if case is None else reductions.declared(case)):
        out[r.name] = r.units
    return out


def motor_units(section=None, si=None, case=None):
    """{quantity: units text} of a motor-driven crank's branch point (crankgen's units, or SI with si):
    MOTOR_QUANTITIES, then units()'s."""
    speed = schema.OUTPUTS["crank_speed"].units
    out = {"mean_speed": speed, "revolution_time": f"1/{speed}", "min_crank_speed": speed,
           "max_crank_speed": speed, **motor_duty.duty_units()}
    return dict(out, **units(section, si, case))


@dataclass(frozen=True)
class Orbit(DeclaredOutputs):
    """One orbit of a branch point, every declared output by name (outputs.DeclaredOutputs)."""

    case: object
    t: np.ndarray = field(repr=False)
    theta: np.ndarray = field(repr=False)
    v_mid: np.ndarray = field(repr=False)
    states: np.ndarray = field(repr=False)
    rates: np.ndarray = field(repr=False)
    accelerations: np.ndarray = field(repr=False)
    crank: np.ndarray = field(default=None, repr=False)    # a driven crank's (theta, thetad, thetadd) per step
    coordinates: dict = field(default=None, repr=False)    # a driven motion's co-ordinates: name -> (steps, 3)


def _peak_signed(values):
    values = np.asarray(values, dtype=float)
    k = int(np.argmax(np.abs(values)))
    return float(values.ravel()[k])


def _joint_magnitude(orbit, choices):
    """max |F| over the orbit of the first joint force of choices the case's guide declares."""
    here = orbit.case.guide_record.name
    name = next(c for c in choices if here in schema.OUTPUTS[c + "_x"].guides)
    if not available(name + "_x", orbit.case):      # a force a flexible rocker's joints do not give (yet)
        return math.nan
    return float(np.max(np.hypot(*(np.asarray(orbit.quantity(name + p), dtype=float) for p in ("_x", "_y")))))


def orbit_quantities(orbit, section=None, si=None):
    """{quantity: value} of one Orbit (module docstring)."""
    n = orbit.case.n_elements
    xs = np.arange(2 * n + 1) / (2 * n)
    out = {"peak_v": float(np.max(np.abs(orbit.v_mid)))}
    try:
        out["peak_torque"] = _peak_signed(orbit.quantity("torque"))
    except Exception:
        out["peak_torque"] = math.nan
    for quantity, choices in JOINTS.items():
        out[quantity] = _joint_magnitude(orbit, choices)
    out["peak_axial_force"] = _peak_signed(orbit.quantity("axial_force", xs))
    fibres = ((section.c_top / section.radius_of_gyration, -section.c_bottom / section.radius_of_gyration)
              if section is not None else (RECTANGLE_FIBRE, -RECTANGLE_FIBRE))
    out["peak_strain"] = max(float(np.max(np.abs(orbit.quantity("surface_strain", xs, fiber=f)))) for f in fibres)
    if section is not None:
        from ..stresses import stress
        hist = stress(orbit, section, si=si)
        out["peak_stress"] = hist.largest.value
    for r in reductions.declared(orbit.case):       # the declared reductions over the orbit
        x = reductions.value(orbit, r)
        out[r.name] = math.nan if x is None else x
    return out


def branch_quantities(case, parameter, branch, section=None, si=None):
    """({quantity: (points,) array}, notes): the quantities of every point of a Branch whose states
    are the revolution map's at theta0 ((d, v), or (d, v, a) for generalized-alpha), `parameter` the diagram's, case the diagram's case."""
    names = list(units(section, si, case))
    values = {k: np.full(len(branch), math.nan) for k in names}
    notes = []
    period = int(branch.period)
    cases = [replace(case, **{parameter: float(p)}) for p in branch.parameter]
    template = None
    for lo in range(0, len(cases), CHUNK):
        part = cases[lo:lo + CHUNK]
        batch = engine.Batch(part, like=template, entries=("march",))
        template = template or batch
        spr = batch.steps_per_rev
        X = np.asarray(branch.states[lo:lo + CHUNK], dtype=float)
        res = engine.march_state(batch, period * spr, X, keep_history=True, parallel=len(part) > 1)
        for j, c in enumerate(part):
            i = lo + j
            if res.status[j] != engine.OK:
                notes.append(f"point {i}: the orbit's march failed ({engine.STATUS_TEXT[int(res.status[j])]})")
                continue
            t = float(batch.dt[j]) * np.arange(period * spr + 1)
            orbit = Orbit(c, t, _kinematics.case_state(c, t).theta, res.y[j, :, V_MID], res.D_history[j],
                          res.V_history[j], res.A_history[j])
            for k, v in orbit_quantities(orbit, section, si).items():
                values[k][i] = v
    return values, notes


def motor_orbit(fmap, state, p, period):
    """(Orbit, T): the orbit of a driven crank's branch point (module docstring): its section state
    (physical, as a Branch holds it) marched `period` revolutions by the AutonomousMap fmap at
    parameter p, T their time; the crank angle (and every angle that turns with it) runs on over
    the revolutions.  MapError if a revolution fails."""
    _, T, revolutions = fmap.revolutions(state, p, period)
    case = fmap.case_at(p)
    n_rod = fmap.n_rod
    turning = [j for j, c in enumerate(case.motion_record.coordinates) if c.units == "rad"]
    X, V, A, y, Z, t = [], [], [], [], [], []
    start = 0.0
    for k, rev in enumerate(revolutions):
        skip = 0 if k == 0 else 1                 # a revolution starts where the last one landed
        z = rev["Z"][skip:].copy()
        z[:, turning] += 2.0 * math.pi * k
        X.append(rev["X"][skip:, :n_rod])
        V.append(rev["V"][skip:, :n_rod])
        A.append(rev["A"][skip:, :n_rod])
        y.append(rev["y"][skip:])
        Z.append(z)
        t.append(rev["t"][skip:] + start)
        start += rev["t"][-1]
    X, V, A, y, Z, t = (np.concatenate(a) for a in (X, V, A, y, Z, t))
    coordinates = coordinate_histories(case, Z)
    crank = crank_of(case, coordinates)
    orbit = Orbit(case, t, crank[:, 0], y[:, V_MID], X, V, A, crank=crank, coordinates=coordinates)
    return orbit, T


def motor_orbit_quantities(orbit, T, period, section=None, si=None):
    """{quantity: value} of one driven Orbit of `period` revolutions in the time T (module
    docstring); the motor's duty at the speed of the co-ordinate it drives."""
    speed = orbit.crank[:, 1]
    motor = next(c.name for c in orbit.case.motion_record.coordinates if c.motor)
    out = {"mean_speed": 2.0 * math.pi * period / T, "revolution_time": T / period,
           "min_crank_speed": float(np.min(speed)), "max_crank_speed": float(np.max(speed)),
           **motor_duty.duty(orbit.case, orbit.t, orbit.coordinates[motor][:, 1])}
    return dict(out, **orbit_quantities(orbit, section, si))


def motor_branch_quantities(fmap, branch, section=None, si=None):
    """({quantity: (points,) array}, notes): the quantities of every point of a motor-driven
    crank's Branch (its states the section states of the AutonomousMap fmap), one orbit at a time."""
    values = {k: np.full(len(branch), math.nan) for k in motor_units(section, si, fmap.case)}
    notes = []
    period = int(branch.period)
    for i, (state, p) in enumerate(zip(branch.states, branch.parameter)):
        try:
            orbit, T = motor_orbit(fmap, state, float(p), period)
        except MapError as exc:
            notes.append(f"point {i}: the orbit's march failed ({exc})")
            continue
        for k, v in motor_orbit_quantities(orbit, T, period, section, si).items():
            values[k][i] = v
    return values, notes
