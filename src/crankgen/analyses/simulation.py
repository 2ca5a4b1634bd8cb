"""`simulate`: one run of the flexible mechanism, by default from the paper's zero initial conditions
(or from a given elastic state: crankgen.discrete.initial), with the state and every output at requested
times, in crankgen's units or in SI."""

from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from .. import engine as _engine
from .. import notices
from ..discrete import time_scheme
from ..discrete import kinematics as _kinematics
from ..discrete.kinematics import check_crank_steps
from ..declaration.cases import Case, run_case
from ..errors import ConvergenceError, ParameterError
from .limits import check_run_size
from ..discrete.mesh import components_of
from ..discrete.system import Model, check_coordinates
from ..discrete.initial import initial_state
from ..discrete.newmark import NewmarkSettings, integrate
from ..declaration import schema
from ..results.outputs import DeclaredOutputs, StateHistory, engine_columns, takes_engine_outputs
from .marching import coordinate_histories, crank_of, march_in_chunks, run_angle, run_kinematics, start_state
from ..declaration.si import si_input
from ..declaration.torque_curve import step_hint
from .theory import warn_beyond
from ..declaration.units import Scales
from ..declaration.validation import choice, in_range, numbers_array

ENGINES = ("compiled", "numpy")


@takes_engine_outputs
@dataclass(frozen=True)
class SimulationResult(DeclaredOutputs):
    """Per-step outputs: t*, theta (rad, unwrapped), the engine's outputs (`outputs`, by name:
    v* at x* = 1/2, u*(1), delta* of eq. 40; each an attribute, `result.v_mid`, and a keyword of
    the constructor), and every declared output by name (crankgen.results.outputs): step and reduction
    quantities as attributes (`slider_position`, `crank_speed`, `chord_angle`, `torque`,
    `crank_on_rod_x`, ...), fields as methods (`axial_force(x)`, `bending_moment(x)`,
    `surface_strain(x, fiber)`, `chord_deflection(x)`), any of them by `quantity(name, ...)`.

    at_times: the same at the times a run was asked for (`simulate(..., times=...)`), else None.
    si: the SI view (seconds, metres, radians, newtons, N m) of a run given in SI
    (`simulate(..., units="si")`); `si_view(si_mechanism)` gives it for any run."""

    t: np.ndarray
    theta: np.ndarray
    iterations: np.ndarray
    settings: dict
    outputs: dict = field(default=None, repr=False)                 # the engine's outputs by name
    nodes: Optional[np.ndarray] = field(default=None, repr=False)   # (steps, 3 (n+1)) if requested
    case: Optional[Case] = field(default=None, repr=False)
    states: Optional[np.ndarray] = field(default=None, repr=False)  # (steps, N) reduced displacements
    rates: Optional[np.ndarray] = field(default=None, repr=False)   # (steps, N) reduced velocities
    accelerations: Optional[np.ndarray] = field(default=None, repr=False)
    at_times: Optional["SimulationResult"] = field(default=None, repr=False)
    scales: Optional[Scales] = field(default=None, repr=False)      # crankgen's units in SI (units="si")
    crank: Optional[np.ndarray] = field(default=None, repr=False)   # a driven crank's (theta, thetad, thetadd)
    coordinates: Optional[dict] = field(default=None, repr=False)   # a driven motion's co-ordinates: name -> (steps, 3)

    @property
    def crank_angle(self):
        """The crank angle theta (rad, unwrapped) per step."""
        return self.theta

    @property
    def motor_torque(self):
        """A motor's torque T_m per step, on its torque-speed curve at the speed of the co-ordinate it
        drives (units of the output torque; crankgen.declaration.torque_curve); None for a
        prescribed crank."""
        if not self.coordinates:
            return None
        from ..results.motor_duty import motor_torque
        motor = next(c.name for c in self.case.motion_record.coordinates if c.motor)
        return motor_torque(self.case, self.coordinates[motor][:, 1])

    def last_revolution(self):
        """{name: value} of every declared reduction over time (schema.REDUCTIONS: a peak, RMS,
        mean or range of an output) over the run's last crank revolution (crankgen.results.reductions;
        None without states)."""
        from ..results import reductions
        return reductions.values(self, reductions.last_revolution(self))

    @property
    def crank_acceleration(self):
        """The crank's angular acceleration per step (units of omega_b^2)."""
        if self.crank is not None:
            return self.crank[:, 2]
        return _kinematics.case_state(self.case, self.t).thetadd


def run_length(case, revolutions):
    """(time step, number of steps) of a run of `revolutions` crank revolutions (a driven crank's:
    revolutions of its step period, the no-load revolution of a motor)."""
    dt = _kinematics.step_period(case) / case.steps_per_rev
    if case.periodic or case.motion_record.driven:
        return dt, max(1, int(round(revolutions * case.steps_per_rev)))
    return dt, max(1, int(round(_kinematics.time_of_revolutions(case, revolutions) / dt)))


# a requested time closer than this fraction of a step to a step of the run is that step
ON_STEP = 1e-9


def _requested_times(times, factor):
    """The requested times as a 1-d array in crankgen's units (times / factor), checked: numbers
    (text and booleans refused, as everywhere), finite and >= 0."""
    values = numbers_array("times", times)
    if values.size == 0 or not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ParameterError(f"times must be one or more finite numbers >= 0, got {times!r}")
    return values / factor


def _landing(t_req, dt):
    """(k, tau): for each requested time the step k before it and the remaining time tau (0: on
    step k), in one pass over the times."""
    k = np.floor(t_req / dt)
    tau = t_req - k * dt
    on = tau <= ON_STEP * dt
    up = ~on & (dt - tau <= ON_STEP * dt)
    k = np.where(up, k + 1, k)
    tau = np.where(on | up, 0.0, tau)
    return k, tau


def _check_steps_needed(t_req, dt):
    """Refuse, before any array is made, a last time so far away that its step count is not even
    a machine integer (the run-size check then gives the memory of what remains)."""
    last = float(np.max(t_req)) / dt
    if not last < 2.0 ** 62:
        raise ParameterError(f"times: t* = {float(np.max(t_req)):.6g} needs about {last:.3g} time steps "
                             f"of dt* = {dt:.3g}; ask for earlier times")


def _steps_to_reach(k, tau):
    """The steps a run needs to reach every requested time (one more past a time between steps)."""
    return int(np.max(k + (tau > 0)))


def _check_landing(k, tau, t_req, dt, n_steps):
    beyond = (k > n_steps) | ((k == n_steps) & (tau > 0))
    if np.any(beyond):
        tr = float(t_req[np.argmax(beyond)])
        raise ParameterError(f"times: t* = {tr:.6g} is beyond the run's end t* = {n_steps * dt:.6g} "
                             "(give more revolutions, or leave revolutions out to run up to the last time)")


def simulate(mech=None, omega=None, *, model=None, case=None, crank=None, revolutions=None, times=None,
             units="crankgen", history=True, store_nodes=False, tol=1e-10, progress=None, initial=None,
             engine="compiled", **fields):
    """Integrate the mechanism from t = 0 (the crank at its start angle theta0, default 0) for
    `revolutions` crank revolutions.

    The case: a Mechanism `mech` and the run's settings (omega, and any Case field: approach,
    n_elements, steps_per_rev, integrator, theta0, the model options, the crank motion's parameters),
    or case=Case(...).  model: "consistent" (the default), "paper" or "exact"; an option given explicitly
    (formulation, damping, membrane, ...) overrides the model's value.  crank: a crank motion,
    crankgen.Constant(omega=...), crankgen.RunUp(start=..., stop=..., revolutions=...) or
    crankgen.Fluctuation(omega=..., amplitude=..., order=...) (default: constant speed omega).

    initial: the rod's elastic state at t = 0, a crankgen.InitialState (displacement and velocity
    fields in the rigid moving frame at theta0, projected onto the mesh by nodal interpolation and
    checked against the pin and the guide: crankgen.discrete.initial), a dict of its fields, a pair (d0,
    v0) of reduced vectors, or a triple (d0, v0, a0) with generalized-alpha's algorithmic
    accelerations (a SteadyState.state split in three: its orbit marched on exactly).  Default: the
    rigid mechanism with the rod undeformed and at rest in the moving frame (the paper's initial
    conditions).

    times: times at which to give the state and every output as well (`result.at_times`, a
    SimulationResult at those times, in the order given).  A time on a step of the run (within
    1e-9 of a step) is that step; a time between steps k and k + 1 is reached by one Newmark step
    of the remaining length from the state of step k (the run's own steps are not changed).  revolutions: default 10, or,
    with times, just enough steps to reach the last of them.  history=False keeps, of the run's
    steps, only t, theta, v_mid, u_end, extension and iterations (no states: the declared outputs
    are then given at the requested times only), for long runs asked at a few times.

    units: "crankgen" (dimensionless, the default) or "si": then mech is a crankgen.SIMechanism
    (with its crank motion: omega, crank and case are not given), times are in seconds, the
    initial state's fields in metres and m/s, and `result.si` gives every output in SI
    (crankgen.results.outputs.SIView).

    progress(step, n_steps) is called as the run advances.
    engine: "compiled" (numba, crankgen.engine) or "numpy" (model.py + newmark.py, the reference).
    """
    choice("engine", engine, ENGINES)
    mech, crank, scales = si_input(mech, units, fields, omega=omega, crank=crank, case=case, what="simulate")
    if revolutions is not None:
        revolutions = in_range("revolutions", revolutions, 0, None, True)
    case = run_case(mech, case, model=model, omega=omega, crank=crank, **fields)
    driven = bool(case.motion_record.coordinates)
    if driven:
        check_coordinates(case)
    else:
        time_scheme.warn_steps([case], omega_b=None if scales is None else scales.omega_b)
    settings = NewmarkSettings.of_case(case, tol=tol)
    reference = Model.from_case(case)          # the case's runtime model (model= names its preset)
    if not isinstance(history, (bool, np.bool_)):
        raise ParameterError(f"history must be True or False, got {history!r}")
    history = bool(history)
    if store_nodes and not history:
        raise ParameterError("store_nodes needs the run's states: leave history=True")
    landing = None
    if times is not None:
        t_req = _requested_times(times, 1.0 if scales is None else scales.factor("1/omega_b"))
    if revolutions is None and times is not None:
        dt = _kinematics.step_period(case) / case.steps_per_rev
        _check_steps_needed(t_req, dt)
        landing = _landing(t_req, dt)
        n_steps = max(1, _steps_to_reach(*landing))
        revolutions = n_steps / case.steps_per_rev        # step periods: revolutions of a periodic crank
    else:
        revolutions = 10.0 if revolutions is None else revolutions
        dt, n_steps = run_length(case, revolutions)
        if times is not None:
            landing = _landing(t_req, dt)
            _check_landing(*landing, t_req, dt, n_steps)
    check_run_size(case.n_elements, n_steps, stored=("nodes" if store_nodes else "states") if history else "outputs",
                   n_times=0 if times is None else len(t_req),
                   names={"n_steps": "revolutions" if times is None else "revolutions (or the last of times)",
                          "n_times": "times"})
    if not driven:
        check_crank_steps(case, dt, n_steps * dt)
    if landing is not None:
        landing = list(zip(landing[0].astype(np.int64).tolist(), landing[1].tolist()))
    d0, v0, g0 = initial_state(case, initial, scales)
    if driven and g0 is not None:
        raise ParameterError("a driven crank's run starts from (d0, v0): give no algorithmic accelerations")
    d0, v0 = start_state(case, d0, v0)
    info = dict(case.as_dict(), revolutions=revolutions, tol=tol, engine=engine)
    if driven:
        info["revolutions_of"] = "no-load revolutions"
    stops = sorted({k for k, _ in landing}) if landing is not None else []
    if engine == "numpy":
        hist = integrate(reference, d0, v0, 0.0, dt, n_steps, settings, progress=progress, g0=g0)
        result = _numpy_result(reference, case, hist, info, store_nodes, scales)
        if landing is not None:
            # g: generalized-alpha's algorithmic accelerations; None at a start (step 0 without
            # them: a step from there is the run's starter step too)
            g = hist.a if hist.g is None else hist.g
            states = {k: (hist.d[k], hist.v[k], hist.a[k], None if k == 0 and g0 is None else g[k])
                      for k in stops}
            result = replace(result, at_times=_numpy_at_times(reference, case, result, states, landing, t_req,
                                                              settings, store_nodes, info, scales))
        if not history:
            result = replace(result, states=None, rates=None, accelerations=None)
        warn_beyond([result], "run")
        return result

    captured = {}
    y, iterations, status, fail_step, fail_res, D, V, A, Z = march_in_chunks(
        _engine.Batch([case]), d0[None], v0[None], n_steps, tol, history,
        None if progress is None else (lambda done: progress(done, n_steps)), stops=stops, captured=captured,
        G0=None if g0 is None else g0[None])
    y, iterations, Z = y[0], iterations[0].astype(np.int32, copy=False), Z[0]
    if history:
        D, V, A = D[0], V[0], A[0]
    t = np.arange(n_steps + 1, dtype=float)
    t *= dt                                          # no temporary of the run's length
    result = _result(reference, case, t, y, iterations, dict(info, history=history), D, V, A, Z, store_nodes, scales)
    if status[0] != _engine.OK:
        raise _failure(status[0], fail_step[0], fail_res[0], dt, result)
    if landing is not None:
        states = {k: tuple(None if x is None else x[0] for x in captured[k]) for k in stops}
        result = replace(result, at_times=_compiled_at_times(reference, case, result, states, landing, t_req, tol,
                                                             store_nodes, info, scales))
    warn_beyond([result], "run")
    return result


def _result(model, case, t, y, iterations, info, D, V, A, Z, store_nodes, scales):
    """The SimulationResult of a run's steps on the DOF map: y the engine's outputs, D, V, A the
    states (None: not kept; their nodal part is kept, the co-ordinates go to `coordinates`), Z the
    declared co-ordinates per step (MarchResult.Z)."""
    coordinates = coordinate_histories(case, Z) if case.motion_record.coordinates else None
    crank = None if coordinates is None else crank_of(case, coordinates)
    n_rod = model.n_rod
    nodal = [None if x is None else x[..., :n_rod] for x in (D, V, A)]
    # theta alone, not the run's whole kinematic state (8 bytes a step; the nodes need the rest)
    theta = run_angle(case, t, crank)
    return SimulationResult(t=np.asarray(t, dtype=float), theta=theta, outputs=engine_columns(y),
                            iterations=np.asarray(iterations, dtype=np.int32), settings=info,
                            nodes=model.full_nodal(nodal[0], run_kinematics(case, t, crank)) if store_nodes else None,
                            case=case,
                            states=nodal[0], rates=nodal[1], accelerations=nodal[2], scales=scales, crank=crank,
                            coordinates=coordinates)


def _numpy_result(model, case, hist, info, store_nodes, scales):
    n_rod = model.n_rod
    m = hist.d.shape[1] - n_rod
    Z = np.concatenate([hist.d[:, n_rod:], hist.v[:, n_rod:], hist.a[:, n_rod:]], axis=1)
    crank = crank_of(case, coordinate_histories(case, Z)) if m else None
    y = StateHistory(case, hist.t, hist.d[:, :n_rod], hist.v[:, :n_rod], hist.a[:, :n_rod], crank).engine_outputs()
    return _result(model, case, hist.t, y, hist.iterations, info, hist.d, hist.v, hist.a, Z, store_nodes, scales)


def _at_times_result(model, case, t_req, rows, info, store_nodes, scales):
    """The SimulationResult at the requested times from rows (the engine's outputs y, iterations,
    d, v, a, ...) each (states on the DOF map: the co-ordinates after the nodal unknowns)."""
    y = np.array([r[0] for r in rows], dtype=float).reshape(len(rows), len(schema.ENGINE_OUTPUTS))
    D, V, A = (np.array([r[k] for r in rows], dtype=float) for k in (2, 3, 4))
    n_rod = model.n_rod
    Z = np.concatenate([D[:, n_rod:], V[:, n_rod:], A[:, n_rod:]], axis=1)
    return _result(model, case, t_req, y, [r[1] for r in rows], dict(info, times=True), D, V, A, Z, store_nodes,
                   scales)


def _engine_row(result, k):
    """The engine's outputs of a result at its step k, (len(schema.ENGINE_OUTPUTS),)."""
    return np.array([result.outputs[name][k] for name in schema.ENGINE_OUTPUTS])


def _numpy_at_times(model, case, result, states, landing, t_req, settings, store_nodes, info, scales):
    rows = []
    for (k, tau), tr in zip(landing, t_req):
        if tau == 0.0:
            rows.append((_engine_row(result, k), 0) + states[k])
            continue
        d, v, a, g = states[k]
        hist = integrate(model, d, v, result.t[k], tau, 1, settings, a0=a, g0=g)
        one = _numpy_result(model, case, hist, info, False, scales)
        rows.append((_engine_row(one, 1), int(hist.iterations[0]), hist.d[1], hist.v[1], hist.a[1]))
    return _at_times_result(model, case, t_req, rows, info, store_nodes, scales)


def _compiled_at_times(model, case, result, states, landing, t_req, tol, store_nodes, info, scales):
    """States at the requested times: steps of the run, or one step of the remaining length from the
    step before (such steps in one compiled batch, those from a start in another: its step is the
    starter).  states: {step: (d, v, a, g)}, g generalized-alpha's algorithmic accelerations (a for
    Newmark; None at a start)."""
    between = [j for j, (_, tau) in enumerate(landing) if tau > 0.0]
    stepped = {}
    for group in ([j for j in between if states[landing[j][0]][3] is not None],
                  [j for j in between if states[landing[j][0]][3] is None]):
        if not group:
            continue
        ks = np.array([landing[j][0] for j in group])
        taus = np.array([landing[j][1] for j in group])
        batch = _engine.Batch([case] * len(group), dt=taus)
        D0, V0, A0 = (np.array([states[k][c] for k in ks]) for c in range(3))
        G0 = None if states[ks[0]][3] is None else np.array([states[k][3] for k in ks])
        res = _engine.march(batch, 1, D0=D0, V0=V0, A0=A0, G0=G0, t0=result.t[ks], tol=tol)
        bad = np.nonzero(res.status != _engine.OK)[0]
        if bad.size:
            j = int(bad[0])
            raise ConvergenceError(
                f"the step to the requested time t* = {t_req[group[j]]:.6g}: "
                f"{_engine.STATUS_TEXT[int(res.status[j])]} (residual norm {res.fail_residual[j]:.3e})",
                step=int(ks[j]) + 1, time=float(t_req[group[j]]), residual=float(res.fail_residual[j]),
                partial=result)
        for i, j in enumerate(group):
            stepped[j] = (res.y[i, 1], int(res.iterations[i, 0]), res.D[i], res.V[i], res.A[i], res.G[i])
    rows = []
    for j, (k, tau) in enumerate(landing):
        if j in stepped:
            rows.append(stepped[j])
        else:
            rows.append((_engine_row(result, k), 0) + states[k])
    return _at_times_result(model, case, t_req, rows, info, store_nodes, scales)


def _failure(status, step, residual, dt, result=None):
    """The ConvergenceError of a case that stopped in the compiled engine; its `partial` holds
    result cut to the steps before the failed one (the states computed before the failure)."""
    partial = None
    if result is not None:
        partial = _truncated(result, int(step))
    return ConvergenceError(
        f"{_engine.STATUS_TEXT[int(status)]} in step {step} (t* = {step * dt:.6g}): residual norm "
        f"{residual:.3e}{_exact_rod_hint(status, result)}{_motor_hint(result, dt)}", step=int(step), time=step * dt,
        residual=float(residual), partial=partial)


def _exact_rod_hint(status, result):
    """For the geometrically exact rod, what a non-finite state may mean: a section rotation is not
    a limit of its element, an element folded onto itself (|r'| = 0: compressed to a point) is."""
    case = getattr(result, "case", None)
    if status != _engine.NOT_FINITE or case is None or case.approach != "exact":
        return ""
    return ("; the exact rod's element has no rotation limit, but an element compressed to zero length "
            "(|r'| = 0) has no tangent: try more elements or steps per revolution")


def _motor_hint(result, dt):
    """For a motor-driven crank, whether the step can follow the motor (torque_curve.step_hint: its
    time constant against the step, and the steps_per_rev that resolves it); "" otherwise."""
    case = getattr(result, "case", None)
    if case is None or not case.motion_record.coordinates:
        return ""
    return step_hint(case, dt)


def _truncated(result, n_points):
    """result with its per-step arrays cut to the first n_points points (steps 0 .. n_points-1)."""
    cut = {name: getattr(result, name)[:n_points] for name in ("t", "theta")}
    cut["outputs"] = {name: values[:n_points] for name, values in result.outputs.items()}
    cut["iterations"] = result.iterations[:max(0, n_points - 1)]
    for name in ("nodes", "states", "rates", "accelerations", "crank"):
        value = getattr(result, name)
        cut[name] = None if value is None else value[:n_points]
    cut["coordinates"] = None if result.coordinates is None else {
        name: values[:n_points] for name, values in result.coordinates.items()}
    return SimulationResult(settings=dict(result.settings, failed_at_step=n_points), case=result.case,
                            scales=result.scales, **cut)


def simulate_many(cases, revolutions, progress=None, chunks=20, keep_states=False):
    """Transient runs of many cases from zero initial conditions (a driven crank's co-ordinates at
    their start), in lock-step compiled batches (cases sharing n_elements, steps_per_rev and the
    co-ordinates of their motion run together: one state layout).

    Returns, in input order, a SimulationResult per case, or the ConvergenceError of a case whose
    integration failed (its `partial` holds the run up to the failure; the others are not
    affected).  progress(done, total) counts case-steps.  keep_states: store the reduced states
    (needed for the field outputs, e.g. axial_force)."""
    cases = [c if isinstance(c, Case) else Case.from_dict(c) for c in cases]
    revolutions = in_range("revolutions", revolutions, 0, None, True)
    for c in cases:
        if c.motion_record.coordinates:
            check_coordinates(c)
    time_scheme.warn_steps([c for c in cases if not c.motion_record.coordinates])
    groups = {}
    for i, c in enumerate(cases):          # one state layout a batch: the mesh, its nodes and the motion's co-ordinates
        groups.setdefault((c.n_elements, c.steps_per_rev, run_length(c, revolutions)[1],
                           tuple(x.name for x in c.motion_record.coordinates), components_of(c.options)),
                          []).append(i)
    total = sum(key[2] * len(idx) for key, idx in groups.items())
    for (n, _, n_steps, _, _), idx in groups.items():
        check_run_size(n, n_steps, n_cases=len(idx), stored="states" if keep_states else "outputs",
                       names={"n_steps": "revolutions", "n_cases": "cases"})
    for i, c in enumerate(cases):
        dt, n_steps = run_length(c, revolutions)
        if not c.motion_record.coordinates:
            check_crank_steps(c, dt, n_steps * dt, f"cases[{i}]: " if len(cases) > 1 else "")
    out = [None] * len(cases)
    done_total = 0
    for (n, spr, n_steps, _, _), idx in sorted(groups.items()):
        batch = _engine.Batch([cases[i] for i in idx])
        B, n_rod = len(idx), batch.mesh.n_rod
        starts = [start_state(cases[i], np.zeros(n_rod), np.zeros(n_rod)) for i in idx]
        report = None if progress is None else (lambda done, o=done_total, b=B: progress(o + done * b, total))
        y, iterations, status, fail_step, fail_res, D, V, A, Z = march_in_chunks(
            batch, np.array([d for d, _ in starts]), np.array([v for _, v in starts]), n_steps,
            keep_states=keep_states, progress=report, chunks=chunks)
        done_total += n_steps * B
        for j, i in enumerate(idx):
            c, dt = cases[i], float(batch.dt[j])
            t = dt * np.arange(n_steps + 1)
            result = _result(Model(c), c, t, y[j], iterations[j], dict(c.as_dict(), revolutions=revolutions,
                                                                         engine="compiled"),
                             *(None if X is None else X[j] for X in (D, V, A)), Z[j], False, None)
            if status[j] != _engine.OK:
                result = _failure(status[j], fail_step[j], fail_res[j], dt, result)
            out[i] = result
    warn_beyond([r for r in out if isinstance(r, SimulationResult)], "run")
    return out
