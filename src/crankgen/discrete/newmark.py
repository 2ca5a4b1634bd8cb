"""Newmark integration (beta = 1/4, gamma = 1/2 by default) of the reduced equations R = 0, or
generalized-alpha (alpha_m, alpha_f non-zero: crankgen.discrete.time_scheme), in the form of Arnold & Bruls:
R = 0 at every step, the step's unknown the acceleration qdd_{n+1}, an algorithmic acceleration
a_n carried beside it (for Newmark a = qdd):
    dp = d_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta abar,  vp = v_n + h (1 - gamma) a_n + h gamma abar,
    abar = (alpha_f qdd_n - alpha_m a_n) / (1 - alpha_m),
    d_{n+1} = dp + cd qdd_{n+1},  v_{n+1} = vp + cv qdd_{n+1},  a_{n+1} = abar + r qdd_{n+1},
    r = (1 - alpha_f) / (1 - alpha_m),  cd = beta r h^2,  cv = gamma r h.

Three schemes (the constants and the decisions of the iteration live in newton.py, shared with the
compiled engine):
- "one-pass": the paper's eqs. (34)-(39): predictors (35)-(36), one linear solve (37) with the
  iteration matrix evaluated at the predictor, correctors (38)-(39) (errata applied).  For the
  `paper` formulation the matrix is the printed M + gamma dt C + beta dt^2 (K_lin + K_non); for
  `lagrange` it is the exact tangent, i.e. a single Newton iteration.
- "full-newton": the same predictors, then Newton iterations on a_{m+1} with the exact tangent,
  refreshed and factorized at every iteration, until the largest displacement increment, in the
  paper's scaled units (u*, v*), is below tol * (1 + largest scaled displacement).
- "newton" (default): the same iteration, but the factorization of the exact tangent from the first
  iteration is reused (each such iteration costs a residual and a back-substitution) while the
  increments contract at least tenfold per iteration (rate theta_k = |delta_k| / |delta_{k-1}|
  <= 0.1); otherwise the tangent is refreshed.  Besides the increment test, the iteration stops when
  the estimated remaining error theta_k / (1 - theta_k) |delta_k| is below 10 % of the tolerance
  (the stopping test of simplified Newton iterations, Hairer & Wanner, Solving ODEs II, sec. IV.8),
  with theta_k taken only from two increments of the same kind (both fresh or both reused): across
  the switch from a fresh to a reused factorization the ratio measures Newton's contraction, not
  the slower one of the reused iterations.  The converged state agrees with "full-newton" far
  within the tolerance (tests check it).
The state is the DOF map's: the rod's nodal co-ordinates, then the co-ordinates a driven motion
declares (a motor's crank angle, ...), whose equations border the band (`_Border`: the same
bordered iteration as the compiled engine, crankgen.engine.coordinates); the scaled increments of
every unknown count in Newton's test, the divergence test reads the nodal ones alone.
Newton starts from the acceleration that puts d_{m+1} on the quartic extrapolation of the last
five displacements (lower order over the first steps, a_m at the first): the displacements are
smooth even where the stiff axial modes make the accelerations oscillate from step to step, and
this guess leaves a first increment of about 1e-4 to 1e-3 scaled units (about 1 when starting from
a_m), so that most steps take one fresh and one or two reused iterations (quartic did better than
cubic and quintic in trials).  The initial acceleration solves eq. (34) exactly (R is linear in
the accelerations).
"""

from dataclasses import dataclass

import numpy as np

from . import kinematics as _kinematics
from . import newton, time_scheme
from ..declaration import schema
from ..errors import ConvergenceError, ParameterError
from .newton import ESTIMATE_FRACTION, HISTORY, REFRESH_RATE, SCHEMES  # noqa: F401  (re-exported)

_PIN = next(c for c in schema.CONSTRAINTS if c.map is None and c.node == 0)     # the crank pin (its reaction)
from ..declaration.validation import choice, in_range, integer


@dataclass(frozen=True)
class NewmarkSettings:
    scheme: str = "newton"
    beta: float = 0.25
    gamma: float = 0.5
    tol: float = 1e-10
    max_iterations: int = 30
    alpha_m: float = 0.0
    alpha_f: float = 0.0

    def __post_init__(self):
        choice("integrator", self.scheme, SCHEMES)
        in_range("beta", self.beta, 0, 1, True)
        in_range("gamma", self.gamma, 0, 2, True)
        in_range("tol", self.tol, 0, None, True)
        integer("max_iterations", self.max_iterations, 1)
        in_range("alpha_m", self.alpha_m, -1, 1, False, True)
        in_range("alpha_f", self.alpha_f, 0, 1, False, True)

    @classmethod
    def of_case(cls, case, tol=1e-10):
        """The settings of a case: its integrator and its time scheme (rho_inf)."""
        c = time_scheme.coefficients(case.rho_inf)
        return cls(scheme=case.integrator, beta=c.beta, gamma=c.gamma, tol=tol, alpha_m=c.alpha_m,
                   alpha_f=c.alpha_f)

    @property
    def generalized(self):
        return self.alpha_m != 0.0 or self.alpha_f != 0.0


@dataclass(frozen=True)
class NewmarkHistory:
    t: np.ndarray            # (n_steps + 1,)
    d: np.ndarray            # (n_steps + 1, N) reduced displacements
    v: np.ndarray
    a: np.ndarray            # accelerations qdd (R = 0 holds with them)
    iterations: np.ndarray   # (n_steps,) Newton iterations per step (1 for one-pass)
    g: np.ndarray = None     # algorithmic accelerations of generalized-alpha (None for Newmark: a)


def _singular(step, t, rhs):
    return ConvergenceError(f"singular or non-finite iteration matrix in step {step} (t* = {t:.6g})",
                            step=step, time=t, residual=float(np.linalg.norm(rhs)))


def _solve(model, S, rhs, step, t):
    x = model.assembler.solve(S, rhs)
    if x is None or not np.all(np.isfinite(x)):
        raise _singular(step, t, rhs)
    return x


def extrapolate(D):
    """Polynomial extrapolation one step ahead of the rows of D (oldest first, 2 to HISTORY + 1
    rows): linear to quartic (weights: newton.extrapolation_weight, oldest term first)."""
    n_prev = len(D) - 1
    out = np.zeros_like(D[-1])
    for k in range(n_prev, -1, -1):
        out = out + newton.extrapolation_weight(n_prev, k) * D[n_prev - k]
    return out


# the crank's column of the border is differenced with this step relative to max(1, |zdd_c|)
COLUMN_STEP = 1e-7


class _Border:
    """The bordered Newton system of a state with declared co-ordinates (crankgen.engine.coordinates
    gives the equations): the band S of the nodal unknowns, the co-ordinates' rows C^T (their pin
    forces' dependence on the first element's rows of S), the crank's column differenced, the other
    co-ordinates' columns from their equations' derivatives; solved by the Schur complement."""

    def __init__(self, model):
        self.model, self.mesh = model, model.mesh
        self.n_rod, self.m = model.mesh.n_rod, len(model.mesh.coordinates)
        self.pin_slots = list(model.mesh.holders(_PIN)[0][1])
        self.dofs0 = model.mesh.element_dofs[0]
        self.crank = model.mesh.crank_coordinate

    def residual(self, t, d, v, a, matrices=False, cv=0.0, cd=0.0, secant=False):
        """(R (n_rod,), g rows (m, 3 m + 3), kin[, S band, S0 the first element's iteration matrix])."""
        model = self.model
        kin = model.state_kinematics(t, d, v, a)
        terms = model.element_terms(kin, d, v, a, secant=secant)     # (n >= 2: element 0 holds no mapped node)
        geq = model.coordinate_equations(kin, d, v, a, terms.r)
        R = model.assembler.vector(terms.r)
        if not matrices:
            return R, geq, kin
        S = terms.M + cv * terms.C + cd * terms.K
        return R, geq, kin, model.assembler.banded(S), S[0]

    def linearize(self, t, d, v, a, cv, cd):
        """(R, g, factors of S, Y = S^-1 B, C^T, Schur complement): the system at the state."""
        model, n_rod, m = self.model, self.n_rod, self.m
        R, geq, _, S, S0 = self.residual(t, d, v, a, True, cv, cd)
        factors = model.assembler.factorize(S)
        if factors is None:
            return R, geq, None, None, None, None
        C = np.zeros((m, n_rod))
        for i in range(m):
            row = geq[i, 1 + 3 * m] * S0[self.pin_slots[0]] + geq[i, 2 + 3 * m] * S0[self.pin_slots[1]]
            for k, idx in enumerate(self.dofs0):
                if idx < n_rod:
                    C[i, idx] += row[k]
        Y = np.zeros((m, n_rod))
        E = np.zeros((m, m))
        for j in range(m):
            if j == self.crank:
                c = n_rod + j
                h = COLUMN_STEP * max(1.0, abs(a[c]))
                d1, v1, a1 = np.array(d, dtype=float), np.array(v, dtype=float), np.array(a, dtype=float)
                d1[c], v1[c], a1[c] = d[c] + cd * h, v[c] + cv * h, a[c] + h
                R1, g1, _ = self.residual(t, d1, v1, a1)
                Y[j] = model.assembler.solve_factorized(factors, (R1 - R) / h)
                E[:, j] = (g1[:, 0] - geq[:, 0]) / h
            else:
                E[:, j] = geq[:, 1 + 2 * m + j] + cv * geq[:, 1 + m + j] + cd * geq[:, 1 + j]
        return R, geq, factors, Y, C, E - C @ Y.T

    def solve(self, factors, Y, C, Sm, R, geq):
        """(dqdd (n_rod,), dzdd (m,)) of the bordered system (the Schur complement's solve)."""
        x = self.model.assembler.solve_factorized(factors, -R)
        dz = np.linalg.solve(Sm, -geq[:, 0] - C @ x)
        return x - Y.T @ dz, dz


def initial_acceleration(model, t0, d0, v0):
    """a_0 from eq. (34): M a_0 = F - C v_0 - K d_0, i.e. R(t0, d0, v0, a0) = 0; with declared
    co-ordinates their equations g = 0 too (both linear in the accelerations: a bordered solve,
    a second to round-off, the crank's column being differenced)."""
    zero = np.zeros_like(d0)
    if not model.mesh.coordinates:
        R, S = model.linearize(model.kinematics(t0), d0, v0, zero, 0.0, 0.0)
        return _solve(model, S, -R, 0, t0)
    border = _Border(model)
    a = np.zeros(model.n_dofs)
    for _ in range(2):
        R, geq, factors, Y, C, Sm = border.linearize(t0, d0, v0, a, 0.0, 0.0)
        if factors is None:
            raise _singular(0, t0, R)
        da, dz = border.solve(factors, Y, C, Sm, R, geq)
        a = a + np.concatenate([da, dz])
    return a


def integrate(model, d0, v0, t0, dt, n_steps, settings=NewmarkSettings(), progress=None, a0=None, g0=None):
    """March n_steps of size dt from (d0, v0) at t0 (a0: the accelerations there, by default solved
    from eq. (34); g0: the algorithmic accelerations of generalized-alpha, by default a0).
    progress(step, n_steps) is called per step."""
    n_steps = integer("number of steps", n_steps, 1)
    dt = in_range("dt", dt, 0, None, True)
    beta, gamma = settings.beta, settings.gamma
    generalized = settings.generalized
    am, af = settings.alpha_m, settings.alpha_f
    ratio = (1.0 - af) / (1.0 - am)
    scales = model.mesh.dof_scales(model.case.natural_sizes, _kinematics.end_scale(model.case))
    scheme = SCHEMES.index(settings.scheme)
    secant = scheme == newton.ONE_PASS and model.selection.printed_iteration
    one_pass = scheme == newton.ONE_PASS
    border = _Border(model) if model.mesh.coordinates else None
    if border is not None and one_pass:
        raise ParameterError("declared co-ordinates (a driven crank) need integrator 'newton' or 'full-newton' "
                             "(the one-pass scheme has no bordered form)")

    N = model.n_dofs
    n_rod = model.n_rod
    t = t0 + dt * np.arange(n_steps + 1)
    D, V, A = (np.empty((n_steps + 1, N)) for _ in range(3))
    G = np.empty((n_steps + 1, N)) if generalized else A
    iterations = np.zeros(n_steps, dtype=np.int32)
    D[0], V[0] = d0, v0
    A[0] = (initial_acceleration(model, t0, np.asarray(d0, float), np.asarray(v0, float)) if a0 is None
            else a0)
    if generalized:
        G[0] = A[0] if g0 is None else g0
    starter = generalized and g0 is None       # a start: the first step is time_scheme.STARTER
    c_d, c_v = beta * dt**2 * ratio, gamma * dt * ratio
    steady = (beta, gamma, am, af, ratio, c_d, c_v)

    for m in range(n_steps):
        if starter and m == 0:
            s = time_scheme.STARTER
            beta, gamma, am, af, ratio = s.beta, s.gamma, s.alpha_m, s.alpha_f, s.ratio
            c_d, c_v = beta * dt**2, gamma * dt
        elif starter and m == 1:
            beta, gamma, am, af, ratio, c_d, c_v = steady
        d, v, a, g = D[m], V[m], A[m], G[m]
        d_pred = d + dt * v + 0.5 * dt**2 * (1 - 2 * beta) * g            # eq. (35)
        v_pred = v + dt * (1 - gamma) * g                                  # eq. (36)
        abar = 0.0
        if generalized and not (starter and m == 0):
            abar = (af * a - am * g) / (1.0 - am)
            d_pred = d_pred + dt**2 * beta * abar
            v_pred = v_pred + dt * gamma * abar
        kin = model.kinematics(t[m + 1]) if border is None else None
        if one_pass:
            a_new = np.zeros(N)
        elif m == 0:
            a_new = a.copy()
        else:                                     # starting guess: extrapolated displacements
            a_new = (extrapolate(D[max(0, m - HISTORY):m + 1]) - d_pred) / c_d
        refresh, previous, reused_before, full = True, 0.0, False, False
        d_new, v_new = d_pred + c_d * a_new, v_pred + c_v * a_new          # eqs. (38)-(39)
        for it in range(1, settings.max_iterations + 1):
            if border is not None:
                if refresh:
                    R, geq, factors, Y, C, Sm = border.linearize(t[m + 1], d_new, v_new, a_new, c_v, c_d)
                    if factors is None:
                        raise _singular(m + 1, t[m + 1], R)
                else:
                    R, geq, _ = border.residual(t[m + 1], d_new, v_new, a_new)
            elif refresh:
                R, S = model.linearize(kin, d_new, v_new, a_new, c_v, c_d, secant=secant)
            else:
                R = model.assembler.vector(model.element_terms(kin, d_new, v_new, a_new).r)
            if not np.all(np.isfinite(R)) or (border is not None and not np.all(np.isfinite(geq[:, 0]))):
                raise ConvergenceError(
                    f"non-finite residual in step {m + 1} (t* = {t[m + 1]:.6g})",
                    step=m + 1, time=t[m + 1], residual=float("nan"))
            if border is not None:
                try:
                    da, dz = border.solve(factors, Y, C, Sm, R, geq)
                except np.linalg.LinAlgError:
                    raise _singular(m + 1, t[m + 1], R) from None
                delta = np.concatenate([da, dz])
            else:
                if refresh:
                    factors = model.assembler.factorize(S)
                    if factors is None:
                        raise _singular(m + 1, t[m + 1], R)
                delta = model.assembler.solve_factorized(factors, -R)
            if not np.all(np.isfinite(delta)):
                raise _singular(m + 1, t[m + 1], R)
            a_new += delta
            d_new, v_new = d_pred + c_d * a_new, v_pred + c_v * a_new
            increment = np.max(np.abs(c_d * delta) / scales)
            size = np.max(np.abs(d_new[:n_rod]) / scales[:n_rod])
            done, reject, refresh, reused_before, full = newton.next_iteration(
                scheme, it, increment, previous, size, settings.tol, refresh, reused_before, full)
            if done:
                break
            if reject:
                a_new -= delta
                d_new, v_new = d_pred + c_d * a_new, v_pred + c_v * a_new
                continue
            previous = increment
        else:
            raise ConvergenceError(
                f"Newton did not converge in step {m + 1} (t* = {t[m + 1]:.6g}): residual norm "
                f"{np.linalg.norm(R):.3e}, last scaled increment {increment:.3e} after "
                f"{settings.max_iterations} iterations",
                step=m + 1, time=t[m + 1], residual=float(np.linalg.norm(R)))
        D[m + 1] = d_new
        V[m + 1] = v_new
        A[m + 1] = a_new
        if generalized:
            G[m + 1] = abar + ratio * a_new if not (starter and m == 0) else a_new
        iterations[m] = it
        if not (np.all(np.isfinite(D[m + 1])) and np.all(np.isfinite(V[m + 1]))):
            raise ConvergenceError(f"non-finite state in step {m + 1} (t* = {t[m + 1]:.6g})",
                                   step=m + 1, time=t[m + 1], residual=float("nan"))
        if not np.max(np.abs(D[m + 1, :n_rod])) < newton.DIVERGED:
            raise ConvergenceError(f"{newton.DIVERGED_TEXT} in step {m + 1} (t* = {t[m + 1]:.6g})",
                                   step=m + 1, time=t[m + 1], residual=float(np.linalg.norm(R)))
        if progress is not None:
            progress(m + 1, n_steps)
    return NewmarkHistory(t, D, V, A, iterations, G if generalized else None)
