"""Exact elimination of the slider constraint, eq. (26): v_{n+1} = u_{n+1} tan phi.

The slider end is written (u, v)_{n+1} = s (cos phi, sin phi): s is the slider's displacement
along the guide, and every such (u, v) satisfies eq. (26) identically, at every instant.  The map
q = T(phi) p from the last element's reduced slots p (slot 3 holds s, slot 4 is unused) is
rheonomic, so velocities and accelerations carry its time derivatives:

    qd = T pd + Td p,        qdd = T pdd + 2 Td pd + Tdd p,

and the reduced equations are the projection T^T r with the tangents
    M' = T^T M T,   C' = T^T (C T + 2 M Td),   K' = T^T (K T + C Td + M Tdd)
(d'Alembert with virtual displacements dq = T dp; no multiplier, so no constraint drift and no
parasitic multiplier mode).
"""

import numpy as np

S_SLOT, UNUSED_SLOT = 3, 4


def slider_map(phi, phid, phidd):
    """T, Td, Tdd of shape (..., 6, 6) for the last element."""
    phi, phid, phidd = np.broadcast_arrays(np.asarray(phi, float), phid, phidd)
    c, sn = np.cos(phi), np.sin(phi)
    shape = phi.shape + (6, 6)
    T = np.broadcast_to(np.eye(6), shape).copy()
    T[..., S_SLOT, S_SLOT] = c
    T[..., UNUSED_SLOT, S_SLOT] = sn
    T[..., UNUSED_SLOT, UNUSED_SLOT] = 0.0
    Td = np.zeros(shape)
    Td[..., S_SLOT, S_SLOT] = -sn * phid
    Td[..., UNUSED_SLOT, S_SLOT] = c * phid
    Tdd = np.zeros(shape)
    Tdd[..., S_SLOT, S_SLOT] = -c * phid**2 - sn * phidd
    Tdd[..., UNUSED_SLOT, S_SLOT] = -sn * phid**2 + c * phidd
    return T, Td, Tdd


def _mv(A, x):
    return np.einsum("...ij,...j->...i", A, x)


def expand(T, Td, Tdd, p, pd, pdd):
    """Nodal q, qd, qdd of the last element from its reduced slots."""
    return _mv(T, p), _mv(T, pd) + _mv(Td, p), _mv(T, pdd) + 2 * _mv(Td, pd) + _mv(Tdd, p)


def project(T, Td, Tdd, r, K, C, M):
    """Reduced residual and tangents of the last element (see module docstring)."""
    Tt = np.swapaxes(T, -1, -2)
    r_red = _mv(Tt, r)
    M_red = Tt @ M @ T
    C_red = Tt @ (C @ T + 2 * M @ Td)
    K_red = Tt @ (K @ T + C @ Td + M @ Tdd)
    return r_red, K_red, C_red, M_red
