"""The revolution map of the Newton-Newmark (or generalized-alpha) scheme and its exact
linearization (compiled), for shooting on periodic states (steady.py) and continuation.

The linearization propagates the sensitivities of (d, v, qdd) (and a) to the state's components
(and optionally to a parameter) through every converged step, as (N, columns) arrays whose rows
are updated whole (the innermost loops run over the columns, which LLVM vectorizes; the columns
are padded to a multiple of 8).  Per step: K dd~ + C dv~ row by row from the assembled band
matrices, and the solve with the iteration matrix at the converged state, factorized like the
Newton iterations' (the fixed-bandwidth LU without pivoting where it is safe, else the pivoted
band LU: banded.py)."""

import numpy as np

from ..discrete import newton
from .banded import (assemble_band, assemble_fixed, assemble_vector, band_factor, band_lu_solve, factor_fixed,
                     fixed_width, solve_fixed_columns)
from .borrow import borrowed_cases, borrowed_kernels, borrowed_mesh, borrowed_work, keep
from .compiled import jit
from .elements import FULL, RESIDUAL, element_loop, iteration_matrices, kinematics, step_outputs
from .build import entry_point
from .batch import compiling_batch, parallel_slices
from .records import N_OUTPUTS, Scheme, make_work
from .step import OK, SINGULAR, initial_acceleration, newmark_step

HISTORY = newton.HISTORY
PAD = 8                 # the sensitivity columns are padded to a multiple of PAD


@jit
def _residual_into(kern, cases, b, sel, mesh, t, d, v, a, w, out):
    """out = R(t, d, v, a) with the coefficients and kinematic parameters of row b of `cases` (the
    family selection `sel` of the case being linearized); leaves w.kin at t for that row."""
    kinematics(kern, sel, cases.params[b], t, w)
    element_loop(RESIDUAL, kern, sel, cases.coef[b], cases.params[b], False, mesh.dofs, mesh.l, d, v, a,
                 0.0, 0.0, w)
    assemble_vector(mesh.dofs, w.rE, out)


@jit
def _parameter_forcing(kern, minus, plus, b, sel, mesh, k, h, d, v, a, w, rm, rp, g):
    """g = dR/dp at the fixed state (d, v, a) of step k: a central difference of the residual
    between the cases at p - h and p + h (coefficients, kinematic parameters and time
    t = k dt(p), all at the perturbed p)."""
    _residual_into(kern, minus, b, sel, mesh, k * minus.dt[b], d, v, a, w, rm)
    _residual_into(kern, plus, b, sel, mesh, k * plus.dt[b], d, v, a, w, rp)
    inv = 0.5 / h
    for i in range(g.shape[0]):
        g[i] = (rp[i] - rm[i]) * inv


@jit
def _tangent_rhs(Kb, Cb, kb, Dd, Dv, Da):
    """Da = -(K Dd + C Dv) (N, m); K, C in row band storage (offset kb)."""
    N, m = Da.shape
    for i in range(N):
        for c in range(m):
            Da[i, c] = 0.0
        for j in range(max(0, i - kb), min(N - 1, i + kb) + 1):
            k = Kb[i, j - i + kb]
            cc = Cb[i, j - i + kb]
            for c in range(m):
                Da[i, c] -= k * Dd[j, c] + cc * Dv[j, c]


@jit
def _revolution_cases(kern, cases, mesh, scheme, lo, hi, step0, n_steps, spr, X0, active, minus, plus, h,
                      with_j, with_p, X1, J, Y, XR, status):
    """For every active case of lo..hi-1: state x at step step0 -> state after n_steps Newton
    steps, and (with_j) J = dx1/dx0, the exact linearization of the converged steps.  x = (d, v)
    for Newmark (S = 2N numbers), x = (d, v, a) for generalized-alpha (S = 3N: its algorithmic
    accelerations carry memory); the accelerations qdd at the start solve eq. (34).  Per step,
    with abar = (alpha_f qdd - alpha_m a) / (1 - alpha_m) (0 for Newmark, where a = qdd):
        dd~ = dd + dt dv + dt^2 (1/2 - beta) da + dt^2 beta dabar,  dv~ = dv + dt (1 - gamma) da + dt gamma dabar,
        S dqdd' = -(K dd~ + C dv~),  dd' = dd~ + cd dqdd',  dv' = dv~ + cv dqdd',  da' = dabar + r dqdd'
    with S, K, C the exact tangents at the converged state of each step (time_scheme: cd, cv, r).
    with_p: J has one more column, dx1/dp for the parameter whose perturbed cases are `minus`
    (p - h) and `plus` (p + h), rows matching `cases`; x0 does not depend on p, the steps do
    through R (at the fixed state: _parameter_forcing) and through dt:
        dd~ += (v + dt (1 - 2 beta) a + 2 beta dt abar + 2 beta r dt qdd') ddt/dp,
        dv~ += ((1 - gamma) a + gamma abar + gamma r qdd') ddt/dp
    (with a fixed number of steps per revolution the crank angles of the steps need not depend on
    p, the times t = k dt do).
    Y[b, m]: the engine's outputs (schema.ENGINE_OUTPUTS) at step step0 + m; XR[b, r]: the state after r
    times spr steps (r = 0 .. n_steps // spr)."""
    n = mesh.dofs.shape[0]
    S = X0.shape[1]
    kern, cases, mesh = borrowed_kernels(kern), borrowed_cases(cases), borrowed_mesh(mesh)    # the caller's
    minus, plus = borrowed_cases(minus), borrowed_cases(plus)
    dofs, kb, l = mesh.dofs, mesh.kb, mesh.l
    for b in range(lo, hi):
        if not active[b]:
            continue
        beta, gamma, am, af = cases.integ[b, 0], cases.integ[b, 1], cases.integ[b, 2], cases.integ[b, 3]
        generalized = am != 0.0 or af != 0.0
        N = S // 3 if generalized else S // 2
        ncol = S + (1 if with_p else 0)
        width = (ncol + PAD - 1) // PAD * PAD if with_j else 0
        P = S                                       # the parameter column
        ratio = (1.0 - af) / (1.0 - am)
        owned = make_work(mesh, N)
        w = borrowed_work(owned)
        sel, coef, params = cases.select[b], cases.coef[b], cases.params[b]
        dt = cases.dt[b]
        ddt = (plus.dt[b] - minus.dt[b]) / (2.0 * h) if with_p else 0.0
        cd, cv = beta * dt * dt * ratio, gamma * dt * ratio
        c1, c2 = 0.5 * dt * dt * (1.0 - 2.0 * beta), dt * (1.0 - gamma)
        c3, c4 = dt * dt * beta, dt * gamma
        d, v = X0[b, :N].copy(), X0[b, N:2 * N].copy()
        acc = np.zeros(N)
        alg = X0[b, 2 * N:3 * N].copy() if generalized else np.zeros(N)
        dn, vn, an, gn = np.zeros(N), np.zeros(N), np.zeros(N), np.zeros(N)
        rm, rp, g = np.zeros(N), np.zeros(N), np.zeros(N)
        Kb = np.zeros((N, 3 * kb + 1))
        Cb = np.zeros((N, 3 * kb + 1))
        y = np.zeros(N_OUTPUTS)
        if not initial_acceleration(kern, cases, b, mesh, step0 * dt, d, v, acc, w):
            status[b] = SINGULAR
            continue
        if not generalized:
            for i in range(N):
                alg[i] = acc[i]
        step_outputs(kern, sel, params, cases.p[b], mesh, d, w, y)
        for k in range(N_OUTPUTS):
            Y[b, 0, k] = y[k]
        for i in range(S):
            XR[b, 0, i] = X0[b, i]
        # sensitivities (N, width)
        Dd = np.zeros((N, width))
        Dv = np.zeros((N, width))
        Da = np.zeros((N, width))
        Dg = np.zeros((N, width if generalized else 0))
        if with_j:
            for i in range(N):
                Dd[i, i] = 1.0
                Dv[i, N + i] = 1.0
                if generalized:
                    Dg[i, 2 * N + i] = 1.0
            # da0 = -M^-1 (K dd0 + C dv0 + dR/dp) at t0 (initial_acceleration left the kinematics
            # at t0 in w)
            element_loop(FULL, kern, sel, coef, params, False, dofs, l, d, v, acc, 0.0, 0.0, w)
            assemble_band(dofs, kb, w.ME, w.CE, w.KE, 0.0, 0.0, 1.0, Kb)
            assemble_band(dofs, kb, w.ME, w.CE, w.KE, 0.0, 1.0, 0.0, Cb)
            assemble_band(dofs, kb, w.ME, w.CE, w.KE, 1.0, 0.0, 0.0, w.W)
            if not band_factor(w.W, kb, w.piv, w.ext):
                status[b] = SINGULAR
                continue
            if with_p:
                _parameter_forcing(kern, minus, plus, b, sel, mesh, step0, h, d, v, acc, w, rm, rp, g)
            _tangent_rhs(Kb, Cb, kb, Dd, Dv, Da)
            if with_p:
                for i in range(N):
                    Da[i, P] -= g[i]
            band_lu_solve(w.W, kb, w.piv, w.ext, Da)
        ok = True
        hist = np.zeros((HISTORY, N))
        for m in range(n_steps):
            t_new = (step0 + m + 1) * dt
            st, it, rn = newmark_step(kern, cases, b, mesh, scheme, t_new, d, v, acc, alg, hist, min(m, HISTORY),
                                      dn, vn, an, gn, w)
            if st != OK:
                status[b] = st
                ok = False
                break
            if with_j:
                # exact tangents at the converged state, the iteration matrix factorized
                element_loop(FULL, kern, sel, coef, params, False, dofs, l, dn, vn, an, 0.0, 0.0, w)
                assemble_band(dofs, kb, w.ME, w.CE, w.KE, 0.0, 0.0, 1.0, Kb)
                assemble_band(dofs, kb, w.ME, w.CE, w.KE, 0.0, 1.0, 0.0, Cb)
                fixed = False
                if fixed_width(kb):
                    iteration_matrices(w.ME, w.CE, w.KE, cv, cd, w.SE, 0, dofs.shape[0])
                    assemble_fixed(dofs, w.SE, w.F, N)
                    fixed = factor_fixed(w.F, N, w.diag)
                if not fixed:
                    assemble_band(dofs, kb, w.ME, w.CE, w.KE, 1.0, cv, cd, w.W)
                    if not band_factor(w.W, kb, w.piv, w.ext):
                        status[b] = SINGULAR
                        ok = False
                        break
                if with_p:
                    _parameter_forcing(kern, minus, plus, b, sel, mesh, step0 + m + 1, h, dn, vn, an, w, rm, rp, g)
                # predictor sensitivities (in place): Dd <- dd~, Dv <- dv~ (and Dg <- dabar)
                if generalized:
                    for i in range(N):
                        for c in range(width):
                            ab = (af * Da[i, c] - am * Dg[i, c]) / (1.0 - am)
                            Dd[i, c] += dt * Dv[i, c] + c1 * Dg[i, c] + c3 * ab
                            Dv[i, c] += c2 * Dg[i, c] + c4 * ab
                            Dg[i, c] = ab
                else:
                    for i in range(N):
                        for c in range(width):
                            Dd[i, c] += dt * Dv[i, c] + c1 * Da[i, c]
                            Dv[i, c] += c2 * Da[i, c]
                if with_p:
                    for i in range(N):
                        if generalized:
                            abar = (af * acc[i] - am * alg[i]) / (1.0 - am)
                            Dd[i, P] += (v[i] + dt * (1.0 - 2.0 * beta) * alg[i] + 2.0 * beta * dt * abar
                                         + 2.0 * beta * ratio * dt * an[i]) * ddt
                            Dv[i, P] += ((1.0 - gamma) * alg[i] + gamma * abar + gamma * ratio * an[i]) * ddt
                        else:
                            Dd[i, P] += (v[i] + dt * (1.0 - 2.0 * beta) * acc[i] + 2.0 * beta * dt * an[i]) * ddt
                            Dv[i, P] += ((1.0 - gamma) * acc[i] + gamma * an[i]) * ddt
                _tangent_rhs(Kb, Cb, kb, Dd, Dv, Da)
                if with_p:
                    for i in range(N):
                        Da[i, P] -= g[i]
                if fixed:
                    solve_fixed_columns(w.F, Da)
                else:
                    band_lu_solve(w.W, kb, w.piv, w.ext, Da)
                for i in range(N):
                    for c in range(width):
                        Dd[i, c] += cd * Da[i, c]
                        Dv[i, c] += cv * Da[i, c]
                if generalized:
                    for i in range(N):
                        for c in range(width):
                            Dg[i, c] += ratio * Da[i, c]
            for k in range(HISTORY - 1, 0, -1):
                for i in range(N):
                    hist[k, i] = hist[k - 1, i]
            for i in range(N):
                hist[0, i] = d[i]
                d[i] = dn[i]
                v[i] = vn[i]
                acc[i] = an[i]
                alg[i] = gn[i]
            if with_p:                  # _parameter_forcing moved the kinematics to p +- h
                kinematics(kern, sel, params, t_new, w)
            step_outputs(kern, sel, params, cases.p[b], mesh, d, w, y)
            for k in range(N_OUTPUTS):
                Y[b, m + 1, k] = y[k]
            if (m + 1) % spr == 0:
                r = (m + 1) // spr
                for i in range(N):
                    XR[b, r, i] = d[i]
                    XR[b, r, N + i] = v[i]
                    if generalized:
                        XR[b, r, 2 * N + i] = alg[i]
        keep(owned)
        if not ok:
            continue
        for i in range(N):
            X1[b, i] = d[i]
            X1[b, N + i] = v[i]
            if generalized:
                X1[b, 2 * N + i] = alg[i]
        if with_j:
            for i in range(N):
                for c in range(ncol):
                    J[b, i, c] = Dd[i, c]
                    J[b, N + i, c] = Dv[i, c]
                    if generalized:
                        J[b, 2 * N + i, c] = Dg[i, c]


class Revolution:
    """Result of shoot: X1 (B, S) the states after the revolutions, J (B, S, S) = dX1/dX0 (None
    without jacobian), Jp (B, S) = dX1/dp (None without a parameter), y (B, steps + 1, outputs) the
    engine's outputs (schema.ENGINE_OUTPUTS), states (B, revolutions + 1, S) at theta = 0, status
    (B,).  S = batch.state_size: 2N, (d, v), for Newmark; 3N, (d, v, a), for generalized-alpha."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


def shoot(batch, X0, step0=0, active=None, parallel=None, tol=1e-10, max_iter=30, revolutions=1, jacobian=True,
          parameter=None):
    """The map over `revolutions` crank revolutions of the cases' time scheme, with its exact
    Jacobian (jacobian=True) and the orbit it marches, for states X0 (B, S) at step index step0
    (S = batch.state_size: (d, v) for Newmark, (d, v, a) for generalized-alpha).  parameter:
    (minus, plus, h): Batches of the cases at p - h and p + h (case for case like `batch`, same
    mesh and steps per revolution) for the exact derivative dX1/dp (docstring of
    _revolution_cases)."""
    B, N, S = len(batch), batch.N, batch.state_size
    if batch.mesh.coordinates:
        raise ValueError("the revolution map of a time-periodic crank: a driven motion's co-ordinates make the "
                         "motion autonomous (its map is on a section of the crank angle: crankgen.analyses.section)")
    X0 = np.ascontiguousarray(X0, dtype=float)
    if X0.shape != (B, S):
        raise ValueError(f"the states must be ({B}, {S}) (the batch's state size), got {X0.shape}")
    active = np.ones(B, dtype=np.bool_) if active is None else np.asarray(active, dtype=np.bool_)
    with_p = parameter is not None
    if with_p:
        if not jacobian:
            raise ValueError("the parameter derivative comes with the Jacobian (jacobian=True)")
        minus, plus, h = parameter
        if (len(minus) != B or len(plus) != B or minus.N != N or plus.N != N
                or not np.array_equal(minus.records.select, batch.records.select)
                or not np.array_equal(plus.records.select, batch.records.select)
                or not np.array_equal(minus.records.integ, batch.records.integ)
                or not np.array_equal(plus.records.integ, batch.records.integ)):
            raise ValueError("the perturbed batches must match the batch case for case (same models)")
        minus, plus, h = minus.records, plus.records, float(h)
    else:
        minus, plus, h = batch.records, batch.records, 1.0
    n_steps = int(revolutions) * batch.steps_per_rev
    X1 = np.full((B, S), np.nan)
    J = np.full((B, S, S + (1 if with_p else 0)) if jacobian else (1, 1, 1), np.nan)
    Y = np.full((B, n_steps + 1, N_OUTPUTS), np.nan)
    XR = np.full((B, int(revolutions) + 1, S), np.nan)
    status = np.zeros(B, dtype=np.int64)
    if parallel is None:
        parallel = int(active.sum()) > 1
    scheme = Scheme(float(tol), int(max_iter))
    parallel_slices(_revolution_cases, batch, parallel, (batch.records, batch.meshdata, scheme),
                    (step0, n_steps, batch.steps_per_rev, X0, active, minus, plus, h, bool(jacobian), with_p,
                     X1, J, Y, XR, status), active=active)
    return Revolution(X1=X1, J=J[:, :, :S] if jacobian else None, Jp=J[:, :, S] if with_p else None,
                      y=Y, states=XR, status=status)


def revolution(batch, X0, step0=0, active=None, parallel=None, tol=1e-10, max_iter=30, revolutions=1):
    """(X1, J, status): the map over `revolutions` crank revolutions of the cases' time scheme and
    its Jacobian, for states X0 (B, batch.state_size) at step index step0."""
    r = shoot(batch, X0, step0, active, parallel, tol, max_iter, revolutions)
    return r.X1, r.J, r.status


@entry_point("revolution")
def _compile_revolution():
    batch = compiling_batch()
    revolution(batch, np.zeros((1, batch.state_size)), parallel=False)
