"""Exact elimination of the end constraint through the guide's end map (NumPy, vectorized).

The rod's end node is written (u, v) = g(s, t), s the reduced co-ordinate of the guide
(derive/guides.py: a slider's displacement along its line, g = s (cos phi, sin phi), so that eq.
(26) v = u tan phi holds identically; a rocker's angle deviation on a four-bar).  Every such (u, v)
keeps the end on its guide, at every instant.  The map is rheonomic, so velocities and
accelerations carry its time derivatives; the generated end map kernel gives, at (s, sd, sdd) and
the kinematics, the rows (schema.END_MAP_ROWS)

    q, qd, qdd        the end node's (u, v) and rates,
    g_s               dq/ds = dqd/dsd = dqdd/dsdd,
    dqd_ds, dqdd_ds, dqdd_dsd, g_ss.

The reduced equations are d'Alembert's projection: with virtual displacements dq = g_s ds the end
node's residual rows become r_s = g_s . r_end, and the tangents (the last element's slot 3 holds s,
slot 4 is unused)

    K' = T^T (K dq/ds + C dqd/ds + M dqdd/ds) + e_s e_s^T (g_ss . r_end),
    C' = T^T (C g_s + M dqdd/dsd),        M' = T^T M g_s

(T: identity except the end node's column g_s), so there is no multiplier, no constraint drift and
no parasitic multiplier mode.  engine/elements.py computes the same in compiled form.
"""

import numpy as np

from . import schema

IU, IV = schema.END_SLOTS
S_SLOT, UNUSED_SLOT = IU, IV
_R = schema.END_MAP_ROWS


def expand(E, p, pd, pdd):
    """Nodal q, qd, qdd of the last element from its reduced slots (slot IU holds s) and the end
    map values E (..., 8, 2)."""
    q, qd, qdd = np.array(p, dtype=float), np.array(pd, dtype=float), np.array(pdd, dtype=float)
    for out, row in ((q, "q"), (qd, "qd"), (qdd, "qdd")):
        out[..., IU] = E[..., _R[row], 0]
        out[..., IV] = E[..., _R[row], 1]
    return q, qd, qdd


def _column(E, row):
    """(..., 6) vector with the end map row on the end node's (u, v) slots."""
    col = np.zeros(E.shape[:-2] + (schema.ELEMENT_DOFS,))
    col[..., IU] = E[..., _R[row], 0]
    col[..., IV] = E[..., _R[row], 1]
    return col


def project_residual(E, r):
    """The end element's residual (..., 6) on the reduced co-ordinate: g_s . r_end in slot IU."""
    out = np.array(r, dtype=float)
    out[..., IU] = np.einsum("...i,...i->...", _column(E, "g_s"), r)
    out[..., IV] = 0.0
    return out


def project(E, r, K, C, M):
    """Reduced residual and tangents of the last element (see module docstring)."""
    g_s = _column(E, "g_s")
    n = schema.ELEMENT_DOFS

    def right(X, d_row):            # X with its end node's columns replaced by X . d_row on column IU
        out = np.array(X, dtype=float)
        out[..., :, IU] = np.einsum("...ij,...j->...i", X, d_row)
        out[..., :, IV] = 0.0
        return out

    def left(X):                    # rows: the end node's rows combined by g_s on row IU
        out = np.array(X, dtype=float)
        out[..., IU, :] = np.einsum("...i,...ij->...j", g_s, X)
        out[..., IV, :] = 0.0
        return out

    K_col = right(K, g_s)
    K_col[..., :, IU] += (np.einsum("...ij,...j->...i", C, _column(E, "dqd_ds"))
                          + np.einsum("...ij,...j->...i", M, _column(E, "dqdd_ds")))
    C_col = right(C, g_s)
    C_col[..., :, IU] += np.einsum("...ij,...j->...i", M, _column(E, "dqdd_dsd"))
    M_col = right(M, g_s)
    K_red, C_red, M_red = left(K_col), left(C_col), left(M_col)
    K_red[..., IU, IU] += np.einsum("...i,...i->...", _column(E, "g_ss"), r)
    r_red = np.array(r, dtype=float)
    r_red[..., IU] = np.einsum("...i,...i->...", g_s, r)
    r_red[..., IV] = 0.0
    assert K_red.shape[-1] == n
    return r_red, K_red, C_red, M_red
