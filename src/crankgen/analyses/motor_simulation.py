"""`simulate` of a motor-driven crank (crankgen.discrete.motor): the run from the crank's start (theta0 at
its initial speed, default at rest) with the crank angle a degree of freedom, by the compiled
engine (engine/motor.py) or the NumPy reference (motor.integrate).

A motor's run is measured in no-load revolutions (`revolutions` times 2 pi / Omega_nl: the crank
turns fewer while it runs up or is held back), its time step is the no-load revolution over
steps_per_rev.  The result holds the crank's history (`crank`: theta, thetad, thetadd per step),
from which its kinematics, and so every declared output, follow; `crank_angle`, `crank_speed`
and `crank_acceleration` give it by name, at the requested times too."""

from dataclasses import replace

import numpy as np

from .. import engine as _engine
from ..engine import motor as engine_motor
from ..discrete import kinematics as _kinematics
from ..discrete import motor
from ..errors import ConvergenceError
from .limits import check_run_size
from ..discrete.system import Model
from ..discrete.newmark import NewmarkSettings
from ..results.outputs import StateHistory, engine_columns


def _result(cls, model, case, t, d, v, a, crank, y, iterations, info, store_nodes, scales):
    kin = motor.crank_state(case, crank)
    return cls(t=np.asarray(t, dtype=float), theta=crank[:, 0].copy(), outputs=engine_columns(y),
               iterations=np.asarray(iterations, dtype=np.int32), settings=info,
               nodes=model.full_nodal(d, kin) if store_nodes else None, case=case, states=d, rates=v,
               accelerations=a, scales=scales, crank=crank)


def _split(X, N):
    return X[..., :N], X[..., N]


def _reference(model, case, d0, v0, dt, n_steps, settings, progress):
    hist = motor.integrate(model, d0, v0, 0.0, dt, n_steps, settings, progress=progress)
    y = StateHistory(case, hist.t, hist.d, hist.v, hist.a, hist.crank).engine_outputs()
    g = hist.g
    return hist.t, hist.d, hist.v, hist.a, hist.crank, y, hist.iterations, g


def _compiled(case, d0, v0, n_steps, tol, progress):
    batch = _engine.Batch([case], entries=(engine_motor.ENTRY,))
    N = batch.N
    theta0, speed0 = motor.crank_start(case)
    res = _engine.march_motor(batch, n_steps, np.append(d0, theta0)[None], np.append(v0, speed0)[None],
                              keep_history=True, tol=tol)
    if progress is not None:
        progress(n_steps, n_steps)
    X, V, A = res.X_history[0], res.V_history[0], res.A_history[0]
    t = batch.dt[0] * np.arange(n_steps + 1)
    crank = np.stack([X[:, N], V[:, N], A[:, N]], axis=-1)
    if res.status[0] != _engine.OK:
        k = int(res.fail_step[0])
        raise ConvergenceError(f"step {k} (t* = {t[k]:.6g}) of the motor-driven crank: "
                               f"{_engine.STATUS_TEXT[int(res.status[0])]} (residual norm {res.fail_residual[0]:.3e})"
                               + motor.step_hint(case, float(batch.dt[0])),
                               step=k, time=float(t[k]), residual=float(res.fail_residual[0]))
    return t, X[:, :N], V[:, :N], A[:, :N], crank, res.y[0], res.iterations[0], res.G_history[0]


def _step_to(case, model, settings, engine, tol, x, v, a, g, tau):
    """One step of length tau from the bordered state (x, v, a, g) (N + 1 each; g None: a start, the
    step the starter): (d, v, a, crank, y)."""
    N = model.n_dofs
    if engine == "numpy":
        h = motor.integrate(model, x[:N], v[:N], 0.0, tau, 1, settings, crank0=(x[N], v[N]), a0=a, g0=g)
        y = StateHistory(case, h.t[1:], h.d[1:], h.v[1:], h.a[1:], h.crank[1:]).engine_outputs()[0]
        return h.d[1], h.v[1], h.a[1], h.crank[1], y
    batch = _engine.Batch([case], dt=[tau], entries=(engine_motor.ENTRY,))
    res = _engine.march_motor(batch, 1, x[None], v[None], A0=a[None], G0=None if g is None else g[None], tol=tol)
    if res.status[0] != _engine.OK:
        raise ConvergenceError(f"the step to a requested time: {_engine.STATUS_TEXT[int(res.status[0])]}",
                               step=1, time=float(tau), residual=float(res.fail_residual[0]))
    X, Vv, Aa = res.X[0], res.V[0], res.A[0]
    return X[:N], Vv[:N], Aa[:N], np.array([X[N], Vv[N], Aa[N]]), res.y[0, 1]


def simulate_motor(cls, case, revolutions, t_req, history, store_nodes, tol, progress, d0, v0, engine, info,
                   scales):
    """The SimulationResult (class cls) of a motor-driven case: `revolutions` no-load revolutions
    (module docstring), or just enough steps to reach the last of the requested times t_req."""
    from .simulation import _landing, run_length
    motor.check_driven(case)
    model = Model.from_case(case)
    settings = NewmarkSettings.of_case(case, tol=tol)
    dt = _kinematics.step_period(case) / case.steps_per_rev
    if revolutions is None and t_req is not None:
        n_steps = max(1, int(np.ceil(max(t_req) / dt - 1e-9)))
    else:
        n_steps = run_length(case, 10.0 if revolutions is None else revolutions)[1]
    check_run_size(case.n_elements, n_steps, stored="nodes" if store_nodes else "states",
                   n_times=0 if t_req is None else len(t_req),
                   names={"n_steps": "revolutions", "n_times": "times"})
    info = dict(info, revolutions=n_steps / case.steps_per_rev, revolutions_of="no-load revolutions")
    if engine == "numpy":
        t, d, v, a, crank, y, iterations, g = _reference(model, case, d0, v0, dt, n_steps, settings, progress)
    else:
        t, d, v, a, crank, y, iterations, g = _compiled(case, d0, v0, n_steps, tol, progress)
    result = _result(cls, model, case, t, d, v, a, crank, y, iterations, dict(info, history=history), store_nodes,
                     scales)
    if t_req is not None:
        landing = list(zip(*(x.tolist() for x in _landing(t_req, dt))))
        rows = []
        for k, tau in landing:
            k = int(k)
            if tau == 0.0:
                rows.append((d[k], v[k], a[k], crank[k], y[k]))
                continue
            x = np.append(d[k], crank[k, 0])
            xv = np.append(v[k], crank[k, 1])
            xa = np.append(a[k], crank[k, 2])
            xg = None if g is None or k == 0 else g[k]
            rows.append(_step_to(case, model, settings, engine, tol, x, xv, xa, xg, tau))
        D, Vr, Ar, C, Y = (np.array([r[j] for r in rows]) for j in range(5))
        at = _result(cls, model, case, t_req, D, Vr, Ar, C, Y, np.zeros(len(rows)), dict(info, times=True),
                     store_nodes, scales)
        result = replace(result, at_times=at)
    if not history:
        result = replace(result, states=None, rates=None, accelerations=None)
    return result
