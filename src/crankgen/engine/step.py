"""One Newmark step of one case (compiled), the same scheme as newmark.py: predictors (35)-(36),
Newton iterations on a_{m+1} with the decisions of newton.py (shared with the NumPy reference),
correctors (38)-(39); and the initial acceleration of eq. (34).  The state is the DOF map's: the
rods' nodal co-ordinates, then the co-ordinates a driven motion declares (the crank angle of a
motor, ...), whose equations border the band (coordinates.py); a prescribed crank has none, and
its step is the band's alone.

Arguments travel as records (records.py): `kern` (the model's kernel tables), `cases` with the row
`b` of the case at hand, `mesh`, `scheme`, and the case's Work arrays `w`."""

import math

import numpy as np

from ..discrete import newton, time_scheme
from .banded import (assemble_band, assemble_band_newmark, assemble_fixed, assemble_vector,
                     band_factor, band_lu_solve, band_solve, factor_fixed, fixed_width, solve_fixed)
from .compiled import jit
from .coordinates import (COLUMN_STEP, border_rows, bordered_solve, equations, schur, solve_band,
                          state_kinematics)
from .elements import FULL, NEWMARK, RESIDUAL, element_loop, kinematics
from .kernels import extrapolation_weight, next_iteration

# status codes of a case
OK, NOT_CONVERGED, SINGULAR, NOT_FINITE, TOO_LARGE = 0, 1, 2, 3, 4
STATUS_TEXT = {OK: "ok", NOT_CONVERGED: "Newton did not converge", SINGULAR: "singular iteration matrix",
               NOT_FINITE: "non-finite state", TOO_LARGE: newton.DIVERGED_TEXT}
ONE_PASS = newton.ONE_PASS
DIVERGED = newton.DIVERGED
STARTER_BETA, STARTER_GAMMA = time_scheme.STARTER.beta, time_scheme.STARTER.gamma

@jit(python=False)
def initial_acceleration(kern, cases, b, mesh, t0, d, v, out, w):
    """Solve R(t0, d, v, a) = 0 for a (eq. 34; R is linear in a), with the declared co-ordinates'
    equations g = 0 (two bordered solves: the crank's column is differenced).  Returns False if
    singular."""
    N = d.shape[0]
    n_rod = mesh.n_rod
    m = N - n_rod
    sel, coef, params = cases.select[b], cases.coef[b], cases.params[b]
    kb = mesh.kb
    if m == 0:
        kinematics(kern, sel, params, t0, w)
        zero = np.zeros(N)
        element_loop(FULL, kern, sel, coef, params, False, mesh.dofs, mesh.l, d, v, zero, 0.0, 0.0, w)
        assemble_vector(mesh.dofs, w.rE, w.R)
        W = np.zeros((N, 3 * kb + 1))
        assemble_band(mesh.dofs, kb, w.ME, w.CE, w.KE, 1.0, 0.0, 0.0, W)
        rhs = np.zeros((N, 1))
        for i in range(N):
            rhs[i, 0] = -w.R[i]
        ok = band_solve(W, kb, rhs)
        for i in range(N):
            out[i] = rhs[i, 0]
        return ok
    a = np.zeros(N)
    for _ in range(2):
        state_kinematics(kern, params, mesh, t0, d, v, a, w)
        element_loop(FULL, kern, sel, coef, params, False, mesh.dofs, mesh.l, d, v, a, 0.0, 0.0, w)
        assemble_vector(mesh.dofs, w.rE, w.R)
        equations(kern, cases, b, mesh, d, v, a, w, w.geq)
        for i in range(n_rod):
            w.R0[i] = w.R[i]
        assemble_band(mesh.dofs, kb, w.ME, w.CE, w.KE, 1.0, 0.0, 0.0, w.W)
        if not band_factor(w.W, kb, w.piv, w.ext):
            return False
        border_rows(mesh, w.geq, w.ME[0], m, w.Cb)
        h = 1.0
        if mesh.crank_index >= 0:
            c = n_rod + mesh.crank_index
            keep = a[c]
            h = COLUMN_STEP * max(1.0, abs(keep))
            a[c] = keep + h
            state_kinematics(kern, params, mesh, t0, d, v, a, w)
            element_loop(RESIDUAL, kern, sel, coef, params, False, mesh.dofs, mesh.l, d, v, a, 0.0, 0.0, w)
            assemble_vector(mesh.dofs, w.rE, w.R)
            equations(kern, cases, b, mesh, d, v, a, w, w.geq1)
            a[c] = keep
        if not schur(False, mesh, kb, w.geq, w.geq1, w.R0, w.R, h, 0.0, 0.0, w):
            return False
        for i in range(n_rod):
            w.rhs[i, 0] = -w.R0[i]
        band_lu_solve(w.W, kb, w.piv, w.ext, w.rhs)
        bordered_solve(m, n_rod, w, w.geq)
        for i in range(n_rod):
            a[i] += w.rhs[i, 0]
        for j in range(m):
            a[n_rod + j] += w.gz[j]
    for i in range(N):
        out[i] = a[i]
    return True


@jit(python=False)
def newmark_step(kern, cases, b, mesh, scheme, t_new, d, v, acc, alg, hist, n_prev, d_new, v_new, a_new, alg_new, w,
                 start=False):
    """One step of case b from (d, v, acc, alg) to (d_new, v_new, a_new, alg_new) at t_new: Newmark,
    or generalized-alpha in Arnold & Bruls' form (crankgen.discrete.time_scheme; the case's row of
    cases.integ: beta, gamma, alpha_m, alpha_f).  acc: the accelerations qdd (R = 0 holds with
    them), alg: the algorithmic accelerations (for Newmark read as acc).  The predictors
        dp = d + dt v + dt^2 (1/2 - beta) alg + dt^2 beta abar,  vp = v + dt (1 - gamma) alg + dt gamma abar,
        abar = (alpha_f acc - alpha_m alg) / (1 - alpha_m)  (0 for Newmark: eqs. 35-36),
    then Newton on a_new = qdd_{n+1}, d_new = dp + cd a_new, v_new = vp + cv a_new (eqs. 38-39),
    cd = beta r dt^2, cv = gamma r dt, r = (1 - alpha_f) / (1 - alpha_m); alg_new = abar + r a_new.
    The state holds the rods' nodal co-ordinates (mesh.n_rod), then the declared co-ordinates,
    whose equations border the iteration matrix (coordinates.py); their scaled increments count in
    Newton's test, the divergence test reads the nodal co-ordinates alone (a crank angle grows).
    hist[k]: the states k + 1 steps before d, of which the first n_prev (0 to HISTORY) are
    known, for the starting guess.  start: the first step of a generalized-alpha run from a state
    without algorithmic accelerations, taken with Newmark's beta = 1/2, gamma = 1 (STARTER:
    crankgen.discrete.time_scheme), alg_new = a_new.  Returns (status, iterations, residual norm)."""
    N = d.shape[0]
    n_rod = mesh.n_rod
    m = N - n_rod
    sel, coef, params, scales = cases.select[b], cases.coef[b], cases.params[b], cases.scales[b]
    dofs, kb, l = mesh.dofs, mesh.kb, mesh.l
    tol, max_iter = scheme.tol, scheme.max_iter
    beta, gamma, am, af = cases.integ[b, 0], cases.integ[b, 1], cases.integ[b, 2], cases.integ[b, 3]
    generalized = am != 0.0 or af != 0.0
    if start and generalized:
        beta, gamma, am, af = STARTER_BETA, STARTER_GAMMA, 0.0, 0.0
        generalized = False
    ratio = (1.0 - af) / (1.0 - am)
    dt = cases.dt[b]
    code = cases.scheme[b]
    one_pass = code == ONE_PASS
    printed = one_pass and cases.printed[b]
    cd = beta * dt * dt * ratio
    cv = gamma * dt * ratio
    if m == 0:
        kinematics(kern, sel, params, t_new, w)
    R, rhs, dp, vp = w.R, w.rhs, w.dp, w.vp
    for i in range(N):                  # predictors
        if generalized:
            abar = (af * acc[i] - am * alg[i]) / (1.0 - am)
            alg_new[i] = abar
            dp[i] = d[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * alg[i] + dt * dt * beta * abar
            vp[i] = v[i] + dt * (1.0 - gamma) * alg[i] + dt * gamma * abar
        else:
            dp[i] = d[i] + dt * v[i] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * acc[i]
            vp[i] = v[i] + dt * (1.0 - gamma) * acc[i]
    for i in range(N):
        if one_pass:
            a_new[i] = 0.0
        elif n_prev == 0:
            a_new[i] = acc[i]
        else:                           # d_{m+1} on the extrapolation of the last displacements
            dx = 0.0
            for k in range(n_prev, 0, -1):
                dx += extrapolation_weight(n_prev, k) * hist[k - 1, i]
            dx += extrapolation_weight(n_prev, 0) * d[i]
            a_new[i] = (dx - dp[i]) / cd
    rnorm = 0.0
    refresh = True
    full = False
    fixed = False
    previous = 0.0
    reused_before = False
    for i in range(N):                  # eqs. (38)-(39) at the starting guess
        d_new[i] = dp[i] + cd * a_new[i]
        v_new[i] = vp[i] + cv * a_new[i]
    for it in range(1, max_iter + 1):
        mode = NEWMARK if refresh else RESIDUAL
        if m > 0:                       # the crank's kinematics from the state
            state_kinematics(kern, params, mesh, t_new, d_new, v_new, a_new, w)
        element_loop(mode, kern, sel, coef, params, printed, dofs, l, d_new, v_new, a_new, cv, cd, w)
        assemble_vector(dofs, w.rE, R)
        rnorm = 0.0
        for i in range(n_rod):
            rnorm += R[i] * R[i]
        if m > 0:
            equations(kern, cases, b, mesh, d_new, v_new, a_new, w, w.geq)
            for i in range(m):
                rnorm += w.geq[i, 0] * w.geq[i, 0]
        rnorm = math.sqrt(rnorm)
        if not np.isfinite(rnorm):
            return NOT_FINITE, it, rnorm
        if refresh:
            fixed = False
            if fixed_width(kb):
                assemble_fixed(dofs, w.SE, w.F, n_rod)
                fixed = factor_fixed(w.F, n_rod, w.diag)
            if not fixed:
                assemble_band_newmark(dofs, kb, w.SE, w.W)
                if not band_factor(w.W, kb, w.piv, w.ext):
                    return SINGULAR, it, rnorm
            if m > 0 and not _border(kern, cases, b, mesh, t_new, d_new, v_new, a_new, cv, cd, fixed, w):
                return SINGULAR, it, rnorm
        for i in range(n_rod):
            rhs[i, 0] = -R[i]
        if fixed:
            solve_fixed(w.F, n_rod, rhs[:, 0])
        else:
            band_lu_solve(w.W, kb, w.piv, w.ext, rhs)
        if m > 0:
            bordered_solve(m, n_rod, w, w.geq)
        inc = 0.0
        size = 0.0
        largest = 0.0
        for i in range(n_rod):
            a_new[i] += rhs[i, 0]
            x = abs(cd * rhs[i, 0]) / scales[i]
            if x > inc:
                inc = x
        for j in range(m):
            a_new[n_rod + j] += w.gz[j]
            x = abs(cd * w.gz[j]) / scales[n_rod + j]
            if x > inc:
                inc = x
        for i in range(N):
            d_new[i] = dp[i] + cd * a_new[i]
            v_new[i] = vp[i] + cv * a_new[i]
            if i < n_rod:
                x = abs(d_new[i]) / scales[i]
                if x > size:
                    size = x
                if abs(d_new[i]) > largest:
                    largest = abs(d_new[i])
        if not np.isfinite(inc):
            return NOT_FINITE, it, rnorm
        done, reject, refresh, reused_before, full = next_iteration(code, it, inc, previous, size, tol,
                                                                    refresh, reused_before, full)
        if done:
            if not largest < DIVERGED:
                return TOO_LARGE, it, rnorm
            for i in range(N):
                alg_new[i] = alg_new[i] + ratio * a_new[i] if generalized else a_new[i]
            return OK, it, rnorm
        if reject:                      # undo the update of a diverging reused factorization
            for i in range(n_rod):
                a_new[i] -= rhs[i, 0]
            for j in range(m):
                a_new[n_rod + j] -= w.gz[j]
            for i in range(N):
                d_new[i] = dp[i] + cd * a_new[i]
                v_new[i] = vp[i] + cv * a_new[i]
            continue
        previous = inc
    return NOT_CONVERGED, max_iter, rnorm


@jit(python=False)
def _border(kern, cases, b, mesh, t_new, d_new, v_new, a_new, cv, cd, fixed, w):
    """With a fresh factorization of the band: the border of the declared co-ordinates (their rows
    C^T from the first element's iteration matrix, the crank's column differenced at the state
    bumped by h in its acceleration, the Schur complement; coordinates.py).  w.R keeps the residual
    at the state.  Returns False if singular."""
    n_rod = mesh.n_rod
    m = d_new.shape[0] - n_rod
    sel, coef, params = cases.select[b], cases.coef[b], cases.params[b]
    for i in range(n_rod):
        w.R0[i] = w.R[i]
    border_rows(mesh, w.geq, w.SE[0], m, w.Cb)
    h = 1.0
    if mesh.crank_index >= 0:
        c = n_rod + mesh.crank_index
        z, zd, zdd = d_new[c], v_new[c], a_new[c]
        h = COLUMN_STEP * max(1.0, abs(zdd))
        d_new[c] = z + cd * h
        v_new[c] = zd + cv * h
        a_new[c] = zdd + h
        state_kinematics(kern, params, mesh, t_new, d_new, v_new, a_new, w)
        element_loop(RESIDUAL, kern, sel, coef, params, False, mesh.dofs, mesh.l, d_new, v_new, a_new, cv, cd, w)
        assemble_vector(mesh.dofs, w.rE, w.R)
        equations(kern, cases, b, mesh, d_new, v_new, a_new, w, w.geq1)
        d_new[c], v_new[c], a_new[c] = z, zd, zdd
    ok = schur(fixed, mesh, mesh.kb, w.geq, w.geq1, w.R0, w.R, h, cv, cd, w)
    for i in range(n_rod):
        w.R[i] = w.R0[i]
    return ok
