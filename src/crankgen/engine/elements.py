"""The element loop of the compiled engine: gather the elements' nodal states, map the end node
through the guide's end map, call the case's term families (the model's table of compiled kernels,
one per family slot: engine/kernels.py), the rod's families on lanes of schema.LANES elements a
call (their loop over the elements vectorized), project the end element's terms on the reduced
co-ordinate (the exact constraint elimination of constraints.py), and the per-step outputs.

Three modes: FULL (residual and tangents K, C, M), NEWMARK (residual and the iteration matrix
S = M + cv C + cd K of eq. 37: each kernel's newmark mode, except for the end element, whose
separate matrices the projection needs), RESIDUAL (residual only, for iterations that reuse a
factorization).  Nothing here names a family, a guide or a motion.
"""

from .. import schema
from .._generated import per_step as _per_step
from .calls import call
from .compiled import jit, plain
from .kernels import N_END, N_ROD
from .records import NDOF

FULL, NEWMARK, RESIDUAL = 0, 1, 2          # what the element loop computes
# what an element kernel adds, by its mode argument (derive/emit.py)
ADD_FULL, ADD_PRINTED, ADD_RESIDUAL, ADD_NEWMARK = (schema.ELEMENT_MODES.index(m) for m in (
    "full", "printed", "residual", "newmark"))
IU, IV = schema.END_SLOTS                      # the end node's (u, v) in the last element's vector
_R = schema.END_MAP_ROWS
Q, QD, QDD, G_S, DQD_DS, DQDD_DS, DQDD_DSD, G_SS = (_R[k] for k in (
    "q", "qd", "qdd", "g_s", "dqd_ds", "dqdd_ds", "dqdd_dsd", "g_ss"))
LANES = schema.LANES
per_step = jit(_per_step.per_step_into, python=False)    # the engine's outputs from their primitives
LQ, LQD, LQDD, LGEO, LR, LK, LC, LM, LS = (schema.LANE_ROWS[k] for k in (
    "q", "qd", "qdd", "geo", "r", "K", "C", "M", "S"))


@jit(python=False)
def kinematics(kern, sel, params, t, w):
    """w.kin at time t: the crank motion's (theta, thetad, thetadd), then the guide's closure."""
    call(kern.motion, 0, (t, params, w.crank))
    call(kern.guide, 0, (w.crank, params, w.kin))


@jit(python=False)
def end_map(kern, sel, params, s, sd, sdd, w):
    """w.E: the end map at the reduced end co-ordinate (s, sd, sdd) and w.kin."""
    w.send[0] = s
    w.send[1] = sd
    w.send[2] = sdd
    call(kern.end_map, 0, (w.send, w.kin, params, w.E))


@jit(python=False)
def project_residual(E, r):
    """r <- the reduced residual: the end node's rows become g_s . r_end (d'Alembert), in the
    reduced co-ordinate's slot IU; slot IV is unused."""
    r[IU] = E[G_S, 0] * r[IU] + E[G_S, 1] * r[IV]
    r[IV] = 0.0


@jit(python=False)
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


_gather = jit(_gather, inline="always", python=False)


def _map_end(kern, sel, params, q, qd, qdd, w):
    """The last element's end node: slot IU holds the reduced co-ordinate s (and its rates); the
    end map gives (u, v) and their rates."""
    end_map(kern, sel, params, q[IU], qd[IU], qdd[IU], w)
    E = w.E
    q[IU], q[IV] = E[Q, 0], E[Q, 1]
    qd[IU], qd[IV] = E[QD, 0], E[QD, 1]
    qdd[IU], qdd[IV] = E[QDD, 0], E[QDD, 1]


_map_end = jit(_map_end, inline="always", python=False)


def _lane_loop(add, e0, e1, kern, sel, coef, params, dofs, l, d, v, acc, cv, cd, w):
    """The rod families' terms (their kernels' mode `add`) of the elements e0 <= e < e1, LANES at a
    time: each group's nodal states gathered into a lane buffer of w.lanes (the end element's end
    node through the end map, its state left in w.q, w.qd, w.qdd; unused lanes at rest), the lane
    function of each family slot called once, the terms copied into w.rE[e] and (by add) w.SE[e]
    or w.KE[e], w.CE[e], w.ME[e]."""
    n = dofs.shape[0]
    q, qd, qdd, kin, rod = w.q, w.qd, w.qdd, w.kin, kern.rod
    rE, SE, KE, CE, ME = w.rE, w.SE, w.KE, w.CE, w.ME
    for c in range(e0, e1, LANES):
        b = w.lanes[(c - e0) // LANES]
        m = min(LANES, e1 - c)
        for j in range(LANES):
            e = c + j
            if j < m:
                _gather(dofs, e, d, v, acc, q, qd, qdd)
                if e == n - 1:
                    _map_end(kern, sel, params, q, qd, qdd, w)
                for k in range(NDOF):
                    b[(LQ + k) * LANES + j] = q[k]
                    b[(LQD + k) * LANES + j] = qd[k]
                    b[(LQDD + k) * LANES + j] = qdd[k]
            else:
                for k in range(NDOF):
                    b[(LQ + k) * LANES + j] = 0.0
                    b[(LQD + k) * LANES + j] = 0.0
                    b[(LQDD + k) * LANES + j] = 0.0
            b[LGEO * LANES + j] = l
            b[(LGEO + 1) * LANES + j] = e * l
        for i in range(LR * LANES, (LR + NDOF) * LANES):
            b[i] = 0.0
        if add == ADD_NEWMARK:
            for i in range(LS * LANES, (LS + NDOF * NDOF) * LANES):
                b[i] = 0.0
        elif add != ADD_RESIDUAL:
            for block in (LK, LC, LM):
                for i in range(block * LANES, (block + NDOF * NDOF) * LANES):
                    b[i] = 0.0
        for k in range(N_ROD):
            if sel[k] >= 0:
                call(rod, k, (add, b, coef, kin, cv, cd))
        for j in range(m):
            e = c + j
            for i in range(NDOF):
                rE[e, i] = b[(LR + i) * LANES + j]
            if add == ADD_NEWMARK:
                for i in range(NDOF * NDOF):
                    SE[e, i // NDOF, i % NDOF] = b[(LS + i) * LANES + j]
            elif add != ADD_RESIDUAL:
                for i in range(NDOF * NDOF):
                    KE[e, i // NDOF, i % NDOF] = b[(LK + i) * LANES + j]
                    CE[e, i // NDOF, i % NDOF] = b[(LC + i) * LANES + j]
                    ME[e, i // NDOF, i % NDOF] = b[(LM + i) * LANES + j]


_lane_loop = jit(_lane_loop, python=False)


@jit(python=False)
def iteration_matrices(ME, CE, KE, cv, cd, SE, e0, e1):
    """SE[e] = M_e + cv C_e + cd K_e, the element part of the iteration matrix of eq. (37), for
    e0 <= e < e1."""
    for e in range(e0, e1):
        for i in range(NDOF):
            for j in range(NDOF):
                SE[e, i, j] = ME[e, i, j] + cv * CE[e, i, j] + cd * KE[e, i, j]


def element_loop(mode, kern, sel, coef, params, printed, dofs, l, d, v, acc, cv, cd, w):
    """_element_loop, compiled once whether mode and printed are constants or not (plain)."""
    _element_loop(plain(mode), kern, sel, coef, params, plain(printed), dofs, l, d, v, acc, cv, cd, w)


element_loop = jit(element_loop, inline="always", python=False)


@jit(python=False)
def _element_loop(mode, kern, sel, coef, params, printed, dofs, l, d, v, acc, cv, cd, w):
    """Element terms of one case into w.rE and (by mode) w.KE, w.CE, w.ME / w.SE, at w.kin; the
    end element's terms are projected on the reduced end co-ordinate.  printed: the one-pass
    scheme's printed iteration matrices.  The rod's families run on lanes of elements
    (_lane_loop); the end element gets its separate matrices (for the projection), then the end
    node's families and the projection, in the scratch arrays w.r1, w.K1, ..."""
    n = dofs.shape[0]
    full = ADD_PRINTED if printed else ADD_FULL
    apart = mode == NEWMARK and not printed     # the end element's separate matrices on lanes of their own
    split = n - 1 if apart else n
    for part in range(2):               # one call site: one compilation of _lane_loop
        if part == 0:
            lo, hi = 0, split
            add = ADD_RESIDUAL if mode == RESIDUAL else (ADD_NEWMARK if apart else full)
        else:
            lo, hi, add = split, n, full
        if lo < hi:
            _lane_loop(add, lo, hi, kern, sel, coef, params, dofs, l, d, v, acc, cv, cd, w)
    e = n - 1                           # the end element (its mapped nodal state in w.q, w.qd, w.qdd)
    add = ADD_RESIDUAL if mode == RESIDUAL else full
    q, qd, qdd, geo, kin = w.q, w.qd, w.qdd, w.geo, w.kin
    rE, KE, CE, ME, SE = w.rE, w.KE, w.CE, w.ME, w.SE
    r, K, C, M, S = w.r1, w.K1, w.C1, w.M1, w.S1
    end = kern.end
    geo[0] = l
    geo[1] = e * l
    for i in range(NDOF):
        r[i] = rE[e, i]
    if add != ADD_RESIDUAL:
        for i in range(NDOF):
            for j in range(NDOF):
                K[i, j] = KE[e, i, j]
                C[i, j] = CE[e, i, j]
                M[i, j] = ME[e, i, j]
    for k in range(N_END):
        if sel[N_ROD + k] >= 0:
            call(end, k, (add, q, qd, qdd, geo, coef, kin, cv, cd, r, K, C, M, S))
    if add == ADD_RESIDUAL:
        project_residual(w.E, r)
    else:
        project_last(w.E, r, K, C, M)
    for i in range(NDOF):
        rE[e, i] = r[i]
    if add != ADD_RESIDUAL:
        for i in range(NDOF):
            for j in range(NDOF):
                KE[e, i, j] = K[i, j]
                CE[e, i, j] = C[i, j]
                ME[e, i, j] = M[i, j]
    if mode == NEWMARK:                 # the end element's, and with printed matrices every element's
        iteration_matrices(ME, CE, KE, cv, cd, SE, n - 1 if apart else 0, n)


@jit(python=False)
def step_outputs(kern, sel, params, p, mesh, d, w, out):
    """out = the engine's outputs (schema.ENGINE_OUTPUTS, e.g. v* at x* = 1/2, u*(1), delta* of
    eq. 40) of the state d at w.kin: what they read (schema.PRIMITIVES) accumulated element by
    element, each element's nodal vector with its end node through the end map (a point: the
    field's shape functions at x* times the nodal vector of the element holding it; an integral over
    the rod: q^T G q summed over the elements), then the generated per_step of those and the
    parameter vector p."""
    dofs = mesh.dofs
    n = dofs.shape[0]
    N = d.shape[0]
    q, prims = w.q, w.prims
    for k in range(prims.shape[0]):
        prims[k] = 0.0
    for e in range(n):
        for k in range(NDOF):
            idx = dofs[e, k]
            q[k] = d[idx] if idx < N else 0.0
        if e == n - 1:
            end_map(kern, sel, params, q[IU], 0.0, 0.0, w)
            q[IU] = w.E[Q, 0]
            q[IV] = w.E[Q, 1]
            w.q_end[0] = q[IU]
            w.q_end[1] = q[IV]
        for j in range(mesh.point_slots.shape[0]):
            if mesh.point_elements[j] == e:
                k = mesh.point_slots[j]
                for i in range(NDOF):
                    prims[k] += mesh.point_weights[j, i] * q[i]
        for g in range(mesh.gram_slots.shape[0]):
            k = mesh.gram_slots[g]
            for i in range(NDOF):
                for jj in range(NDOF):
                    prims[k] += q[i] * mesh.grams[g, i, jj] * q[jj]
    per_step(prims, w.q_end, p, out)


def _element_terms(mode, kern, sel, coef, params, printed, dofs, l, d, v, acc, t, cv, cd, w):
    """The kinematics at t, then the element loop (see element_loop): callable from Python, for
    tests and diagnostics (compiled only when first used)."""
    kinematics(kern, sel, params, t, w)
    _element_loop(mode, kern, sel, coef, params, printed, dofs, l, d, v, acc, cv, cd, w)


element_terms = jit(_element_terms)
