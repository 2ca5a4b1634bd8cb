"""Hand-written NumPy reference of the geometrically exact rod's element energies (test helper,
independent of derive/ and SymPy).

From the kinematics, not from the derivation: the centre line's tangent r' = (1 + u_x, v_x) in
the moving frame, the stretch |r'| (numpy.hypot), the section rotation theta of an element of
constant stretch lambda (lambda sin(theta) = v_x, numpy.arcsin), lambda by its stated closed form
(element_stretch; implicit_stretch solves its defining equation exactly, to check it), the curvature
kappa = d theta / dx by a central difference of theta along the element (not a closed formula), the strain and curvature rates and the section's angular velocity
theta' by central differences in time along q + s qd.  Integrals by the Gauss-Legendre rule whose
number of points the schema declares for the exact kernels (their Variant.quadrature, "3-point
Gauss-Legendre ..."): the discrete model is defined by that rule.
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


def _fields_at(q, l, z):
    """u_x, v_x, v_xx (each S + (len(z),)) of nodal vectors q (S + (6,)) at zeta = z."""
    _, _, _, b_u, b_v, b_psi = ref.shape_at(z, np.asarray(l, float)[..., None])
    q = np.asarray(q, float)[..., None, :]
    return np.sum(b_u * q, -1), np.sum(b_v * q, -1), np.sum(b_psi * q, -1)


def strain(q, l, z):
    """e = |r'| - 1 at zeta = z."""
    u_x, v_x, _ = _fields_at(q, l, z)
    return np.hypot(1 + u_x, v_x) - 1


def element_stretch(q, l, n=N_POINTS):
    """lambda of an element of constant stretch, the discrete model's closed form: lambda^2 =
    c^2 + <v_x^2> + var(v_x^2) / (4 c^2), c = 1 + u_x, the means by the rule (the second-order
    solution of implicit_stretch's equation)."""
    z, w = rule(n)
    u_x, v_x, _ = _fields_at(q, l, z)
    c = 1 + u_x[..., 0]
    m2, m4 = np.sum(w * v_x**2, -1), np.sum(w * v_x**4, -1)
    return np.sqrt(c**2 + m2 + (m4 - m2**2) / (4 * c**2))


def implicit_stretch(q, l, n=40):
    """lambda solving <sqrt(lambda^2 - v_x^2)> = 1 + u_x over the element (an n-point rule): the
    constant stretch whose tangents lambda (cos(theta), sin(theta)), sin(theta) = v_x / lambda,
    span the element's axial extent l (1 + u_x).  Bisection."""
    z, w = rule(n)
    u_x, v_x, _ = _fields_at(q, l, z)
    c = 1 + u_x[..., 0]
    low = np.max(np.abs(v_x), -1)
    high = np.sqrt(c**2 + np.max(v_x**2, -1)) + 1.0
    for _ in range(200):
        mid = (low + high) / 2
        axial = np.sum(w * np.sqrt(np.maximum(mid[..., None] ** 2 - v_x**2, 0.0)), -1)
        low, high = np.where(axial < c, mid, low), np.where(axial < c, high, mid)
    return (low + high) / 2


def rotation(q, l, z):
    """theta at zeta = z of an element of constant stretch lambda whose tangent's e_j component is
    the slope v_x: lambda sin(theta) = v_x."""
    _, v_x, _ = _fields_at(q, l, z)
    return np.arcsin(v_x / element_stretch(q, l)[..., None])


def curvature(q, l, z, h=1e-4):
    """kappa = d theta / dx = (1/l) d theta / d zeta, by a 5-point central difference in zeta."""
    return ref.fd_derivative(lambda zz: rotation(q, l, zz), np.asarray(z, float), h) / np.asarray(l)[..., None]


def rate(fn, q, qd, l, z, h=1e-4):
    """d/dt fn(q, l, z) along q + t qd, by a 5-point central difference."""
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    return ref.fd_derivative(lambda s: fn(q + s * qd, l, z), 0.0, h)


def integrate(values, l, w):
    return np.asarray(l) * np.sum(values * w, -1)


def element_strain(q, l):
    """The element's membrane strain lambda - 1 (the averaged membrane)."""
    return element_stretch(q, l) - 1


def strain_energy(q, l, EA, EI, averaged, n=N_POINTS):
    """1/2 int (EA e^2 + EI kappa^2) dx; averaged: the membrane part l EA e_bar^2 / 2 with e_bar the
    element's stretch less 1 (element_strain)."""
    z, w = rule(n)
    e, kappa = strain(q, l, z), curvature(q, l, z)
    bending = integrate(EI * kappa**2 / 2, l, w)
    if averaged:
        return np.asarray(l) * EA * element_strain(q, l) ** 2 / 2 + bending
    return integrate(EA * e**2 / 2, l, w) + bending


def dissipation(q, qd, l, EA, EI, mu, averaged, n=N_POINTS):
    """mu/2 int (EA e'^2 + EI kappa'^2) dx (' = d/dt); averaged: l EA e_bar'^2 for the membrane."""
    z, w = rule(n)
    ed, kd = rate(strain, q, qd, l, z), rate(curvature, q, qd, l, z)
    bending = integrate(mu * EI * kd**2 / 2, l, w)
    if averaged:
        e_bar_rate = ref.fd_derivative(lambda s: element_strain(np.asarray(q) + s * np.asarray(qd), l), 0.0, 1e-4)
        return mu * np.asarray(l) * EA * e_bar_rate**2 / 2 + bending
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
