"""Periodic steady state over one crank revolution, computed directly by shooting.

The unknown is the state x = (d, v) at theta = 0, with the algorithmic accelerations a for
generalized-alpha (crankgen.discrete.time_scheme: (d, v, a)); the revolution map P (steps_per_rev Newton
steps of the case's time scheme) and its exact linearization J = dP/dx (engine.revolution) give
Newton's method on P(x) - x = 0:  (J - I) dx = -(P(x) - x).  A few marched revolutions from the paper's zero initial
conditions give the starting point.  Convergence measure: the scaled change
    |P(x) - x|_s = max_i |P(x)_i - x_i| / s_i  /  (1 + max_i |P(x)_i| / s_i)
with s the natural size of each DOF (eps^2 for axial, eps for transverse; velocities likewise).

Status of a result:
- "periodic": the state repeats with the crank period to `tol` and the periodic orbit is stable
  (every Floquet multiplier, eigenvalue of J, inside the unit circle);
- "unstable": a periodic orbit with the crank period exists but has a multiplier outside the unit
  circle, so the physical response does not settle on it (amplitude of the orbit still reported);
- "not-periodic": shooting did not converge and marching up to max_revolutions did not reach a
  state periodic with the crank period (the message says whether it repeats every 2 revolutions,
  i.e. a sub-harmonic response);
- "failed": the integration itself failed (Newton divergence, non-finite state); message says why.
`method="march"` skips shooting and marches revolution by revolution (the paper's way).
With integrator="one-pass" the step map is not the converged Newton map, so marching is used.

No result holds NaN or inf: a number that does not exist (the amplitude of a failed case, the
multiplier of a one-pass run) is None, and the status and message say why.  The multiplier of a
state found by marching comes from one linearized revolution at that state (newton, full-newton).

Speeds whose time step 2 pi / (Omega* steps_per_rev) exceeds the period of the rod's first
bending mode (2 pi in crankgen's time unit), i.e. Omega* * steps_per_rev < 1, are refused
(ParameterError).  With such steps Newmark's average-acceleration rule neither follows nor damps
the rod's vibration: every mode's step factor tends to -1, the one-revolution map tends to +-I and
all its Floquet multipliers crowd at modulus 1, off it by amounts set by the time step (at
Omega* = 1e-6, 4 elements: 1.008, 1.0018, 1.0004, 1.0001 for 50, 100, 200, 400 steps), while the
rod's own vibration decays within a tiny fraction of the revolution.  The verdict would then be a
property of the discretization, not of the mechanism.
"""

import math
import time
from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from .. import engine
from ..declaration import schema
from ..discrete import time_scheme
from ..discrete import kinematics as _kinematics
from ..declaration.cases import Case, run_case
from ..errors import ParameterError
from .limits import check_run_size
from ..results.outputs import DeclaredOutputs, engine_columns, takes_engine_outputs
from ..declaration.si import si_input
from .theory import warn_beyond
from ..declaration.units import Scales
from ..declaration.validation import choice, in_range, integer

STATUSES = ("periodic", "not-periodic", "unstable", "failed")
# a state repeating every second revolution is a sub-harmonic response when its change per
# revolution shrinks by less than this factor's complement over two revolutions
STEADY_CHANGE = 0.999
METHODS = ("shooting", "march")


@takes_engine_outputs
@dataclass(frozen=True)
class SteadyState(DeclaredOutputs):
    """One steady revolution of a case (arrays over steps_per_rev + 1 points, theta from 0 to 2 pi),
    with the engine's outputs (`outputs`, by name: v_mid, u_end, extension, each an attribute) and
    every declared output by name (crankgen.results.outputs: `slider_position`, `axial_force(x)`, ...).

    Numbers that do not exist for a result are None (never NaN); status and message say why.
    """

    case: Case
    status: str
    amplitude: Optional[float]          # max |v*(1/2)| over the revolution (None: no orbit)
    half_peak_to_peak: Optional[float]  # (max v* - min v*) / 2 (None: no orbit)
    periods: int                        # revolutions marched (warm-up and any marching fallback)
    iterations: int                     # shooting Newton iterations
    residual: Optional[float]           # scaled |P(x) - x| of the returned state (None: none)
    message: str = ""
    wall_time: float = 0.0       # seconds; for a batch, its wall time shared equally by its cases
    multiplier: Optional[float] = None  # largest |Floquet multiplier| (None: not computed, see message)
    theta: np.ndarray = field(default=None, repr=False)
    t: np.ndarray = field(default=None, repr=False)
    outputs: dict = field(default=None, repr=False)       # the engine's outputs over the revolution, by name
    state: np.ndarray = field(default=None, repr=False)   # reduced (d, v) at theta = 0, (2 N,); (d, v, a)
    #                                                       (3 N,) for generalized-alpha (its algorithmic a)
    states: np.ndarray = field(default=None, repr=False)  # reduced displacements over the revolution
    rates: np.ndarray = field(default=None, repr=False)   # reduced velocities over the revolution
    accelerations: np.ndarray = field(default=None, repr=False)
    scales: Optional[Scales] = field(default=None, repr=False)    # crankgen's units in SI (units="si")
    # a motor-driven crank's steady motion (crankgen.analyses.motor_steady): its crank's (theta, thetad,
    # thetadd) over the revolution, the revolution time, the state on the section theta = theta0
    # (d, v, thetad[, a, a_theta]) and every multiplier of the section map (by modulus; the trivial
    # multiplier of the autonomous flow is not among them)
    crank: Optional[np.ndarray] = field(default=None, repr=False)
    period: Optional[float] = None
    section_state: Optional[np.ndarray] = field(default=None, repr=False)
    multipliers: Optional[np.ndarray] = field(default=None, repr=False)

    @property
    def mean_speed(self):
        """A motor-driven crank's mean speed 2 pi / T over the steady revolution (None otherwise)."""
        return None if self.period is None else 2.0 * math.pi / self.period

    @property
    def speed_fluctuation(self):
        """A motor-driven crank's speed fluctuation (max - min thetad) / mean speed over the steady
        revolution (None otherwise)."""
        if self.crank is None:
            return None
        w = self.crank[:, 1]
        return float((w.max() - w.min()) / self.mean_speed)

    @property
    def motor_duty(self):
        """A motor-driven crank's {peak_motor_torque, rms_motor_torque, mean_motor_power} over the
        steady revolution (crankgen.torque_curve.duty; None otherwise)."""
        if self.crank is None or self.t is None:
            return None
        from ..declaration.torque_curve import duty
        return duty(self.case, self.t, self.crank[:, 1])

    @property
    def ok(self):
        return self.status == "periodic"

    def row(self):
        """Flat record for tables (crankgen.results.steady_row): the case's parameters (None where its guide
        or crank motion does not read them), its model and options, the scalar results, the range
        of the theory and the peak loads over the orbit."""
        from ..results.steady_row import row
        return row(self)


def _scaled_change(X0, X1, S):
    """Row-wise scaled change between states (B, 2N) with scales S (B, 2N)."""
    num = np.max(np.abs(X1 - X0) / S, axis=1)
    return num / (1.0 + np.max(np.abs(X1) / S, axis=1))


def _shooting_failure(history, status, J):
    """Why shooting stopped, in numbers: the scaled changes |P(x) - x| of its iterates, and the
    revolution map's multiplier nearest +1 at the last iterate (Newton's matrix J - I is singular
    where a multiplier is 1: a fold, or a slowly decaying mode that the step does not damp)."""
    parts = []
    if status != engine.OK:
        parts.append(f"a step of the revolution from its last iterate failed: {engine.STATUS_TEXT[int(status)]}")
    if history:
        parts.append("|P(x) - x| " + " -> ".join(f"{c:.2g}" for c in history[-4:]))
    if J is not None and np.all(np.isfinite(J)):
        mu = np.linalg.eigvals(J)
        near = mu[np.argmin(np.abs(mu - 1.0))]
        largest = mu[np.argmax(np.abs(mu))]
        parts.append(f"multiplier nearest +1: {near.real:.4g}{near.imag:+.2g}j, largest |mu| = {abs(largest):.4g}")
    return "; ".join(parts) or "no iterate"


def _failure_text(res, b, dt, before=0, steps_per_rev=None):
    """The failure of case b in a march that started `before` steps into the run: the step counted
    from the start of the run (and its revolution)."""
    code = int(res.status[b])
    step = before + int(res.fail_step[b])
    where = f", revolution {(step - 1) // steps_per_rev + 1}" if steps_per_rev else ""
    return (f"{engine.STATUS_TEXT[code]} in step {step} of the run{where} (t* = {step * dt:.6g}), "
            f"residual norm {res.fail_residual[b]:.3e}")


class _BatchSolver:
    """Steady states of one engine.Batch (cases sharing mesh and steps per revolution)."""

    def __init__(self, cases, tol, max_revolutions, warmup, max_shooting, method, parallel=None):
        self.batch = engine.Batch(cases, entries=("march", "revolution"))
        self.parallel = parallel
        self.cases = list(cases)
        self.tol, self.max_revolutions = tol, max_revolutions
        self.warmup, self.max_shooting, self.method = warmup, max_shooting, method
        B, N = len(self.cases), self.batch.N
        self.size = self.batch.state_size            # (d, v), or (d, v, a) for generalized-alpha
        self.generalized = self.size == 3 * N
        self.S = np.concatenate([self.batch.scales] * (self.size // N), axis=1)   # d, v (and a) alike
        self.status = np.array(["pending"] * B, dtype=object)
        self.message = [""] * B
        self.periods = np.zeros(B, dtype=int)
        self.iterations = np.zeros(B, dtype=int)
        self.residual = [None] * B
        self.multiplier = [None] * B
        self.X = np.zeros((B, self.size))

    def _march(self, revs, active, start=False):
        """March the active cases revs revolutions from their current X (theta = 0); start: from
        (d, v) alone (a run's start: generalized-alpha's first step is its starter)."""
        b, spr = self.batch, self.batch.steps_per_rev
        pre = np.where(active, engine.OK, engine.NOT_CONVERGED)
        X = self.X[:, :2 * b.N] if start else self.X
        res = engine.march_state(b, revs * spr, X, status=pre, parallel=self.parallel)
        X1 = engine.join_state(res, self.generalized)
        for i in np.flatnonzero(active & (res.status != engine.OK)):
            self.status[i] = "failed"
            self._note(i, _failure_text(res, i, float(b.dt[i]), int(self.periods[i]) * spr, spr))
        return X1, res

    def run(self):
        B = len(self.cases)
        active = np.ones(B, dtype=bool)
        # warm-up from the paper's zero initial conditions
        X1, _ = self._march(self.warmup, active, start=True)
        self.periods[:] = self.warmup
        can_shoot = np.array([c.integrator == "newton" for c in self.cases]) & (self.method == "shooting")
        # a warm-up that diverged still leaves its last state before the failure: a periodic orbit
        # (stable or not) may be found by shooting from there; the message keeps the failure
        rescued = (self.status == "failed") & can_shoot
        for i in np.flatnonzero(rescued):
            self.status[i] = "pending"
            self.message[i] = (f"the transient from rest failed ({self.message[i]}); shooting from its "
                               "last state before the failure")
        active &= self.status == "pending"
        self.X[active] = X1[active]
        shoot = active & can_shoot
        if shoot.any():
            self._shoot(shoot)
        rest = self.status == "pending"
        if rest.any():
            self._march_until_periodic(rest.copy())          # clears its argument
            self._marched_multipliers(rest & (self.status == "periodic"))
        return self._results()

    def _marched_multipliers(self, found):
        """Largest Floquet multiplier of states found by marching: one linearized revolution at
        the state (its Jacobian is exact only for converged Newton steps, so not for one-pass)."""
        newton = np.array([c.integrator in ("newton", "full-newton") for c in self.cases])
        for i in np.flatnonzero(found & ~newton):
            self._note(i, "multiplier not computed: the one-pass step is not a converged Newton "
                          "step, so the revolution map has no exact linearization")
        found = found & newton
        if not found.any():
            return
        _, J, st = engine.revolution(self.batch, self.X, active=found, parallel=self.parallel)
        for i in np.flatnonzero(found):
            if st[i] != engine.OK or not np.all(np.isfinite(J[i])):
                self._note(i, f"multiplier not computed: the linearized revolution failed "
                              f"({engine.STATUS_TEXT.get(int(st[i]), 'non-finite Jacobian')})")
                continue
            rho = float(np.max(np.abs(np.linalg.eigvals(J[i]))))
            self.multiplier[i] = rho
            if rho >= 1.0:
                self._note(i, f"marching settled although the largest Floquet multiplier is "
                              f"{rho:.4f}")

    def _note(self, i, text):
        self.message[i] = f"{self.message[i]}; {text}" if self.message[i] else text

    def _shoot(self, active):
        best = np.full(len(self.cases), math.inf)
        start = self.X.copy()
        history = [[] for _ in self.cases]           # the scaled change of every iterate, per case
        for it in range(1, self.max_shooting + 1):
            X1, J, st = engine.revolution(self.batch, self.X, active=active, parallel=self.parallel)
            change = _scaled_change(self.X, X1, self.S)
            for i in np.flatnonzero(active):
                if st[i] == engine.OK and np.isfinite(change[i]):
                    history[i].append(float(change[i]))
                if st[i] != engine.OK or not np.isfinite(change[i]) or change[i] > 1e3 * min(best[i], 1.0):
                    active[i] = False           # shooting diverged: fall back to marching
                    self.X[i] = start[i]
                    self._note(i, "shooting did not converge (" + _shooting_failure(
                        history[i], st[i], J[i] if st[i] == engine.OK else None) + "); marched instead")
                    continue
                best[i] = min(best[i], change[i])
                self.iterations[i] = it
                if change[i] < self.tol:
                    self.X[i] = X1[i]
                    self.residual[i] = float(change[i])
                    rho = float(np.max(np.abs(np.linalg.eigvals(J[i]))))
                    self.multiplier[i] = rho
                    if rho < 1.0:
                        self.status[i] = "periodic"
                    else:
                        self.status[i] = "unstable"
                        self._note(i, f"periodic orbit with the crank period is unstable "
                                      f"(largest Floquet multiplier {rho:.4f})")
                    active[i] = False
            if not active.any():
                return
            idx = np.flatnonzero(active)
            A = J[idx] - np.eye(J.shape[1])[None]
            rhs = -(X1[idx] - self.X[idx])
            try:
                delta = np.linalg.solve(A, rhs[..., None])[..., 0]
            except np.linalg.LinAlgError:
                delta = np.stack([np.linalg.lstsq(a, r, rcond=None)[0] for a, r in zip(A, rhs)])
            self.X[idx] = self.X[idx] + delta
        for i in np.flatnonzero(active):
            self.X[i] = start[i]
            self._note(i, f"shooting did not converge in {self.max_shooting} iterations (" + _shooting_failure(
                history[i], engine.OK, J[i]) + "); marched instead")

    def _march_until_periodic(self, active):
        """March revolution by revolution until the state repeats every revolution (periodic),
        every second revolution (a period-2, sub-harmonic response: reported, not averaged away),
        or max_revolutions is reached.  Repeating every second revolution is a sub-harmonic
        response only when the change per revolution has stopped shrinking (by less than
        1 - STEADY_CHANGE over two revolutions): a response settling onto a period-1 state through
        an alternation that decays slowly (a Floquet multiplier near -1) repeats every second
        revolution long before it repeats every revolution, and is marched on."""
        prev2 = np.full_like(self.X, np.nan)
        prev = self.X.copy()
        changes = [[] for _ in self.cases]
        while active.any():
            X1, _ = self._march(1, active)
            for i in np.flatnonzero(active):
                if self.status[i] == "failed":
                    active[i] = False
                    continue
                self.periods[i] += 1
                change = _scaled_change(prev[i:i + 1], X1[i:i + 1], self.S[i:i + 1])[0]
                two = _scaled_change(prev2[i:i + 1], X1[i:i + 1], self.S[i:i + 1])[0]
                changes[i].append(float(change))
                self.residual[i] = float(change)
                self.X[i] = X1[i]
                shrink = changes[i][-1] / changes[i][-3] if len(changes[i]) >= 3 and changes[i][-3] > 0 else 0.0
                if change < self.tol:
                    self.status[i] = "periodic"
                    active[i] = False
                elif (two < self.tol and shrink >= STEADY_CHANGE) or self.periods[i] >= self.max_revolutions:
                    if two < self.tol and shrink >= STEADY_CHANGE:
                        kind = "repeats every 2 revolutions (sub-harmonic response)"
                    else:
                        kind = "no periodic state with the crank period"
                        if 0.0 < shrink < 1.0:
                            more = math.log(self.tol / change) / math.log(shrink) * 2
                            kind += (f" within max_revolutions = {self.max_revolutions} (the change per "
                                     f"revolution shrinks by {shrink:.3g} every 2 revolutions: about "
                                     f"{more:.0f} more would reach tol)")
                    self.status[i] = "not-periodic"
                    self.message[i] = (f"{kind}: state still changing by {change:.2e} per revolution "
                                       f"after {self.periods[i]} revolutions")
                    active[i] = False
            prev2, prev = prev, X1

    def _results(self):
        b, spr, N = self.batch, self.batch.steps_per_rev, self.batch.N
        show = np.array([s in ("periodic", "unstable") for s in self.status])
        pre = np.where(show, engine.OK, engine.NOT_CONVERGED)
        res = engine.march_state(b, spr, self.X, status=pre, parallel=self.parallel, keep_history=True)
        out = []
        for i, case in enumerate(self.cases):
            if show[i] and res.status[i] == engine.OK:
                outputs = engine_columns(res.y[i])
                v = outputs["v_mid"]
                t = float(b.dt[i]) * np.arange(spr + 1)
                out.append(SteadyState(
                    case, self.status[i], float(np.max(np.abs(v))), float((v.max() - v.min()) / 2),
                    int(self.periods[i]), int(self.iterations[i]), self.residual[i],
                    self.message[i], multiplier=self.multiplier[i],
                    theta=_kinematics.case_state(case, t).theta, t=t, outputs=outputs,
                    state=self.X[i].copy(), states=res.D_history[i],
                    rates=res.V_history[i], accelerations=res.A_history[i]))
            else:
                status = self.status[i] if self.status[i] != "pending" else "failed"
                message = self.message[i]
                if show[i]:                   # the orbit was found but its revolution failed
                    status = "failed"
                    message = f"{message}; " if message else ""
                    message += "the revolution at the periodic state failed: " + _failure_text(
                        res, i, float(b.dt[i]))
                out.append(SteadyState(case, status, None, None, int(self.periods[i]),
                                       int(self.iterations[i]), self.residual[i],
                                       message or "no result", multiplier=self.multiplier[i]))
        return out


def _check_resolved(case, where=""):
    """Refuse a crank motion that is not periodic in the crank angle (a run-up), and a time step
    longer than the rod's first bending period (see the module docstring).  A motor-driven crank
    (steady_states takes it by its own path, shooting on a section) is checked by that path's rules."""
    if case.motion_record.driven:
        from .motor_steady import check_steady
        return check_steady(case, where)
    if not case.periodic:
        raise ParameterError(
            f"{where}a steady state needs a crank motion periodic in the crank angle; the "
            f"{case.motion_record.name!r} motion is not (a transient: simulate runs it)")
    T = _kinematics.period(case)
    dt = T / case.steps_per_rev
    if dt > 2 * math.pi:
        speed = schema.PARAMETERS[schema.CRANK_SPEED]
        value = getattr(case, speed.name)
        nominal = T == 2 * math.pi / value            # one revolution at the crank speed: T = 2 pi / Omega*
        raise ParameterError(
            f"{where}steps_per_rev must be at least {f'1/{speed.axis} = ' if nominal else ''}"
            f"{math.ceil(T / (2 * math.pi) * (1 - 1e-12)):d} for a "
            f"steady state at {speed.axis} = {value:g} (got {case.steps_per_rev}): the time step "
            f"dt* = {dt:.3g} would exceed the period 2 pi of the rod's first bending mode, and with "
            f"such steps the Floquet multipliers, hence the stability verdict, are set by the time "
            f"step instead of the mechanism; simulate() marches such slow, quasi-static runs")
    _kinematics.check_crank_steps(case, dt, T, where)


def _driven_states(cases, driven, tol, max_revolutions, progress, warmup, max_shooting, method, stacklevel):
    """steady_states of a list holding motor-driven cases (crankgen.analyses.motor_steady; by shooting on the
    section theta = theta0): each in turn, the prescribed ones as usual."""
    from .motor_steady import check_steady, steady_motor
    where = (lambda i: f"cases[{i}]: ") if len(cases) > 1 else (lambda i: "")
    for i in driven:
        check_steady(cases[i], where(i))
    if method != "shooting":
        raise ParameterError("a motor-driven crank's steady motion is found by shooting (method='shooting')")
    tol = in_range("tol", tol, 0, None, True)
    max_revolutions = integer("max_revolutions", max_revolutions, 1)
    warmup = integer("warmup", warmup, 1)
    others = [i for i in range(len(cases)) if i not in driven]
    results = [None] * len(cases)
    if others:
        for i, r in zip(others, steady_states([cases[i] for i in others], tol, max_revolutions, None, method,
                                              warmup, max_shooting, _stacklevel=stacklevel + 1)):
            results[i] = r
    for k, i in enumerate(driven):
        start = time.perf_counter()
        results[i] = replace(steady_motor(cases[i], tol, max_revolutions, max(warmup, MOTOR_WARMUP), max_shooting),
                             wall_time=time.perf_counter() - start)
        if progress is not None:
            progress(len(others) + k + 1, len(cases))
    warn_beyond([results[i] for i in driven], "steady motion", stacklevel=stacklevel)
    return results


# the no-load revolutions a motor-driven crank runs up before shooting
MOTOR_WARMUP = 30


def steady_states(cases, tol=1e-8, max_revolutions=400, progress=None, method="shooting",
                  warmup=3, max_shooting=12, parallel=None, _stacklevel=3, _omega_b=None):
    """Steady states of many cases (list in, list out, same order), batched: cases that share
    n_elements and steps_per_rev run together in the compiled engine.  A failing case comes back
    with status "failed" and its message; it does not stop the others.
    progress(done, total) is called after each batch.  parallel: run a batch's cases on all cores
    (default: when there is more than one case), or serially (False).  A case with
    Omega* * steps_per_rev < 1 raises ParameterError before any work (see the module docstring).
    A StepWarning (once) says when a case's step leaves the rod's first bending or axial mode
    unresolved and undamped (crankgen.discrete.time_scheme.step_warning)."""
    cases = [c if isinstance(c, Case) else Case.from_dict(c) for c in cases]
    driven = [i for i, c in enumerate(cases) if c.motion_record.driven]
    if driven:
        return _driven_states(cases, driven, tol, max_revolutions, progress, warmup, max_shooting, method,
                              _stacklevel)
    for i, c in enumerate(cases):
        _check_resolved(c, f"cases[{i}]: " if len(cases) > 1 else "")
    time_scheme.warn_steps(cases, stacklevel=_stacklevel, omega_b=_omega_b)   # _omega_b: rad/s too (SI)
    tol = in_range("tol", tol, 0, None, True)
    max_revolutions = integer("max_revolutions", max_revolutions, 1)
    warmup = integer("warmup", warmup, 1)
    choice("method", method, METHODS)
    groups = {}
    for i, c in enumerate(cases):
        generalized = time_scheme.coefficients(c.rho_inf).generalized    # shooting's state size
        groups.setdefault((c.n_elements, c.steps_per_rev, generalized), []).append(i)
    results = [None] * len(cases)
    done = 0
    for key in sorted(groups):
        idx = groups[key]
        check_run_size(key[0], key[1], n_cases=len(idx), stored="steady", batch=len(idx),
                       names={"n_steps": "steps_per_rev", "n_cases": "cases"})
        start = time.perf_counter()
        solver = _BatchSolver([cases[i] for i in idx], tol, max_revolutions,
                              min(warmup, max_revolutions), max_shooting, method, parallel)
        group_results = solver.run()
        share = (time.perf_counter() - start) / len(idx)
        for i, r in zip(idx, group_results):
            results[i] = replace(r, wall_time=share)
        done += len(idx)
        if progress is not None:
            progress(done, len(cases))
    warn_beyond(results, "periodic response" if len(results) == 1 else "periodic response of a case",
                stacklevel=_stacklevel)
    return results


def steady_state(mech=None, omega=None, *, model=None, case=None, crank=None, tol=1e-8,
                 max_revolutions=400, method="shooting", units="crankgen", **fields):
    """Periodic response over one crank revolution of one case (see module docstring): a Mechanism
    with the run's settings (omega, any Case field, the model `model` with explicit options
    overriding it, a periodic crank motion `crank`), or case=Case(...).  units="si": mech is a
    crankgen.SIMechanism with its crank motion (omega, crank and case are not given), and
    `result.si` gives the orbit in SI (crankgen.results.outputs.SIView)."""
    mech, crank, scales = si_input(mech, units, fields, omega=omega, crank=crank, case=case, what="steady_state")
    case = run_case(mech, case, model=model, omega=omega, crank=crank, **fields)
    result = steady_states([case], tol=tol, max_revolutions=max_revolutions, method=method, _stacklevel=4,
                           _omega_b=None if scales is None else scales.omega_b)[0]
    return result if scales is None else replace(result, scales=scales)
