"""The revolution map of the Newton-Newmark scheme and its exact linearization (compiled), for
shooting on periodic states (steady.py) and continuation."""

import numpy as np

from .. import newton
from .banded import assemble_band, band_factor, band_lu_solve, band_matmul, band_solve
from .compiled import jit
from .elements import FULL, element_loop
from .march import parallel_slices
from .records import Scheme, make_work
from .step import OK, SINGULAR, initial_acceleration, newmark_step

HISTORY = newton.HISTORY


@jit
def _revolution_cases(kern, cases, mesh, scheme, lo, hi, step0, n_steps, X0, active, X1, J, status):
    """For every active case of lo..hi-1: state x = (d, v) at step step0 -> state after n_steps
    Newton steps, and J = dx1/dx0, the exact linearization of the converged Newmark steps:
        S da' = -(K dd~ + C dv~),  dd' = dd~ + beta dt^2 da',  dv' = dv~ + gamma dt da'
    with S, K, C the exact tangents at the converged state of each step (a0 from eq. 34)."""
    n = mesh.dofs.shape[0]
    N = X0.shape[1] // 2
    dofs, kb, l = mesh.dofs, mesh.kb, mesh.l
    beta, gamma = scheme.beta, scheme.gamma
    for b in range(lo, hi):
        if not active[b]:
            continue
        w = make_work(n, N, kb)
        sel, coef, params = cases.select[b], cases.coef[b], cases.params[b]
        dt = cases.dt[b]
        cd, cv = beta * dt * dt, gamma * dt
        d, v = X0[b, :N].copy(), X0[b, N:].copy()
        acc = np.zeros(N)
        dn, vn, an = np.zeros(N), np.zeros(N), np.zeros(N)
        if not initial_acceleration(kern, cases, b, mesh, step0 * dt, d, v, acc, w):
            status[b] = SINGULAR
            continue
        # sensitivities (N, 2N)
        Dd = np.zeros((N, 2 * N))
        Dv = np.zeros((N, 2 * N))
        for i in range(N):
            Dd[i, i] = 1.0
            Dv[i, N + i] = 1.0
        Da = np.zeros((N, 2 * N))
        tmp = np.zeros((N, 2 * N))
        # da0 = -M^-1 (K dd0 + C dv0) at t0 (initial_acceleration left the kinematics at t0 in w)
        element_loop(FULL, kern, sel, coef, params, False, dofs, l, d, v, acc, 0.0, 0.0, w)
        band_matmul(dofs, kb, w.KE, Dd, Da)
        band_matmul(dofs, kb, w.CE, Dv, tmp)
        for i in range(N):
            for c in range(2 * N):
                Da[i, c] = -(Da[i, c] + tmp[i, c])
        assemble_band(dofs, kb, w.ME, w.CE, w.KE, 1.0, 0.0, 0.0, w.W)
        if not band_solve(w.W, kb, Da):
            status[b] = SINGULAR
            continue
        ok = True
        hist = np.zeros((HISTORY, N))
        for m in range(n_steps):
            t_new = (step0 + m + 1) * dt
            st, it, rn = newmark_step(kern, cases, b, mesh, scheme, t_new, d, v, acc, hist, min(m, HISTORY),
                                      dn, vn, an, w)
            if st != OK:
                status[b] = st
                ok = False
                break
            # predictor sensitivities (in place): Dd <- dd~, Dv <- dv~
            for i in range(N):
                for c in range(2 * N):
                    Dd[i, c] = Dd[i, c] + dt * Dv[i, c] + 0.5 * dt * dt * (1.0 - 2.0 * beta) * Da[i, c]
                    Dv[i, c] = Dv[i, c] + dt * (1.0 - gamma) * Da[i, c]
            # exact tangents at the converged state
            element_loop(FULL, kern, sel, coef, params, False, dofs, l, dn, vn, an, 0.0, 0.0, w)
            band_matmul(dofs, kb, w.KE, Dd, Da)
            band_matmul(dofs, kb, w.CE, Dv, tmp)
            for i in range(N):
                for c in range(2 * N):
                    Da[i, c] = -(Da[i, c] + tmp[i, c])
            assemble_band(dofs, kb, w.ME, w.CE, w.KE, 1.0, cv, cd, w.W)
            if not band_factor(w.W, kb, w.piv, w.ext):
                status[b] = SINGULAR
                ok = False
                break
            band_lu_solve(w.W, kb, w.piv, w.ext, Da)
            for i in range(N):
                for c in range(2 * N):
                    Dd[i, c] += cd * Da[i, c]
                    Dv[i, c] += cv * Da[i, c]
            for k in range(HISTORY - 1, 0, -1):
                for i in range(N):
                    hist[k, i] = hist[k - 1, i]
            for i in range(N):
                hist[0, i] = d[i]
                d[i] = dn[i]
                v[i] = vn[i]
                acc[i] = an[i]
        if not ok:
            continue
        for i in range(N):
            X1[b, i] = d[i]
            X1[b, N + i] = v[i]
            for c in range(2 * N):
                J[b, i, c] = Dd[i, c]
                J[b, N + i, c] = Dv[i, c]


def revolution(batch, X0, step0=0, active=None, parallel=None, beta=0.25, gamma=0.5, tol=1e-10,
               max_iter=30, revolutions=1):
    """(X1, J, status): the map over `revolutions` crank revolutions of the Newton-Newmark scheme and
    its Jacobian, for states X0 (B, 2N) = (d, v) at step index step0."""
    B, N = len(batch), batch.N
    X0 = np.ascontiguousarray(X0, dtype=float)
    active = np.ones(B, dtype=np.bool_) if active is None else np.asarray(active, dtype=np.bool_)
    X1 = np.full((B, 2 * N), np.nan)
    J = np.full((B, 2 * N, 2 * N), np.nan)
    status = np.zeros(B, dtype=np.int64)
    if parallel is None:
        parallel = int(active.sum()) > 1
    scheme = Scheme(float(beta), float(gamma), float(tol), int(max_iter))
    parallel_slices(_revolution_cases, B, parallel, (batch.kernels, batch.records, batch.meshdata, scheme),
                    (step0, int(revolutions) * batch.steps_per_rev, X0, active, X1, J, status))
    return X1, J, status
