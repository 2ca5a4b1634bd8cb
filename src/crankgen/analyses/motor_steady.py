"""The steady motion of a motor-driven crank: a periodic orbit of an autonomous system, whose period
(the revolution time) is unknown.

The section is theta = theta0 (mod 2 pi).  On it the state is y = (d, v, thetad) (with
generalized-alpha's algorithmic accelerations of the rod and the crank: (d, v, thetad, a, a_theta)),
and the map P(y) marches from (d, theta0; v, thetad) with the case's steps until the crank angle
passes theta0 + 2 pi, then takes the last step with the length tau that lands on theta0 + 2 pi
exactly (Newton on tau: the same time scheme, one step of another length); the revolution time is
T = (steps before it) dt + tau.  Shooting is Newton's method on P(y) - y = 0 with the Jacobian
dP/dy by central differences (one batch of 2 dim(y) revolutions in the compiled engine, each step
converged to 1e-13), the marches' Newton iterations converged well below the differences' steps.
On the section the map has no trivial multiplier: the flow's monodromy matrix over T (the state
with theta) has the multiplier 1 of the motion along the orbit, the map's eigenvalues are its other
ones (`monodromy`, a diagnostic, shows it).  The verdict is that of the map's multipliers.

A run-up from the start (theta0 at the initial speed, default from rest) of `warmup` no-load
revolutions gives the starting point; where shooting fails, the map is iterated (marching,
revolution by revolution) up to max_revolutions.
"""

import math

import numpy as np

from .. import engine
from ..discrete import motor
from ..discrete import kinematics as _kinematics
from ..engine import motor as engine_motor
from ..errors import ParameterError
from ..results.outputs import engine_columns

TWO_PI = 2.0 * math.pi
FD_STEP = 1e-6          # central differences: this times each component's natural size
MARCH_TOL = 1e-12       # the marches' Newton tolerance (scaled increments)
TAU_ITERATIONS = 8


class SectionMap:
    """P on the section theta = theta0 (mod 2 pi) of a motor-driven case (module docstring)."""

    def __init__(self, case, tol=MARCH_TOL, max_chunks=40):
        motor.check_driven(case)
        self.case, self.tol, self.max_chunks = case, tol, max_chunks
        self.batch = engine.Batch([case], entries=(engine_motor.ENTRY,))
        self.N = self.batch.N
        self.dt = float(self.batch.dt[0])
        self.generalized = bool(self.batch.generalized[0])
        self.theta_s, _ = motor.crank_start(case)
        speed = 2 * math.pi / _kinematics.step_period(case)      # the no-load speed
        scales = self.batch.scales[0]
        part = np.append(scales, speed)
        self.scales = np.concatenate([scales, part] + ([part] if self.generalized else []))
        self.size = self.scales.size

    # ---- the state on the section and the bordered state of the engine ---------------------------
    def full(self, Y):
        """(X, V, G) (B, N + 1) of section states Y (B, size): the crank at theta0; G None for Newmark."""
        Y = np.atleast_2d(Y)
        N, B = self.N, Y.shape[0]
        X = np.concatenate([Y[:, :N], np.full((B, 1), self.theta_s)], axis=1)
        V = Y[:, N:2 * N + 1]
        G = Y[:, 2 * N + 1:] if self.generalized else None
        return X, V, G

    def section(self, X, V, G):
        """Y of bordered states on the section (their crank angle dropped)."""
        parts = [X[:, :self.N], V]
        if self.generalized:
            parts.append(G)
        return np.concatenate(parts, axis=1)

    def _batch(self, B, dt=None):
        return engine.Batch([self.case] * B, dt=dt, entries=(engine_motor.ENTRY,), like=self.batch)

    # ---- the map ---------------------------------------------------------------------------------
    def __call__(self, Y, keep=False):
        """(P(Y) (B, size), T (B,), status (B,), orbit): the map of section states Y (B, size), the
        revolution times, the engine's status per case; orbit (keep=True, case 0): the revolution's
        bordered states, times and engine outputs."""
        X, V, G = self.full(Y)
        A = None
        return self.to_angle(X, V, A, G, self.theta_s + TWO_PI, keep)

    def to_angle(self, X, V, A, G, target, keep=False):
        """March bordered states (X, V, accelerations A (None: solved), G (None: a start)) until the
        crank angle reaches `target` (per case, or one for all), the last step landing on it:
        (Y there with the crank angle brought back to the section, the time taken, status, orbit)."""
        X = np.array(X, dtype=float)
        B, N = X.shape[0], self.N
        target = np.broadcast_to(np.asarray(target, dtype=float), (B,)).copy()
        batch = self._batch(B)
        status = np.zeros(B, dtype=np.int64)
        before = np.full((B, 4, N + 1), np.nan)          # the state before the crossing: X, V, A, G
        steps = np.zeros(B, dtype=np.int64)              # full steps before the crossing
        crossed = np.zeros(B, dtype=bool)
        taken = 0
        orbit = {"X": [], "V": [], "A": [], "y": []} if keep else None
        for _ in range(self.max_chunks):
            n = self.batch.steps_per_rev
            res = engine.march_motor(batch, n, X, V, A0=A, G0=G, keep_history=True, tol=self.tol, status=status)
            theta = res.X_history[:, :, N]
            for b in np.flatnonzero(~crossed & (res.status == engine.OK)):
                hit = np.flatnonzero(theta[b, 1:] >= target[b])
                if hit.size:
                    k = int(hit[0])                       # the crossing lies in step k -> k + 1
                    before[b] = (res.X_history[b, k], res.V_history[b, k], res.A_history[b, k],
                                 res.G_history[b, k])
                    steps[b] = taken + k
                    crossed[b] = True
                    if keep and b == 0:
                        for key, h in (("X", res.X_history), ("V", res.V_history), ("A", res.A_history)):
                            orbit[key].append(h[0, :k + 1])
                        orbit["y"].append(res.y[0, :k + 1])
            if keep and not crossed[0]:
                for key, h in (("X", res.X_history), ("V", res.V_history), ("A", res.A_history)):
                    orbit[key].append(h[0, :n])
                orbit["y"].append(res.y[0, :n])
            status = res.status.copy()
            status[crossed] = engine.NOT_CONVERGED            # done: not advanced further
            if not np.any(~crossed & (res.status == engine.OK)):
                break
            X, V, A, G = res.X, res.V, res.A, res.G
            taken += n
        ok = crossed.copy()
        T = np.full(B, np.nan)
        Y1 = np.full((B, self.size), np.nan)
        final_status = np.where(ok, engine.OK, np.where(res.status == engine.OK, engine.NOT_CONVERGED, res.status))
        if not ok.any():
            return Y1, T, final_status, orbit
        idx = np.flatnonzero(ok)
        Xb, Vb, Ab, Gb = (before[idx, j] for j in range(4))
        tau = np.clip((target[idx] - Xb[:, N]) / np.maximum(Vb[:, N], 1e-300), 0.0, 2.0 * self.dt)
        for _ in range(TAU_ITERATIONS):
            last = engine.march_motor(self._batch(len(idx), dt=tau), 1, Xb, Vb, A0=Ab, G0=Gb, tol=self.tol)
            miss = target[idx] - last.X[:, N]
            if not np.all(last.status == engine.OK):
                break
            tau = tau + miss / last.V[:, N]
            if np.max(np.abs(miss)) < 1e-14 * TWO_PI:
                break
        last = engine.march_motor(self._batch(len(idx), dt=tau), 1, Xb, Vb, A0=Ab, G0=Gb, tol=self.tol)
        good = last.status == engine.OK
        final_status[idx[~good]] = last.status[~good]
        Xe = last.X.copy()
        Xe[:, N] -= target[idx] - self.theta_s
        Y1[idx] = self.section(Xe, last.V, last.G if self.generalized else None)
        T[idx] = steps[idx] * self.dt + tau
        if keep and ok[0]:
            orbit["X"].append(Xe[:1] + np.append(np.zeros(N), target[0] - self.theta_s))
            orbit["V"].append(last.V[:1])
            orbit["A"].append(last.A[:1])
            orbit["y"].append(last.y[0, 1:2])
            orbit = {k: np.concatenate(v) for k, v in orbit.items()}
            orbit["t"] = np.append(self.dt * np.arange(len(orbit["X"]) - 1), T[0])
        Y1[~(final_status == engine.OK)] = np.nan
        return Y1, T, final_status, orbit

    def jacobian(self, Y):
        """dP/dY (size, size) at Y by central differences (module docstring)."""
        h = FD_STEP * self.scales
        E = np.diag(h)
        P, _, st, _ = self(np.concatenate([Y[None] + E, Y[None] - E]))
        if np.any(st != engine.OK):
            return None
        n = self.size
        return ((P[:n] - P[n:]) / (2.0 * h)[:, None]).T

    def change(self, Y, Y1):
        """Scaled change |P(y) - y|_s (steady.py's measure)."""
        return float(np.max(np.abs(Y1 - Y) / self.scales) / (1.0 + np.max(np.abs(Y1) / self.scales)))


def monodromy(section_map, Y, T):
    """The flow's monodromy matrix over the time T on the bordered state (d, theta, v, thetad[, a,
    a_theta]) at the section state Y, by central differences of marches of exactly T (the steps of
    the map and a last one of the remaining length): a diagnostic of the trivial multiplier 1."""
    m = section_map
    N = m.N
    n_full = int(math.floor(T / m.dt + 1e-9))
    tau = T - n_full * m.dt
    X, V, G = m.full(Y)
    Z = np.concatenate([X[0], V[0]] + ([G[0]] if m.generalized else []))
    scale = np.concatenate([np.append(m.batch.scales[0], 1.0), m.scales[N:2 * N + 1]]
                           + ([m.scales[2 * N + 1:]] if m.generalized else []))
    h = FD_STEP * scale
    Zs = np.concatenate([Z[None] + np.diag(h), Z[None] - np.diag(h)])
    B, M1 = Zs.shape[0], N + 1
    Xs, Vs = Zs[:, :M1], Zs[:, M1:2 * M1]
    Gs = Zs[:, 2 * M1:] if m.generalized else None
    res = engine.march_motor(m._batch(B), n_full, Xs, Vs, G0=Gs, tol=m.tol)
    last = engine.march_motor(m._batch(B, dt=np.full(B, tau)), 1, res.X, res.V, A0=res.A, G0=res.G, tol=m.tol)
    if np.any(last.status != engine.OK):
        return None
    out = np.concatenate([last.X, last.V] + ([last.G] if m.generalized else []), axis=1)
    n = Z.size
    return ((out[:n] - out[n:]) / (2.0 * h)[:, None]).T


def warm_start(m, warmup, limit):
    """(the section state after the run-up from the case's start, why not, the no-load revolutions
    it took): marched in chunks of
    `warmup` no-load revolutions until the crank's mean speed over a chunk changes by less than 1 %
    from the last chunk's (a weak motor on a heavy crank takes long to settle), at most `limit`
    no-load revolutions; shooting starts from there.  A crank that does not turn forward is held
    back (its stall torque below the load)."""
    N = m.N
    theta0, speed0 = motor.crank_start(m.case)
    X = np.append(np.zeros(N), theta0)[None]
    V = np.append(np.zeros(N), speed0)[None]
    A = G = None
    steps = warmup * m.batch.steps_per_rev
    previous, total = None, 0
    while True:
        res = engine.march_motor(m.batch, steps, X, V, A0=A, G0=G, tol=m.tol)
        if res.status[0] != engine.OK:
            return None, (f"the run-up from the start failed: {engine.STATUS_TEXT[int(res.status[0])]} in step "
                          f"{total * m.batch.steps_per_rev + int(res.fail_step[0])}"), total
        total += warmup
        mean = (res.X[0, N] - X[0, N]) / (steps * m.dt)
        X, V, A, G = res.X, res.V, res.A, res.G
        if previous is not None and abs(mean - previous) < 0.01 * abs(mean) or total >= limit:
            break
        previous = mean
    theta = X[0, N]
    if not (mean > 0 and theta > theta0 + TWO_PI):
        return None, (f"the crank turned {(theta - theta0) / TWO_PI:.3g} revolutions in the {total} no-load "
                      f"revolutions of the run-up (mean speed {mean:.3g} over the last {warmup}): it is held back "
                      "(stall torque below the load)"), total
    turns = math.floor((theta - m.theta_s) / TWO_PI) + 1
    Y, _, st, _ = m.to_angle(X, V, A, G, m.theta_s + TWO_PI * turns)
    if st[0] != engine.OK:
        return None, "the march to the section after the run-up failed", total
    return Y[0], "", total


def steady_motor(case, tol=1e-8, max_revolutions=400, warmup=30, max_shooting=12):
    """The SteadyState of a motor-driven case (module docstring): status, the orbit over one
    revolution (its t from 0 to the revolution time, the crank's history `crank`), `period` (the
    revolution time T), `mean_speed` = 2 pi / T, `speed_fluctuation` = (max - min thetad) / mean,
    `multiplier` (the largest |multiplier| of the section map: the trivial one is not among them),
    `multipliers` (all, by modulus)."""
    from .steady import SteadyState
    m = SectionMap(case)
    Y, why, periods = warm_start(m, warmup, max_revolutions)
    if Y is None:
        return SteadyState(case, "failed", None, None, periods, 0, None, why)
    message, status, iterations, residual, J = "", None, 0, None, None
    for it in range(1, max_shooting + 1):
        Y1, T, st, _ = m(Y[None])
        if st[0] != engine.OK:
            message = f"shooting: a revolution failed ({engine.STATUS_TEXT[int(st[0])]}); marched instead"
            break
        residual = m.change(Y, Y1[0])
        iterations = it
        if residual < tol:
            status = "found"
            Y = Y1[0]
            break
        J = m.jacobian(Y)
        if J is None:
            message = "shooting: a revolution of the differenced Jacobian failed; marched instead"
            break
        try:
            Y = Y + np.linalg.solve(J - np.eye(m.size), -(Y1[0] - Y))
        except np.linalg.LinAlgError:
            message = "shooting: singular J - I; marched instead"
            break
    else:
        message = f"shooting did not converge in {max_shooting} iterations; marched instead"
    if status is None:                               # iterate the map: the motion, revolution by revolution
        Y = warm_start(m, warmup, max_revolutions)[0]
        for k in range(max_revolutions):
            Y1, T, st, _ = m(Y[None])
            periods += 1
            if st[0] != engine.OK:
                return SteadyState(case, "failed", None, None, periods, iterations, None,
                                   f"{message}; a revolution failed: {engine.STATUS_TEXT[int(st[0])]}")
            residual = m.change(Y, Y1[0])
            Y = Y1[0]
            if residual < tol:
                status = "found"
                break
        else:
            return SteadyState(case, "not-periodic", None, None, periods, iterations, residual,
                               f"{message}; no periodic state within max_revolutions = {max_revolutions}")
    J = m.jacobian(Y)
    mu = None if J is None else np.linalg.eigvals(J)
    _, T, st, orbit = m(Y[None], keep=True)
    X, V, A = orbit["X"], orbit["V"], orbit["A"]
    N = m.N
    crank = np.stack([X[:, N], V[:, N], A[:, N]], axis=-1)
    outputs = engine_columns(orbit["y"])
    v = outputs["v_mid"]
    rho = None if mu is None else float(np.max(np.abs(mu)))
    verdict = "periodic" if rho is not None and rho < 1.0 else "unstable" if rho is not None else "periodic"
    if rho is None:
        message = (message + "; " if message else "") + "multipliers not computed (a differenced revolution failed)"
    elif verdict == "unstable":
        message = (message + "; " if message else "") + f"the periodic motion is unstable (largest multiplier {rho:.4f})"
    state = np.concatenate([Y[:N], Y[N:2 * N]] + ([Y[2 * N + 1:3 * N + 1]] if m.generalized else []))
    result = SteadyState(case, verdict, float(np.max(np.abs(v))), float((v.max() - v.min()) / 2), periods,
                         iterations, residual, message, multiplier=rho, theta=crank[:, 0], t=orbit["t"],
                         outputs=outputs, state=state, states=X[:, :N], rates=V[:, :N], accelerations=A[:, :N],
                         crank=crank, period=float(T[0]), section_state=Y,
                         multipliers=None if mu is None else mu[np.argsort(-np.abs(mu))])
    return result


def check_steady(case, where=""):
    """Refuse what the autonomous shooting cannot take."""
    try:
        motor.check_driven(case)
    except ParameterError as exc:
        raise ParameterError(f"{where}{exc}") from None
    if case.integrator == "one-pass":
        raise ParameterError(f"{where}a motor-driven crank needs integrator 'newton' or 'full-newton'")
