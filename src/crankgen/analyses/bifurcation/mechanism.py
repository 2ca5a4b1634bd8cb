"""The mechanism as a map of the continuation core, on the section its declaration gives
(crankgen.analyses.section): `mechanism_map(case, parameter)` is the crank-revolution shooting map
of a prescribed periodic crank (MechanismMap, below), or a driven crank's map on the section of its
crank angle (AutonomousMap).

MechanismMap, the crank-revolution shooting map of the engine:

State y = x / s, x = (d, v) the reduced displacements and velocities at theta = 0 (with the
algorithmic accelerations a for generalized-alpha: (d, v, a), crankgen.discrete.time_scheme) and s the natural
size of each DOF at the starting case (eps^2 axial, eps transverse; rates alike), so that every
component is of the order of v* and the arclength metric is well conditioned.  P^k and its exact
Jacobian come from engine.shoot(..., revolutions=k), and so does dP^k/dp (derivative="exact", the
default): one more sensitivity column of the linearized steps, forced by dR/dp at the converged
state of each step (a central difference of the residual alone between the cases at p -/+ h,
h = 1e-5 max(|p|, 0.01): truncation ~1e-10 relative, no Newton noise) and by the dependence of the
time step on p.  derivative="central" keeps the former central difference of two marches at
p -/+ h, h = 1e-5 max(1, |p|) (Newton noise ~1e-5 relative), as a baseline to measure against.
value(y, p, k) marches P^k alone.  Amplitude: max |v*(1/2)| over the k revolutions of the orbit
(orbit_peak: the largest sample raised to the peak of the parabola through it and its neighbours),
marched from the state as in steady_state (taken from the last evaluation with Jacobians when that
was at the same state and parameter: the same steps).
"""

import math
from dataclasses import replace

import numpy as np

from ... import engine
from ...declaration import schema
from ...errors import NoResultError, ParameterError
from ...declaration.validation import choice
from ..section import WARMUP, CrankSection
from .maps import Map, MapError

V_MID = schema.ENGINE_OUTPUTS.index("v_mid")     # the observable: v* at x* = 1/2, in the engine's outputs

# the parameters a continuation may vary: those the schema declares continuable
PARAMETERS = schema.CONTINUABLE


def difference_pair(name, p, h):
    """The parameter values p - h and p + h of a central difference, shifted by h into the
    parameter's declared range where one of them would leave it (a continuation starting at a
    bound: mu = 0): (p, p + 2 h) or (p - 2 h, p), whose difference over 2 h is the derivative at
    p +/- h, first order in h (1e-7 relative with the maps' steps)."""
    spec = schema.PARAMETERS[name]
    lo, hi = p - h, p + h
    below = spec.low is not None and (lo <= spec.low if spec.low_open else lo < spec.low)
    above = spec.high is not None and (hi >= spec.high if spec.high_open else hi > spec.high)
    if below and not above:
        return p, p + 2 * h
    if above and not below:
        return p - 2 * h, p
    return lo, hi


def state_metric(N):
    """The weights of generalized-alpha's state (d, v, a) in the continuation's metric
    (maps.state_weights): 1/(2N) on (d, v), as Newmark's map (whose metric is the default 1/dim),
    and 0 on the algorithmic accelerations, which are slaved to the orbit; in the scaled units their
    stiff (axial) components are several times larger than (d, v) and would otherwise set the step
    length and let the corrector jump between branches."""
    w = np.full(3 * N, 1.0 / (2 * N))
    w[2 * N:] = 0.0
    return w


def orbit_peak(v):
    """max |v| over a periodic orbit sampled at v[0], ..., v[-1] (v[-1] the start again): the
    largest sample, raised to the peak of the parabola through it and its two neighbours (the
    orbit wraps around).  The largest sample alone falls short of the orbit's maximum by up to
    (pi / samples per revolution)^2 / 2 relative, and which sample is largest changes along a
    branch, which kinked the amplitude curves; the parabola's error is of third order."""
    v = np.asarray(v, dtype=float)
    n = len(v) - 1                          # distinct samples of the closed orbit
    k = int(np.argmax(np.abs(v[:n]))) if n >= 3 else int(np.argmax(np.abs(v)))
    top = abs(float(v[k]))
    if n < 3:
        return top
    sign = 1.0 if v[k] >= 0 else -1.0
    left, mid, right = sign * v[(k - 1) % n], sign * v[k], sign * v[(k + 1) % n]
    curvature = left - 2 * mid + right
    if not curvature < 0:
        return top
    return top - (right - left) ** 2 / (8 * curvature)


class MechanismMap(Map):
    """P: scaled state at theta = 0 -> scaled state one crank revolution later, for the case with
    `parameter` set to p."""

    def __init__(self, case, parameter, dp_step=1e-5, derivative="exact"):
        choice("parameter", parameter, PARAMETERS)
        choice("derivative", derivative, ("exact", "central"))
        if not case.periodic:
            raise ParameterError(f"continuation and poincare follow the crank-revolution map, which needs a "
                                 f"crank motion periodic in the crank angle; the {case.motion_record.name!r} motion is "
                                 f"not (a run-up is a transient: simulate runs it)")
        if case.integrator != "newton":
            raise ParameterError(f"continuation needs integrator='newton' (the converged step map "
                                 f"is differentiated), got {case.integrator!r}")
        self.case, self.parameter, self.dp_step, self.derivative = case, parameter, dp_step, derivative
        b = self._template = engine.Batch([case], entries=("march", "revolution"))
        self.N, self.spr = b.N, b.steps_per_rev
        self.dim = b.state_size
        self.generalized = self.dim == 3 * self.N
        self.s = np.concatenate([b.scales[0]] * (self.dim // self.N))
        self.reported = 2 * self.N        # the multipliers reported (time_scheme.reported_multipliers)
        self.weights = state_metric(self.N) if self.generalized else None
        self._cache = {}
        self._orbits = {}

    def case_at(self, p):
        return replace(self.case, **{self.parameter: float(p)})

    def _batch(self, key, values):
        b = self._cache.get(key)
        if b is None:
            if len(self._cache) > 16:
                self._cache.clear()
            b = self._cache[key] = engine.Batch([self.case_at(v) for v in values], like=self._template,
                                                entries=("march", "revolution"))
        return b

    def _check(self, status, p, what):
        for st in np.atleast_1d(status):
            if st != engine.OK:
                raise MapError(f"{what} at {self.parameter} = {p:.6g}: {engine.STATUS_TEXT[int(st)]}")

    def _shoot(self, y, p, period, jacobian, parameter=None):
        """engine.shoot from the scaled state y; the orbit it marched is kept for orbit()."""
        X = np.asarray(y, dtype=float) * self.s
        b = self._batch(("one", p), [p])
        r = engine.shoot(b, X[None], parallel=False, revolutions=period, jacobian=jacobian,
                         parameter=parameter)
        self._check(r.status, p, "revolution map")
        if not np.all(np.isfinite(r.X1)):
            raise MapError(f"revolution map not finite at {self.parameter} = {p:.6g}")
        if len(self._orbits) > 8:
            self._orbits.clear()
        idx = np.arange(period + 1) * self.spr
        self._orbits[(np.asarray(y, dtype=float).tobytes(), float(p), period)] = (
            orbit_peak(r.y[0, :, V_MID]), r.states[0] / self.s, r.y[0, idx, V_MID])
        return X, r

    def evaluate(self, y, p, period=1, dp=True):
        parameter = None
        if dp and self.derivative == "exact":
            h = self.dp_step * max(abs(p), 0.01)
            lo, hi = difference_pair(self.parameter, p, h)
            parameter = (self._batch(("one", lo), [lo]), self._batch(("one", hi), [hi]), h)
            here = self._batch(("one", p), [p]).records.select
            if any(not np.array_equal(b.records.select, here) for b in parameter[:2]):
                parameter = None        # a term family switches at p (its coefficient vanishes): marches
        X, r = self._shoot(y, p, period, True, parameter)
        J = r.J[0]
        if not np.all(np.isfinite(J)):
            raise MapError(f"revolution map not finite at {self.parameter} = {p:.6g}")
        jy = J / self.s[:, None] * self.s[None, :]
        jp = None
        if parameter is not None:
            if not np.all(np.isfinite(r.Jp)):
                raise MapError(f"dP/d{self.parameter} not finite at {self.parameter} = {p:.6g}")
            jp = r.Jp[0] / self.s
        elif dp:
            jp = self._central_dp(X, p, period)
        return r.X1[0] / self.s, jy, jp

    def value(self, y, p, period=1):
        """P^period(y, p) alone: the revolutions without linearization."""
        return self._shoot(y, p, period, False)[1].X1[0] / self.s

    def _central_dp(self, X, p, period):
        """dP^k/dp by a central difference of two marches at p -/+ h (derivative="central")."""
        h = self.dp_step * max(1.0, abs(p))
        b2 = self._batch(("pair", p), list(difference_pair(self.parameter, p, h)))
        XX = np.repeat(X[None], 2, axis=0)
        res = engine.march_state(b2, period * self.spr, XX, parallel=False)
        self._check(res.status, p, "march for dP/dp")
        Xh = engine.join_state(res, self.generalized)
        return (Xh[1] - Xh[0]) / (2 * h) / self.s

    def rest(self):
        """The scaled state of the mechanism at rest at theta = 0 (the rod undeformed): zero, with
        generalized-alpha's algorithmic accelerations None (NaN): a march from it starts the run
        (the scheme's starter step)."""
        y = np.zeros(self.dim)
        if self.generalized:
            y[2 * self.N:] = np.nan
        return y

    def march(self, y, p, revolutions, history=False):
        X = np.asarray(y, dtype=float) * self.s
        if self.generalized and np.isnan(X[2 * self.N:]).all():
            X = X[:2 * self.N]                 # from rest: a start
        b = self._batch(("one", p), [p])
        res = engine.march_state(b, revolutions * self.spr, X[None], keep_history=history, parallel=False)
        if res.status[0] != engine.OK:
            step = int(res.fail_step[0])
            raise MapError(f"march at {self.parameter} = {p:.6g} failed: "
                           f"{engine.STATUS_TEXT[int(res.status[0])]} in step {step}")
        return res

    def orbit(self, y, p, period=1):
        known = self._orbits.get((np.asarray(y, dtype=float).tobytes(), float(p), period))
        if known is not None:
            return known
        res = self.march(y, p, period, history=True)
        idx = np.arange(period + 1) * self.spr
        states = engine.join_state(res, self.generalized, idx) / self.s
        return orbit_peak(res.y[0, :, V_MID]), states, res.y[0, idx, V_MID]

    def iterate(self, y, p, n, jacobian=False):
        res = self.march(y, p, n, history=True)
        idx = np.arange(n + 1) * self.spr
        states = engine.join_state(res, self.generalized, idx) / self.s
        jacs = None
        if jacobian:
            jacs = np.array([self.evaluate(states[j], p, 1, dp=False)[1] for j in range(n)])
        return states, res.y[0, idx, V_MID], jacs

    def physical(self, y):
        return np.asarray(y, dtype=float) * self.s

    def from_steady(self, state):
        """The scaled state of a SteadyState (its state at theta0)."""
        return state.state / self.s


def mechanism_map(case, parameter, derivative="exact"):
    """The map of the case's steady motion on its section: MechanismMap for a prescribed periodic
    crank, AutonomousMap for a driven one (the declaration's co-ordinates)."""
    if case.motion_record.coordinates:
        return AutonomousMap(case, parameter)
    return MechanismMap(case, parameter, derivative=choice("derivative", derivative, ("exact", "central")))


class AutonomousMap(Map):
    """A driven crank's map on the section of its crank angle (crankgen.analyses.section,
    CrankSection): P: scaled section state -> the scaled section state one crank revolution later.

    State y = Y / s: the section state Y (the DOF map's without the crank angle: for a motor (d, v,
    thetad), with generalized-alpha's algorithmic accelerations (d, v, thetad, a, a_theta)) in units
    of each component's natural size.  P^k and its Jacobian dP^k/dy by central differences of the
    section map (one compiled batch of 2 dim + 1 states, each marched k revolutions of the crank,
    every step converged to 1e-12); dP^k/dp by a central difference at p -/+ h, h = dp_step
    max(|p|, 0.01) (difference_pair at a bound).  The section map has no trivial multiplier, so the
    core's fold, period-doubling and Neimark-Sacker tests read the map's multipliers as they are;
    generalized-alpha's algorithmic roots are small and weigh nothing in the metric.  Amplitude:
    max |v*(1/2)| over the k revolutions (orbit_peak).  `speeds(states, p)`: the mean crank speed
    of each point's orbit, 2 pi k / (its k revolutions' time)."""

    def __init__(self, case, parameter, dp_step=1e-5):
        choice("parameter", parameter, PARAMETERS)
        self.case, self.parameter, self.dp_step = case, parameter, dp_step
        base = CrankSection(case)
        self.N, self.dim, self.s, self.generalized = base.N, base.size, base.state_scales, base.generalized
        self.n_rod = base.n_rod
        self.reported = 2 * self.N - 1          # (x without theta, v): generalized-alpha's algorithmic roots left out
        if self.generalized:
            w = np.zeros(self.dim)
            w[:self.reported] = 1.0 / self.reported
            self.weights = w
        else:
            self.weights = None
        self._maps = {float(getattr(case, parameter)): base}

    def case_at(self, p):
        return replace(self.case, **{self.parameter: float(p)})

    def _section_map(self, p):
        m = self._maps.get(float(p))
        if m is None:
            if len(self._maps) > 8:
                self._maps.clear()
            m = self._maps[float(p)] = CrankSection(self.case_at(p))
        return m

    def _apply(self, Y, p, period, keep=False):
        """(P^period of the states Y (B, dim), their total times (B,), orbits of case 0 if keep)."""
        m = self._section_map(p)
        Y = np.atleast_2d(np.asarray(Y, dtype=float))
        T = np.zeros(Y.shape[0])
        orbits = []
        for _ in range(period):
            Y, dT, st, orbit = m(Y, keep=keep)
            bad = np.flatnonzero(st != engine.OK)
            if bad.size:
                raise MapError(f"the section map at {self.parameter} = {p:.6g}: "
                               f"{engine.STATUS_TEXT.get(int(st[bad[0]]), 'the crank did not reach the section')}")
            T += dT
            orbits.append(orbit)
        return Y, T, orbits

    def revolutions(self, Y, p, period=1):
        """(the physical section state `period` revolutions after the physical section state Y (as a
        Branch holds it), their time, each revolution's orbit: the section map's states X, V, A (the
        DOF map's), engine outputs y, co-ordinates Z and times t from 0 to its revolution time).
        MapError if one fails."""
        Y1, T, orbits = self._apply(np.asarray(Y, dtype=float)[None], p, period, keep=True)
        return Y1[0], float(T[0]), orbits

    def evaluate(self, y, p, period=1, dp=True):
        Y = np.asarray(y, dtype=float) * self.s
        h = 1e-6 * self.s
        E = np.diag(h)
        P, _, _ = self._apply(np.concatenate([Y[None], Y[None] + E, Y[None] - E]), p, period)
        n = self.dim
        J = ((P[1:n + 1] - P[n + 1:]) / (2.0 * h)[:, None]).T
        jy = J / self.s[:, None] * self.s[None, :]
        jp = None
        if dp:
            hp = self.dp_step * max(abs(p), 0.01)
            lo, hi = difference_pair(self.parameter, p, hp)
            Plo = self._apply(Y[None], lo, period)[0][0]
            Phi = self._apply(Y[None], hi, period)[0][0]
            jp = (Phi - Plo) / (hi - lo) / self.s
        if not (np.all(np.isfinite(P[0])) and np.all(np.isfinite(jy))):
            raise MapError(f"the section map is not finite at {self.parameter} = {p:.6g}")
        return P[0] / self.s, jy, jp

    def value(self, y, p, period=1):
        return self._apply(np.asarray(y, dtype=float) * self.s, p, period)[0][0] / self.s

    def orbit(self, y, p, period=1):
        Y = np.asarray(y, dtype=float) * self.s
        states, samples, v = [Y], [], []
        for _ in range(period):
            Y1, _, orbits = self._apply(states[-1], p, 1, keep=True)
            o = orbits[0]
            samples.append(o["y"][0, V_MID])
            v.append(o["y"][:-1, V_MID])
            states.append(Y1[0])
        samples.append(samples[0] if period else 0.0)
        v = np.concatenate(v + [v[0][:1]])
        return orbit_peak(v), np.array(states) / self.s, np.array(samples)

    def iterate(self, y, p, n, jacobian=False):
        Y = np.asarray(y, dtype=float) * self.s
        states, samples, jacs = [Y], [], []
        for _ in range(n):
            Y1, _, orbits = self._apply(states[-1], p, 1, keep=True)
            samples.append(orbits[0]["y"][0, V_MID])
            states.append(Y1[0])
            if jacobian:
                jacs.append(self.evaluate(states[-2] / self.s, p, 1, dp=False)[1])
        samples.append(samples[-1] if n else 0.0)
        return np.array(states) / self.s, np.array(samples), (np.array(jacs) if jacobian else None)

    def physical(self, y):
        return np.asarray(y, dtype=float) * self.s

    def speeds(self, states, parameters, period=1):
        """(mean crank speed, revolution time) of each point (its physical section state, as a
        Branch holds it, and its parameter): 2 pi k / T and T / k over its k revolutions (NaN where
        the map fails)."""
        speed, time = np.full(len(states), math.nan), np.full(len(states), math.nan)
        for i, (Y, p) in enumerate(zip(states, parameters)):
            try:
                _, T, _ = self._apply(np.asarray(Y, dtype=float), p, period)
            except MapError:
                continue
            speed[i], time[i] = 2 * math.pi * period / T[0], T[0] / period
        return speed, time

    def from_steady(self, state):
        """The scaled state of a SteadyState (its section state)."""
        return state.section_state / self.s

    def rest(self):
        """The scaled section state after the run-up from the case's start (poincare's first):
        WARMUP revolutions of the step period, longer while the mean speed still changes by
        1 % (CrankSection.warm_start)."""
        Y0, why, _ = self._maps[float(getattr(self.case, self.parameter))].warm_start(WARMUP, 20 * WARMUP)
        if Y0 is None:
            raise NoResultError(f"the driven crank at {self.parameter} = {getattr(self.case, self.parameter):g}: {why}")
        return Y0 / self.s
