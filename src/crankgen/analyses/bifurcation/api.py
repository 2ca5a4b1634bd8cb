"""crankgen.continuation and crankgen.poincare: the mechanism on the continuation core."""

import time
from dataclasses import replace

import numpy as np

from ...discrete import kinematics as _kinematics
from ... import notices
from ...declaration import schema
from ...discrete import time_scheme
from ...notices import BeyondTheoryWarning
from ...declaration.cases import run_case
from ...errors import NoResultError, ParameterError
from ...declaration.parameters import check_full_turn
from ..limits import count
from ...declaration.validation import choice, in_range, sequence
from .core import CORRECTORS, PREDICTORS, Continuer, Settings
from .mechanism import PARAMETERS, MechanismMap, mechanism_map


def make_case(mech, parameter, value, case, **fields):
    """The Case of the first point: case (if given) or mech + the run's fields and model, with
    parameter = value; its time step checked against the crank motion (kinematics.check_crank_steps)."""
    choice("parameter", parameter, PARAMETERS)
    base = run_case(mech, case, **fields)
    p = schema.PARAMETERS[parameter]
    if not p.read_by(base.guide, base.motion):
        current = base.guide if p.owner == "guide" else base.motion
        raise ParameterError(f"cannot vary {p.label}: it belongs to the "
                             f"{' and '.join(p.readers)} {p.owner}; this case's {p.owner} is {current!r}")
    out = replace(base, **{parameter: value})
    if out.periodic:
        T = _kinematics.period(out)
        _kinematics.check_crank_steps(out, T / out.steps_per_rev, T, f"{parameter} = {value:g}: ")
    return out


def locking_limit(case, parameter, start, stop, samples=400):
    """(value, the guide's condition that fails) of the first value of `parameter` from start
    towards stop at which the crank cannot turn a full revolution (the guide's margins,
    parameters.check_full_turn), to 1e-12 of the range by bisection; None when there is none.
    A four-bar that locks for |d| < 0.3 continued from d = -1 to 1 stops short of -0.3: this
    names why."""
    def fails(p):
        try:
            check_full_turn(dict(case.parameters(), **{parameter: float(p)}))
            return None
        except ParameterError as exc:
            return str(exc)
    hi = _boundary(fails, start, stop, samples)
    if hi is None:
        return None
    why = fails(hi)
    needs = why.split("needs ", 1)[-1].split("; got", 1)[0]
    return hi, f"the {case.guide_record.name} guide needs {needs}"


def _motor_shortfall(case, speed):
    """T_load - T_m(speed) (...,): the sum of the declared co-ordinates' equations (the generated
    coordinates_<motion>, a torque curve's departure from the linear law on the motor's row, as
    discrete.system.Model.coordinate_equations) with every co-ordinate at rest at its start but
    turning at `speed`, no acceleration and no force at the pin (no linkage): what couples the
    co-ordinates (a shaft's torque, untwisted and not twisting) cancels in the sum."""
    from ..._generated import kinematics as generated
    from ...declaration import torque_curve
    from ...discrete import kinematics
    coords = case.motion_record.coordinates
    m = len(coords)
    speed = np.asarray(speed, dtype=float)
    z0, _ = kinematics.coordinates_start(case)
    z = np.concatenate([np.broadcast_to(z0, speed.shape + (m,)), np.repeat(speed[..., None], m, axis=-1),
                        np.zeros(speed.shape + (m,))], axis=-1)
    theta0 = z0[next(j for j, c in enumerate(coords) if c.crank)]
    kin = kinematics.crank_state(case, np.stack([np.full_like(speed, theta0), speed, np.zeros_like(speed)], axis=-1))
    g = np.array(getattr(generated, f"coordinates_{case.motion_record.name}")(
        kin.vector, z, np.zeros(speed.shape + (2,)), case.kinematic_parameters), dtype=float)[..., 0]
    law = torque_curve.of(case)
    motor = next((j for j, c in enumerate(coords) if c.motor), None)
    if motor is not None and law is not None and tuple(law[0]) != torque_curve.LINEAR:
        curve, stall, no_load, _ = law
        g[..., motor] -= stall * torque_curve.departure(curve, speed / no_load)[0]
    return g.sum(axis=-1)


def stall_limit(case, parameter, start, stop, samples=400):
    """(value, why) of the first value of `parameter` from start towards stop at which a motor
    cannot turn the crank: its drive T_m(speed) - T_load (the declared co-ordinates' equations at
    rest on no linkage: _motor_shortfall) is nowhere positive for speeds in [0, 1.2 Omega_nl]; to
    1e-12 of the range by bisection; None when there is none or the crank is prescribed.  A motor
    continued in its load torque towards its stall torque stops short of it (the linkage's own
    torque over a revolution takes the rest): this names why."""
    from dataclasses import replace as _replace

    from ...declaration import torque_curve
    if not case.motion_record.coordinates or torque_curve.of(case) is None:
        return None
    s = np.linspace(torque_curve.SPAN[0], torque_curve.SPAN[1], 241)

    def stalls(p):
        c = _replace(case, **{parameter: float(p)})
        return bool(np.all(_motor_shortfall(c, s * torque_curve.of(c)[2]) >= 0))   # speeds up to 1.2 Omega_nl
    try:
        hi = _boundary(stalls, start, stop, samples)
    except (ParameterError, ValueError, ZeroDivisionError, FloatingPointError):
        return None
    return None if hi is None else (hi, "the motor's torque T_m no longer exceeds the load torque at any speed")


def _boundary(bad, start, stop, samples):
    """The first parameter value from start towards stop where bad(value) holds, to 1e-12 of the
    range: samples + 1 values, then bisection; None where it holds at none of them or at start."""
    values = np.linspace(start, stop, samples + 1)
    k = next((k for k, p in enumerate(values) if bad(p)), None)
    if k is None or k == 0:
        return None
    lo, hi = float(values[k - 1]), float(values[k])
    while abs(hi - lo) > 1e-12 * abs(stop - start):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if bad(mid) else (mid, hi)
    return hi


def _check_progress(progress):
    if progress is not None and not callable(progress):
        raise ParameterError(f"progress must be None or a function, got {progress!r}")


def si_parameter(mech, parameter, units, fields, case, values):
    """(mechanism, fields, scales, values in crankgen's units) of an analysis over `parameter`: with
    units="si" the SIMechanism's dimensionless mechanism and crank motion, and the parameter's
    values given in its SI unit (crankgen.declaration.si), a parameter that is a unit (the slenderness: the
    rod's section, which sets the units) refused."""
    from ...declaration.si import si_input, to_crankgen
    mech, crank, scales = si_input(mech, units, fields, case=case, crank=fields.pop("crank", None),
                                   what="a continuation")
    if scales is None:
        return mech, dict(fields, crank=crank) if crank is not None else fields, None, values
    if parameter in schema.UNIT_PARAMETERS.values():
        raise ParameterError(f"in SI, {schema.PARAMETERS[parameter].label} is the rod's section (it sets the "
                             f"units: omega_b, r): vary it in crankgen's units, or the SI mechanism's I and A")
    choice("parameter", parameter, PARAMETERS)
    return mech, dict(fields, crank=crank), scales, [to_crankgen(parameter, v, scales) for v in values]


def _add_quantities(diagram, case, parameter, section, progress, fmap=None):
    """Every branch point's physical quantities (quantities.py); fmap: a driven crank's
    AutonomousMap, whose section map marches its points' orbits."""
    from .quantities import branch_quantities, motor_branch_quantities, motor_units, units
    for k, br in enumerate(diagram.branches):
        if progress is not None:
            progress(f"branch {k}: the physical quantities of its {len(br)} orbits")
        if fmap is None:
            br.quantities, br.quantity_notes = branch_quantities(case, parameter, br, section)
            br.quantity_units = units(section, case=case)
        else:
            br.quantities, br.quantity_notes = motor_branch_quantities(fmap, br, section)
            br.quantity_units = motor_units(section, case=case)


def continuation(mech=None, parameter=schema.CRANK_SPEED, start=0.2, stop=1.6, *, model=None, max_period=4, ds=0.05,
                 ds_min=1e-4, ds_max=100.0, dp_max=None, max_points=400, tol=1e-9, switch_step=0.05,
                 case=None, progress=None, corrector="broyden", predictor="quadratic", derivative="exact",
                 quantities=True, section=None, units="crankgen", **fields):
    """Follow the periodic response of the mechanism as `parameter` goes from start to stop, by
    pseudo-arclength continuation of the fixed points of the crank-revolution map, and return a
    BifurcationDiagram: branches (period, parameter, amplitude = max |v*(1/2)| over the orbit,
    stable, Floquet multipliers, states) and special points (fold, period-doubling,
    neimark-sacker), with the period-2 (then 4, ... up to max_period) branches born at period
    doublings.  parameter: any continuable parameter of the schema (crankgen.declaration.schema.CONTINUABLE:
    {continuable}; a guide's or a crank motion's with that guide or motion, e.g.
    guide=crankgen.Circle(...) or crank=crankgen.Fluctuation(...)).  The case as in steady_state (a Mechanism with the run's
    fields and model=, or case=Case(...)); the value of `parameter` given among them is replaced
    by start.  The start must have a periodic response (NoResultError otherwise; a continuation
    can start from either end of its range).  Steps ds, ds_min, ds_max are arclengths in the metric
    |dy|^2 / dim + dp^2, y the state (d, v) in v*-like units (generalized-alpha's algorithmic
    accelerations, slaved to the orbit, do not count); no step changes the parameter by more than
    dp_max (default |stop - start| / 50).  progress(text) receives progress lines.
    corrector ("broyden" or "newton"), predictor ("quadratic" or "tangent") and derivative
    ("exact" or "central", the map's parameter derivative) select the methods
    (bifurcation/core.py, mechanism.py): the defaults are the fast ones; "newton", "tangent" and
    "central" together are the former method, kept as a baseline.  quantities: every branch
    point also stores the physical quantities of its orbit (Branch.quantities: peak torque, pin and
    end forces, axial force, |v*|, outer-fibre strain, and with a crankgen.sections.Section
    `section` the peak stress in units of E; bifurcation/quantities.py); a motor-driven crank's
    points also its mean speed and revolution time (kept with quantities=False), its crank-speed
    range, peak and RMS motor torque and mean motor power.  units="si": mech is a
    crankgen.SIMechanism with its crank motion, start and stop are in the parameter's SI unit
    (crank speed in rad/s, a four-bar's c and d in m, ...), and `diagram.si` gives the diagram in
    SI (the parameter in its SI unit, the amplitude in m, the quantities in N, N m, Pa)."""
    _check_progress(progress)
    if section is not None:
        from ...declaration.sections import Section
        if not isinstance(section, Section):
            raise ParameterError(f"section must be a crankgen.sections.Section, got {type(section).__name__}")
    start = in_range("start", start)
    stop = in_range("stop", stop)
    given = mech
    mech, fields, scales, (start, stop) = si_parameter(mech, parameter, units, fields, case, (start, stop))
    if start == stop:
        raise ParameterError(f"start and stop must differ, got {start:g}")
    c0 = make_case(mech, parameter, start, case, model=model, **fields)
    make_case(None, parameter, stop, c0)                       # validates stop for the parameter
    settings = Settings(ds=in_range("ds", ds, 0, None, True), ds_min=in_range("ds_min", ds_min, 0, None, True),
                        ds_max=in_range("ds_max", ds_max, 0, None, True),
                        dp_max=(abs(stop - start) / 50 if dp_max is None
                                else in_range("dp_max", dp_max, 0, None, True)),
                        max_points=count("max_points", max_points),
                        tol=in_range("tol", tol, 0, None, True),
                        max_period=count("max_period", max_period),
                        switch_step=in_range("switch_step", switch_step, 0, None, True),
                        corrector=choice("corrector", corrector, CORRECTORS),
                        predictor=choice("predictor", predictor, PREDICTORS)).check()
    t0 = time.perf_counter()
    driven = bool(c0.motion_record.coordinates)
    fmap = mechanism_map(c0, parameter, derivative)    # the map on the section the declaration gives
    from ..steady import steady_states
    with notices.quiet(BeyondTheoryWarning):            # the continuation warns once, for every point
        first = steady_states([c0], _omega_b=None if scales is None else scales.omega_b)[0]
    if first.state is None:
        other = ("; a continuation can start from the other end of the range (swap its start and "
                 f"stop: from {stop:g} to {start:g})" if first.status != "failed" else "")
        raise NoResultError(f"no periodic response to start from at {parameter} = {start:g}: "
                            f"{first.status}, {first.message}{other}")
    cont = Continuer(fmap, start, stop, settings, log=progress)
    diagram = cont.diagram(fmap.from_steady(first), start,
                           1.0 if stop > start else -1.0)
    lock = locking_limit(c0, parameter, start, stop)
    if lock is not None:
        value, why = lock
        for br in diagram.branches:
            if not br.stop_reason.startswith("reached"):
                br.stop_reason += (f"; {parameter} = {value:.6g} is the locking limit: beyond it the crank "
                                   f"cannot turn a full revolution ({why})")
    stall = stall_limit(c0, parameter, start, stop) if driven else None
    if stall is not None:
        value, why = stall
        for br in diagram.branches:
            if not br.stop_reason.startswith("reached"):
                br.stop_reason += (f"; {parameter} = {value:.6g} is the stall limit: there {why}, so it cannot "
                                   "turn the crank (the motion stalls before it, where the linkage's own torque "
                                   "over a revolution takes what is left)")
    for sp in diagram.special_points:
        sp.case = fmap.case_at(sp.parameter)
    if driven and quantities:        # a driven crank's branches: its orbits' quantities, the crank's speeds among them
        _add_quantities(diagram, c0, parameter, section, progress, fmap)
    elif driven:                     # a driven crank's branches: the mean crank speed and revolution time of each orbit
        for br in diagram.branches:
            speed, period = fmap.speeds(br.states, br.parameter, br.period)
            br.quantities = {"mean_speed": speed, "revolution_time": period}
            br.quantity_units = {"mean_speed": "omega_b", "revolution_time": "1/omega_b"}
    elif quantities:
        _add_quantities(diagram, c0, parameter, section, progress)
    info = c0.as_dict()
    info.pop(parameter)
    info.update(parameter=parameter, start=start, stop=stop, max_period=max_period,
                corrector=corrector, predictor=predictor, derivative=derivative,
                map_evaluations=cont.evaluations, map_values=cont.values, wall_time=time.perf_counter() - t0)
    diagram.info = info
    diagram.si_mechanism = None if scales is None else given
    diagram.flag_range()
    flag = diagram.beyond_theory
    if flag:
        notices.warn(BeyondTheoryWarning, f"branches of the continuation reach beyond the theory "
                     f"({flag.reason}): their numbers there are the equations' output, not a prediction of the "
                     f"rod; branch.beyond_theory marks the points" + (f"; {flag.remedy}" if flag.remedy else ""),
                     stacklevel=2)
    return diagram


continuation.__doc__ = continuation.__doc__.replace("{continuable}", ", ".join(
    f"{n} ({' and '.join(p.readers)} {p.owner})" if p.owner in ("guide", "motion") and len(p.readers) == 1 else n
    for n, p in schema.PARAMETERS.items() if p.continuable))


def poincare(mech=None, parameter=schema.CRANK_SPEED, values=None, direction="up", *, model=None, transient=100,
             samples=64, max_period=8, tol=1e-8, lyapunov_tol=0.01, case=None, progress=None, units="crankgen",
             **fields):
    """Brute-force bifurcation diagram (a PoincareDiagram): for each value of `parameter` in
    `values`, swept "up", "down" or "both" (up, then down from where up ended), march `transient`
    crank revolutions from the last state of the previous value (the first from rest), then sample
    v*(1/2) at theta = 0 once per revolution for `samples` revolutions and classify the response:
    period-k (k <= max_period), quasi-periodic, irregular or unsettled, with the evidence (repeat
    residual, largest Lyapunov exponent of the revolution map, distinct samples).  The case as in
    steady_state.  progress(done, total) after each value.  units="si": mech is a
    crankgen.SIMechanism, the values are in the parameter's SI unit, and `result.si` gives the
    diagram in SI (the samples in m)."""
    from .sweeps import sweep_map

    _check_progress(progress)
    values = sequence("values", values, f"{parameter} values")
    if not values:
        raise ParameterError("values must hold at least one parameter value")
    count("values", len(values), f"values ({len(values)} {parameter} values)")
    values = [in_range(f"values ({parameter})", v) for v in values]
    given = mech
    mech, fields, scales, values = si_parameter(mech, parameter, units, fields, case, values)
    choice("direction", direction, ("up", "down", "both"))
    c0 = make_case(mech, parameter, min(values), case, model=model, **fields)
    for v in values:
        make_case(None, parameter, v, c0)                      # validates every value
    transient = count("transient", transient)
    samples = count("samples", samples)
    time_scheme.warn_steps([c0], omega_b=None if scales is None else scales.omega_b)
    max_period = count("max_period", max_period)
    t0 = time.perf_counter()
    fmap = mechanism_map(c0, parameter)      # from rest (a driven crank: after its run-up)
    x0 = fmap.rest()
    result = sweep_map(fmap, values, x0, direction, transient, samples, max_period,
                       in_range("tol", tol, 0, None, True),
                       in_range("lyapunov_tol", lyapunov_tol, 0, None, True), progress)
    info = c0.as_dict()
    info.pop(parameter)
    info.update(parameter=parameter, direction=direction, transient=transient, samples=samples,
                wall_time=time.perf_counter() - t0)
    result.info = info
    result.si_mechanism = None if scales is None else given
    return result
