"""The motor-driven crank in the compiled engine: the bordered Newton step of crankgen.discrete.motor (the
NumPy reference; its docstring gives the equations) on the state (d, theta) of N + 1 numbers, and
the march of a batch of such cases.

Per Newton iteration: the crank's kinematics from (theta, thetad, thetadd) (the guide's closure,
no prescribed motion), the element loop (the rod's residual R; with a fresh matrix the element
iteration matrices), the crank pin's force from the first element's pin rows, the generated crank
equation g (`drive_<motion>`); with a fresh matrix S factorized, the crank's row c from the pin
rows of the first element's S and the crank's column (b, e) differenced (one more residual), then
two solves with S's factors (bordering).  Newton's decisions are newton.py's, as in step.py.
"""

import math

import numpy as np

from ..discrete import newton
from ..declaration import schema
from .banded import assemble_band, assemble_band_newmark, assemble_vector, band_factor, band_lu_solve, band_solve
from .borrow import borrowed_cases, borrowed_kernels, borrowed_mesh, borrowed_work, keep
from .build import entry_point
from .calls import call
from .compiled import jit
from .elements import FULL, NEWMARK, RESIDUAL, element_loop, step_outputs
from .kernels import next_iteration
from .records import N_OUTPUTS, make_work
from .step import NOT_CONVERGED, NOT_FINITE, OK, SINGULAR, STARTER_BETA, STARTER_GAMMA, TOO_LARGE

COLUMN_STEP = 1e-7               # crankgen.discrete.motor.COLUMN_STEP
ENTRY = "driven"                 # the entry point's name (engine/build.py): the march of driven cranks
_PIN = next(c for c in schema.CONSTRAINTS if c.map is None and c.node == 0)
PIN_SLOTS = np.array([schema.NODE.index(c) for c in _PIN.eliminated], dtype=np.int64)
DIVERGED = newton.DIVERGED


@jit                                # with a Python wrapper: tests call it against scipy
def hermite(tab, n, x):
    """(y(x), y'(x)) of the cubic Hermite pieces through the rows tab[:n] = (x_k, y_k, y'_k), x_k
    increasing, continued linearly with the end slopes beyond them: a torque curve's departure from
    the drive's linear law (crankgen.torque_curve.departure_table)."""
    if x <= tab[0, 0]:
        return tab[0, 1] + tab[0, 2] * (x - tab[0, 0]), tab[0, 2]
    if x >= tab[n - 1, 0]:
        return tab[n - 1, 1] + tab[n - 1, 2] * (x - tab[n - 1, 0]), tab[n - 1, 2]
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tab[mid, 0] <= x:
            lo = mid
        else:
            hi = mid
    h = tab[hi, 0] - tab[lo, 0]
    t = (x - tab[lo, 0]) / h
    y = ((2 * t - 3) * t * t + 1) * tab[lo, 1] + ((t - 2) * t + 1) * t * h * tab[lo, 2] \
        + (3 - 2 * t) * t * t * tab[hi, 1] + (t - 1) * t * t * h * tab[hi, 2]
    dy = 6 * t * (t - 1) / h * (tab[lo, 1] - tab[hi, 1]) + ((3 * t - 4) * t + 1) * tab[lo, 2] \
        + (3 * t - 2) * t * tab[hi, 2]
    return y, dy


@jit(python=False)
def crank_kinematics(kern, params, theta, thetad, thetadd, w):
    """w.kin of the guide with the crank at (theta, thetad, thetadd)."""
    w.crank[0] = theta
    w.crank[1] = thetad
    w.crank[2] = thetadd
    call(kern.guide, 0, (w.crank, params, w.kin))


@jit(python=False)
def evaluate(mode, kern, cases, b, mesh, d, v, a, theta, thetad, thetadd, cv, cd, w, pin, geq):
    """The rod's residual into w.R (and, by mode, its element matrices) and the crank equation geq
    (g and its derivatives, drive_<motion>) at the state; the crank's kinematics into w.kin."""
    sel, coef, params = cases.select[b], cases.coef[b], cases.params[b]
    crank_kinematics(kern, params, theta, thetad, thetadd, w)
    element_loop(mode, kern, sel, coef, params, False, mesh.dofs, mesh.l, d, v, a, cv, cd, w)
    assemble_vector(mesh.dofs, w.rE, w.R)
    for k in range(PIN_SLOTS.shape[0]):
        pin[k] = w.rE[0, PIN_SLOTS[k]]
    call(kern.drive, 0, (w.kin, pin, params, geq))
    n = cases.curve_n[b]
    if n > 0:                       # a torque curve: its departure from the drive kernel's linear law
        extra, slope = hermite(cases.curve[b], n, thetad)
        geq[0] -= extra
        geq[2] -= slope


@jit(python=False)
def _crank_row(mesh, w, geq, S0, N, c):
    """c = dg/dF_pin . (pin rows of the first element's matrix S0), on the reduced DOFs."""
    for i in range(N):
        c[i] = 0.0
    for k in range(S0.shape[1]):
        idx = mesh.dofs[0, k]
        if idx < N:
            for p in range(PIN_SLOTS.shape[0]):
                c[idx] += geq[3 + p] * S0[PIN_SLOTS[p], k]


@jit(python=False)
def initial_acceleration(kern, cases, b, mesh, d, v, theta, thetad, out, w):
    """The rod's and the crank's accelerations out (N + 1) with R = 0 and g = 0 (linear in them):
    two bordered solves from zero.  Returns False if singular."""
    N = d.shape[0]
    kb = mesh.kb
    pin, geq, g1 = np.zeros(2), np.zeros(5), np.zeros(5)
    a = np.zeros(N)
    c = np.zeros(N)
    R0 = np.zeros(N)
    thdd = 0.0
    for _ in range(2):
        evaluate(FULL, kern, cases, b, mesh, d, v, a, theta, thetad, thdd, 0.0, 0.0, w, pin, geq)
        for i in range(N):
            R0[i] = w.R[i]
        _crank_row(mesh, w, geq, w.ME[0], N, c)
        W = np.zeros((N, 3 * kb + 1))
        assemble_band(mesh.dofs, kb, w.ME, w.CE, w.KE, 1.0, 0.0, 0.0, W)
        h = COLUMN_STEP * max(1.0, abs(thdd))
        evaluate(RESIDUAL, kern, cases, b, mesh, d, v, a, theta, thetad, thdd + h, 0.0, 0.0, w, pin, g1)
        rhs = np.zeros((N, 2))
        for i in range(N):
            rhs[i, 0] = -R0[i]
            rhs[i, 1] = (w.R[i] - R0[i]) / h
        if not band_solve(W, kb, rhs):
            return False
        e = (g1[0] - geq[0]) / h
        cx, cy = 0.0, 0.0
        for i in range(N):
            cx += c[i] * rhs[i, 0]
            cy += c[i] * rhs[i, 1]
        dz = (-geq[0] - cx) / (e - cy)
        for i in range(N):
            a[i] += rhs[i, 0] - rhs[i, 1] * dz
        thdd += dz
    for i in range(N):
        out[i] = a[i]
    out[N] = thdd
    return True


@jit(python=False)
def motor_step(kern, cases, b, mesh, scheme, x, v, acc, alg, x_new, v_new, a_new, alg_new, w, start=False):
    """One step of the case's time scheme (step.newmark_step's, without the one-pass scheme) on
    the bordered state of N + 1 numbers (the rod's reduced DOFs, then the crank angle), Newton on
    the accelerations with the bordered iteration matrix (module docstring).  Returns (status,
    iterations, residual norm)."""
    M1 = x.shape[0]
    N = M1 - 1
    scales = cases.scales[b]
    kb = mesh.kb
    tol, max_iter = scheme.tol, scheme.max_iter
    beta, gamma, am, af = cases.integ[b, 0], cases.integ[b, 1], cases.integ[b, 2], cases.integ[b, 3]
    generalized = am != 0.0 or af != 0.0
    if start and generalized:
        beta, gamma, am, af = STARTER_BETA, STARTER_GAMMA, 0.0, 0.0
        generalized = False
    ratio = (1.0 - af) / (1.0 - am)
    dt = cases.dt[b]
    code = cases.scheme[b]
    cd = beta * dt * dt * ratio
    cv = gamma * dt * ratio
    dp, vp = np.zeros(M1), np.zeros(M1)
    for i in range(M1):
        if generalized:
            abar = (af * acc[i] - am * alg[i]) / (1.0 - am)
            alg_new[i] = abar
            dp[i] = x[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * alg[i] + dt * dt * beta * abar
            vp[i] = v[i] + dt * (1.0 - gamma) * alg[i] + dt * gamma * abar
        else:
            dp[i] = x[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * acc[i]
            vp[i] = v[i] + dt * (1.0 - gamma) * acc[i]
        a_new[i] = acc[i]
        x_new[i] = dp[i] + cd * a_new[i]
        v_new[i] = vp[i] + cv * a_new[i]
    pin, geq, g1 = np.zeros(2), np.zeros(5), np.zeros(5)
    R0, c, B = np.zeros(N), np.zeros(N), np.zeros((N, 2))
    e = 1.0
    cy = 0.0
    rnorm = 0.0
    refresh = True
    full = False
    previous = 0.0
    reused_before = False
    for it in range(1, max_iter + 1):
        mode = NEWMARK if refresh else RESIDUAL
        evaluate(mode, kern, cases, b, mesh, x_new[:N], v_new[:N], a_new[:N], x_new[N], v_new[N], a_new[N], cv, cd,
                 w, pin, geq)
        rnorm = geq[0] * geq[0]
        for i in range(N):
            R0[i] = w.R[i]
            rnorm += R0[i] * R0[i]
        rnorm = math.sqrt(rnorm)
        if not np.isfinite(rnorm):
            return NOT_FINITE, it, rnorm
        if refresh:
            _crank_row(mesh, w, geq, w.SE[0], N, c)
            assemble_band_newmark(mesh.dofs, kb, w.SE, w.W)
            if not band_factor(w.W, kb, w.piv, w.ext):
                return SINGULAR, it, rnorm
            h = COLUMN_STEP * max(1.0, abs(a_new[N]))
            evaluate(RESIDUAL, kern, cases, b, mesh, x_new[:N], v_new[:N], a_new[:N], x_new[N] + cd * h,
                     v_new[N] + cv * h, a_new[N] + h, cv, cd, w, pin, g1)
            for i in range(N):
                B[i, 1] = (w.R[i] - R0[i]) / h
                B[i, 0] = 0.0
            e = (g1[0] - geq[0]) / h
            band_lu_solve(w.W, kb, w.piv, w.ext, B[:, 1:2])
            cy = 0.0
            for i in range(N):
                cy += c[i] * B[i, 1]
        for i in range(N):
            B[i, 0] = -R0[i]
        band_lu_solve(w.W, kb, w.piv, w.ext, B[:, 0:1])
        cx = 0.0
        for i in range(N):
            cx += c[i] * B[i, 0]
        dz = (-geq[0] - cx) / (e - cy)
        inc = abs(cd * dz)              # the crank angle's natural size: 1 rad
        for i in range(N):
            delta = B[i, 0] - B[i, 1] * dz
            B[i, 0] = delta
            a_new[i] += delta
            xx = abs(cd * delta) / scales[i]
            if xx > inc:
                inc = xx
        a_new[N] += dz
        size = 0.0
        largest = 0.0
        for i in range(M1):
            x_new[i] = dp[i] + cd * a_new[i]
            v_new[i] = vp[i] + cv * a_new[i]
            if i < N:
                xx = abs(x_new[i]) / scales[i]
                if xx > size:
                    size = xx
                if abs(x_new[i]) > largest:
                    largest = abs(x_new[i])
        if not np.isfinite(inc):
            return NOT_FINITE, it, rnorm
        done, reject, refresh, reused_before, full = next_iteration(code, it, inc, previous, size, tol,
                                                                    refresh, reused_before, full)
        if done:
            if not largest < DIVERGED:
                return TOO_LARGE, it, rnorm
            for i in range(M1):
                alg_new[i] = alg_new[i] + ratio * a_new[i] if generalized else a_new[i]
            return OK, it, rnorm
        if reject:
            for i in range(N):
                a_new[i] -= B[i, 0]
            a_new[N] -= dz
            for i in range(M1):
                x_new[i] = dp[i] + cd * a_new[i]
                v_new[i] = vp[i] + cv * a_new[i]
            continue
        previous = inc
    return NOT_CONVERGED, max_iter, rnorm


@jit
def _march_motor(kern, cases, mesh, scheme, lo, hi, n_steps, X0, V0, A0, G0, start, solve_a0, keep_history, out_y,
                 out_iter, status, fail_step, fail_res, Xh, Vh, Ah, Gh, X1, V1, A1, G1):
    """Advance cases lo..hi-1 n_steps (see march)."""
    n = mesh.dofs.shape[0]
    M1 = X0.shape[1]
    N = M1 - 1
    kern, cases, mesh = borrowed_kernels(kern), borrowed_cases(cases), borrowed_mesh(mesh)
    for b in range(lo, hi):
        if status[b] != OK:             # not advanced: its state stays
            for i in range(M1):
                X1[b, i] = X0[b, i]
                V1[b, i] = V0[b, i]
                A1[b, i] = A0[b, i]
                G1[b, i] = G0[b, i]
            continue
        owned = make_work(n, N, mesh.kb)
        w = borrowed_work(owned)
        sel, params = cases.select[b], cases.params[b]
        x, v, acc, alg = X0[b].copy(), V0[b].copy(), A0[b].copy(), G0[b].copy()
        if solve_a0:
            if not initial_acceleration(kern, cases, b, mesh, x[:N], v[:N], x[N], v[N], acc, w):
                status[b] = SINGULAR
                continue
            if start:                   # a start: the algorithmic accelerations are the accelerations
                for i in range(M1):
                    alg[i] = acc[i]
        xn, vn, an, gn = np.zeros(M1), np.zeros(M1), np.zeros(M1), np.zeros(M1)
        y = np.zeros(N_OUTPUTS)
        crank_kinematics(kern, params, x[N], v[N], acc[N], w)
        step_outputs(kern, sel, params, cases.p[b], mesh, x[:N], w, y)
        for k in range(N_OUTPUTS):
            out_y[b, 0, k] = y[k]
        if keep_history:
            for i in range(M1):
                Xh[b, 0, i] = x[i]
                Vh[b, 0, i] = v[i]
                Ah[b, 0, i] = acc[i]
                Gh[b, 0, i] = alg[i]
        for m in range(n_steps):
            if status[b] != OK:
                break
            st, it, rn = motor_step(kern, cases, b, mesh, scheme, x, v, acc, alg, xn, vn, an, gn, w, start and m == 0)
            out_iter[b, m] = it
            if st == OK:
                for i in range(M1):
                    if not (np.isfinite(xn[i]) and np.isfinite(vn[i])):
                        st = NOT_FINITE
                        break
            if st != OK:
                status[b] = st
                fail_step[b] = m + 1
                fail_res[b] = rn
                break
            for i in range(M1):
                x[i] = xn[i]
                v[i] = vn[i]
                acc[i] = an[i]
                alg[i] = gn[i]
            crank_kinematics(kern, params, x[N], v[N], acc[N], w)
            step_outputs(kern, sel, params, cases.p[b], mesh, x[:N], w, y)
            for k in range(N_OUTPUTS):
                out_y[b, m + 1, k] = y[k]
            if keep_history:
                for i in range(M1):
                    Xh[b, m + 1, i] = x[i]
                    Vh[b, m + 1, i] = v[i]
                    Ah[b, m + 1, i] = acc[i]
                    Gh[b, m + 1, i] = alg[i]
        for i in range(M1):
            X1[b, i] = x[i]
            V1[b, i] = v[i]
            A1[b, i] = acc[i]
            G1[b, i] = alg[i]
        keep(owned)


class MotorMarch:
    """What march_motor gives: y (B, steps + 1, engine outputs), iterations, status, fail_step,
    fail_residual, the final X, V, A, G (B, N + 1: the crank last) and, with keep_history, their
    histories X_history, V_history, A_history, G_history (B, steps + 1, N + 1)."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


def march_motor(batch, n_steps, X0, V0, A0=None, G0=None, keep_history=False, tol=1e-10, max_iter=30, parallel=None,
                status=None):
    """Advance the motor-driven cases of the batch n_steps from X0, V0 (B, N + 1: the rod's reduced
    DOFs, then the crank angle / speed).  A0: the accelerations (default solved: R = 0, g = 0);
    G0: generalized-alpha's algorithmic accelerations (default: a start, its first step the
    starter, time_scheme.STARTER, and G0 = A0).  status: cases not OK on entry are not advanced."""
    from .batch import parallel_slices
    from .records import Scheme
    B, M1 = len(batch), batch.N + 1
    X0 = np.ascontiguousarray(X0, dtype=float).reshape(B, M1)
    V0 = np.ascontiguousarray(V0, dtype=float).reshape(B, M1)
    solve_a0 = A0 is None
    A0 = np.zeros((B, M1)) if A0 is None else np.ascontiguousarray(A0, dtype=float)
    start = G0 is None
    G0 = A0.copy() if G0 is None else np.ascontiguousarray(G0, dtype=float)
    status = np.zeros(B, dtype=np.int64) if status is None else np.array(status, dtype=np.int64)
    out_y = np.full((B, n_steps + 1, N_OUTPUTS), np.nan)
    out_iter = np.zeros((B, max(n_steps, 1)), dtype=np.int64)
    fail_step, fail_res = np.zeros(B, dtype=np.int64), np.zeros(B)
    shape = (B, n_steps + 1, M1) if keep_history else (1, 1, 1)
    Xh, Vh, Ah, Gh = (np.zeros(shape) for _ in range(4))
    X1, V1, A1, G1 = (np.zeros((B, M1)) for _ in range(4))
    scheme = Scheme(float(tol), int(max_iter))
    parallel = B > 1 if parallel is None else parallel
    parallel_slices(_march_motor, batch, parallel, (batch.records, batch.meshdata, scheme),
                    (n_steps, X0, V0, A0, G0, start, solve_a0, bool(keep_history), out_y, out_iter, status, fail_step,
                     fail_res, Xh, Vh, Ah, Gh, X1, V1, A1, G1), active=status == OK)
    hist = dict(X_history=Xh, V_history=Vh, A_history=Ah, G_history=Gh) if keep_history else {}
    return MotorMarch(y=out_y, iterations=out_iter[:, :n_steps], status=status, fail_step=fail_step,
                      fail_residual=fail_res, X=X1, V=V1, A=A1, G=G1, **hist)


def compiling_batch():
    from ..declaration.cases import Case
    from .kernels import noop_tables
    from .batch import Batch
    driven = next(name for name, m in schema.MOTIONS.items() if m.driven)
    return Batch([Case(motion=driven, n_elements=2, steps_per_rev=4)], entries=(ENTRY,), kernels_table=noop_tables())


@entry_point(ENTRY)
def _compile_motor():
    batch = compiling_batch()
    M1 = batch.N + 1
    march_motor(batch, 1, np.zeros((1, M1)), np.zeros((1, M1)), parallel=False)
