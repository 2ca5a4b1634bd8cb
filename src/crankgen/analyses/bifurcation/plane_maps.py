"""Maps in two parameters, the interface of the two-parameter continuation (codim2.py).

A PlaneMap is x -> P(x, p), p = (p1, p2), whose fixed points of P^k are followed with one defining
condition more (a multiplier at +1, -1 or on the unit circle).  It supplies
- jacobians(requests, period, dp): for each (x, p) of `requests`, (P^k(x, p), dP^k/dx, dP^k/dp)
  with dP^k/dp of shape (dim, 2) (None without dp); a map that can evaluate several requests at once (the mechanism: one
  batch of the engine on every core) does so; the continuation asks for the base point and its
  finite-difference neighbours together;
- orbit(x, p, period): (amplitude, states, section) as maps.Map.orbit;
- multipliers(jx): the multipliers of a Jacobian, by decreasing modulus (the mechanism's
  generalized-alpha map may report fewer than its dimension);
- physical(x): the state in the user's units.
FunctionPlaneMap builds all of this from f(x, p) -> (f, df/dx, df/dp (dim, 2)).
"""

import numpy as np

from .maps import MapError


class PlaneMap:
    """Base class: subclasses define dim, names and jacobians (and may override the rest)."""

    dim = 0
    names = ("p1", "p2")

    def jacobians(self, requests, period=1, dp=True):
        raise NotImplementedError

    def observe(self, x):
        return float(x[0])

    def orbit(self, x, p, period=1):
        states = [np.asarray(x, dtype=float)]
        for _ in range(period):
            states.append(self.jacobians([(states[-1], p)], 1, dp=False)[0][0])
        states = np.array(states)
        section = np.array([self.observe(s) for s in states])
        return float(np.max(np.abs(section[:period]))), states, section

    def multipliers(self, jx):
        mu = np.linalg.eigvals(jx)
        return mu[np.argsort(-np.abs(mu), kind="stable")]

    def physical(self, x):
        return np.asarray(x, dtype=float).copy()


class FunctionPlaneMap(PlaneMap):
    """A map from f(x, p) -> (f, df/dx, df/dp) for one application, p = (p1, p2), df/dp (dim, 2);
    P^k and its Jacobians by the chain rule."""

    def __init__(self, f, dim, names=("p1", "p2"), observable=None):
        self.f, self.dim, self.names = f, int(dim), tuple(names)
        self._obs = observable

    def observe(self, x):
        return float(self._obs(x)) if self._obs is not None else float(x[0])

    def _one(self, x, p, period, dp=True):
        x = np.asarray(x, dtype=float)
        p = np.asarray(p, dtype=float)
        jx = np.eye(self.dim)
        jp = np.zeros((self.dim, 2))
        for _ in range(period):
            fx, fxx, fxp = self.f(x, p)
            fx = np.atleast_1d(np.asarray(fx, dtype=float))
            fxx = np.atleast_2d(np.asarray(fxx, dtype=float))
            fxp = np.asarray(fxp, dtype=float).reshape(self.dim, 2)
            jp = fxx @ jp + fxp
            jx = fxx @ jx
            x = fx
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(jx)) and np.all(np.isfinite(jp))):
            raise MapError(f"the map left the finite numbers at {self.names[0]} = {p[0]:g}, "
                           f"{self.names[1]} = {p[1]:g}")
        return x, jx, (jp if dp else None)

    def jacobians(self, requests, period=1, dp=True):
        return [self._one(x, p, period, dp) for x, p in requests]
