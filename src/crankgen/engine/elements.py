"""The element loop of the compiled engine: gather each element's nodal state, map the end node
through the guide's end map, call the case's term families (tables of compiled kernels, indexed by
the case's `select` row: engine/kernels.py), project the end element's terms on the reduced
co-ordinate (the exact constraint elimination of constraints.py), and the per-step outputs.

Three modes: FULL (residual and tangents K, C, M), NEWMARK (residual and the iteration matrix
S = M + cv C + cd K of eq. 37; interior elements through the accumulating `_newmark_add` kernels),
RESIDUAL (residual only, for iterations that reuse a factorization).  Nothing here names a family,
a guide or a motion.
"""

from .. import schema
from .compiled import jit
from .kernels import GUIDE_SLOT, MOTION_SLOT, N_END, N_ROD
from .records import NDOF

FULL, NEWMARK, RESIDUAL = 0, 1, 2
IU, IV = schema.END_SLOTS                      # the end node's (u, v) in the last element's vector
_R = schema.END_MAP_ROWS
Q, QD, QDD, G_S, DQD_DS, DQDD_DS, DQDD_DSD, G_SS = (_R[k] for k in (
    "q", "qd", "qdd", "g_s", "dqd_ds", "dqdd_ds", "dqdd_dsd", "g_ss"))
PHI = schema.KIN["phi"]


@jit
def kinematics(kern, sel, params, t, w):
    """w.kin at time t: the crank motion's (theta, thetad, thetadd), then the guide's closure."""
    kern.motion[sel[MOTION_SLOT]](t, params, w.crank)
    kern.guide[sel[GUIDE_SLOT]](w.crank, params, w.kin)


@jit
def end_map(kern, sel, params, s, sd, sdd, w):
    """w.E: the end map at the reduced end co-ordinate (s, sd, sdd) and w.kin."""
    w.send[0] = s
    w.send[1] = sd
    w.send[2] = sdd
    kern.end_map[sel[GUIDE_SLOT]](w.send, w.kin, params, w.E)


@jit
def project_residual(E, r):
    """r <- the reduced residual: the end node's rows become g_s . r_end (d'Alembert), in the
    reduced co-ordinate's slot IU; slot IV is unused."""
    r[IU] = E[G_S, 0] * r[IU] + E[G_S, 1] * r[IV]
    r[IV] = 0.0


@jit
def project_last(E, r, K, C, M):
    """The end element's terms on the reduced co-ordinate s of its end node, (u, v) = g(s, t):
        columns: K' = K dq/ds + C dqd/ds + M dqdd/ds,  C' = C dqd/dsd + M dqdd/dsd,  M' = M g_s;
        rows: g_s^T (...), and K'[s, s] += g_ss . r_end (the end map's curvature);
        r' = g_s . r_end  (dqd/dsd = dqdd/dsdd = g_s)."""
    gs0, gs1 = E[G_S, 0], E[G_S, 1]
    a0, a1 = E[DQD_DS, 0], E[DQD_DS, 1]
    b0, b1 = E[DQDD_DS, 0], E[DQDD_DS, 1]
    c0, c1 = E[DQDD_DSD, 0], E[DQDD_DSD, 1]
    for i in range(NDOF):               # right factors: column IU changes, column IV vanishes
        k3, k4, c3, c4, m3, m4 = K[i, IU], K[i, IV], C[i, IU], C[i, IV], M[i, IU], M[i, IV]
        K[i, IU] = gs0 * k3 + gs1 * k4 + a0 * c3 + a1 * c4 + b0 * m3 + b1 * m4
        C[i, IU] = gs0 * c3 + gs1 * c4 + (c0 * m3 + c1 * m4)
        M[i, IU] = gs0 * m3 + gs1 * m4
        K[i, IV] = 0.0
        C[i, IV] = 0.0
        M[i, IV] = 0.0
    for j in range(NDOF):               # g_s^T from the left: row IU combines rows IU and IV
        K[IU, j] = gs0 * K[IU, j] + gs1 * K[IV, j]
        C[IU, j] = gs0 * C[IU, j] + gs1 * C[IV, j]
        M[IU, j] = gs0 * M[IU, j] + gs1 * M[IV, j]
        K[IV, j] = 0.0
        C[IV, j] = 0.0
        M[IV, j] = 0.0
    K[IU, IU] += E[G_SS, 0] * r[IU] + E[G_SS, 1] * r[IV]
    project_residual(E, r)


def _gather(dofs, e, d, v, acc, q, qd, qdd):
    """Nodal q, qd, qdd of element e (a pinned or constrained slot reads 0)."""
    N = d.shape[0]
    for k in range(NDOF):
        idx = dofs[e, k]
        if idx < N:
            q[k] = d[idx]
            qd[k] = v[idx]
            qdd[k] = acc[idx]
        else:
            q[k] = 0.0
            qd[k] = 0.0
            qdd[k] = 0.0


_gather = jit(_gather, inline="always")


def _map_end(kern, sel, params, q, qd, qdd, w):
    """The last element's end node: slot IU holds the reduced co-ordinate s (and its rates); the
    end map gives (u, v) and their rates."""
    end_map(kern, sel, params, q[IU], qd[IU], qdd[IU], w)
    E = w.E
    q[IU], q[IV] = E[Q, 0], E[Q, 1]
    qd[IU], qd[IV] = E[QD, 0], E[QD, 1]
    qdd[IU], qdd[IV] = E[QDD, 0], E[QDD, 1]


_map_end = jit(_map_end, inline="always")


@jit
def element_loop(mode, kern, sel, coef, params, printed, dofs, l, d, v, acc, cv, cd, w):
    """Element terms of one case into w.rE and (by mode) w.KE, w.CE, w.ME / w.SE, at w.kin; the
    end element's terms are projected on the reduced end co-ordinate.  printed: the one-pass
    scheme's printed iteration matrices."""
    n = dofs.shape[0]
    q, qd, qdd, geo, kin = w.q, w.qd, w.qdd, w.geo, w.kin
    rE, KE, CE, ME, SE = w.rE, w.KE, w.CE, w.ME, w.SE
    geo[0] = l
    for e in range(n):
        last = e == n - 1
        _gather(dofs, e, d, v, acc, q, qd, qdd)
        if last:
            _map_end(kern, sel, params, q, qd, qdd, w)
        geo[1] = e * l
        r = rE[e]
        r[:] = 0.0
        if mode == RESIDUAL:
            for k in range(N_ROD):
                i = sel[k]
                if i >= 0:
                    kern.rod_residual[i](q, qd, qdd, geo, coef, kin, r)
            if last:
                for k in range(N_END):
                    i = sel[N_ROD + k]
                    if i >= 0:
                        kern.end_residual[i](q, qd, qdd, geo, coef, kin, r)
                project_residual(w.E, r)
            continue
        if mode == NEWMARK and not last and not printed:
            S = SE[e]
            S[:, :] = 0.0
            for k in range(N_ROD):
                i = sel[k]
                if i >= 0:
                    kern.rod_newmark[i](q, qd, qdd, geo, coef, kin, cv, cd, r, S)
            continue
        K, C, M = KE[e], CE[e], ME[e]
        K[:, :] = 0.0
        C[:, :] = 0.0
        M[:, :] = 0.0
        for k in range(N_ROD):
            i = sel[k]
            if i >= 0:
                if printed:
                    kern.rod_printed[i](q, qd, qdd, geo, coef, kin, r, K, C, M)
                else:
                    kern.rod_add[i](q, qd, qdd, geo, coef, kin, r, K, C, M)
        if last:
            for k in range(N_END):
                i = sel[N_ROD + k]
                if i >= 0:
                    if printed:
                        kern.end_printed[i](q, qd, qdd, geo, coef, kin, r, K, C, M)
                    else:
                        kern.end_add[i](q, qd, qdd, geo, coef, kin, r, K, C, M)
            project_last(w.E, r, K, C, M)
        if mode == NEWMARK:
            for i in range(NDOF):
                for j in range(NDOF):
                    SE[e, i, j] = ME[e, i, j] + cv * CE[e, i, j] + cd * KE[e, i, j]


@jit
def step_outputs(kern, sel, params, dofs, mid_e, Nv_mid, G, eps, d, w, out):
    """out = (v* at x* = 1/2, u*(1), delta* of eq. 40) of the state d at w.kin."""
    n = dofs.shape[0]
    N = d.shape[0]
    q = w.q
    vmid = 0.0
    slope = 0.0
    u_end = 0.0
    for e in range(n):
        for k in range(NDOF):
            idx = dofs[e, k]
            q[k] = d[idx] if idx < N else 0.0
        if e == n - 1:
            end_map(kern, sel, params, q[IU], 0.0, 0.0, w)
            q[IU] = w.E[Q, 0]
            q[IV] = w.E[Q, 1]
            u_end = q[IU]
        if e == mid_e:
            for k in range(NDOF):
                vmid += Nv_mid[k] * q[k]
        for i in range(NDOF):
            for j in range(NDOF):
                slope += q[i] * G[i, j] * q[j]
    out[0] = vmid / eps
    out[1] = u_end / (eps * eps)
    out[2] = u_end + 0.5 * slope
