"""The slider-crank as a map: the crank-revolution shooting map of the engine.

State y = x / s, x = (d, v) the reduced displacements and velocities at theta = 0 and s the natural
size of each DOF at the starting case (eps^2 axial, eps transverse; velocities alike), so that every
component is of the order of v* and the arclength metric is well conditioned.  P^k and its exact
Jacobian come from engine.revolution(..., revolutions=k); dP^k/dp is a central difference of two
marches at p -/+ h, h = 1e-5 max(1, |p|) (truncation ~1e-10, Newton noise ~1e-5 relative: the
corrector needs it only approximately).  Amplitude: max |v*(1/2)| over the k revolutions of the
orbit, marched from the state as in steady_state.
"""

from dataclasses import replace

import numpy as np

from .. import engine, schema
from ..errors import ParameterError
from ..validation import choice
from .maps import Map, MapError

# the parameters a continuation may vary: those the schema declares continuable
PARAMETERS = schema.CONTINUABLE


class MechanismMap(Map):
    """P: scaled state at theta = 0 -> scaled state one crank revolution later, for the case with
    `parameter` set to p."""

    def __init__(self, case, parameter, dp_step=1e-5):
        choice("parameter", parameter, PARAMETERS)
        if case.integrator != "newton":
            raise ParameterError(f"continuation needs integrator='newton' (the converged step map "
                                 f"is differentiated), got {case.integrator!r}")
        self.case, self.parameter, self.dp_step = case, parameter, dp_step
        b = engine.Batch([case], entries=("march", "revolution"))
        self.N, self.spr = b.N, b.steps_per_rev
        self.s = np.concatenate([b.scales[0], b.scales[0]])
        self.dim = 2 * self.N
        self._cache = {}

    def case_at(self, p):
        return replace(self.case, **{self.parameter: float(p)})

    def _batch(self, key, values):
        b = self._cache.get(key)
        if b is None:
            if len(self._cache) > 16:
                self._cache.clear()
            b = self._cache[key] = engine.Batch([self.case_at(v) for v in values])
        return b

    def _check(self, status, p, what):
        for st in np.atleast_1d(status):
            if st != engine.OK:
                raise MapError(f"{what} at {self.parameter} = {p:.6g}: {engine.STATUS_TEXT[int(st)]}")

    def evaluate(self, y, p, period=1, dp=True):
        X = np.asarray(y, dtype=float) * self.s
        b = self._batch(("one", p), [p])
        X1, J, st = engine.revolution(b, X[None], parallel=False, revolutions=period)
        self._check(st, p, "revolution map")
        if not (np.all(np.isfinite(X1)) and np.all(np.isfinite(J))):
            raise MapError(f"revolution map not finite at {self.parameter} = {p:.6g}")
        jy = J[0] / self.s[:, None] * self.s[None, :]
        jp = None
        if dp:
            h = self.dp_step * max(1.0, abs(p))
            b2 = self._batch(("pair", p), [p - h, p + h])
            N = self.N
            XX = np.repeat(X[None], 2, axis=0)
            res = engine.march(b2, period * self.spr, D0=XX[:, :N], V0=XX[:, N:], parallel=False)
            self._check(res.status, p, "march for dP/dp")
            Xh = np.concatenate([res.D, res.V], axis=1)
            jp = (Xh[1] - Xh[0]) / (2 * h) / self.s
        return X1[0] / self.s, jy, jp

    def march(self, y, p, revolutions, history=False):
        X = np.asarray(y, dtype=float) * self.s
        b = self._batch(("one", p), [p])
        res = engine.march(b, revolutions * self.spr, D0=X[None, :self.N], V0=X[None, self.N:],
                           keep_history=history, parallel=False)
        if res.status[0] != engine.OK:
            step = int(res.fail_step[0])
            raise MapError(f"march at {self.parameter} = {p:.6g} failed: "
                           f"{engine.STATUS_TEXT[int(res.status[0])]} in step {step}")
        return res

    def orbit(self, y, p, period=1):
        res = self.march(y, p, period, history=True)
        idx = np.arange(period + 1) * self.spr
        states = np.concatenate([res.D_history[0, idx], res.V_history[0, idx]], axis=1) / self.s
        return float(np.max(np.abs(res.y[0, :, 0]))), states, res.y[0, idx, 0]

    def iterate(self, y, p, n, jacobian=False):
        res = self.march(y, p, n, history=True)
        idx = np.arange(n + 1) * self.spr
        states = np.concatenate([res.D_history[0, idx], res.V_history[0, idx]], axis=1) / self.s
        jacs = None
        if jacobian:
            jacs = np.array([self.evaluate(states[j], p, 1, dp=False)[1] for j in range(n)])
        return states, res.y[0, idx, 0], jacs

    def physical(self, y):
        return np.asarray(y, dtype=float) * self.s
