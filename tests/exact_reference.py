"""Hand-written NumPy reference of the geometrically exact rod's element energies (test helper,
independent of derive/ and SymPy).

From the kinematics, not from the derivation: the element interpolates u as it does v, by cubic
Hermite polynomials in the nodal values and slopes (u, chi = u_x; v, psi = v_x: tests/reference.py
cubic_u_at and shape_at, typed in by hand); the centre line's tangent r' = (1 + u_x, v_x) in the
moving frame, the stretch |r'| (numpy.hypot), the section rotation theta = the angle of r' from e_i
(numpy.arctan2), the curvature kappa = d theta / dx by a central difference of that angle along the
element (not a closed formula; the angle measured from the tangent at the point itself, so that no
branch of arctan2 is ever crossed), the strain and curvature rates and the section's angular
velocity theta' by central differences in time along q + s qd.  Integrals by the Gauss-Legendre
rule whose number of points the schema declares for the exact kernels (their Variant.quadrature,
"3-point Gauss-Legendre ..."): the discrete model is defined by that rule.
"""

import numpy as np

import reference as ref
from crankgen.declaration import schema

QUADRATURE = {v.kernel: v.quadrature for f in schema.FAMILIES for v in f.variants if v.quadrature}
EXACT_POINTS = {int(text.split("-point")[0]) for text in QUADRATURE.values()}
assert len(EXACT_POINTS) == 1, QUADRATURE
N_POINTS = EXACT_POINTS.pop()


def rule(n=N_POINTS):
    x, w = np.polynomial.legendre.leggauss(n)
    return (x + 1) / 2, w / 2


def tangent(q, l, z):
    """(1 + u_x, v_x) (each S + (len(z),)) of nodal vectors q (S + (8,)) at zeta = z: the exact rod's
    cubic u, the cubic v."""
    l = np.asarray(l, float)[..., None]
    _, b_u, _ = ref.cubic_u_at(z, l)
    b_v = ref.shape_at(z, l)[4]
    q = np.asarray(q, float)[..., None, :]
    return 1 + np.sum(b_u * q, -1), np.sum(b_v * q, -1)


def strain(q, l, z):
    """e = |r'| - 1 at zeta = z."""
    c, s = tangent(q, l, z)
    return np.hypot(c, s) - 1


def rotation(q, l, z):
    """theta at zeta = z: the angle of the tangent r' from e_i, in (-pi, pi]."""
    c, s = tangent(q, l, z)
    return np.arctan2(s, c)


def _turn(q, l, z, q_ref, z_ref):
    """The angle from the tangent of q_ref at z_ref to the tangent of q at z (arctan2 of their
    cross and dot products: continuous while the two tangents are less than pi apart)."""
    c, s = tangent(q, l, z)
    c0, s0 = tangent(q_ref, l, z_ref)
    return np.arctan2(c0 * s - s0 * c, c0 * c + s0 * s)


def curvature(q, l, z, h=1e-4):
    """kappa = d theta / dx = (1/l) d theta / d zeta, by a 5-point central difference in zeta."""
    z = np.asarray(z, float)
    return ref.fd_derivative(lambda zz: _turn(q, l, zz, q, z), z, h) / np.asarray(l)[..., None]


def rotation_rate(q, qd, l, z, h=1e-4):
    """theta' (d/dt along q + t qd), by a 5-point central difference."""
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    return ref.fd_derivative(lambda s: _turn(q + s * qd, l, z, q, z), 0.0, h)


def rate(fn, q, qd, l, z, h=1e-4):
    """d/dt fn(q, l, z) along q + t qd, by a 5-point central difference."""
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    return ref.fd_derivative(lambda s: fn(q + s * qd, l, z), 0.0, h)


def integrate(values, l, w):
    return np.asarray(l) * np.sum(values * w, -1)


def strain_energy(q, l, EA, EI, n=N_POINTS):
    """1/2 int (EA e^2 + EI kappa^2) dx, the strain pointwise."""
    z, w = rule(n)
    e, kappa = strain(q, l, z), curvature(q, l, z)
    return integrate(EA * e**2 / 2 + EI * kappa**2 / 2, l, w)


def dissipation(q, qd, l, EA, EI, mu, n=N_POINTS):
    """mu/2 int (EA e'^2 + EI kappa'^2) dx (' = d/dt)."""
    z, w = rule(n)
    ed, kd = rate(strain, q, qd, l, z), rate(curvature, q, qd, l, z)
    return integrate(mu * (EA * ed**2 + EI * kd**2) / 2, l, w)


def rotary_kinetic_energy(q, qd, l, rhoI, phid, n=N_POINTS):
    """rho I / 2 int (theta' - phid)^2 dx: the unit director -sin(theta) e_i + cos(theta) e_j turns
    at theta' - phid in the inertial frame."""
    z, w = rule(n)
    omega = rotation_rate(q, qd, l, z) - np.asarray(phid)[..., None]
    return integrate(rhoI * omega**2 / 2, l, w)


def nodal(u, v, psi, chi):
    """Element nodal vectors (..., 8) from (first node, second node) pairs (..., 2) of each
    component."""
    out = np.zeros(np.shape(u)[:-1] + (ref.NDOF,))
    for slots, values in ((ref.AXIAL, u), (ref.TRANSVERSE, v), (ref.SLOPES, psi), (ref.CHIS, chi)):
        out[..., slots] = values
    return out


def rigid_element(x0, l, alpha, cu=0.0, cv=0.0, rate_alpha=0.0, rate_u=0.0, rate_v=0.0):
    """Nodal vector and its rate of an element moved rigidly in the moving frame: turned by alpha
    about its first node, then translated by (cu, cv): the material point x goes to
    (x0 + cu + (x - x0) cos(alpha), cv + (x - x0) sin(alpha)), so u(x) = x0 + cu + (x - x0)
    cos(alpha) - x, v(x) = cv + (x - x0) sin(alpha), u_x = cos(alpha) - 1, v_x = sin(alpha); its
    rate for alpha' and (cu', cv')."""
    c, s = np.cos(alpha), np.sin(alpha)
    q = nodal([cu, cu + l * (c - 1)], [cv, cv + l * s], [s, s], [c - 1, c - 1])
    qd = nodal([rate_u, rate_u - l * s * rate_alpha], [rate_v, rate_v + l * c * rate_alpha],
               [c * rate_alpha] * 2, [-s * rate_alpha] * 2)
    return q, qd
