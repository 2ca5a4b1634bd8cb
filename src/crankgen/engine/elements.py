"""The element loop of the compiled engine: gather each element's nodal state, apply the slider map
on the last element, call the generated dispatch of the case's term families, project the last
element's terms (the exact constraint elimination of constraints.py), and the per-step outputs.

Three modes: FULL (residual and tangents K, C, M), NEWMARK (residual and the iteration matrix
S = M + cv C + cd K of eq. 37; interior elements through the accumulating `_newmark_add` kernels),
RESIDUAL (residual only, for iterations that reuse a factorization).
"""

import math

from .compiled import jit
from .kernels import end_add, end_residual_add, rod_add, rod_newmark_add, rod_residual_add

FULL, NEWMARK, RESIDUAL = 0, 1, 2
PHI, PHID, PHIDD = 3, 4, 5          # places of phi, phid, phidd in kin (a, theta, thetad, phi, phid, phidd)


@jit
def project_residual(c, s, r):
    """r <- T^T r of the slider map (c, s = cos phi, sin phi): see project_last."""
    r[3] = c * r[3] + s * r[4]
    r[4] = 0.0


@jit
def project_last(kin, r, K, C, M):
    """The slider map of the last element, q = T p with T = I except T[3, 3] = cos phi,
    T[4, 3] = sin phi, T[4, 4] = 0 (constraints.py):
        r <- T^T r,  M <- T^T M T,  C <- T^T (C T + 2 M Td),  K <- T^T (K T + C Td + M Tdd),
    written out for the two non-trivial columns and rows of T, Td and Tdd."""
    ph, phd, phdd = kin[PHI], kin[PHID], kin[PHIDD]
    c, s = math.cos(ph), math.sin(ph)
    td3, td4 = -s * phd, c * phd                                   # Td[3, 3], Td[4, 3]
    tdd3, tdd4 = -c * phd * phd - s * phdd, -s * phd * phd + c * phdd   # Tdd[3, 3], Tdd[4, 3]
    for i in range(6):                  # right factors: only column 3 changes, column 4 vanishes
        k3, k4, c3, c4, m3, m4 = K[i, 3], K[i, 4], C[i, 3], C[i, 4], M[i, 3], M[i, 4]
        K[i, 3] = c * k3 + s * k4 + td3 * c3 + td4 * c4 + tdd3 * m3 + tdd4 * m4
        C[i, 3] = c * c3 + s * c4 + 2.0 * (td3 * m3 + td4 * m4)
        M[i, 3] = c * m3 + s * m4
        K[i, 4] = 0.0
        C[i, 4] = 0.0
        M[i, 4] = 0.0
    for j in range(6):                  # T^T from the left: row 3 combines rows 3 and 4
        K[3, j] = c * K[3, j] + s * K[4, j]
        C[3, j] = c * C[3, j] + s * C[4, j]
        M[3, j] = c * M[3, j] + s * M[4, j]
        K[4, j] = 0.0
        C[4, j] = 0.0
        M[4, j] = 0.0
    project_residual(c, s, r)


def _gather(dofs, e, d, v, acc, kin, last, q, qd, qdd):
    """Nodal q, qd, qdd of element e; on the last element the slider slot s becomes
    (u, v) = s (cos phi, sin phi) with the rates of that rheonomic map (constraints.expand)."""
    N = d.shape[0]
    for k in range(6):
        idx = dofs[e, k]
        if idx < N:
            q[k] = d[idx]
            qd[k] = v[idx]
            qdd[k] = acc[idx]
        else:
            q[k] = 0.0
            qd[k] = 0.0
            qdd[k] = 0.0
    if last:
        ph, phd, phdd = kin[PHI], kin[PHID], kin[PHIDD]
        c, s = math.cos(ph), math.sin(ph)
        p, pd, pdd = q[3], qd[3], qdd[3]
        q[3] = c * p
        q[4] = s * p
        qd[3] = c * pd - s * phd * p
        qd[4] = s * pd + c * phd * p
        qdd[3] = c * pdd - 2.0 * s * phd * pd - (c * phd * phd + s * phdd) * p
        qdd[4] = s * pdd + 2.0 * c * phd * pd + (-s * phd * phd + c * phdd) * p


_gather = jit(_gather, inline="always")


@jit
def element_loop(mode, families, coef, printed, dofs, l, d, v, acc, kin, cv, cd, w):
    """Element terms of one case into w.rE and (by mode) w.KE, w.CE, w.ME / w.SE; the last element's
    terms are projected by the slider map.  printed: the one-pass scheme's printed matrices."""
    n = dofs.shape[0]
    q, qd, qdd, geo = w.q, w.qd, w.qdd, w.geo
    rE, KE, CE, ME, SE = w.rE, w.KE, w.CE, w.ME, w.SE
    geo[0] = l
    for e in range(n):
        last = e == n - 1
        _gather(dofs, e, d, v, acc, kin, last, q, qd, qdd)
        geo[1] = e * l
        rE[e, :] = 0.0
        if mode == RESIDUAL:
            rod_residual_add(families, q, qd, qdd, geo, coef, kin, rE[e])
            if last:
                end_residual_add(families, q, qd, qdd, geo, coef, kin, rE[e])
                project_residual(math.cos(kin[PHI]), math.sin(kin[PHI]), rE[e])
            continue
        if mode == NEWMARK and not last and not printed:
            SE[e, :, :] = 0.0
            rod_newmark_add(families, q, qd, qdd, geo, coef, kin, cv, cd, rE[e], SE[e])
            continue
        KE[e, :, :] = 0.0
        CE[e, :, :] = 0.0
        ME[e, :, :] = 0.0
        rod_add(families, printed, q, qd, qdd, geo, coef, kin, rE[e], KE[e], CE[e], ME[e])
        if last:
            end_add(families, printed, q, qd, qdd, geo, coef, kin, rE[e], KE[e], CE[e], ME[e])
            project_last(kin, rE[e], KE[e], CE[e], ME[e])
        if mode == NEWMARK:
            for i in range(6):
                for j in range(6):
                    SE[e, i, j] = ME[e, i, j] + cv * CE[e, i, j] + cd * KE[e, i, j]


@jit
def step_outputs(dofs, mid_e, Nv_mid, G, eps, phi, d, q, out):
    """out = (v* at x* = 1/2, u*(1), delta* of eq. 40) of the state d (q: scratch 6-vector)."""
    n = dofs.shape[0]
    N = d.shape[0]
    c, s = math.cos(phi), math.sin(phi)
    vmid = 0.0
    slope = 0.0
    u_end = 0.0
    for e in range(n):
        for k in range(6):
            idx = dofs[e, k]
            q[k] = d[idx] if idx < N else 0.0
        if e == n - 1:
            p = q[3]
            q[3] = c * p
            q[4] = s * p
            u_end = q[3]
        if e == mid_e:
            for k in range(6):
                vmid += Nv_mid[k] * q[k]
        for i in range(6):
            for j in range(6):
                slope += q[i] * G[i, j] * q[j]
    out[0] = vmid / eps
    out[1] = u_end / (eps * eps)
    out[2] = u_end + 0.5 * slope
