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
from .limits import check_run_size, count
from .section import WARMUP, CrankSection, TimeSection
from .blas import single_thread
from ..discrete.mesh import components_of
from ..discrete.system import check_coordinates
from ..results.outputs import DeclaredOutputs, engine_columns, takes_engine_outputs
from ..declaration.si import si_input
from .theory import warn_beyond
from ..declaration.units import Scales
from ..declaration.validation import choice, in_range

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
    # every multiplier of the map (by modulus; None where not computed)
    multipliers: Optional[np.ndarray] = field(default=None, repr=False)
    # a driven crank's steady motion (crankgen.analyses.section, CrankSection): its crank's (theta,
    # thetad, thetadd) over the revolution, every declared co-ordinate's (name -> (steps, 3)), the
    # revolution time, the state on the section of the crank angle (the DOF map's without it: for a
    # motor (d, v, thetad[, a, a_theta])); the trivial multiplier of the autonomous flow is not
    # among its multipliers
    crank: Optional[np.ndarray] = field(default=None, repr=False)
    coordinates: Optional[dict] = field(default=None, repr=False)
    period: Optional[float] = None
    section_state: Optional[np.ndarray] = field(default=None, repr=False)

    @property
    def mean_speed(self):
        """A motor-driven crank's mean speed 2 pi / T over the steady revolution (None otherwise)."""
        return None if self.period is None else 2.0 * math.pi / self.period

    @property
    def speed_fluctuation(self):
        """A driven crank's speed fluctuation (max - min thetad) / mean speed over the steady
        revolution (None otherwise)."""
        if self.crank is None:
            return None
        w = self.crank[:, 1]
        return float((w.max() - w.min()) / self.mean_speed)

    @property
    def motor_duty(self):
        """A motor's {peak_motor_torque, rms_motor_torque, mean_motor_power} over the steady
        revolution, at the speed of the co-ordinate it drives (crankgen.results.motor_duty.duty;
        None otherwise)."""
        if not self.coordinates or self.t is None:
            return None
        from ..results.motor_duty import duty
        motor = next(c.name for c in self.case.motion_record.coordinates if c.motor)
        return duty(self.case, self.t, self.coordinates[motor][:, 1])

    @property
    def reductions(self):
        """{name: value} of every declared reduction over time (schema.REDUCTIONS: a peak, RMS, mean
        or range of an output) over the steady revolution (crankgen.results.reductions; None
        without an orbit)."""
        from ..results import reductions
        return reductions.values(self)

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


class _BatchSolver:
    """Steady states of cases that share one section map (crankgen.analyses.section): a batch of
    prescribed periodic cranks on the time section (mesh and steps per revolution shared), or one
    driven crank on the section of its crank angle.  The same shooting, marching and verdicts for
    both; only the map differs."""

    def __init__(self, cases, tol, max_revolutions, warmup, max_shooting, method, parallel=None):
        self.cases = list(cases)
        autonomous = bool(self.cases[0].motion_record.coordinates)
        self.map = CrankSection(self.cases[0]) if autonomous else TimeSection(self.cases, parallel)
        self.tol, self.max_revolutions = tol, max_revolutions
        self.warmup, self.max_shooting, self.method = warmup, max_shooting, method
        B = len(self.cases)
        self.size = self.map.size
        self.S = self.map.scales if autonomous else self.map.scales      # (B, size): d, v (and a) alike
        self.status = np.array(["pending"] * B, dtype=object)
        self.message = [""] * B
        self.periods = np.zeros(B, dtype=int)
        self.iterations = np.zeros(B, dtype=int)
        self.residual = [None] * B
        self.multiplier = [None] * B
        self.multipliers = [None] * B
        self.X = np.zeros((B, self.size))

    def _march(self, revs, active):
        """March the active cases revs revolutions of their map from their current X."""
        X1, status, why = self.map.march(self.X, revs, active, before=self.periods)
        for i in np.flatnonzero(active & (status != engine.OK)):
            self.status[i] = "failed"
            self._note(i, why[i])
        return X1

    def run(self):
        B = len(self.cases)
        active = np.ones(B, dtype=bool)
        X1, status, why, periods = self.map.start(self.warmup, self.max_revolutions, active)
        self.periods[:] = periods
        for i in np.flatnonzero(status != engine.OK):
            self.status[i] = "failed"
            self._note(i, why[i])
        # shooting needs the converged step map (newton; the time section's exact Jacobian its reuse too)
        newton = np.array([c.integrator == "newton" or (self.map.autonomous and c.integrator == "full-newton")
                           for c in self.cases])
        can_shoot = newton & (self.method == "shooting")
        # a warm-up that diverged still leaves its last state before the failure: a periodic orbit
        # (stable or not) may be found by shooting from there; the message keeps the failure
        rescued = (self.status == "failed") & can_shoot & np.all(np.isfinite(X1), axis=1)
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
        _, J, st = self.map.revolution(self.X, found)
        for i in np.flatnonzero(found):
            if st[i] != engine.OK or not np.all(np.isfinite(J[i])):
                self._note(i, f"multiplier not computed: the linearized revolution failed "
                              f"({engine.STATUS_TEXT.get(int(st[i]), 'non-finite Jacobian')})")
                continue
            self._multipliers(i, J[i])
            if self.multiplier[i] >= 1.0:
                self._note(i, f"marching settled although the largest Floquet multiplier is "
                              f"{self.multiplier[i]:.4f}")

    def _multipliers(self, i, J):
        mu = np.linalg.eigvals(J)
        self.multipliers[i] = mu[np.argsort(-np.abs(mu))]
        self.multiplier[i] = float(np.max(np.abs(mu)))

    def _note(self, i, text):
        self.message[i] = f"{self.message[i]}; {text}" if self.message[i] else text

    def _shoot(self, active):
        best = np.full(len(self.cases), math.inf)
        start = self.X.copy()
        history = [[] for _ in self.cases]           # the scaled change of every iterate, per case
        for it in range(1, self.max_shooting + 1):
            X1, J, st = self.map.revolution(self.X, active)
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
                    self._multipliers(i, J[i])
                    rho = self.multiplier[i]
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
            X1 = self._march(1, active)
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
        show = np.array([s in ("periodic", "unstable") for s in self.status])
        orbits, failure = self.map.orbit(self.X, show)
        out = []
        for i, case in enumerate(self.cases):
            o = orbits[i]
            if show[i] and o is not None:
                outputs = engine_columns(o["y"])
                v = outputs["v_mid"]
                extra = {}
                if self.map.autonomous:          # the section state, the revolution time, the co-ordinates
                    X, V, G = self.map.full(self.X[i:i + 1])
                    n_rod = self.map.n_rod
                    state = np.concatenate([X[0, :n_rod], V[0, :n_rod]] + ([G[0, :n_rod]] if G is not None else []))
                    extra = dict(crank=o["crank"], coordinates=o["coordinates"], period=o["period"],
                                 section_state=self.X[i].copy())
                else:
                    state = self.X[i].copy()
                out.append(SteadyState(
                    case, self.status[i], float(np.max(np.abs(v))), float((v.max() - v.min()) / 2),
                    int(self.periods[i]), int(self.iterations[i]), self.residual[i],
                    self.message[i], multiplier=self.multiplier[i], theta=o["theta"], t=o["t"], outputs=outputs,
                    state=state, states=o["states"], rates=o["rates"], accelerations=o["accelerations"],
                    multipliers=self.multipliers[i], **extra))
            else:
                status = self.status[i] if self.status[i] != "pending" else "failed"
                message = self.message[i]
                if show[i]:                   # the orbit was found but its revolution failed
                    status = "failed"
                    message = f"{message}; " if message else ""
                    message += "the revolution at the periodic state failed: " + failure(i)
                out.append(SteadyState(case, status, None, None, int(self.periods[i]),
                                       int(self.iterations[i]), self.residual[i],
                                       message or "no result", multiplier=self.multiplier[i]))
        return out


def _check_resolved(case, where=""):
    """Refuse a crank motion that is not periodic in the crank angle (a run-up), and a time step
    longer than the rod's first bending period (see the module docstring).  A driven crank (its
    steady motion is shot on the section of its crank angle) is checked by the bordered step's rules."""
    if case.motion_record.coordinates:
        try:
            return check_coordinates(case)
        except ParameterError as exc:
            raise ParameterError(f"{where}{exc}") from None
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


MOTOR_WARMUP = WARMUP   # the revolutions of its step period (no-load revolutions) a driven crank runs up first


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
    for i, c in enumerate(cases):
        _check_resolved(c, f"cases[{i}]: " if len(cases) > 1 else "")
    time_scheme.warn_steps([c for c in cases if not c.motion_record.coordinates], stacklevel=_stacklevel,
                           omega_b=_omega_b)   # _omega_b: rad/s too (SI)
    tol = in_range("tol", tol, 0, None, True)
    max_revolutions = count("max_revolutions", max_revolutions)
    warmup = count("warmup", warmup)
    choice("method", method, METHODS)
    groups = {}
    for i, c in enumerate(cases):
        generalized = time_scheme.coefficients(c.rho_inf).generalized    # shooting's state size
        alone = i if c.motion_record.coordinates else -1                # a driven crank: its own section map
        groups.setdefault((c.n_elements, c.steps_per_rev, generalized, alone, components_of(c.options)),
                          []).append(i)
    results = [None] * len(cases)
    with single_thread():                   # the multipliers' eigenvalues, the shooting's solves
        _solve_groups(cases, groups, results, tol, max_revolutions, warmup, max_shooting, method, parallel,
                      progress)
    what = "steady motion" if all(c.motion_record.coordinates for c in cases) else "periodic response"
    warn_beyond(results, what if len(results) == 1 else f"{what} of a case", stacklevel=_stacklevel)
    return results


def _solve_groups(cases, groups, results, tol, max_revolutions, warmup, max_shooting, method, parallel,
                  progress):
    """steady_states' batches: the cases of each group (same mesh, steps and scheme) solved together
    into results."""
    done = 0
    for key in sorted(groups):
        idx = groups[key]
        check_run_size(key[0], key[1], n_cases=len(idx), stored="steady", batch=len(idx),
                       names={"n_steps": "steps_per_rev", "n_cases": "cases"})
        start = time.perf_counter()
        driven = key[3] >= 0
        solver = _BatchSolver([cases[i] for i in idx], tol, max_revolutions,
                              max(warmup, MOTOR_WARMUP) if driven else min(warmup, max_revolutions), max_shooting,
                              method, parallel)
        group_results = solver.run()
        share = (time.perf_counter() - start) / len(idx)
        for i, r in zip(idx, group_results):
            results[i] = replace(r, wall_time=share)
        done += len(idx)
        if progress is not None:
            progress(done, len(cases))


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
