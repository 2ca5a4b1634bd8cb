"""Condensation of the mapped constraint of the DOF map through its generated map (NumPy,
vectorized): the exact elimination of the end constraint through the guide's end map.

The constraint (schema.CONSTRAINTS: the one with a map; the guide's, declared in
derive/declaration.py) writes the k components it eliminates at its node through m reduced
co-ordinates s: for the guide, the end node's (u, v) = g(s, t), s the reduced co-ordinate of the
guide (derive/guides.py: a slider's displacement along its line, g = s (cos phi, sin phi), so that
eq. (26) v = u tan phi holds identically; a rocker's angle deviation on a four-bar).  Every such
(u, v) keeps the end on its guide, at every instant.  The map is rheonomic, so velocities and
accelerations carry its time derivatives; the generated map kernel gives, at (s, sd, sdd) and the
kinematics, the rows (schema.END_MAP_ROWS; `map_rows(m)` for m co-ordinates)

    q, qd, qdd                   the eliminated components and their rates,
    g_s_j                        dq/ds_j = dqd/dsd_j = dqdd/dsdd_j,
    dqd_ds_j, dqdd_ds_j, dqdd_dsd_j, g_ss_jl.

The reduced equations are d'Alembert's projection: with virtual displacements dq = g_s ds the
eliminated rows become r_s_j = g_s_j . r_elim in the slot of s_j (the other eliminated slots of the
element are unused), and the tangents

    K' = T^T (K dq/ds + C dqd/ds + M dqdd/ds) + e_s e_s^T (g_ss . r_elim),
    C' = T^T (C g_s + M dqdd/dsd),        M' = T^T M g_s

(T: identity except the eliminated slots' columns g_s), so there is no multiplier, no constraint
drift and no parasitic multiplier mode.  engine/elements.py computes the same in compiled form.
"""

import numpy as np

from ..declaration import schema
from .mesh import MAPPED, element_slots

_R = schema.END_MAP_ROWS


def map_rows(m):
    """{row name: row} of a map of m reduced co-ordinates: q, qd, qdd, then per co-ordinate j g_s,
    dqd_ds, dqdd_ds, dqdd_dsd (suffixed _j for m > 1), then g_ss (_jl for m > 1)."""
    rows = {"q": 0, "qd": 1, "qdd": 2}
    tag = (lambda *i: "") if m == 1 else (lambda *i: "_" + "".join(map(str, i)))
    for j in range(m):
        for k, name in enumerate(("g_s", "dqd_ds", "dqdd_ds", "dqdd_dsd")):
            rows[name + tag(j)] = 3 + 4 * j + k
    for j in range(m):
        for i in range(m):
            rows["g_ss" + tag(j, i)] = 3 + 4 * m + j * m + i
    return rows


ROWS = map_rows(len(MAPPED.reduced))
assert all(ROWS[name] == row for name, row in _R.items()), "the end map's rows are not map_rows(m)"
# the eliminated components' slots in the element whose last (or first) node holds the constraint,
# and the slots of its reduced co-ordinates (the first of those)
SLOTS = element_slots(1 if MAPPED.node == -1 else 0, MAPPED.eliminated)
REDUCED = SLOTS[:len(MAPPED.reduced)]


def _tag(j, m):
    return "" if m == 1 else f"_{j}"


def expand(E, p, pd, pdd, slots=SLOTS):
    """Nodal q, qd, qdd of an element holding the constraint's node, from its reduced slots (they
    hold s, sd, sdd) and the map's values E (..., rows, k)."""
    q, qd, qdd = np.array(p, dtype=float), np.array(pd, dtype=float), np.array(pdd, dtype=float)
    for out, row in ((q, "q"), (qd, "qd"), (qdd, "qdd")):
        for a, slot in enumerate(slots):
            out[..., slot] = E[..., ROWS[row], a]
    return q, qd, qdd


def rows_of(E):
    """map_rows(m) of a map's values E (..., 3 + 4 m + m^2, k)."""
    m = next(m for m in range(1, 8) if 3 + 4 * m + m * m == E.shape[-2])
    return map_rows(m)


def _on(E, row, slots, X, axis):
    """sum over the eliminated slots a of E[row, a] X[..., slot_a] along `axis` (-1: columns of a
    matrix or entries of a vector; -2: rows)."""
    total = 0.0
    rows = rows_of(E)
    for a, slot in enumerate(slots):
        part = np.take(X, slot, axis=axis)
        weight = E[..., rows[row], a]
        total = total + (weight[..., None] * part if part.ndim > weight.ndim else weight * part)
    return total


def tangents(E, m=len(REDUCED)):
    """The map's tangents g_s_j (..., m, k): the directions its node moves in as s_j varies."""
    return np.stack([E[..., map_rows(m)["g_s" + _tag(j, m)], :] for j in range(m)], axis=-2)


def project_residual(E, r, slots=SLOTS, reduced=REDUCED):
    """An element's residual (..., NDOF) on the reduced co-ordinates: g_s_j . r_elim in the slot of
    s_j, the other eliminated slots 0."""
    m = len(reduced)
    out = np.array(r, dtype=float)
    values = [_on(E, "g_s" + _tag(j, m), slots, r, -1) for j in range(m)]
    for slot in slots:
        out[..., slot] = 0.0
    for j, slot in enumerate(reduced):
        out[..., slot] = values[j]
    return out


def project(E, r, K, C, M, slots=SLOTS, reduced=REDUCED):
    """Reduced residual and tangents of an element holding the constraint's node (module docstring)."""
    m = len(reduced)

    def columns(parts):                    # X with the eliminated columns combined, per s_j
        outs = []
        for X, cols in parts:
            out = np.array(X, dtype=float)
            for slot in slots:
                out[..., :, slot] = 0.0
            for j, slot in enumerate(reduced):
                out[..., :, slot] = sum(_on(E, row + _tag(j, m), slots, Y, -1) for Y, row in cols)
            outs.append(out)
        return outs

    def rows(X):                           # the eliminated rows combined by g_s_j
        out = np.array(X, dtype=float)
        values = [_on(E, "g_s" + _tag(j, m), slots, X, -2) for j in range(m)]
        for slot in slots:
            out[..., slot, :] = 0.0
        for j, slot in enumerate(reduced):
            out[..., slot, :] = values[j]
        return out

    K_col, C_col, M_col = columns([(K, ((K, "g_s"), (C, "dqd_ds"), (M, "dqdd_ds"))),
                                   (C, ((C, "g_s"), (M, "dqdd_dsd"))), (M, ((M, "g_s"),))])
    K_red, C_red, M_red = rows(K_col), rows(C_col), rows(M_col)
    for j, sj in enumerate(reduced):
        for i, si in enumerate(reduced):
            K_red[..., sj, si] += _on(E, "g_ss" + ("" if m == 1 else f"_{j}{i}"), slots, r, -1)
    return project_residual(E, r, slots, reduced), K_red, C_red, M_red
