"""Pseudo-arclength continuation of the fixed points of P^k for a map x -> P(x, p) (maps.Map).

Unknown z = (x, p); metric <a, b> = sum_i w_i a_x,i b_x,i + a_p b_p, w_i = 1/dim or the map's weights
(maps.state_weights).  A step predicts z + ds t along the unit tangent t (plus a curvature term:
_predict) and corrects on
    P^k(x, p) - x = 0,   <t, z - z_pred> = 0
(bordered Jacobian [[dP/dx - I, dP/dp], [w t_x, t_p]]) with one of two correctors:
- "broyden" (default): quasi-Newton from the Jacobians of the accepted point the step starts from
  (or of the prediction where there is none), with Broyden's rank-one update after each iteration,
  which evaluates P^k alone (for the mechanism a march, several times cheaper than P^k with its
  Jacobians); the Jacobians are refreshed at the iterate when an iteration contracts less than
  REFRESH_RATE-fold, and evaluated at the converged point (its tangent, multipliers and test
  functions are those of the exact Jacobians there): at the iterate expected to be the last, or
  once more after it converged;
- "newton": the Jacobians at every iterate (the former corrector, kept as a baseline).
Both accept a point on the same residual test, so they find the same points to within the
tolerance, and the special points, located on the exact Jacobians, to within the location's.
The step grows after easy corrections, shrinks after hard ones and is halved on failure or on a
sharp turn of the tangent (backtracking) down to ds_min; no step changes p by more than dp_max.
The tangent solves [[dP/dx - I, dP/dp], [t_old]] t = (0, 1), which keeps its orientation through
folds.  A branch ends on the ends of the parameter range (its last point exactly there), after
max_points, or when the step falls below ds_min (the reason is kept in Branch.stop_reason).

Test functions between consecutive points (each is located by the Illinois false-position method on
the arclength from the earlier point, to ~1e-9 in the test function, or, once it is below 1e-6, until
STALLED iterations in a row fail to halve its smallest value: its noise floor, set by the
corrector's tolerance, is reached):
- fold: the branch turns (t_p, the tangent's parameter component, changes sign between two points,
  or p's direction reverses at a point: a sign change outside the interval) and det(dP/dx - I)
  changes sign across the bracket (a real multiplier through +1); located on the latter, or on t_p,
  along the bracket's first tangent or, where both fail (a sharp turn), along its chord;
- period-doubling: (mu_c + 1) times the sign of prod(mu + 1) over the others, mu_c the real
  multiplier nearest -1 (det(dP/dx + I) changes sign);
- Neimark-Sacker: the parity of the number of complex multipliers outside the unit circle changes;
  located on |mu_c| - 1, mu_c the complex multiplier nearest the circle (two real multipliers that
  meet outside the circle also change the count: no sign change of |mu_c| - 1, not reported).
A special point is reported only when its critical multiplier is within 1e-4 of +1, -1 or the
circle after location (typically 1e-9).
At a period doubling of P^k the branch of P^2k starts from x* + h e (e the critical eigenvector,
<e, e> = 1) with the constraint <(e, 0), z - z_pred> = 0, and is continued away from x*.  A period-2k
branch that folds back onto the period-k branch (x and P^k(x) closer than h/4) ends there.  Near
its start such a branch can be flat in p to the map's precision (its p - p* ~ c a^2 with c tiny), so
folds are not sought while both points lie within 1e-6 (1 + |p*|) of the period doubling.
"""

import math
from dataclasses import dataclass

import numpy as np

from ..blas import single_thread
from .diagram import BifurcationDiagram, Branch, SpecialPoint
from .false_position import FalsePosition
from .maps import MapError, state_weights
from ...errors import CrankgenError, NoResultError, ParameterError

KINDS = ("fold", "period-doubling", "neimark-sacker")
CORRECTORS = ("broyden", "newton")
PREDICTORS = ("quadratic", "tangent")
STALLED = 4              # location iterations without halving |test function| (its noise floor) ...
NOISE = 1e3              # ... once it is below NOISE locate_tol
REFRESH_RATE = 0.5       # "broyden": refresh the Jacobians when |residual| falls less than this
# iterations of an easy (the step grows) and of a hard correction (the step shrinks), per corrector
EASY, HARD = {"broyden": 4, "newton": 2}, {"broyden": 8, "newton": 5}


@dataclass
class Settings:
    """Step control and tolerances (the metric is <a, b> = w a_x . b_x + a_p b_p: module docstring)."""

    ds: float = 0.01             # first step
    ds_min: float = 1e-5         # smallest step before the branch is given up
    ds_max: float = 0.05         # largest step
    max_points: int = 500        # per branch
    tol: float = 1e-9            # max |P^k(x) - x| / (1 + max |x|) of a converged point
    max_newton: int = 8          # corrector iterations ("newton")
    corrector: str = "broyden"   # or "newton" (module docstring)
    max_broyden: int = 16        # corrector iterations ("broyden")
    predictor: str = "quadratic"  # or "tangent" (_predict)
    max_turn: float = 0.5        # largest angle (rad) between consecutive tangents
    max_period: int = 4          # switch at period doublings up to this period
    switch_step: float = 0.02    # h of the branch switch, in the metric
    locate_tol: float = 1e-9     # |test function| at a located special point
    max_jump: float = 10.0       # largest corrector distance from the prediction, in steps ds
    dp_max: float = math.inf     # largest parameter change per step

    def check(self):
        for name in ("ds", "ds_min", "ds_max", "tol", "max_turn", "switch_step", "locate_tol", "max_jump", "dp_max"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and v > 0 and (math.isfinite(v) or name == "dp_max")):
                raise ParameterError(f"{name} must be a positive number, got {v!r}")
        if self.ds_min > self.ds or self.ds > self.ds_max:
            raise ParameterError(f"the steps must satisfy ds_min <= ds <= ds_max, got "
                                 f"{self.ds_min:g}, {self.ds:g}, {self.ds_max:g}")
        if self.predictor not in PREDICTORS:
            raise ParameterError(f"predictor must be one of {', '.join(PREDICTORS)}, got {self.predictor!r}")
        if self.corrector not in CORRECTORS:
            raise ParameterError(f"corrector must be one of {', '.join(CORRECTORS)}, got {self.corrector!r}")
        for name, low in (("max_points", 2), ("max_newton", 1), ("max_period", 1), ("max_broyden", 1)):
            v = getattr(self, name)
            if not isinstance(v, int) or isinstance(v, bool) or v < low:
                raise ParameterError(f"{name} must be an integer >= {low}, got {v!r}")
        return self


class _Point:
    __slots__ = ("z", "jx", "jp", "_mu", "t", "iterations", "amplitude", "orbit", "section")

    def __init__(self, z, jx, jp, iterations):
        self.z, self.jx, self.jp, self.iterations = z, jx, jp, iterations
        self._mu = None
        self.t = None
        self.amplitude = math.nan
        self.orbit = None
        self.section = None

    @property
    def mu(self):
        """Multipliers (eigenvalues of dP^k/dx) by decreasing modulus, computed when first asked."""
        if self._mu is None:
            mu = np.linalg.eigvals(self.jx)
            self._mu = mu[np.argsort(-np.abs(mu), kind="stable")]
        return self._mu

    @property
    def p(self):
        return float(self.z[-1])

    @property
    def x(self):
        return self.z[:-1]


class _Failed(Exception):
    pass


class Continuer:
    """Continuation of one map over [p_lo, p_hi]; builds a BifurcationDiagram."""

    def __init__(self, fmap, p_lo, p_hi, settings=None, log=None):
        self.map = fmap
        self.s = (settings or Settings()).check()
        self.lo, self.hi = min(p_lo, p_hi), max(p_lo, p_hi)
        weights = state_weights(fmap)    # per state component, or 1/dim each (maps.state_weights)
        self.w = 1.0 / fmap.dim if weights is None else weights
        self.log = log or (lambda text: None)
        self.evaluations = 0         # of P^k with its Jacobians
        self.values = 0              # of P^k alone

    # -- linear algebra ------------------------------------------------------------------------
    def _dot(self, a, b):
        if np.ndim(self.w):
            return float(np.dot(self.w * a[:-1], b[:-1])) + float(a[-1] * b[-1])
        return self.w * float(np.dot(a[:-1], b[:-1])) + float(a[-1] * b[-1])

    def _bordered(self, jx, jp, row):
        n = self.map.dim
        A = np.empty((n + 1, n + 1))
        A[:n, :n] = jx - np.eye(n)
        A[:n, n] = jp
        A[n, :n] = self.w * row[:-1]
        A[n, n] = row[-1]
        return A

    def _tangent(self, pt, t_old):
        rhs = np.zeros(self.map.dim + 1)
        rhs[-1] = 1.0
        t = np.linalg.solve(self._bordered(pt.jx, pt.jp, t_old), rhs)
        return t / math.sqrt(self._dot(t, t))

    # -- corrector -----------------------------------------------------------------------------
    def correct(self, z_pred, t, period, max_jump=math.inf, near=None):
        """Correct z_pred onto the branch (P^k(x) - x = 0, <t, z - z_pred> = 0); a converged
        _Point or _Failed.  near: Jacobians (dP/dx, dP/dp) near z_pred (those of an accepted point
        close by, or their extrapolation: _predict), which start the "broyden" corrector (without
        them it starts from the Jacobians at z_pred)."""
        if self.s.corrector == "newton":
            return self._newton(z_pred, t, period, max_jump)
        return self._broyden(z_pred, t, period, max_jump, near)

    def _evaluate(self, z, period, jacobians=True):
        try:
            if jacobians:
                out = self.map.evaluate(z[:-1], z[-1], period)
                self.evaluations += 1
            else:
                out = self.map.value(z[:-1], z[-1], period)
                self.values += 1
        except (MapError, CrankgenError, np.linalg.LinAlgError) as exc:
            raise _Failed(str(exc))
        return out

    def _residual(self, z, P, best):
        r = P - z[:-1]
        res = float(np.max(np.abs(r))) / (1.0 + float(np.max(np.abs(z[:-1]))))
        if not math.isfinite(res) or res > 1e3 * min(best, 1.0):
            raise _Failed(f"corrector diverged (residual {res:.3g})")
        return r, res

    def _check_jump(self, z, z_pred, max_jump):
        d = z - z_pred
        dist = math.sqrt(max(self._dot(d, d), 0.0))
        if dist > max_jump:
            raise _Failed(f"corrector left the neighbourhood of the prediction ({dist:.3g} > {max_jump:.3g})")

    def _broyden(self, z_pred, t, period, max_jump, near):
        z = np.array(z_pred, dtype=float)
        A = None if near is None else self._bordered(near[0], near[1], t)
        fresh = A is None                   # evaluate the Jacobians at this iterate
        best = math.inf
        F_old = dz = None
        res_old = math.inf
        for it in range(self.s.max_broyden + 1):
            if fresh:
                P, jx, jp = self._evaluate(z, period)
            else:
                P = self._evaluate(z, period, jacobians=False)
            r, res = self._residual(z, P, best)
            best = min(best, res)
            F = np.append(r, self._dot(t, z - z_pred))
            if res < self.s.tol and it > 0 or res < 0.01 * self.s.tol:
                if not fresh:
                    P, jx, jp = self._evaluate(z, period)
                return _Point(z.copy(), jx, jp, it)
            if it == self.s.max_broyden:
                break
            if fresh:
                A = self._bordered(jx, jp, t)
                fresh = False
            elif dz is not None:
                # Broyden's update: A dz = F - F_old afterwards, A unchanged orthogonally to dz
                A += np.outer(F - F_old - A @ dz, dz / float(dz @ dz))
            try:
                dz = np.linalg.solve(A, -F)
            except np.linalg.LinAlgError:
                raise _Failed("singular bordered Jacobian")
            # the next iterate gets its own Jacobians after a slow contraction, and when it is
            # likely the last (the superlinear estimate res^2 / res_old of its residual is far
            # below tol): they are needed there anyway, and P^k comes with them
            fresh = it > 0 and (res > REFRESH_RATE * res_old or res * res < 0.1 * self.s.tol * res_old)
            F_old, res_old = F, res
            z = z + dz
            self._check_jump(z, z_pred, max_jump)
        raise _Failed(f"corrector did not converge in {self.s.max_broyden} iterations "
                      f"(residual {res:.3g})")

    def _newton(self, z_pred, t, period, max_jump):
        """Newton on P^k(x) - x = 0, <t, z - z_pred> = 0 from z_pred, the Jacobians at every iterate."""
        z = np.array(z_pred, dtype=float)
        best = math.inf
        for it in range(self.s.max_newton + 1):
            P, jx, jp = self._evaluate(z, period)
            r, res = self._residual(z, P, best)
            best = min(best, res)
            pt = _Point(z.copy(), jx, jp, it)
            if res < self.s.tol and it > 0 or res < 0.01 * self.s.tol:
                return pt
            if it == self.s.max_newton:
                break
            A = self._bordered(jx, jp, t)
            rhs = -np.append(r, self._dot(t, z - z_pred))
            try:
                dz = np.linalg.solve(A, rhs)
            except np.linalg.LinAlgError:
                raise _Failed("singular bordered Jacobian")
            z = z + dz
            if it > 0 and np.max(np.abs(dz[:-1])) < self.s.tol * (1.0 + np.max(np.abs(z[:-1]))) \
                    and abs(dz[-1]) < self.s.tol * (1.0 + abs(z[-1])):
                # quadratic convergence: the last update is below tol, so z is converged far
                # below it; keep the Jacobians of the previous iterate (O(|dz|) away)
                pt.z = z.copy()
                return pt
            self._check_jump(z, z_pred, max_jump)
        raise _Failed(f"corrector did not converge in {self.s.max_newton} iterations "
                      f"(residual {res:.3g})")

    def _predict(self, points, ds):
        """The prediction ds along the branch from its last point, and Jacobians there (those of
        the last point).  The "quadratic" predictor adds half ds^2 times the curvature, the change
        of the tangent from the point before over their distance h, and extrapolates the
        Jacobians linearly from those two points (when h is not much shorter than ds)."""
        prev = points[-1]
        z = prev.z + ds * prev.t
        near = (prev.jx, prev.jp)
        if self.s.predictor == "quadratic" and len(points) > 1:
            before = points[-2]
            d = prev.z - before.z
            h = math.sqrt(max(self._dot(d, d), 0.0))
            if h > 0.25 * ds:
                z = z + (0.5 * ds * ds / h) * (prev.t - before.t)
                f = ds / h
                near = (prev.jx + f * (prev.jx - before.jx), prev.jp + f * (prev.jp - before.jp))
        return z, near

    def _finish(self, pt, period):
        """Amplitude and orbit states of an accepted point."""
        try:
            pt.amplitude, pt.orbit, pt.section = self.map.orbit(pt.x, pt.p, period)
        except (MapError, CrankgenError) as exc:
            raise _Failed(str(exc))
        return pt

    # -- test functions ------------------------------------------------------------------------
    @staticmethod
    def _real_crossing(mu, target):
        """(mu_c - target) * sign(prod over the others of (mu - target)), mu_c the real multiplier
        nearest target: continuous, with the sign of det(J - target I)."""
        tiny = 1e-10
        real = np.flatnonzero(np.abs(mu.imag) <= tiny * np.maximum(1.0, np.abs(mu)))
        vals = mu - target
        if real.size == 0:
            return float(np.sign(np.prod(vals).real) or 1.0)
        c = real[np.argmin(np.abs(vals[real]))]
        sign = np.sign(np.prod(np.delete(vals, c)).real) or 1.0
        return float(vals[c].real * sign)

    def _test(self, kind, pt, locate=False):
        mu = pt.mu
        if kind == "fold":
            return self._real_crossing(mu, 1.0) if locate else float(pt.t[-1])
        if kind == "period-doubling":
            return self._real_crossing(mu, -1.0)
        # neimark-sacker: detection by the parity of the number of complex multipliers outside the
        # unit circle, location on |mu_c| - 1, mu_c the complex multiplier nearest the circle
        cpx = mu[(np.abs(mu.imag) > 1e-8 * np.abs(mu)) & (np.abs(mu) > 1e-6)]
        if locate:
            return float(abs(cpx[np.argmin(np.abs(np.abs(cpx) - 1.0))]) - 1.0) if cpx.size else 1.0
        return float((-1.0) ** (np.sum(np.abs(cpx) > 1.0) // 2))

    @staticmethod
    def critical(kind, pt):
        """The critical multiplier of a located special point."""
        mu = pt.mu
        if kind == "fold":
            return complex(mu[np.argmin(np.abs(mu - 1.0))])
        if kind == "period-doubling":
            return complex(mu[np.argmin(np.abs(mu + 1.0))])
        upper = mu[mu.imag > 0]
        return complex(upper[np.argmin(np.abs(np.abs(upper) - 1.0))]) if upper.size else complex(mu[0])

    def _locate(self, kind, a, b, period):
        """Special point between accepted points a and b (b corrected from a along a.t).  A fold
        is located on det(dP/dx - I), or on t_p where that fails; where both fail along a.t (a sharp
        turn: the hyperplanes normal to a.t miss the branch beyond it), along the chord from a to b
        (its normal hyperplanes cross the branch on either side of the turn)."""
        sp = self._illinois(kind, a, b, period, True)
        if sp is None and kind == "fold":
            sp = self._illinois(kind, a, b, period, False)
        if sp is None and kind == "fold":
            chord = b.z - a.z
            along = chord / math.sqrt(max(self._dot(chord, chord), 1e-300))
            sp = self._illinois(kind, a, b, period, False, along)
            if sp is None:
                sp = self._illinois(kind, a, b, period, True, along)
        if sp is None:
            self.log(f"period {period}: {kind} test changed sign between {self.map.parameter} = "
                     f"{a.p:.6g} and {b.p:.6g}, but no critical multiplier was found there; "
                     f"not reported")
        return sp

    def _oriented(self, kind, pt, locate, along):
        """The test function of pt; a fold's t_p with the tangent oriented along `along`."""
        if kind == "fold" and not locate and along is not None:
            return float(pt.t[-1]) * (1.0 if self._dot(pt.t, along) >= 0.0 else -1.0)
        return self._test(kind, pt, locate)

    def _illinois(self, kind, a, b, period, locate, along=None):
        """Illinois false position for the test function between a and b, on the points corrected
        on hyperplanes normal to `along` (a unit vector in the metric; default a.t) at distances s
        from a along it."""
        d = a.t if along is None else along
        s_b = self._dot(d, b.z - a.z)
        f_a, f_b = self._oriented(kind, a, locate, along), self._oriented(kind, b, locate, along)
        if f_a * f_b >= 0:
            return None
        bracket = FalsePosition(0.0, f_a, s_b, f_b)
        best = a if abs(f_a) < abs(f_b) else b
        jump = self.s.max_jump * abs(s_b)
        stalled = 0
        for _ in range(40):
            s_c = bracket.trial()
            try:
                pt = self.correct(a.z + s_c * d, d, period, max_jump=jump, near=(a.jx, a.jp))
                pt.t = self._tangent(pt, d)
            except (_Failed, np.linalg.LinAlgError):
                s_c = 0.5 * (bracket.s_a + bracket.s_b)
                try:
                    pt = self.correct(a.z + s_c * d, d, period, max_jump=jump, near=(a.jx, a.jp))
                    pt.t = self._tangent(pt, d)
                except (_Failed, np.linalg.LinAlgError):
                    break
            f_c = self._oriented(kind, pt, locate, along)
            f_best = abs(self._oriented(kind, best, locate, along))
            near = f_best < NOISE * self.s.locate_tol
            stalled = stalled + 1 if near and abs(f_c) >= 0.5 * f_best else 0
            if abs(f_c) < f_best:
                best = pt
            if abs(f_c) < self.s.locate_tol or bracket.width < 1e-13 or stalled == STALLED:
                break
            bracket.update(s_c, f_c)
        mu_c = self.critical(kind, best)
        ok = {"fold": abs(mu_c - 1.0), "period-doubling": abs(mu_c + 1.0),
              "neimark-sacker": abs(abs(mu_c) - 1.0)}[kind] < 1e-4
        return self._finish(best, period) if ok else None

    def _fold(self, points, new, period, turned):
        """(a, fold or None) where the branch turns (t_p changes sign from prev = points[-1] to new, or
        p reverses at prev: bracket [before, new]) and det(dP/dx - I) changes sign across it (t_p
        alone is noise where the branch runs flat in p); a: the bracket's first point."""
        prev = points[-1]
        before = points[-2] if len(points) > 1 else None
        if prev.t[-1] * new.t[-1] < 0:
            a = prev
        elif (before is not None and (new.p - prev.p) * (prev.p - before.p) < 0
              and id(before) not in turned and id(prev) not in turned):
            a = before
        else:
            return prev, None
        outer = before if before is not None and id(before) not in turned else prev
        if self._test("fold", outer, True) * self._test("fold", new, True) >= 0 and \
                self._test("fold", a, True) * self._test("fold", new, True) >= 0:
            return a, None
        return a, self._locate("fold", a, new, period)

    # -- one branch ----------------------------------------------------------------------------
    def first_point(self, x0, p0, period=1):
        """Fixed point of P^k at p = p0 from the guess x0 (natural-parameter Newton)."""
        e_p = np.eye(self.map.dim + 1)[-1]
        try:
            return self._finish(self.correct(np.append(x0, p0), e_p, period), period)
        except _Failed as exc:
            raise NoResultError(f"no periodic orbit of period {period} found near the starting "
                                f"state at {self.map.parameter} = {p0:g}: {exc}") from None

    def branch(self, start, t0, period, merge=None):
        """Continue from the accepted point start (tangent oriented like t0); merge: (h, k, p_pd)
        for a period-2k branch born at a period doubling at p_pd, which ends when x and P^k(x) come
        closer than h / 4.  Returns (points, [(kind, point)], stop reason)."""
        s = self.s
        start.t = self._tangent(start, t0)
        points, specials = [start], []
        turned = set()                # ids of the points next to a located fold
        ds = s.ds
        e_p = np.eye(self.map.dim + 1)[-1]
        reason = f"{s.max_points} points (max_points)"
        while len(points) < s.max_points:
            prev = points[-1]
            ds = min(ds, s.dp_max / max(abs(prev.t[-1]), 1e-300))
            try:
                z_pred, near = self._predict(points, ds)
                new = self.correct(z_pred, prev.t, period, max_jump=self.s.max_jump * ds, near=near)
                new.t = self._tangent(new, prev.t)
                if self._dot(new.t, prev.t) < math.cos(s.max_turn):
                    raise _Failed("tangent turned too sharply")
                at_end = None
                if not self.lo <= new.p <= self.hi:
                    at_end = self.hi if new.p > self.hi else self.lo
                    frac = (at_end - prev.p) / (new.p - prev.p)
                    guess = prev.z + frac * (new.z - prev.z)
                    guess[-1] = at_end
                    new = self.correct(guess, e_p, period, near=(new.jx, new.jp))
                    new.t = self._tangent(new, prev.t)
                self._finish(new, period)
            except (_Failed, np.linalg.LinAlgError) as exc:
                ds *= 0.5
                if ds < s.ds_min:
                    reason = f"step below ds_min at {self.map.parameter} = {prev.p:.6g} ({exc})"
                    break
                continue
            if merge is not None:
                h, k, _ = merge
                d = np.append(new.orbit[k] - new.orbit[0], 0.0)
                if math.sqrt(self._dot(d, d)) < 0.25 * h:
                    reason = (f"merged into the period-{k} branch at {self.map.parameter} = "
                              f"{new.p:.6g}")
                    break
            found = []
            for kind in KINDS:
                if kind == "fold":
                    if merge is not None and max(abs(prev.p - merge[2]),
                                                 abs(new.p - merge[2])) < 1e-6 * (1 + abs(merge[2])):
                        continue  # flat start of a branch born at a period doubling: see docstring
                    a, sp = self._fold(points, new, period, turned)
                    if sp is not None:
                        turned.add(id(a))
                        turned.add(id(new))
                        found.append((self._dot(a.t, sp.z - a.z) - self._dot(a.t, prev.z - a.z), kind, sp))
                    continue
                fa, fb = self._test(kind, prev), self._test(kind, new)
                if fa * fb < 0:
                    sp = self._locate(kind, prev, new, period)
                    if sp is not None:
                        found.append((self._dot(prev.t, sp.z - prev.z), kind, sp))
            for where, kind, sp in sorted(found, key=lambda f: f[0]):
                if where < 0:                 # a fold before prev (the branch turned at prev)
                    points.insert(len(points) - 1, sp)
                else:
                    points.append(sp)
                specials.append((kind, sp))
                self.log(f"period {period}: {kind} at {self.map.parameter} = {sp.p:.7g}, "
                         f"amplitude {sp.amplitude:.6g}")
            points.append(new)
            if len(points) % 10 == 0:
                self.log(f"period {period}: point {len(points)}, {self.map.parameter} = {new.p:.6g}, "
                         f"amplitude {new.amplitude:.6g}, {'stable' if abs(new.mu[0]) < 1 else 'unstable'}")
            if at_end is not None:
                reason = f"reached {self.map.parameter} = {at_end:g}"
                break
            if new.iterations <= EASY[s.corrector]:
                ds = min(1.5 * ds, s.ds_max)
            elif new.iterations >= HARD[s.corrector]:
                ds = max(0.7 * ds, s.ds_min)
        return points, specials, reason

    def switch(self, pd, period):
        """First point of the period-2k branch born at the period doubling pd of P^k, and the
        tangent that leads away from it."""
        mu, vec = np.linalg.eig(pd.jx)
        c = int(np.argmin(np.abs(mu + 1.0)))
        e = np.real(vec[:, c])
        e = e / math.sqrt(float(np.sum(self.w * (e * e))) if np.ndim(self.w) else self.w * float(e @ e))
        t_e = np.append(e, 0.0)
        h = self.s.switch_step
        for _ in range(4):
            try:
                pt = self.correct(np.append(pd.x + h * e, pd.p), t_e, 2 * period)
                self._finish(pt, 2 * period)
            except _Failed:
                h *= 0.25
                continue
            d = np.append(pt.orbit[period] - pt.orbit[0], 0.0)
            if math.sqrt(self._dot(d, d)) > 0.25 * h:
                return pt, t_e, h
            h *= 4.0
        return None, t_e, h

    def diagram(self, x0, p0, direction):
        """The branch through the fixed point near (x0, p0) in the given direction (+1 or -1), and
        the branches born at its period doublings, recursively up to settings.max_period."""
        with single_thread():
            return self._diagram(x0, p0, direction)

    def _diagram(self, x0, p0, direction):
        t0 = np.zeros(self.map.dim + 1)
        t0[-1] = float(direction)
        first = self.first_point(x0, p0)
        work = [(first, t0, 1, None, "start")]
        branches, specials = [], []
        shown = getattr(self.map, "reported", self.map.dim)   # as the branches report them
        while work:
            start, t_start, period, merge, origin = work.pop(0)
            pts, found, reason = self.branch(start, t_start, period, merge)
            index = len(branches)
            branches.append(self._make_branch(pts, period, origin, reason))
            for kind, sp in found:
                specials.append(SpecialPoint(
                    kind=kind, parameter=sp.p, amplitude=float(sp.amplitude), period=period,
                    branch=index, multiplier=self.critical(kind, sp),
                    state=self.map.physical(sp.x), multipliers=np.array(sp.mu[:shown]),
                    parameter_name=self.map.parameter, range=(self.lo, self.hi)))
                if kind == "period-doubling" and 2 * period <= self.s.max_period:
                    pt, t_e, h = self.switch(sp, period)
                    if pt is None:
                        self.log(f"period {2 * period}: branch switching at "
                                 f"{self.map.parameter} = {sp.p:.6g} failed")
                        continue
                    work.append((pt, t_e, 2 * period, (h, period, sp.p),
                                 f"period-doubling of branch {index} at {self.map.parameter} = {sp.p:.7g}"))
        return BifurcationDiagram(self.map.parameter, branches,
                                  sorted(specials, key=lambda s: (s.period, s.parameter)))

    def _make_branch(self, pts, period, origin, reason):
        shown = getattr(self.map, "reported", self.map.dim)   # a map may hold algorithmic roots
        return Branch(
            period=period, parameter_name=self.map.parameter,
            parameter=np.array([p.p for p in pts]),
            amplitude=np.array([p.amplitude for p in pts]),
            stable=np.array([bool(abs(p.mu[0]) < 1.0) for p in pts]),
            multipliers=np.array([p.mu[:shown] for p in pts]).reshape(len(pts), shown),
            states=np.array([self.map.physical(p.x) for p in pts]).reshape(len(pts), -1),
            section=np.array([p.section[:period] for p in pts]).reshape(len(pts), period),
            origin=origin, stop_reason=reason)


def continue_map(fmap, x0, start, stop, settings=None, log=None):
    """BifurcationDiagram of the map fmap from the fixed point near x0 at p = start towards
    p = stop (the parameter range is [min, max] of the two)."""
    if start == stop:
        raise ParameterError(f"start and stop of the {fmap.parameter} range must differ, got {start:g}")
    c = Continuer(fmap, start, stop, settings, log)
    return c.diagram(np.asarray(x0, dtype=float), float(start), 1.0 if stop > start else -1.0)
