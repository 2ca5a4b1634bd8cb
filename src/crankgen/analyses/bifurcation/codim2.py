"""Two-parameter continuation of fold, period-doubling and Neimark-Sacker points of a PlaneMap, and
the codimension-two points met on the way.

The curve is the solution set of the defining system (defining.py) in Z = (x, q1, q2[, theta]),
followed by pseudo-arclength continuation as the one-parameter core does (core.py): metric
<a, b> = a_x . b_x / (dim X^2) + a_q . b_q + a_theta b_theta (q = p / scale, the parameters in units
of the chart's widths; X = max(1, rms of the start's state), so that the state counts by its
relative change: a slender rod's v* runs to hundreds); a step predicts along the unit tangent and corrects on F(Z) = 0 and
<t, Z - Z_pred> = 0 with Broyden's quasi-Newton method started from the Jacobian of the accepted
point (its defining-system residual needs dP/dx at every iterate, its full Jacobian the
finite-difference neighbours of defining.py only at the start and at the converged point); no
step changes a parameter by more than dq_max of its width.  The tangent solves [[DF], [t_old]] t =
(0, 1).  A curve ends on the edges of the box (its last point exactly there), after max_points, when
the step falls below ds_min, or at a codimension-two point where it cannot go on (a Neimark-Sacker
curve at a 1:1 or 1:2 resonance, where its multipliers leave the circle as a real pair).

Codimension-two points (MatCont's and BifurcationKit's list for maps), by a test function that
changes sign between consecutive points and is located by the Illinois false-position method (false_position.py) on the
arclength, as the one-parameter core locates its points:
- on a fold curve: cusp "CP" (the fold's quadratic coefficient w^T B(v, v), defining.py, through 0:
  the two folds of a hysteresis loop meet and the loop vanishes), 1:1 resonance "R1" (a second
  multiplier through +1), fold-flip "LPPD" (a multiplier through -1), fold-Neimark-Sacker "LPNS"
  (a complex pair through the unit circle);
- on a period-doubling curve: 1:2 resonance "R2" (a second multiplier through -1), fold-flip
  "LPPD" (a multiplier through +1), flip-Neimark-Sacker "PDNS";
- on a Neimark-Sacker curve: 1:1 "R1" (theta through 0), 1:2 "R2" (theta through pi), 1:3 "R3"
  and 1:4 "R4" (theta through 2 pi/3, pi/2), "LPNS" and "PDNS" (a real multiplier through +1, -1).
Not detected: the degenerate flip and Chenciner points (they need the third-order normal-form
coefficients) and double Neimark-Sacker points.
"""

import math
from dataclasses import dataclass

import numpy as np

from .defining import Defining
from .false_position import FalsePosition
from .maps import MapError, state_weights
from ...errors import CrankgenError, NoResultError, ParameterError

CODIM2 = {
    "cusp": ("CP", "two folds meet and the hysteresis between them vanishes"),
    "1:1 resonance": ("R1", "a second multiplier at +1 (Bogdanov-Takens point of the map)"),
    "fold-flip": ("LPPD", "a fold meets a period doubling: multipliers +1 and -1"),
    "fold-neimark-sacker": ("LPNS", "a fold meets a Neimark-Sacker point: +1 and a pair on the circle"),
    "1:2 resonance": ("R2", "two multipliers at -1"),
    "flip-neimark-sacker": ("PDNS", "a period doubling meets a Neimark-Sacker point"),
    "1:3 resonance": ("R3", "the Neimark-Sacker pair at exp(+-2 pi i / 3)"),
    "1:4 resonance": ("R4", "the Neimark-Sacker pair at +-i"),
}
TESTS = {"fold": ("cusp", "1:1 resonance", "fold-flip", "fold-neimark-sacker"),
         "period-doubling": ("1:2 resonance", "fold-flip", "flip-neimark-sacker"),
         "neimark-sacker": ("1:1 resonance", "1:2 resonance", "1:3 resonance", "1:4 resonance",
                            "fold-neimark-sacker", "flip-neimark-sacker")}
ENDS = {("neimark-sacker", "1:1 resonance"), ("neimark-sacker", "1:2 resonance")}
REFRESH_RATE = 0.5            # refresh the Jacobian when |F| falls less than this in an iteration
EASY, HARD = 4, 7             # corrector iterations after which the step grows, shrinks
MULTIPLIER_MATCH = 1e-4       # a located resonance's multiplier within this of its target


@dataclass
class CurveSettings:
    """Step control and tolerances of a two-parameter continuation (metric: module docstring)."""

    ds: float = 0.02             # first step
    ds_min: float = 1e-5         # smallest step before the curve is given up
    ds_max: float = 0.25         # largest step
    dq_max: float = 0.02         # largest change of a parameter per step, in units of its width
    max_points: int = 300        # per direction
    tol: float = 1e-9            # |F| / (1 + max |x|) of a converged point
    max_iter: int = 12           # corrector iterations
    max_turn: float = 0.5        # largest angle (rad) between consecutive tangents
    fd_step: float = 1e-5        # relative step of the second derivatives (defining.py)
    max_jump: float = 10.0       # largest corrector distance from the prediction, in steps ds

    def check(self):
        for name in ("ds", "ds_min", "ds_max", "dq_max", "tol", "max_turn", "fd_step", "max_jump"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (v > 0 and math.isfinite(v)):
                raise ParameterError(f"{name} must be a positive number, got {v!r}")
        if not self.ds_min <= self.ds <= self.ds_max:
            raise ParameterError(f"the steps must satisfy ds_min <= ds <= ds_max, got "
                                 f"{self.ds_min:g}, {self.ds:g}, {self.ds_max:g}")
        for name, low in (("max_points", 2), ("max_iter", 1)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < low:
                raise ParameterError(f"{name} must be an integer >= {low}, got {v!r}")
        return self


class _Failed(Exception):
    pass


class CurvePoint:
    """An accepted point: Z, its Evaluation ev (with DF), tangent t, corrector iterations, the
    orbit's amplitude and section samples, and its test functions (cached)."""

    __slots__ = ("Z", "ev", "t", "iterations", "amplitude", "section", "_tests")

    def __init__(self, ev, iterations):
        self.Z, self.ev, self.iterations = ev.Z, ev, iterations
        self.t = None
        self.amplitude = math.nan
        self.section = None
        self._tests = {}


def _real_crossing(mu, target):
    """(mu_c - target) * sign(prod over the others of (mu - target)), mu_c the real multiplier
    nearest target: continuous, with the sign of prod(mu - target) (core.Continuer._real_crossing)."""
    if mu.size == 0:
        return 1.0
    real = np.flatnonzero(np.abs(mu.imag) <= 1e-10 * np.maximum(1.0, np.abs(mu)))
    vals = mu - target
    if real.size == 0:
        return float(np.sign(np.prod(vals).real) or 1.0)
    c = real[np.argmin(np.abs(vals[real]))]
    return float(vals[c].real * (np.sign(np.prod(np.delete(vals, c)).real) or 1.0))


def _circle(mu, locate):
    """Detection: the parity of the complex multipliers outside the unit circle; location:
    |mu_c| - 1 of the complex multiplier nearest the circle (core.Continuer._test)."""
    cpx = mu[(np.abs(mu.imag) > 1e-8 * np.abs(mu)) & (np.abs(mu) > 1e-6)]
    if locate:
        return float(abs(cpx[np.argmin(np.abs(np.abs(cpx) - 1.0))]) - 1.0) if cpx.size else 1.0
    return float((-1.0) ** (np.sum(np.abs(cpx) > 1.0) // 2))


class CurveContinuer:
    """Continuation of one defining system inside the box lo <= p <= hi (both parameters)."""

    def __init__(self, defining: Defining, lo, hi, settings=None, log=None):
        self.d = defining
        self.s = (settings or CurveSettings()).check()
        self.lo = np.asarray(lo, dtype=float)
        self.hi = np.asarray(hi, dtype=float)
        n = defining.n
        self.W = np.ones(defining.size)
        weights = state_weights(defining.map)       # the map's (maps.state_weights), or 1/n each
        self.W[:n] = 1.0 / n if weights is None else weights
        self.log = log or (lambda text: None)
        self.names = defining.map.names

    # -- linear algebra ---------------------------------------------------------------------------
    def _dot(self, a, b):
        return float(np.sum(self.W * a * b))

    def _norm(self, a):
        return math.sqrt(max(self._dot(a, a), 0.0))

    def _system(self, DF, row):
        return np.vstack([DF, row[None]])

    def tangent(self, DF, t_old):
        rhs = np.zeros(self.d.size)
        rhs[-1] = 1.0
        try:
            t = np.linalg.solve(self._system(DF, self.W * t_old), rhs)
        except np.linalg.LinAlgError:
            raise _Failed("singular Jacobian of the defining system (tangent)")
        return t / self._norm(t)

    def _residual(self, ev):
        n = self.d.n
        fx = float(np.max(np.abs(ev.F[:n]))) / (1.0 + float(np.max(np.abs(ev.Z[:n]))))
        return max(fx, float(np.max(np.abs(ev.F[n:]))))

    def _evaluate(self, Z, jacobian):
        try:
            return self.d.evaluate(Z, jacobian)
        except (MapError, CrankgenError, np.linalg.LinAlgError, FloatingPointError) as exc:
            raise _Failed(str(exc))

    # -- corrector --------------------------------------------------------------------------------
    def correct(self, Z_pred, row, DF=None, max_jump=math.inf):
        """Correct Z_pred onto the curve with the extra equation row . (Z - Z_pred) = 0 (row: the
        weighted tangent, or a unit vector fixing one unknown); DF: the Jacobian to start from.
        Returns the converged CurvePoint (its full Jacobian evaluated there) or raises _Failed."""
        Z = np.array(Z_pred, dtype=float)
        fresh = DF is None
        best, res_old = math.inf, math.inf
        F_old = dz = None
        for it in range(self.s.max_iter + 1):
            ev = self._evaluate(Z, fresh)
            res = self._residual(ev)
            if not math.isfinite(res) or res > 1e3 * min(best, 1.0):
                raise _Failed(f"corrector diverged (residual {res:.3g})")
            best = min(best, res)
            if fresh:
                DF = ev.DF
            elif F_old is not None:
                y = ev.F - F_old
                DF = DF + np.outer(y - DF @ dz, dz) / float(dz @ dz)
            if res < self.s.tol:
                if ev.DF is None:
                    ev = self._evaluate(Z, True)
                    if self._residual(ev) >= 10 * self.s.tol:
                        raise _Failed("the converged point moved on re-evaluation")
                return CurvePoint(ev, it)
            if it == self.s.max_iter:
                break
            fresh = (not fresh) and res > REFRESH_RATE * res_old
            if fresh:
                ev = self._evaluate(Z, True)
                DF = ev.DF
            res_old, F_old = res, ev.F
            try:
                dz = np.linalg.solve(self._system(DF, row), -np.append(ev.F, row @ (Z - Z_pred)))
            except np.linalg.LinAlgError:
                raise _Failed("singular Jacobian of the defining system")
            Z = Z + dz
            if self._norm(Z - Z_pred) > max_jump:
                raise _Failed("corrector left the neighbourhood of the prediction")
        raise _Failed(f"corrector did not converge in {self.s.max_iter} iterations (residual {res:.3g})")

    def _finish(self, pt):
        d = self.d
        try:
            pt.amplitude, _, section = d.map.orbit(d.x(pt.Z), d.p(pt.Z), d.period)
        except (MapError, CrankgenError) as exc:
            raise _Failed(str(exc))
        pt.section = np.asarray(section[:d.period], dtype=float)
        return pt

    # -- test functions ---------------------------------------------------------------------------
    def _others(self, pt):
        """The multipliers of a point less its critical one(s)."""
        mu = pt.ev.mu
        kind = self.d.kind
        if kind == "fold":
            return np.delete(mu, np.argmin(np.abs(mu - 1.0)))
        if kind == "period-doubling":
            return np.delete(mu, np.argmin(np.abs(mu + 1.0)))
        lam = np.exp(1j * pt.Z[-1])
        a = int(np.argmin(np.abs(mu - lam)))
        rest = np.delete(mu, a)
        return np.delete(rest, np.argmin(np.abs(rest - np.conj(lam))))

    def test(self, name, pt, locate=False):
        key = (name, locate)
        if key not in pt._tests:
            pt._tests[key] = self._test(name, pt, locate)
        return pt._tests[key]

    def _test(self, name, pt, locate):
        kind = self.d.kind
        if name == "cusp":
            return self.d.normal_form_fold(pt.ev)
        if kind == "neimark-sacker" and name in ("1:1 resonance", "1:2 resonance", "1:3 resonance",
                                                 "1:4 resonance"):
            target = {"1:1 resonance": 0.0, "1:2 resonance": math.pi, "1:3 resonance": 2 * math.pi / 3,
                      "1:4 resonance": math.pi / 2}[name]
            return float(pt.Z[-1]) - target
        if name == "1:1 resonance":
            return _real_crossing(self._others(pt), 1.0)
        if name == "1:2 resonance":
            return _real_crossing(self._others(pt), -1.0)
        if name == "fold-flip":
            return _real_crossing(self._others(pt), 1.0 if kind == "period-doubling" else -1.0)
        if name == "fold-neimark-sacker" and kind == "neimark-sacker":
            return _real_crossing(self._others(pt), 1.0)
        if name == "flip-neimark-sacker" and kind == "neimark-sacker":
            return _real_crossing(self._others(pt), -1.0)
        return _circle(self._others(pt), locate)

    def _two_valued(self, name):
        return name in ("fold-neimark-sacker", "flip-neimark-sacker") and self.d.kind != "neimark-sacker"

    def _accept(self, name, pt, f0):
        """Is the located point a codimension-two point (not noise)?"""
        mu = self._others(pt)
        kind = self.d.kind
        if name == "cusp":
            return abs(self.test(name, pt)) < 1e-2 * max(abs(f0), 1e-12)
        if kind == "neimark-sacker" and name.endswith("resonance"):
            return abs(self.test(name, pt)) < 1e-3
        if name in ("fold-neimark-sacker", "flip-neimark-sacker") and kind != "neimark-sacker":
            return abs(self.test(name, pt, True)) < MULTIPLIER_MATCH
        target = {"1:1 resonance": 1.0, "1:2 resonance": -1.0, "fold-flip": 1.0 if kind == "period-doubling" else -1.0,
                  "fold-neimark-sacker": 1.0, "flip-neimark-sacker": -1.0}[name]
        return mu.size > 0 and float(np.min(np.abs(mu - target))) < MULTIPLIER_MATCH

    def locate(self, name, a, b):
        """The codimension-two point `name` between accepted points a and b, or None."""
        locate = self._two_valued(name)
        s_b = self._dot(a.t, b.Z - a.Z)
        f_a, f_b = self.test(name, a, locate), self.test(name, b, locate)
        if f_a * f_b >= 0:
            return None
        f0 = max(abs(f_a), abs(f_b))
        bracket = FalsePosition(0.0, f_a, s_b, f_b)
        best = a if abs(f_a) < abs(f_b) else b
        row = self.W * a.t
        for _ in range(30):
            s_c = bracket.trial()
            try:
                pt = self.correct(a.Z + s_c * a.t, row, a.ev.DF, self.s.max_jump * abs(bracket.s_b))
            except _Failed:
                break
            pt.t = a.t
            f_c = self.test(name, pt, locate)
            if abs(f_c) < abs(self.test(name, best, locate)):
                best = pt
            if abs(f_c) < 1e-9 * max(f0, 1.0) or bracket.width < 1e-12:
                break
            bracket.update(s_c, f_c)
        if best is a or best is b or not self._accept(name, best, f0):
            self.log(f"{self.d.kind} curve: the {name} test changed sign near {self._where(b)} but "
                     f"no {name} point was found there; not reported")
            return None
        try:
            best.t = self.tangent(best.ev.DF, a.t)
            return self._finish(best)
        except _Failed:
            return None

    # -- one direction ----------------------------------------------------------------------------
    def _where(self, pt):
        p = self.d.p(pt.Z)
        return f"{self.names[0]} = {p[0]:.6g}, {self.names[1]} = {p[1]:.6g}"

    def _outside(self, Z):
        p = self.d.p(Z)
        return [k for k in range(2) if not self.lo[k] <= p[k] <= self.hi[k]]

    def start(self, x, p, theta=None):
        """The first point: the defining system corrected from (x, p[, theta]) with the second
        parameter held (or the first, where the curve runs along the second), its borders from the
        map's eigenvectors there; its tangent the null vector of the Jacobian."""
        Z = self.d.unknowns(x, p, theta)
        size = max(1.0, float(np.sqrt(np.mean(np.square(x)))))
        self.W[:self.d.n] = 1.0 / (self.d.n * size ** 2)
        try:
            ev = self.d.map.jacobians([(x, p)], self.d.period, dp=False)[0]
            self.d.set_borders(ev[1], theta)
            pt = None
            for k in (1, 0):                # hold the second parameter, else the first
                fixed = np.zeros(self.d.size)
                fixed[self.d.n + k] = 1.0
                try:
                    pt = self.correct(Z, fixed)
                    break
                except _Failed:
                    if k == 0:
                        raise
            # the tangent: the null vector of DF (the curve may run along either parameter)
            t = np.linalg.svd(pt.ev.DF)[2][-1]
            pt.t = t / self._norm(t)
            self._finish(pt)
        except (_Failed, MapError, CrankgenError) as exc:
            raise NoResultError(f"no {self.d.kind} point of period {self.d.period} near "
                                f"{self.names[0]} = {p[0]:.6g}, {self.names[1]} = {p[1]:.6g}: {exc}") from None
        self.d.update_borders(pt.ev)
        return pt

    def run(self, start, direction):
        """Follow the curve from the accepted point start, its second parameter first moving in
        `direction` (+1 or -1).  Returns (points, [(name, point)], stop reason)."""
        s, d = self.s, self.d
        n = d.n
        d.update_borders(start.ev)
        first = start.t * (1.0 if direction * start.t[n + 1] >= 0 else -1.0)
        if abs(start.t[n + 1]) < 1e-12:
            first = start.t * float(direction)
        cur = CurvePoint(start.ev, start.iterations)
        cur.t, cur.amplitude, cur.section, cur._tests = first, start.amplitude, start.section, start._tests
        points, found = [cur], []
        ds = s.ds
        reason = f"{s.max_points} points (max_points)"
        while len(points) < s.max_points:
            prev = points[-1]
            ds = min(ds, s.dq_max / max(float(np.max(np.abs(prev.t[n:n + 2]))), 1e-300))
            at_edge = None
            try:
                new = self.correct(prev.Z + ds * prev.t, self.W * prev.t, prev.ev.DF, s.max_jump * ds)
                new.t = self.tangent(new.ev.DF, prev.t)
                if self._dot(new.t, prev.t) < math.cos(s.max_turn):
                    raise _Failed("tangent turned too sharply")
                out = self._outside(new.Z)
                if out:
                    k = out[0]
                    p_prev, p_new = d.p(prev.Z)[k], d.p(new.Z)[k]
                    edge = self.hi[k] if p_new > self.hi[k] else self.lo[k]
                    frac = (edge - p_prev) / (p_new - p_prev)
                    guess = prev.Z + frac * (new.Z - prev.Z)
                    guess[n + k] = edge / d.scale[k]
                    fixed = np.zeros(d.size)
                    fixed[n + k] = 1.0
                    new = self.correct(guess, fixed, new.ev.DF)
                    new.t = self.tangent(new.ev.DF, prev.t)
                    at_edge = (k, edge)
                self._finish(new)
            except _Failed as exc:
                ds *= 0.5
                if ds < s.ds_min:
                    reason = f"step below ds_min at {self._where(prev)} ({exc})"
                    break
                continue
            hits = []
            for name in TESTS[d.kind]:
                # a two-valued test (the parity of the complex multipliers outside the circle) also
                # changes where two real multipliers meet outside the circle: its located function
                # must change sign as well
                if self.test(name, prev, False) * self.test(name, new, False) < 0 and (
                        not self._two_valued(name) or self.test(name, prev, True) * self.test(name, new, True) < 0):
                    sp = self.locate(name, prev, new)
                    if sp is not None:
                        hits.append((self._dot(prev.t, sp.Z - prev.Z), name, sp))
            stop = None
            for _, name, sp in sorted(hits, key=lambda h: h[0]):
                points.append(sp)
                found.append((name, sp))
                self.log(f"{d.kind} curve: {name} ({CODIM2[name][0]}) at {self._where(sp)}")
                if (d.kind, name) in ENDS:
                    stop = f"{name} ({CODIM2[name][0]}) at {self._where(sp)}: the multipliers leave the circle"
                    break
            if stop is not None:
                reason = stop
                break
            points.append(new)
            d.update_borders(new.ev)
            if len(points) % 10 == 0:
                self.log(f"{d.kind} curve: point {len(points)}, {self._where(new)}, "
                         f"amplitude {new.amplitude:.6g}")
            if at_edge is not None:
                k, edge = at_edge
                reason = f"reached {self.names[k]} = {edge:g}"
                break
            if new.iterations <= EASY:
                ds = min(1.5 * ds, s.ds_max)
            elif new.iterations >= HARD:
                ds = max(0.7 * ds, s.ds_min)
        return points, found, reason
