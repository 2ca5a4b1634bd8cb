"""The element loop of the compiled engine: gather the elements' nodal states, map the node the
DOF map's mapped constraint holds (the guide's end node) through its map, call the case's term
families (the model's table of compiled kernels, one per family slot: engine/kernels.py), the
rod's families on lanes of schema.LANES elements a call (their loop over the elements vectorized),
project the terms of the elements holding that node on its reduced co-ordinates (the exact
condensation of constraints.py: which slots, from records.condensation), and the per-step outputs.

Three modes: FULL (residual and tangents K, C, M), NEWMARK (residual and the iteration matrix
S = M + cv C + cd K of eq. 37: each kernel's newmark mode, except for a holding element, whose
separate matrices the projection needs), RESIDUAL (residual only, for iterations that reuse a
factorization).  Nothing here names a family, a guide, a motion, a slot or an element.
"""

from ..declaration import schema
from .._generated import per_step as _per_step
from .calls import call
from .compiled import jit, plain
from .kernels import N_END, N_ROD
from .records import NDOF

FULL, NEWMARK, RESIDUAL = 0, 1, 2          # what the element loop computes
# what an element kernel adds, by its mode argument (derive/emit.py)
ADD_FULL, ADD_PRINTED, ADD_RESIDUAL, ADD_NEWMARK = (schema.ELEMENT_MODES.index(m) for m in (
    "full", "printed", "residual", "newmark"))
_R = schema.END_MAP_ROWS
# the map's rows: the eliminated components and their rates, then per reduced co-ordinate j its
# derivatives at G_S + 4 j, DQD_DS + 4 j, DQDD_DS + 4 j, DQDD_DSD + 4 j, then the curvature rows
# (constraints.map_rows)
Q, QD, QDD, G_S, DQD_DS, DQDD_DS, DQDD_DSD = (_R[k] for k in (
    "q", "qd", "qdd", "g_s", "dqd_ds", "dqdd_ds", "dqdd_dsd"))
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
def map_values(kern, sel, params, w):
    """w.E: the mapped constraint's map (the guide's end map) at w.send = (s, sd, sdd) of its
    reduced co-ordinates and w.kin."""
    call(kern.end_map, 0, (w.send, w.kin, params, w.E))


@jit(python=False)
def project_residual(E, r, slots, reduced, w):
    """r <- the reduced residual: the eliminated rows become g_s_j . r_elim (d'Alembert) in the
    slot of each reduced co-ordinate s_j; the other eliminated slots are unused (0)."""
    k, m = slots.shape[0], reduced.shape[0]
    pr = w.pr
    for j in range(m):
        g = G_S + 4 * j
        acc = E[g, 0] * r[slots[0]]
        for a in range(1, k):
            acc += E[g, a] * r[slots[a]]
        pr[0, j] = acc
    for a in range(k):
        r[slots[a]] = 0.0
    for j in range(m):
        r[reduced[j]] = pr[0, j]


@jit(python=False)
def project(E, r, K, C, M, slots, reduced, w):
    """An element's terms on the reduced co-ordinates s_j of its constrained node, q = g(s, t)
    (the eliminated components `slots`, s_j in slot reduced[j]; constraints.py):
        columns: K' = K dq/ds + C dqd/ds + M dqdd/ds,  C' = C dqd/dsd + M dqdd/dsd,  M' = M g_s;
        rows: g_s^T (...), and K'[s_j, s_l] += g_ss_jl . r_elim (the map's curvature);
        r' = g_s . r_elim  (dqd/dsd = dqdd/dsdd = g_s)."""
    k, m = slots.shape[0], reduced.shape[0]
    px, pr = w.px, w.pr
    for i in range(NDOF):               # right factors: the eliminated columns combine per s_j
        for a in range(k):
            px[0, a] = K[i, slots[a]]
            px[1, a] = C[i, slots[a]]
            px[2, a] = M[i, slots[a]]
        for j in range(m):
            g, dd, ddd, ddsd = G_S + 4 * j, DQD_DS + 4 * j, DQDD_DS + 4 * j, DQDD_DSD + 4 * j
            kk = E[g, 0] * px[0, 0]
            for a in range(1, k):
                kk += E[g, a] * px[0, a]
            for a in range(k):
                kk += E[dd, a] * px[1, a]
            for a in range(k):
                kk += E[ddd, a] * px[2, a]
            cc = E[g, 0] * px[1, 0]
            for a in range(1, k):
                cc += E[g, a] * px[1, a]
            tt = E[ddsd, 0] * px[2, 0]
            for a in range(1, k):
                tt += E[ddsd, a] * px[2, a]
            mm = E[g, 0] * px[2, 0]
            for a in range(1, k):
                mm += E[g, a] * px[2, a]
            pr[0, j] = kk
            pr[1, j] = cc + tt
            pr[2, j] = mm
        for a in range(k):
            K[i, slots[a]] = 0.0
            C[i, slots[a]] = 0.0
            M[i, slots[a]] = 0.0
        for j in range(m):
            K[i, reduced[j]] = pr[0, j]
            C[i, reduced[j]] = pr[1, j]
            M[i, reduced[j]] = pr[2, j]
    for col in range(NDOF):             # g_s^T from the left: the eliminated rows combine per s_j
        for a in range(k):
            px[0, a] = K[slots[a], col]
            px[1, a] = C[slots[a], col]
            px[2, a] = M[slots[a], col]
        for j in range(m):
            g = G_S + 4 * j
            for x in range(3):
                acc = E[g, 0] * px[x, 0]
                for a in range(1, k):
                    acc += E[g, a] * px[x, a]
                pr[x, j] = acc
        for a in range(k):
            K[slots[a], col] = 0.0
            C[slots[a], col] = 0.0
            M[slots[a], col] = 0.0
        for j in range(m):
            K[reduced[j], col] = pr[0, j]
            C[reduced[j], col] = pr[1, j]
            M[reduced[j], col] = pr[2, j]
    for j in range(m):                  # the map's curvature: g_ss_jl . r_elim
        for jj in range(m):
            g = G_S + 4 * m + j * m + jj
            acc = E[g, 0] * r[slots[0]]
            for a in range(1, k):
                acc += E[g, a] * r[slots[a]]
            K[reduced[j], reduced[jj]] += acc
    project_residual(E, r, slots, reduced, w)


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


def _map_held(kern, sel, params, h, q, qd, qdd, w):
    """An element holding the mapped constraint's node (its holding h): the reduced co-ordinates'
    slots hold (s, sd, sdd); the map gives the eliminated components and their rates.  The mapped
    state and the map's values are kept in w.qc[h], w.qdc[h], w.qddc[h], w.Ec[h]."""
    slots, reduced = w.held_slots[h], w.held_reduced[h]
    m = reduced.shape[0]
    for j in range(m):
        w.send[j] = q[reduced[j]]
        w.send[m + j] = qd[reduced[j]]
        w.send[2 * m + j] = qdd[reduced[j]]
    map_values(kern, sel, params, w)
    E = w.E
    for a in range(slots.shape[0]):
        q[slots[a]] = E[Q, a]
        qd[slots[a]] = E[QD, a]
        qdd[slots[a]] = E[QDD, a]
    for i in range(NDOF):
        w.qc[h, i] = q[i]
        w.qdc[h, i] = qd[i]
        w.qddc[h, i] = qdd[i]
    for i in range(E.shape[0]):
        for a in range(E.shape[1]):
            w.Ec[h, i, a] = E[i, a]


_map_held = jit(_map_held, inline="always", python=False)


def _lane_loop(add, e0, e1, kern, sel, coef, params, dofs, l, d, v, acc, cv, cd, w, kin, first):
    """The rod families' terms (their kernels' mode `add`) of the elements e0 <= e < e1 of one
    flexible body (its first element `first`, its element length l, its frame's kinematics kin, its
    coefficients coef), LANES at a time: each group's nodal states gathered into a lane buffer of
    w.lanes (an element holding the mapped constraint's node through its map, its state kept in
    w.qc; unused lanes at rest), the lane function of each family slot called once, the terms copied
    into w.rE[e] and (by add) w.SE[e] or w.KE[e], w.CE[e], w.ME[e]."""
    q, qd, qdd, rod = w.q, w.qd, w.qdd, kern.rod
    rE, SE, KE, CE, ME = w.rE, w.SE, w.KE, w.CE, w.ME
    for c in range(e0, e1, LANES):
        b = w.lanes[(c - e0) // LANES]
        m = min(LANES, e1 - c)
        for j in range(LANES):
            e = c + j
            if j < m:
                _gather(dofs, e, d, v, acc, q, qd, qdd)
                h = w.mapped[e]
                if h >= 0:
                    _map_held(kern, sel, params, h, q, qd, qdd, w)
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
            b[(LGEO + 1) * LANES + j] = (e - first) * l
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
    terms of an element holding the mapped constraint's node are projected on its reduced
    co-ordinates (the DOF map's condensation).  printed: the one-pass scheme's printed iteration
    matrices.  The rod's families run on lanes of elements (_lane_loop), in runs of consecutive
    elements: in NEWMARK mode a holding element makes a run of its own in full mode (its separate
    matrices for the projection); then, per holding element, the constrained node's families (the
    end mass) and the projection, in the scratch arrays w.r1, w.K1, ..."""
    n = dofs.shape[0]
    full = ADD_PRINTED if printed else ADD_FULL
    apart = mode == NEWMARK and not printed     # a holding element's separate matrices on lanes of their own
    for body in range(w.bodies.shape[0]):       # the rod, then the other flexible bodies (a rocker)
        first, end = w.bodies[body, 0], w.bodies[body, 1]
        kb, cb, lb = w.kinb[body], coef[body], w.lengths[body]
        if body == 0:
            lb = l
            for i in range(kb.shape[0]):
                kb[i] = w.kin[i]
        else:                                   # the body's frame: kin_b = F_b kin
            for i in range(kb.shape[0]):
                acc_k = 0.0
                for j in range(kb.shape[0]):
                    acc_k += w.frames[body, i, j] * w.kin[j]
                kb[i] = acc_k
        lo = first
        while lo < end:                 # one call site: one compilation of _lane_loop
            hi = lo + 1
            if apart and w.mapped[lo] >= 0:
                add = full
            else:
                while hi < end and not (apart and w.mapped[hi] >= 0):
                    hi += 1
                add = ADD_RESIDUAL if mode == RESIDUAL else (ADD_NEWMARK if apart else full)
            _lane_loop(add, lo, hi, kern, sel, cb, params, dofs, lb, d, v, acc, cv, cd, w, kb, first)
            lo = hi
    add = ADD_RESIDUAL if mode == RESIDUAL else full
    geo, kin, coef = w.geo, w.kin, coef[0]
    rE, KE, CE, ME, SE = w.rE, w.KE, w.CE, w.ME, w.SE
    r, K, C, M, S = w.r1, w.K1, w.C1, w.M1, w.S1
    end = kern.end
    for h in range(w.held.shape[0]):
        e = w.held[h]                   # a holding element (its mapped nodal state in w.qc[h], ...)
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
        if h == 0:                      # the constrained node's families act once, on its first holder
            for k in range(N_END):
                if sel[N_ROD + k] >= 0:
                    call(end, k, (add, w.qc[h], w.qdc[h], w.qddc[h], geo, coef, kin, cv, cd, r, K, C, M, S))
        if add == ADD_RESIDUAL:
            project_residual(w.Ec[h], r, w.held_slots[h], w.held_reduced[h], w)
        else:
            project(w.Ec[h], r, K, C, M, w.held_slots[h], w.held_reduced[h], w)
        for i in range(NDOF):
            rE[e, i] = r[i]
        if add != ADD_RESIDUAL:
            for i in range(NDOF):
                for j in range(NDOF):
                    KE[e, i, j] = K[i, j]
                    CE[e, i, j] = C[i, j]
                    ME[e, i, j] = M[i, j]
        if mode == NEWMARK and apart:   # a holding element's own iteration matrix
            iteration_matrices(ME, CE, KE, cv, cd, SE, e, e + 1)
    if mode == NEWMARK and not apart:   # with printed matrices every element's
        iteration_matrices(ME, CE, KE, cv, cd, SE, 0, n)


@jit(python=False)
def step_outputs(kern, sel, params, p, mesh, d, w, out):
    """out = the engine's outputs (schema.ENGINE_OUTPUTS, e.g. v* at x* = 1/2, u*(1), delta* of
    eq. 40) of the state d at w.kin: what they read (schema.PRIMITIVES) accumulated element by
    element, each element's nodal vector with its constrained node through the map (a point: the
    field's shape functions at x* times the nodal vector of the element holding it; an integral over
    the rod: q^T G q summed over the elements), then the generated per_step of those and the
    parameter vector p."""
    dofs = mesh.dofs
    n = mesh.bodies[0, 1]               # the rod's elements
    N = d.shape[0]
    q, prims = w.q, w.prims
    for k in range(prims.shape[0]):
        prims[k] = 0.0
    for e in range(n):
        for k in range(NDOF):
            idx = dofs[e, k]
            q[k] = d[idx] if idx < N else 0.0
        h = w.mapped[e]
        if h >= 0:                      # the mapped node's components from its reduced co-ordinates
            slots, reduced = w.held_slots[h], w.held_reduced[h]
            m = reduced.shape[0]
            for j in range(m):
                w.send[j] = q[reduced[j]]
                w.send[m + j] = 0.0
                w.send[2 * m + j] = 0.0
            map_values(kern, sel, params, w)
            for a in range(slots.shape[0]):
                q[slots[a]] = w.E[Q, a]
                if h == 0:
                    w.q_end[a] = q[slots[a]]
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
