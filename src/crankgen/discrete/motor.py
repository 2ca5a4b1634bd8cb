"""A motor-driven crank (derive/motions.py, motion `motor`): the crank angle theta is one more
unknown beside the rod's reduced DOFs, and the equations are bordered:

    R(d, v, a; theta, thetad, thetadd) = 0              the rod's (eq. 30), the kinematics from the crank
    g = J thetadd - (T_m(thetad) - T_load) + T_rod = 0  the crank's, T_rod = a (e_r x F_pin)

F_pin, the force the crank pin applies to the rod (in the moving frame), is the residual of the
pin's eliminated rows of the first element (Model.reactions), so T_rod is the output `torque`:
the crank's generalized residual of the same energies.  g and its derivatives in thetadd, thetad
and F_pin are generated (`drive_<motion>` in generated/kinematics.py).

The time scheme treats theta as every other unknown (Newmark or generalized-alpha, the crank's
algorithmic acceleration beside the rod's).  Newton's iteration matrix is bordered,

    [ S    b  ] [da     ]     [ R ]     S = dR/da + cv dR/dv + cd dR/dd (the rod's, exact)
    [ c^T  e  ] [dthdd  ] = - [ g ]     c = dg/dF_pin . rows of the pin in S (exact)

with the crank's column (b, e) = d(R, g)/d thetadd_{n+1} (thetad and theta following through
cv and cd) differenced numerically: one more residual per fresh matrix.  Only the iteration
matrix is approximate; the residual is exact, so the converged state is exact to the tolerance.
It is solved by bordering, two solves with S's factors.

This module is the NumPy reference (the compiled engine: engine/motor.py) and the helpers both
use: `crank_state` (the kinematics of given crank angles, speeds and accelerations), `pin_force`.
"""

import math
from dataclasses import dataclass

import numpy as np

from . import kinematics as _kinematics
from . import newton, time_scheme
from ..declaration import schema, torque_curve
from .._generated import kinematics as _generated
from ..errors import ConvergenceError, ParameterError

# the crank's Newton unknown is thetadd_{n+1}; its column is differenced with this relative step
COLUMN_STEP = 1e-7
PIN = next(c for c in schema.CONSTRAINTS if c.map is None and c.node == 0)


def driven(case):
    """Whether the case's crank is motor-driven (its angle a degree of freedom)."""
    return bool(case.motion_record.driven)


def check_driven(case):
    """Refuse a motor-driven case the bordered equations cannot take (one element: the pin's and the
    guide's rows in the same element)."""
    if case.n_elements < 2:
        raise ParameterError("a motor-driven crank needs n_elements >= 2 (the crank pin's element must not "
                             "hold the guide's node)")
    if case.integrator == "one-pass":
        raise ParameterError("a motor-driven crank needs integrator 'newton' or 'full-newton' (the one-pass "
                             "scheme has no bordered form)")


def step_hint(case, dt):
    """A sentence for a step that failed: when the motor's time constant J Omega_nl / (T_stall
    max |f'|) (the crank alone; the linkage adds inertia) is shorter than the step, the step cannot
    follow the motor; else ""."""
    curve, stall, no_load, inertia = torque_curve.of(case)
    tau = inertia * no_load / (stall * torque_curve.steepest(curve))
    if tau >= dt:
        return ""
    return (f"; the motor's time constant J Omega_nl / (T_stall max|f'|) = {tau:.3g} is shorter than the step "
            f"{dt:.3g}: raise steps_per_rev above {math.ceil(case.steps_per_rev * dt / tau)}")


def crank_state(case, crank):
    """CrankState of the case's guide for crank (..., 3) = (theta, thetad, thetadd)."""
    crank = np.asarray(crank, dtype=float)
    params = np.broadcast_to(case.kinematic_parameters, crank.shape[:-1] + (len(schema.KINEMATIC_PARAMETERS),))
    return _kinematics._state(getattr(_generated, f"guide_{case.guide_record.name}")(crank, params))


def crank_start(case):
    """(theta, thetad) of the crank at t = 0 (theta0 and the initial speed): its motion's theta(t) at
    t = 0, which a driven crank declares as its start."""
    crank = getattr(_generated, f"motion_{case.motion_record.name}")(0.0, case.kinematic_parameters)
    return float(crank[0]), float(crank[1])


def crank_equation(case, kin, pin):
    """(g, dg/dthetadd, dg/dthetad, dg/dpin_i, dg/dpin_j) (..., 5): the generated drive kernel, with
    a torque curve's departure from the linear law added (crankgen.torque_curve)."""
    geq = getattr(_generated, f"drive_{case.motion_record.name}")(kin.vector, pin, case.kinematic_parameters)
    curve, stall, no_load, _ = torque_curve.of(case)
    if tuple(curve) != torque_curve.LINEAR:
        geq = np.array(geq, dtype=float)
        extra, slope = torque_curve.departure(curve, np.asarray(kin.thetad, dtype=float) / no_load)
        geq[..., 0] -= stall * extra
        geq[..., 2] -= stall / no_load * slope
    return geq


@dataclass(frozen=True)
class MotorHistory:
    """A motor-driven run of the reference: t, the rod's d, v, a (steps, N), the crank (steps, 3) =
    (theta, thetad, thetadd), generalized-alpha's algorithmic accelerations g (steps, N + 1; the
    crank's last; None for Newmark), Newton's iterations per step."""

    t: np.ndarray
    d: np.ndarray
    v: np.ndarray
    a: np.ndarray
    crank: np.ndarray
    iterations: np.ndarray
    g: np.ndarray = None


class _Bordered:
    """The bordered residual and iteration matrix of one case (the reference's arithmetic)."""

    def __init__(self, model):
        self.model, self.case = model, model.case
        self.pin_slots = list(model.mesh.holders(PIN)[0][1])
        self.dofs0 = model.mesh.element_dofs[0]

    def residual(self, d, v, a, crank, matrices=False, cv=0.0, cd=0.0):
        """(R, g, kin[, S0 rows of the pin]) at the rod's (d, v, a) and crank (theta, thetad, thetadd)."""
        kin = crank_state(self.case, np.asarray(crank, dtype=float))
        q, E, r, K, C, M = self.model.unprojected_terms(kin, d, v, a)
        pin = r[0, self.pin_slots]
        geq = crank_equation(self.case, kin, pin)
        R = self.model.assembler.vector(self.model.element_terms(kin, d, v, a).r)
        if not matrices:
            return R, geq, kin
        S0 = (M[0] + cv * C[0] + cd * K[0])[self.pin_slots]
        return R, geq, kin, S0

    def linearize(self, d, v, a, crank, cv, cd):
        """(R, g, S band, b, c, e): the bordered system of the module docstring at the state."""
        R, geq, kin, S0 = self.residual(d, v, a, crank, True, cv, cd)
        _, S = self.model.linearize(kin, d, v, a, cv, cd)
        N = len(d)
        c = np.zeros(N)
        row = geq[3] * S0[0] + geq[4] * S0[1]
        for k, i in enumerate(self.dofs0):
            if 0 <= i < N:                  # a pinned slot's index is N (mesh.gather's padding)
                c[i] += row[k]
        h = COLUMN_STEP * max(1.0, abs(crank[2]))
        bumped = (crank[0] + cd * h, crank[1] + cv * h, crank[2] + h)
        R1, g1, _ = self.residual(d, v, a, bumped)
        return R, geq[0], S, (R1 - R) / h, c, (g1[0] - geq[0]) / h


def _solve(model, factors, R, g, b, c, e):
    """(da, dthdd) of the bordered system by bordering (two solves with S's factors)."""
    x = model.assembler.solve_factorized(factors, -R)
    y = model.assembler.solve_factorized(factors, b)
    pivot = e - c @ y
    dz = (-g - c @ x) / pivot
    return x - y * dz, dz


def initial_acceleration(model, t0, d0, v0, theta0, thetad0):
    """(a, thetadd) with R = 0 and g = 0 at t0 (both linear in the accelerations: one bordered solve,
    a second to round-off)."""
    sys = _Bordered(model)
    N = len(d0)
    a, thdd = np.zeros(N), 0.0
    for _ in range(2):
        R, g, S, b, c, e = sys.linearize(d0, v0, a, (theta0, thetad0, thdd), 0.0, 0.0)
        factors = model.assembler.factorize(S)
        if factors is None:
            raise ConvergenceError("singular initial mass matrix of the motor-driven mechanism", step=0, time=t0,
                                   residual=float("nan"))
        da, dz = _solve(model, factors, R, g, b, c, e)
        a, thdd = a + da, thdd + dz
    return a, thdd


def integrate(model, d0, v0, t0, dt, n_steps, settings, progress=None, crank0=None, a0=None, g0=None):
    """March the motor-driven mechanism n_steps of size dt from the rod's (d0, v0) and the crank's
    (theta, thetad) = crank0 (default: theta0 and the initial speed) at t0.  a0: the rod's and the
    crank's accelerations there (N + 1; default solved), g0: generalized-alpha's algorithmic
    accelerations (N + 1; default a0: a start, its first step the STARTER).  Newton's decisions are
    newton.py's, the increments scaled by the DOFs' natural sizes (the crank angle's: 1 rad)."""
    case = model.case
    check_driven(case)
    sys = _Bordered(model)
    beta, gamma = settings.beta, settings.gamma
    generalized = settings.generalized
    am, af = settings.alpha_m, settings.alpha_f
    ratio = (1.0 - af) / (1.0 - am)
    N = model.n_dofs
    scales = np.append(model.mesh.dof_scales(schema.natural_sizes(case.parameters()), _kinematics.end_scale(case)), 1.0)
    scheme = newton.SCHEMES.index(settings.scheme)
    if scheme == newton.ONE_PASS:
        raise ParameterError("a motor-driven crank needs integrator 'newton' or 'full-newton' (one-pass has no "
                             "bordered form)")
    theta0, thetad0 = crank_start(case) if crank0 is None else crank0
    t = t0 + dt * np.arange(n_steps + 1)
    X, V, A = (np.empty((n_steps + 1, N + 1)) for _ in range(3))
    G = np.empty((n_steps + 1, N + 1)) if generalized else A
    iterations = np.zeros(n_steps, dtype=np.int32)
    X[0], V[0] = np.append(d0, theta0), np.append(v0, thetad0)
    if a0 is None:
        a_rod, thdd = initial_acceleration(model, t0, np.asarray(d0, float), np.asarray(v0, float), theta0, thetad0)
        A[0] = np.append(a_rod, thdd)
    else:
        A[0] = a0
    if generalized:
        G[0] = A[0] if g0 is None else g0
    starter = generalized and g0 is None
    c_d, c_v = beta * dt**2 * ratio, gamma * dt * ratio
    steady = (beta, gamma, am, af, ratio, c_d, c_v)
    for m in range(n_steps):
        if starter and m == 0:
            s = time_scheme.STARTER
            beta, gamma, am, af, ratio = s.beta, s.gamma, s.alpha_m, s.alpha_f, s.ratio
            c_d, c_v = beta * dt**2, gamma * dt
        elif starter and m == 1:
            beta, gamma, am, af, ratio, c_d, c_v = steady
        x, v, a, g = X[m], V[m], A[m], G[m]
        x_pred = x + dt * v + 0.5 * dt**2 * (1 - 2 * beta) * g
        v_pred = v + dt * (1 - gamma) * g
        abar = 0.0
        if generalized and not (starter and m == 0):
            abar = (af * a - am * g) / (1.0 - am)
            x_pred = x_pred + dt**2 * beta * abar
            v_pred = v_pred + dt * gamma * abar
        a_new = a.copy()
        refresh, previous, reused_before, full = True, 0.0, False, False
        for it in range(1, settings.max_iterations + 1):
            x_new, v_new = x_pred + c_d * a_new, v_pred + c_v * a_new
            crank = (x_new[N], v_new[N], a_new[N])
            if refresh:
                R, geq, S, b, c, e = sys.linearize(x_new[:N], v_new[:N], a_new[:N], crank, c_v, c_d)
                factors = model.assembler.factorize(S)
                if factors is None:
                    raise ConvergenceError(f"singular iteration matrix in step {m + 1} (t* = {t[m + 1]:.6g})",
                                           step=m + 1, time=t[m + 1], residual=float(np.linalg.norm(R)))
            else:
                R, gv, _ = sys.residual(x_new[:N], v_new[:N], a_new[:N], crank)
                geq = gv[0]
            if not (np.all(np.isfinite(R)) and np.isfinite(geq)):
                raise ConvergenceError(f"non-finite residual in step {m + 1} (t* = {t[m + 1]:.6g})",
                                       step=m + 1, time=t[m + 1], residual=float("nan"))
            da, dz = _solve(model, factors, R, geq, b, c, e)
            delta = np.append(da, dz)
            a_new = a_new + delta
            x_new = x_pred + c_d * a_new
            increment = np.max(np.abs(c_d * delta) / scales)
            size = np.max(np.abs(x_new[:N]) / scales[:N])
            done, reject, refresh, reused_before, full = newton.next_iteration(
                scheme, it, increment, previous, size, settings.tol, refresh, reused_before, full)
            if done:
                break
            if reject:
                a_new = a_new - delta
                continue
            previous = increment
        else:
            raise ConvergenceError(
                f"Newton did not converge in step {m + 1} (t* = {t[m + 1]:.6g}) of the motor-driven crank"
                + step_hint(model.case, dt),
                step=m + 1, time=t[m + 1], residual=float(np.linalg.norm(R)))
        X[m + 1], V[m + 1], A[m + 1] = x_pred + c_d * a_new, v_pred + c_v * a_new, a_new
        if generalized:
            G[m + 1] = abar + ratio * a_new if not (starter and m == 0) else a_new
        iterations[m] = it
        if not (np.all(np.isfinite(X[m + 1])) and np.all(np.isfinite(V[m + 1]))):
            raise ConvergenceError(f"non-finite state in step {m + 1} (t* = {t[m + 1]:.6g})",
                                   step=m + 1, time=t[m + 1], residual=float("nan"))
        if progress is not None:
            progress(m + 1, n_steps)
    crank = np.stack([X[:, N], V[:, N], A[:, N]], axis=-1)
    return MotorHistory(t, X[:, :N].copy(), V[:, :N].copy(), A[:, :N].copy(), crank, iterations,
                        G if generalized else None)
