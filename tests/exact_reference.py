"""Hand-written NumPy reference of the geometrically exact rod's element energies (test helper,
independent of derive/ and SymPy).

From the kinematics, not from the derivation: the centre line's tangent r' = (1 + u_x, v_x) in
the moving frame, the stretch |r'| (numpy.hypot), the section rotation theta of an element of
constant stretch, the chord's (lambda_c sin(theta) = v_x, numpy.arcsin), the curvature
kappa = d theta / dx by a central difference of theta along the element (not a closed formula), the strain and curvature rates and the section's angular velocity
theta' by central differences in time along q + s qd.  Integrals by the Gauss-Legendre rule whose
number of points the schema declares for the exact kernels (crankgen.schema.QUADRATURE): the
discrete model is defined by that rule.
"""

import numpy as np

import reference as ref
from crankgen import schema

EXACT_POINTS = {v["points"] for v in schema.QUADRATURE.values()}
assert len(EXACT_POINTS) == 1, schema.QUADRATURE
N_POINTS = EXACT_POINTS.pop()


def rule(n=N_POINTS):
    x, w = np.polynomial.legendre.leggauss(n)
    return (x + 1) / 2, w / 2


def _fields_at(q, l, z):
    """u_x, v_x, v_xx (each S + (len(z),)) of nodal vectors q (S + (6,)) at zeta = z."""
    _, _, _, b_u, b_v, b_psi = ref.shape_at(z, np.asarray(l, float)[..., None])
    q = np.asarray(q, float)[..., None, :]
    return np.sum(b_u * q, -1), np.sum(b_v * q, -1), np.sum(b_psi * q, -1)


def strain(q, l, z):
    """e = |r'| - 1 at zeta = z."""
    u_x, v_x, _ = _fields_at(q, l, z)
    return np.hypot(1 + u_x, v_x) - 1


def chord_stretch(q, l):
    """lambda_c = |chord| / l of the element: sqrt((l + u_{i+1} - u_i)^2 + (v_{i+1} - v_i)^2) / l."""
    q, l = np.asarray(q, float), np.asarray(l, float)
    return np.hypot(l + q[..., 3] - q[..., 0], q[..., 4] - q[..., 1]) / l


def rotation(q, l, z):
    """theta at zeta = z of an element of constant stretch lambda_c whose tangent's e_j component is
    the slope v_x: lambda_c sin(theta) = v_x."""
    _, v_x, _ = _fields_at(q, l, z)
    return np.arcsin(v_x / chord_stretch(q, l)[..., None])


def curvature(q, l, z, h=1e-4):
    """kappa = d theta / dx = (1/l) d theta / d zeta, by a 5-point central difference in zeta."""
    return ref.fd_derivative(lambda zz: rotation(q, l, zz), np.asarray(z, float), h) / np.asarray(l)[..., None]


def rate(fn, q, qd, l, z, h=1e-4):
    """d/dt fn(q, l, z) along q + t qd, by a 5-point central difference."""
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    return ref.fd_derivative(lambda s: fn(q + s * qd, l, z), 0.0, h)


def integrate(values, l, w):
    return np.asarray(l) * np.sum(values * w, -1)


def strain_energy(q, l, EA, EI, averaged, n=N_POINTS):
    """1/2 int (EA e^2 + EI kappa^2) dx; averaged: the membrane part l EA e_bar^2 / 2 with e_bar the
    element mean of e."""
    z, w = rule(n)
    e, kappa = strain(q, l, z), curvature(q, l, z)
    bending = integrate(EI * kappa**2 / 2, l, w)
    if averaged:
        e_bar = np.sum(e * w, -1)
        return np.asarray(l) * EA * e_bar**2 / 2 + bending
    return integrate(EA * e**2 / 2, l, w) + bending


def dissipation(q, qd, l, EA, EI, mu, averaged, n=N_POINTS):
    """mu/2 int (EA e'^2 + EI kappa'^2) dx (' = d/dt); averaged: l EA e_bar'^2 for the membrane."""
    z, w = rule(n)
    ed, kd = rate(strain, q, qd, l, z), rate(curvature, q, qd, l, z)
    bending = integrate(mu * EI * kd**2 / 2, l, w)
    if averaged:
        return mu * np.asarray(l) * EA * np.sum(ed * w, -1) ** 2 / 2 + bending
    return integrate(mu * EA * ed**2 / 2, l, w) + bending


def rotary_kinetic_energy(q, qd, l, rhoI, phid, n=N_POINTS):
    """rho I / 2 int (theta' - phid)^2 dx: the unit director -sin(theta) e_i + cos(theta) e_j turns
    at theta' - phid in the inertial frame."""
    z, w = rule(n)
    omega = rate(rotation, q, qd, l, z) - np.asarray(phid)[..., None]
    return integrate(rhoI * omega**2 / 2, l, w)


def rigid_element(x0, l, alpha, cu=0.0, cv=0.0, rate_alpha=0.0, rate_u=0.0, rate_v=0.0):
    """Nodal vector and its rate of an element moved rigidly in the moving frame: turned by alpha
    about its first node, then translated by (cu, cv): the material point x goes to
    (x0 + cu + (x - x0) cos(alpha), cv + (x - x0) sin(alpha)), so u(x) = x0 + cu + (x - x0)
    cos(alpha) - x, v(x) = cv + (x - x0) sin(alpha), v_x = sin(alpha); its rate for alpha' and
    (cu', cv')."""
    q = np.array([cu, cv, np.sin(alpha), cu + l * (np.cos(alpha) - 1), cv + l * np.sin(alpha), np.sin(alpha)])
    qd = np.array([rate_u, rate_v, np.cos(alpha) * rate_alpha,
                   rate_u - l * np.sin(alpha) * rate_alpha, rate_v + l * np.cos(alpha) * rate_alpha,
                   np.cos(alpha) * rate_alpha])
    return q, qd
