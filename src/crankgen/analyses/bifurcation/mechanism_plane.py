"""The mechanism's crank-revolution map in two parameters (a PlaneMap for codim2.py).

The same map as MechanismMap (mechanism.py): scaled state y = x / s at theta = 0 ((d, v), or (d, v, a)
for generalized-alpha), P^k and its exact
Jacobian from engine.shoot.  dP^k/dp for both parameters: the engine's exact parameter column
(one sensitivity column more, forced by dR/dp at each converged step) for the case perturbed along
p1, and for a copy of it perturbed along p2, in one batch (the engine shoots a batch's cases on
every core).  Each column is dP/dlambda of the cases at p + lambda s_k e_k (s_k = max(|p_k|, 0.01),
lambda = -/+ h, h = dp_step), divided by s_k: the engine's one difference step h then suits
parameters of any size (at a bound of the parameter's range, lambda = 0 and 2 h: difference_pair).  Where a term family switches between p - h s_k and p + h s_k (a
coefficient through zero), that column is a central difference of two marches.  Every request of a
call (the base point and the finite-difference neighbours of defining.py) runs in the same batch.
Amplitude: max |v*(1/2)| over the k revolutions of the orbit (orbit_peak), from the base point's
own shooting when it was asked (the same steps).
"""

from dataclasses import replace

import numpy as np

from ... import engine
from ...errors import ParameterError
from .maps import MapError
from .mechanism import PARAMETERS, V_MID, difference_pair, orbit_peak, state_metric
from .plane_maps import PlaneMap


class MechanismPlaneMap(PlaneMap):
    """P: scaled state at theta = 0 -> the state one crank revolution later, for the case with
    parameters names = (p1, p2) set to p."""

    def __init__(self, case, names, dp_step=1e-5):
        names = tuple(names)
        for name in names:
            if name not in PARAMETERS:
                raise ParameterError(f"parameter must be one of {', '.join(PARAMETERS)}, got {name!r}")
        if names[0] == names[1]:
            raise ParameterError(f"the two parameters must differ, got {names[0]!r} twice")
        if not case.periodic:
            raise ParameterError(f"a two-parameter continuation follows the crank-revolution map, which "
                                 f"needs a crank motion periodic in the crank angle; the {case.motion_record.name!r} "
                                 f"motion is not")
        if case.integrator != "newton":
            raise ParameterError(f"a two-parameter continuation needs integrator='newton', got "
                                 f"{case.integrator!r}")
        self.case, self.names, self.dp_step = case, names, float(dp_step)
        b = self._template = engine.Batch([case], entries=("march", "revolution"))
        self.N, self.spr = b.N, b.steps_per_rev
        self.dim = b.state_size                 # (d, v), or (d, v, a) for generalized-alpha
        self.generalized = self.dim == 3 * self.N
        self.s = np.concatenate([b.scales[0]] * (self.dim // self.N))
        self.weights = state_metric(self.N) if self.generalized else None
        self._orbits = {}
        self.shootings = 0          # cases shot (each with its Jacobian)

    def case_at(self, p):
        return replace(self.case, **{self.names[0]: float(p[0]), self.names[1]: float(p[1])})

    def _batch(self, cases):
        return engine.Batch(cases, like=self._template, entries=("march", "revolution"))

    def _step(self, p, k):
        return self.dp_step * max(abs(float(p[k])), 0.01)

    def _moved(self, p, k, sign):
        q = np.array(p, dtype=float)
        q[k] = difference_pair(self.names[k], float(p[k]), self._step(p, k))[0 if sign < 0 else 1]
        return self.case_at(q)

    def _where(self, p):
        return f"{self.names[0]} = {p[0]:.6g}, {self.names[1]} = {p[1]:.6g}"

    def jacobians(self, requests, period=1, dp=True):
        requests = [(np.asarray(y, dtype=float), np.asarray(p, dtype=float)) for y, p in requests]
        copies = 2 if dp else 1
        cases = [self.case_at(p) for _, p in requests for _ in range(copies)]
        X0 = np.array([y * self.s for y, _ in requests for _ in range(copies)])
        batch = self._batch(cases)
        parameter = None
        if dp:
            minus = self._batch([self._moved(p, k, -1.0) for _, p in requests for k in (0, 1)])
            plus = self._batch([self._moved(p, k, 1.0) for _, p in requests for k in (0, 1)])
            same = (np.array_equal(minus.records.select, batch.records.select)
                    and np.array_equal(plus.records.select, batch.records.select))
            if same:
                parameter = (minus, plus, self.dp_step)
        try:
            r = engine.shoot(batch, X0, parallel=len(cases) > 1, revolutions=period, jacobian=True,
                             parameter=parameter)
        except ValueError as exc:
            raise MapError(str(exc))
        self.shootings += len(cases)
        out = []
        idx = np.arange(period + 1) * self.spr
        for i, (y, p) in enumerate(requests):
            b = copies * i
            if r.status[b] != engine.OK or (dp and r.status[b + 1] != engine.OK):
                bad = r.status[b] if r.status[b] != engine.OK else r.status[b + 1]
                raise MapError(f"revolution map at {self._where(p)}: {engine.STATUS_TEXT[int(bad)]}")
            J = r.J[b]
            if not (np.all(np.isfinite(r.X1[b])) and np.all(np.isfinite(J))):
                raise MapError(f"revolution map not finite at {self._where(p)}")
            jy = J / self.s[:, None] * self.s[None, :]
            jp = None
            if dp:
                if parameter is not None:
                    cols = [r.Jp[b + k] / self.s / max(abs(float(p[k])), 0.01) for k in (0, 1)]
                else:
                    cols = [self._central(y, p, k, period) for k in (0, 1)]
                jp = np.column_stack(cols)
                if not np.all(np.isfinite(jp)):
                    raise MapError(f"dP/dp not finite at {self._where(p)}")
            if len(self._orbits) > 32:
                self._orbits.clear()
            self._orbits[(y.tobytes(), p.tobytes(), period)] = (
                orbit_peak(r.y[b, :, V_MID]), r.states[b] / self.s, r.y[b, idx, V_MID])
            out.append((r.X1[b] / self.s, jy, jp))
        return out

    def _central(self, y, p, k, period):
        """dP^k/dp_k by a central difference of two marches (a family switches within the step)."""
        h = self._step(p, k)
        b2 = self._batch([self._moved(p, k, -1.0), self._moved(p, k, 1.0)])
        X = np.repeat((y * self.s)[None], 2, axis=0)
        res = engine.march_state(b2, period * self.spr, X, parallel=False)
        for st in res.status:
            if st != engine.OK:
                raise MapError(f"march for dP/d{self.names[k]} at {self._where(p)}: {engine.STATUS_TEXT[int(st)]}")
        Xh = engine.join_state(res, self.generalized)
        return (Xh[1] - Xh[0]) / (2 * h) / self.s

    def orbit(self, y, p, period=1):
        y, p = np.asarray(y, dtype=float), np.asarray(p, dtype=float)
        known = self._orbits.get((y.tobytes(), p.tobytes(), period))
        if known is not None:
            return known
        X = y * self.s
        res = engine.march_state(self._batch([self.case_at(p)]), period * self.spr, X[None], keep_history=True,
                                 parallel=False)
        if res.status[0] != engine.OK:
            raise MapError(f"march at {self._where(p)} failed: {engine.STATUS_TEXT[int(res.status[0])]}")
        idx = np.arange(period + 1) * self.spr
        states = engine.join_state(res, self.generalized, idx) / self.s
        return orbit_peak(res.y[0, :, V_MID]), states, res.y[0, idx, V_MID]

    def multipliers(self, jx):
        """By decreasing modulus; for generalized-alpha the 2N largest (its map on (d, v, a) has N
        algorithmic roots besides the mechanism's: crankgen.discrete.time_scheme)."""
        mu = super().multipliers(jx)
        return mu[:2 * self.N] if self.generalized else mu

    def physical(self, y):
        return np.asarray(y, dtype=float) * self.s
