"""`simulate`: one run of the flexible mechanism, by default from the paper's zero initial conditions."""

import csv
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import engine as _engine
from . import kinematics as _kinematics
from .cases import Case, run_case
from .errors import ConvergenceError, ParameterError
from .limits import check_run_size
from .model import Model
from .newmark import NewmarkSettings, integrate
from .outputs import DeclaredOutputs, StateHistory, end_axial, extension, mid_deflection
from .validation import choice, in_range

ENGINES = ("compiled", "numpy")


@dataclass(frozen=True)
class SimulationResult(DeclaredOutputs):
    """Per-step outputs: t*, theta (rad, unwrapped), v* at x* = 1/2, u*(1), delta* (eq. 40), and
    every declared output by name (crankgen.outputs): step quantities as attributes
    (`slider_position`, `crank_speed`, `chord_angle`, `torque`, `pin_force_x`, ...), fields as
    methods (`axial_force(x)`, `bending_moment(x)`, `surface_strain(x, fiber)`,
    `chord_deflection(x)`), any of them by `quantity(name, ...)`."""

    t: np.ndarray
    theta: np.ndarray
    v_mid: np.ndarray
    u_end: np.ndarray
    extension: np.ndarray
    iterations: np.ndarray
    settings: dict
    nodes: Optional[np.ndarray] = field(default=None, repr=False)   # (steps, 3 (n+1)) if requested
    case: Optional[Case] = field(default=None, repr=False)
    states: Optional[np.ndarray] = field(default=None, repr=False)  # (steps, N) reduced displacements
    rates: Optional[np.ndarray] = field(default=None, repr=False)   # (steps, N) reduced velocities
    accelerations: Optional[np.ndarray] = field(default=None, repr=False)

    def to_csv(self, path):
        """Write t*, theta (degrees), v_mid, u_end, extension as CSV (full double precision),
        atomically."""
        from .io import atomic_file
        with atomic_file(path) as fh:
            w = csv.writer(fh)
            w.writerow(["t", "theta_deg", "v_mid", "u_end", "extension"])
            for row in zip(self.t, np.degrees(self.theta), self.v_mid, self.u_end, self.extension):
                w.writerow([repr(float(x)) for x in row])


def run_length(case, revolutions):
    """(time step, number of steps) of a run of `revolutions` crank revolutions."""
    dt = _kinematics.step_period(case) / case.steps_per_rev
    if case.periodic:
        return dt, max(1, int(round(revolutions * case.steps_per_rev)))
    return dt, max(1, int(round(_kinematics.time_of_revolutions(case, revolutions) / dt)))


def simulate(mech=None, omega=None, *, model=None, case=None, crank=None, revolutions=10,
             store_nodes=False, tol=1e-10, progress=None, initial=None, engine="compiled", **fields):
    """Integrate the mechanism from theta = 0 (the crank motion's start) for `revolutions` crank
    revolutions.

    The case: a Mechanism `mech` and the run's settings (omega, and any Case field: approach,
    n_elements, steps_per_rev, integrator, the model options, the crank motion's parameters), or
    case=Case(...).  model: "consistent" (the default) or "paper"; an option given explicitly
    (formulation, damping, membrane, ...) overrides the model's value.  crank: a crank motion,
    crankgen.Constant(omega=...), crankgen.RunUp(start=..., stop=..., revolutions=...) or
    crankgen.Fluctuation(omega=..., amplitude=..., order=...) (default: constant speed omega).
    initial: optional (d0, v0) reduced displacement and velocity vectors (default: zero, the
    paper's initial conditions: rod undeformed and at rest in the moving frame).
    progress(step, n_steps) is called as the run advances.
    engine: "compiled" (numba, crankgen.engine) or "numpy" (model.py + newmark.py, the reference).
    """
    revolutions = in_range("revolutions", revolutions, 0, None, True)
    choice("engine", engine, ENGINES)
    case = run_case(mech, case, model=model, omega=omega, crank=crank, **fields)
    settings = NewmarkSettings(scheme=case.integrator, tol=tol)
    model = Model.from_case(case)
    dt, n_steps = run_length(case, revolutions)
    check_run_size(case.n_elements, n_steps, stored="nodes" if store_nodes else "states",
                   names={"n_steps": "revolutions"})
    N = model.n_dofs
    if initial is None:
        d0, v0 = np.zeros(N), np.zeros(N)
    else:
        d0, v0 = (np.asarray(x, dtype=float) for x in initial)
        if d0.shape != (N,) or v0.shape != (N,) or not (np.all(np.isfinite(d0)) and np.all(np.isfinite(v0))):
            raise ParameterError(f"initial must be two finite vectors of length {N} (3 n_elements)")
    info = dict(case.as_dict(), revolutions=revolutions, tol=tol, engine=engine)
    if engine == "numpy":
        hist = integrate(model, d0, v0, 0.0, dt, n_steps, settings, progress=progress)
        history = StateHistory(case, hist.t, hist.d, hist.v, hist.a)
        q = history.element_vectors()
        kin = history.kinematics()
        return SimulationResult(
            t=hist.t, theta=kin.theta, v_mid=mid_deflection(model.mesh, q, case.eps),
            u_end=end_axial(q, case.eps), extension=extension(model.mesh, q),
            iterations=hist.iterations, settings=info,
            nodes=model.full_nodal(hist.d, kin) if store_nodes else None, case=case, states=hist.d,
            rates=hist.v, accelerations=hist.a)

    y, iterations, status, fail_step, fail_res, D, V, A = _march_in_chunks(
        _engine.Batch([case]), d0[None], v0[None], n_steps, tol, True,
        None if progress is None else (lambda done: progress(done, n_steps)))
    y, iterations, D, V, A = y[0], iterations[0].astype(np.int32), D[0], V[0], A[0]
    t = dt * np.arange(n_steps + 1)
    kin = _kinematics.case_state(case, t)
    nodes = model.full_nodal(D, kin) if store_nodes else None
    result = SimulationResult(t=t, theta=kin.theta, v_mid=y[:, 0], u_end=y[:, 1], extension=y[:, 2],
                              iterations=iterations, settings=info, nodes=nodes, case=case, states=D,
                              rates=V, accelerations=A)
    if status[0] != _engine.OK:
        raise _failure(status[0], fail_step[0], fail_res[0], dt, result)
    return result


def _march_in_chunks(batch, D0, V0, n_steps, tol=1e-10, keep_states=False, progress=None,
                     chunks=20):
    """Run the compiled engine from (D0, V0) in a few chunks, so that progress(done_steps) can be
    shown; a case that fails stops alone.  Returns (y, iterations, status, fail_step,
    fail_residual, D, V, A) with y (B, n_steps + 1, 3) and the histories of the reduced
    displacements, velocities and accelerations (None unless keep_states)."""
    B = len(batch)
    D, V, A, previous = np.array(D0, dtype=float), np.array(V0, dtype=float), None, None
    status = np.zeros(B, dtype=np.int64)
    fail_step, fail_res = np.zeros(B, dtype=np.int64), np.zeros(B)
    ys, its, hist = [], [], ([], [], [])
    size = max(1, -(-n_steps // chunks)) if progress is not None else n_steps
    done = 0
    while done < n_steps:
        k = min(size, n_steps - done)
        res = _engine.march(batch, k, D0=D, V0=V, A0=A, step0=done, keep_history=bool(keep_states),
                            tol=tol, status=status, previous=previous)
        new_fail = (res.status != _engine.OK) & (status == _engine.OK)
        fail_step[new_fail], fail_res[new_fail] = res.fail_step[new_fail], res.fail_residual[new_fail]
        status = res.status
        ys.append(res.y if done == 0 else res.y[:, 1:])
        its.append(res.iterations)
        if keep_states:
            for store, h in zip(hist, (res.D_history, res.V_history, res.A_history)):
                store.append(h if done == 0 else h[:, 1:])
        D, V, A, previous = res.D, res.V, res.A, res.previous
        done += k
        if progress is not None:
            progress(done)
    histories = tuple(np.concatenate(h, axis=1) if keep_states else None for h in hist)
    return (np.concatenate(ys, axis=1), np.concatenate(its, axis=1), status, fail_step, fail_res) + histories


def _failure(status, step, residual, dt, result=None):
    """The ConvergenceError of a case that stopped in the compiled engine; its `partial` holds
    result cut to the steps before the failed one (the states computed before the failure)."""
    partial = None
    if result is not None:
        partial = _truncated(result, int(step))
    return ConvergenceError(
        f"{_engine.STATUS_TEXT[int(status)]} in step {step} (t* = {step * dt:.6g}): residual norm "
        f"{residual:.3e}", step=int(step), time=step * dt, residual=float(residual), partial=partial)


def _truncated(result, n_points):
    """result with its per-step arrays cut to the first n_points points (steps 0 .. n_points-1)."""
    cut = {name: getattr(result, name)[:n_points] for name in ("t", "theta", "v_mid", "u_end", "extension")}
    cut["iterations"] = result.iterations[:max(0, n_points - 1)]
    for name in ("nodes", "states", "rates", "accelerations"):
        value = getattr(result, name)
        cut[name] = None if value is None else value[:n_points]
    return SimulationResult(settings=dict(result.settings, failed_at_step=n_points), case=result.case, **cut)


def simulate_many(cases, revolutions, progress=None, chunks=20, keep_states=False):
    """Transient runs of many cases from zero initial conditions, in lock-step compiled batches
    (cases sharing n_elements and steps_per_rev run together).

    Returns, in input order, a SimulationResult per case, or the ConvergenceError of a case whose
    integration failed (its `partial` holds the run up to the failure; the others are not
    affected).  progress(done, total) counts case-steps.  keep_states: store the reduced states
    (needed for the field outputs, e.g. axial_force)."""
    cases = [c if isinstance(c, Case) else Case.from_dict(c) for c in cases]
    revolutions = in_range("revolutions", revolutions, 0, None, True)
    groups = {}
    for i, c in enumerate(cases):
        groups.setdefault((c.n_elements, c.steps_per_rev, run_length(c, revolutions)[1]), []).append(i)
    total = sum(n_steps * len(idx) for (_, _, n_steps), idx in groups.items())
    for (n, _, n_steps), idx in groups.items():
        check_run_size(n, n_steps, n_cases=len(idx), stored="states" if keep_states else "outputs",
                       names={"n_steps": "revolutions", "n_cases": "cases"})
    out = [None] * len(cases)
    done_total = 0
    for (n, spr, n_steps), idx in sorted(groups.items()):
        batch = _engine.Batch([cases[i] for i in idx])
        B, N = len(idx), batch.N
        report = None if progress is None else (lambda done, o=done_total, b=B: progress(o + done * b, total))
        y, iterations, status, fail_step, fail_res, D, V, A = _march_in_chunks(
            batch, np.zeros((B, N)), np.zeros((B, N)), n_steps, keep_states=keep_states,
            progress=report, chunks=chunks)
        done_total += n_steps * B
        for j, i in enumerate(idx):
            c, dt = cases[i], float(batch.dt[j])
            t = dt * np.arange(n_steps + 1)
            result = SimulationResult(
                t=t, theta=_kinematics.case_state(c, t).theta, v_mid=y[j, :, 0], u_end=y[j, :, 1],
                extension=y[j, :, 2], iterations=iterations[j].astype(np.int32),
                settings=dict(c.as_dict(), revolutions=revolutions, engine="compiled"), case=c,
                states=None if D is None else D[j], rates=None if V is None else V[j],
                accelerations=None if A is None else A[j])
            if status[j] != _engine.OK:
                result = _failure(status[j], fail_step[j], fail_res[j], dt, result)
            out[i] = result
    return out
