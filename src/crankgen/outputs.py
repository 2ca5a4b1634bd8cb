"""Scaled outputs of a run: v* at x* = 1/2, u*(1), and the extension delta* of eq. (40)."""

import numpy as np

from ._generated.shape import shape_functions, slope_gram


def element_history(model, d, phi):
    """Element nodal vectors (steps, n, 6) with the slider constraint applied."""
    q = model.mesh.gather(d)
    s = q[:, -1, 3].copy()
    q[:, -1, 3] = s * np.cos(phi)
    q[:, -1, 4] = s * np.sin(phi)
    return q


def deflection_at(model, q, x):
    """v(x) in units of L, interpolated with the element's shape functions (any element count)."""
    e, zeta = model.mesh.locate(x)
    _, N_v, _ = shape_functions(zeta, model.mesh.length)
    return q[:, e, :] @ N_v


def mid_deflection(model, q):
    """v* = v / r at x* = 1/2."""
    return deflection_at(model, q, 0.5) / model.mechanism.eps


def end_axial(model, q):
    """u*(1) = L u(L) / r^2."""
    return q[:, -1, 3] / model.mechanism.eps**2


def extension(model, q):
    """delta* = u(L)/L + (1/2) int_0^1 (dv/dx)^2 dx  (eq. 40, in units of L)."""
    G = slope_gram(model.mesh.length)
    slope_sq = np.einsum("sei,ij,sej->s", q, G, q)
    return q[:, -1, 3] + 0.5 * slope_sq
