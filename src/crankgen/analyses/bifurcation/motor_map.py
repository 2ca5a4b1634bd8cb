"""The motor-driven crank as a map of the continuation core: its section map (crankgen.analyses.motor_steady),
the autonomous motion's Poincare map on theta = theta0 (mod 2 pi).

State y = Y / s: the section state Y = (d, v, thetad) (with generalized-alpha's algorithmic
accelerations: (d, v, thetad, a, a_theta)) in units of each component's natural size.  P^k and its
Jacobian dP^k/dy by central differences of the section map (one compiled batch of 2 dim + 1
states, each marched k revolutions of the crank, every step converged to 1e-12); dP^k/dp by a
central difference at p -/+ h, h = dp_step max(|p|, 0.01) (crankgen.analyses.bifurcation.mechanism's
difference_pair at a bound).  The section map has no trivial multiplier (crankgen.analyses.motor_steady),
so the core's fold, period-doubling and Neimark-Sacker tests read the map's multipliers as they
are; generalized-alpha's algorithmic roots are small and weigh nothing in the metric.  Amplitude:
max |v*(1/2)| over the k revolutions (orbit_peak).  `speeds(states, p)`: the mean crank speed of
each point's orbit, 2 pi k / (its k revolutions' time).
"""

import math
from dataclasses import replace

import numpy as np

from ... import engine
from ..motor_steady import SectionMap
from ...declaration.validation import choice
from .maps import Map, MapError
from .mechanism import PARAMETERS, V_MID, difference_pair, orbit_peak


class MotorMap(Map):
    """P: scaled section state -> the scaled section state one crank revolution later."""

    def __init__(self, case, parameter, dp_step=1e-5):
        choice("parameter", parameter, PARAMETERS)
        self.case, self.parameter, self.dp_step = case, parameter, dp_step
        base = SectionMap(case)
        self.N, self.dim, self.s, self.generalized = base.N, base.size, base.scales, base.generalized
        self.reported = 2 * self.N + 1          # (d, v, thetad): generalized-alpha's algorithmic roots left out
        if self.generalized:
            w = np.zeros(self.dim)
            w[:2 * self.N + 1] = 1.0 / (2 * self.N + 1)
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
            m = self._maps[float(p)] = SectionMap(self.case_at(p))
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
        Branch holds it), their time, each revolution's orbit: the section map's bordered states X,
        V, A, engine outputs y and times t from 0 to its revolution time).  MapError if one fails."""
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
