"""The map interface of the continuation core: x -> P(x, p) with its Jacobians.

Periodic orbits of period k are the fixed points of P^k.  A map supplies
- evaluate(x, p, period, dp): P^period(x, p), its Jacobian dP^period/dx (exact) and, when dp,
  dP^period/dp (exact or by a documented finite difference);
- value(x, p, period): P^period(x, p) alone (the corrector's quasi-Newton iterations);
- orbit(x, p, period): the amplitude of the orbit through x, its states after 0..period
  applications of P and the observable at each of them (its points on the Poincare section);
- iterate(x, p, n): the states after 0..n applications and one observable sample each
  (the Poincare section of the brute-force sweeps);
- physical(x): the state in the user's units (the core may work in scaled coordinates);
- reported (optional): how many multipliers, the largest, a branch reports (the mechanism's map
  under generalized-alpha has algorithmic roots besides the mechanism's: crankgen.discrete.time_scheme);
- weights (optional): the weight of each state component in the continuation's metric (default
  1/dim each; state_weights).  The mechanism's map under generalized-alpha weighs (d, v) as
  Newmark's map does and its algorithmic accelerations not at all: they are slaved to the orbit,
  and their stiff components, large in the scaled units, would otherwise set the step length.
FunctionMap builds all of this from a one-application function f(x, p) -> (f, df/dx, df/dp).
"""

import numpy as np

from ...errors import CrankgenError


def state_weights(fmap):
    """(dim,) weights of the state's components in a continuation's metric, the map's own
    `weights`; None where it has none (1/dim each)."""
    w = getattr(fmap, "weights", None)
    return None if w is None else np.asarray(w, dtype=float)


class MapError(CrankgenError):
    """The map could not be evaluated at this state and parameter (the core backtracks)."""


class Map:
    """Base class; subclasses define dim and evaluate (and may override orbit, iterate)."""

    dim = 0
    parameter = "p"

    def evaluate(self, x, p, period=1, dp=True):
        """(P^period(x, p), dP^period/dx, dP^period/dp or None)."""
        raise NotImplementedError

    def value(self, x, p, period=1):
        """P^period(x, p) alone (maps whose Jacobians cost more than their value override it)."""
        return self.evaluate(x, p, period, dp=False)[0]

    def observe(self, x):
        """Scalar observable of a state (the amplitude is max |observable| over an orbit)."""
        return float(x[0])

    def orbit(self, x, p, period=1):
        """(amplitude, states (period + 1, dim), section samples (period + 1,)) of the orbit."""
        states = [np.asarray(x, dtype=float)]
        for _ in range(period):
            states.append(self.evaluate(states[-1], p, 1, dp=False)[0])
        states = np.array(states)
        section = np.array([self.observe(s) for s in states])
        return float(np.max(np.abs(section[:period]))), states, section

    def iterate(self, x, p, n, jacobian=False):
        """(states (n + 1, dim) after 0..n applications, samples (n + 1,) of the observable,
        Jacobians (n, dim, dim) of each application when jacobian, else None)."""
        x = np.asarray(x, dtype=float)
        states, samples, jacs = [x], [self.observe(x)], []
        for _ in range(n):
            x1, jx, _ = self.evaluate(x, p, 1, dp=False)
            if not np.all(np.isfinite(x1)):
                raise MapError(f"the map left the finite numbers at {self.parameter} = {p:g}")
            x = x1
            states.append(x)
            samples.append(self.observe(x))
            if jacobian:
                jacs.append(jx)
        return np.array(states), np.array(samples), (np.array(jacs) if jacobian else None)

    def physical(self, x):
        return np.asarray(x, dtype=float).copy()


class FunctionMap(Map):
    """A map from f(x, p) -> (f, df/dx, df/dp) for one application (x a 1-D array); P^k and its
    Jacobians by the chain rule."""

    def __init__(self, f, dim, parameter="p", observable=None):
        self.f, self.dim, self.parameter = f, int(dim), parameter
        self._obs = observable

    def observe(self, x):
        return float(self._obs(x)) if self._obs is not None else float(x[0])

    def evaluate(self, x, p, period=1, dp=True):
        x = np.asarray(x, dtype=float)
        jx = np.eye(self.dim)
        jp = np.zeros(self.dim)
        for _ in range(period):
            fx, fxx, fxp = self.f(x, p)
            fx = np.atleast_1d(np.asarray(fx, dtype=float))
            fxx = np.atleast_2d(np.asarray(fxx, dtype=float))
            fxp = np.atleast_1d(np.asarray(fxp, dtype=float))
            jp = fxx @ jp + fxp
            jx = fxx @ jx
            x = fx
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(jx))):
            raise MapError(f"the map left the finite numbers at {self.parameter} = {p:g}")
        return x, jx, (jp if dp else None)
