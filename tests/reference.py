"""Hand-written NumPy reference for the element kernels (independent of derive/ and SymPy).

Everything here is written from the physics, not from the symbolic derivation:

* shape functions of Appendix A and their x-derivatives, typed in by hand;
* element integrals by Gauss-Legendre quadrature (exact for the polynomial degrees involved);
* inertia forces by d'Alembert: the absolute acceleration of a centre-line point, resolved on the
  moving frame (e_i, e_j), projected on the virtual displacement fields N_u, N_v, plus the rotary
  inertia of the cross-section;
* elastic and damping forces as hand-differentiated gradients of the energy densities;
* the printed matrix form (Appendix B with the two numerical errata applied);
* 5-point central finite differences for derivatives that are checked numerically.

Conventions: a leading "element" shape S (e.g. (n,) or (B, n)) is carried by every array; vector
inputs carry their 8 (or 2) components on the trailing axis; scalars broadcast against S.
Inside the quadrature routines an extra axis of length N_GAUSS is appended after S.
"""

import numpy as np

N_GAUSS = 8                     # exact for polynomials of degree <= 15 (highest needed here: 8)
_XG, _WG = np.polynomial.legendre.leggauss(N_GAUSS)
ZETA = (_XG + 1.0) / 2.0        # Gauss points mapped to [0, 1]
WEIGHTS = _WG / 2.0             # weights for int_0^1 f dzeta

APPROACHES = ("A", "B", "C")


# --------------------------------------------------------------------------------------------
# shape functions (Appendix A)
# --------------------------------------------------------------------------------------------

# The element's nodal vector: (u, v, psi, chi) of its first node, then of its second (typed in
# from the element's definition, eq. 14 with the exact rod's axial slope chi = u_x).  Approaches A,
# B and C interpolate u linearly: chi is no field of theirs, so every shape function of theirs
# vanishes in the chi slots.
NODE = ("u", "v", "psi", "chi")
NDOF = 2 * len(NODE)
U0, V0, PSI0, CHI0, U1, V1, PSI1, CHI1 = range(NDOF)
AXIAL, TRANSVERSE, SLOPES, CHIS = [U0, U1], [V0, V1], [PSI0, PSI1], [CHI0, CHI1]
END_UV = slice(U1, V1 + 1)       # the second node's (u, v): where the slider acts


def _slots(z, **columns):
    """An (..., 8) row from {slot: values} (the other slots zero)."""
    out = np.zeros(np.shape(z) + (NDOF,))
    for slot, values in columns.items():
        out[..., NODE.index(slot[:-1]) + len(NODE) * int(slot[-1])] = values
    return out


def shape_at(z, l):
    """(N_u, N_v, N_psi, B_u, B_v, B_psi) at zeta = z for element length l, each (..., 8).

    z and l broadcast against each other.  B_v = dN_v/dx equals N_psi (written out separately
    below, from the derivative of N_v), B_psi = dN_psi/dx.  u linear (approaches A, B, C).
    """
    z, l = np.broadcast_arrays(np.asarray(z, float), np.asarray(l, float))
    one = np.ones_like(z)
    n_u = _slots(z, u0=1 - z, u1=z)
    n_v = _slots(z, v0=1 - 3 * z**2 + 2 * z**3, psi0=z * (z - 1) ** 2 * l,
                 v1=z**2 * (3 - 2 * z), psi1=z**2 * (z - 1) * l)
    # Appendix A as printed
    n_psi = _slots(z, v0=6 * z * (z - 1) / l, psi0=1 - 4 * z + 3 * z**2,
                   v1=-6 * z * (z - 1) / l, psi1=3 * z**2 - 2 * z)
    # d/dx = (1/l) d/dzeta, differentiated by hand
    b_u = _slots(z, u0=-one / l, u1=one / l)
    b_v = _slots(z, v0=(-6 * z + 6 * z**2) / l, psi0=(z - 1) ** 2 + 2 * z * (z - 1),
                 v1=(6 * z - 6 * z**2) / l, psi1=3 * z**2 - 2 * z)
    b_psi = _slots(z, v0=(12 * z - 6) / l**2, psi0=(6 * z - 4) / l,
                   v1=(6 - 12 * z) / l**2, psi1=(6 * z - 2) / l)
    return n_u, n_v, n_psi, b_u, b_v, b_psi


def cubic_u_at(z, l):
    """(N_u, B_u, B_u') of the exact rod's axial field at zeta = z, each (..., 8): cubic Hermite in
    the nodal values u and slopes chi = u_x, the same polynomials as v's in (v, psi)."""
    z, l = np.broadcast_arrays(np.asarray(z, float), np.asarray(l, float))
    n_u = _slots(z, u0=1 - 3 * z**2 + 2 * z**3, chi0=z * (z - 1) ** 2 * l,
                 u1=z**2 * (3 - 2 * z), chi1=z**2 * (z - 1) * l)
    b_u = _slots(z, u0=(-6 * z + 6 * z**2) / l, chi0=(z - 1) ** 2 + 2 * z * (z - 1),
                 u1=(6 * z - 6 * z**2) / l, chi1=3 * z**2 - 2 * z)
    b_uu = _slots(z, u0=(12 * z - 6) / l**2, chi0=(6 * z - 4) / l,
                  u1=(6 - 12 * z) / l**2, chi1=(6 * z - 2) / l)
    return n_u, b_u, b_uu


def _q(x):
    """Append the quadrature axis to an element scalar."""
    return np.asarray(x, float)[..., None]


def _qv(x):
    """Insert the quadrature axis before the trailing component axis of an element vector."""
    return np.asarray(x, float)[..., None, :]


def element_shapes(l):
    """Shape functions at the Gauss points of elements of length l: each S + (N_GAUSS, 8)."""
    return shape_at(ZETA, _q(l))


def integrate(f, l, trailing=0):
    """int_0^l f dx from values f of shape S + (N_GAUSS,) + trailing dims."""
    w = WEIGHTS.reshape((-1,) + (1,) * trailing)
    l = np.asarray(l, float).reshape(np.shape(l) + (1,) * trailing)
    return l * np.sum(w * f, axis=-(1 + trailing))


def dot(a, b):
    return np.sum(a * b, axis=-1)


def outer(a, b):
    return a[..., :, None] * b[..., None, :]


def element_fields(q, qd, l, cubic_u=False):
    """Interpolated fields at the Gauss points (each S + (N_GAUSS,)) and the shape functions; u
    linear, or (cubic_u) the exact rod's cubic u (cubic_u_at)."""
    n_u, n_v, n_psi, b_u, b_v, b_psi = element_shapes(l)
    if cubic_u:
        n_u, b_u, _ = cubic_u_at(ZETA, _q(l))
    q, qd = _qv(q), _qv(qd)
    f = dict(
        u=dot(n_u, q), v=dot(n_v, q), psi=dot(n_psi, q),
        ud=dot(n_u, qd), vd=dot(n_v, qd), psid=dot(n_psi, qd),
        u_x=dot(b_u, q), v_x=dot(b_v, q), v_xx=dot(b_psi, q),
        ud_x=dot(b_u, qd), vd_x=dot(b_v, qd), vd_xx=dot(b_psi, qd),
        N_u=n_u, N_v=n_v, N_psi=n_psi, B_u=b_u, B_v=b_v, B_psi=b_psi,
    )
    return f


# --------------------------------------------------------------------------------------------
# rigid-body kinematics of a point a e_r + xi e_i + eta e_j (moving-frame components)
# --------------------------------------------------------------------------------------------

def frame_velocity(xi, eta, xid, etad, a, theta, thetad, phi, phid):
    """Absolute velocity on (e_i, e_j); de_i/dt = -phid e_j, de_j/dt = phid e_i."""
    v_i = -a * thetad * np.sin(theta + phi) + xid + eta * phid
    v_j = a * thetad * np.cos(theta + phi) - xi * phid + etad
    return v_i, v_j


def frame_acceleration(xi, eta, xid, etad, xidd, etadd, a, theta, thetad, phi, phid, phidd):
    """Absolute acceleration on (e_i, e_j) with thetadd = 0 (crank pin: -a thetad^2 e_r)."""
    acc_i = (-a * thetad**2 * np.cos(theta + phi) + xidd - xi * phid**2
             + 2 * etad * phid + eta * phidd)
    acc_j = (-a * thetad**2 * np.sin(theta + phi) + etadd - 2 * xid * phid
             - xi * phidd - eta * phid**2)
    return acc_i, acc_j


def slider_crank_angles(t, a, omega, L=1.0):
    """theta = omega t and the rod angle phi (sin phi = (a/L) sin theta) with its rates."""
    theta = omega * t
    thetad = omega * np.ones_like(np.asarray(t, float))
    s = a / L * np.sin(theta)
    phi = np.arcsin(s)
    c = np.cos(phi)
    phid = a / L * omega * np.cos(theta) / c
    phidd = (np.sin(phi) * phid**2 - a / L * omega**2 * np.sin(theta)) / c
    return theta, thetad, phi, phid, phidd


# --------------------------------------------------------------------------------------------
# energies
# --------------------------------------------------------------------------------------------

def rod_kinetic_energy(q, qd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid, cubic_u=False):
    """rhoA/2 |R'|^2 of the centre line plus the small-rotation director's rhoI part (eq. 4); u
    linear, or the exact rod's cubic u."""
    f = element_fields(q, qd, l, cubic_u)
    x = _q(l) * ZETA
    xi = _q(x0) + x + f["u"]
    v_i, v_j = frame_velocity(xi, f["v"], f["ud"], f["vd"], _q(a), _q(theta), _q(thetad),
                              _q(phi), _q(phid))
    dens = (_q(rhoA) / 2 * (v_i**2 + v_j**2)
            + _q(rhoI) / 2 * ((_q(phid) - f["psid"]) ** 2 + (f["psi"] * _q(phid)) ** 2))
    return integrate(dens, l)


def slider_kinetic_energy(qs, qsd, ms, L, a, theta, thetad, phi, phid):
    qs, qsd = np.asarray(qs, float), np.asarray(qsd, float)
    v_i, v_j = frame_velocity(L + qs[..., 0], qs[..., 1], qsd[..., 0], qsd[..., 1],
                              a, theta, thetad, phi, phid)
    return ms / 2 * (v_i**2 + v_j**2)


def strain_energy_density(approach, f, EA, EI):
    u_x, v_x, v_xx = f["u_x"], f["v_x"], f["v_xx"]
    if approach == "A":
        e = u_x + v_x**2 / 2
        axial = e**2          # = u_x^2 + u_x v_x^2 + v_x^4 / 4, eq. (2)
    elif approach == "B":
        axial = u_x**2 + u_x * v_x**2
    else:
        axial = u_x**2
    return _q(EA) / 2 * axial + _q(EI) / 2 * v_xx**2


def strain_energy(approach, q, l, EA, EI):
    f = element_fields(q, np.zeros_like(np.asarray(q, float)), l)
    return integrate(strain_energy_density(approach, f, EA, EI), l)


def _strain_rate(approach, f):
    if approach == "C":
        return f["ud_x"]
    return f["ud_x"] + f["v_x"] * f["vd_x"]


def dissipation(approach, q, qd, l, EA, EI, mu):
    f = element_fields(q, qd, l)
    edot = _strain_rate(approach, f)
    dens = _q(mu) / 2 * (_q(EA) * edot**2 + _q(EI) * f["vd_xx"] ** 2)
    return integrate(dens, l)


def strain_energy_averaged(approach, q, l, EA, EI):
    """Element strain energy with the membrane strain u_x + <v_x^2>/2, <.> the element mean."""
    f = element_fields(q, np.zeros_like(np.asarray(q, float)), l)
    l_, EA_ = np.asarray(l, float), np.asarray(EA, float)
    u_x = f["u_x"][..., 0]                       # linear u: u_x is the same at every point
    mean_sq = integrate(f["v_x"] ** 2, l) / l_
    membrane = {"A": (u_x + mean_sq / 2) ** 2, "B": u_x**2 + u_x * mean_sq, "C": u_x**2}[approach]
    return l_ * EA_ * membrane / 2 + integrate(_q(EI) / 2 * f["v_xx"] ** 2, l)


def dissipation_averaged(approach, q, qd, l, EA, EI, mu):
    """Kelvin-Voigt dissipation with the membrane strain rate u_x' + <v_x v_x'>."""
    f = element_fields(q, qd, l)
    l_, EA_, mu_ = (np.asarray(x, float) for x in (l, EA, mu))
    rate = f["ud_x"][..., 0]
    if approach != "C":
        rate = rate + integrate(f["v_x"] * f["vd_x"], l) / l_
    return mu_ / 2 * (l_ * EA_ * rate**2 + integrate(_q(EI) * f["vd_xx"] ** 2, l))


# --------------------------------------------------------------------------------------------
# exact (Lagrange) element forces
# --------------------------------------------------------------------------------------------

def rod_inertia(q, qd, qdd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid, phidd):
    """d'Alembert inertia force of a rod element and its exact tangents (r, K, C, M)."""
    f = element_fields(q, qd, l)
    fa = element_fields(qdd, qdd, l)
    n_u, n_v, n_psi = f["N_u"], f["N_v"], f["N_psi"]
    x = _q(l) * ZETA
    xi = _q(x0) + x + f["u"]
    kin = [_q(k) for k in (a, theta, thetad, phi, phid, phidd)]
    acc_i, acc_j = frame_acceleration(xi, f["v"], f["ud"], f["vd"], fa["u"], fa["v"], *kin)
    pd, pdd = _q(phid), _q(phidd)
    rA, rI = _q(rhoA), _q(rhoI)
    rot = fa["psi"] - pdd - f["psi"] * pd**2          # psidd - phidd - psi phid^2
    dens = (rA[..., None] * (acc_i[..., None] * n_u + acc_j[..., None] * n_v)
            + rI[..., None] * rot[..., None] * n_psi)
    r = integrate(dens, l, 1)
    # tangents, differentiated by hand: d acc_i/dq = -phid^2 N_u + phidd N_v, etc.
    rA2, rI2 = rA[..., None, None], rI[..., None, None]
    pd2, pdd2 = pd[..., None, None], pdd[..., None, None]
    uu, vv, pp = outer(n_u, n_u), outer(n_v, n_v), outer(n_psi, n_psi)
    uv, vu = outer(n_u, n_v), outer(n_v, n_u)
    K = integrate(rA2 * (-pd2**2 * (uu + vv) + pdd2 * (uv - vu)) - rI2 * pd2**2 * pp, l, 2)
    C = integrate(rA2 * 2 * pd2 * (uv - vu), l, 2)
    M = integrate(rA2 * (uu + vv) + rI2 * pp, l, 2)
    return r, K, C, M


def slider_inertia(qs, qsd, qsdd, ms, L, a, theta, thetad, phi, phid, phidd):
    """d'Alembert inertia force of the slider on (u, v) of the rod's last node (r, K, C, M)."""
    qs, qsd, qsdd = (np.asarray(x, float) for x in (qs, qsd, qsdd))
    acc_i, acc_j = frame_acceleration(L + qs[..., 0], qs[..., 1], qsd[..., 0], qsd[..., 1],
                                      qsdd[..., 0], qsdd[..., 1],
                                      a, theta, thetad, phi, phid, phidd)
    ms = np.asarray(ms, float)
    r = ms[..., None] * bstack([acc_i, acc_j])
    shape = np.shape(r)[:-1]
    pd2 = np.broadcast_to(np.asarray(phid, float) ** 2 * ms, shape)
    pdd = np.broadcast_to(np.asarray(phidd, float) * ms, shape)
    pd = np.broadcast_to(np.asarray(phid, float) * ms, shape)
    m = np.broadcast_to(ms, shape)
    K = np.stack([np.stack([-pd2, pdd], -1), np.stack([-pdd, -pd2], -1)], -2)
    C = np.stack([np.stack([0 * pd, 2 * pd], -1), np.stack([-2 * pd, 0 * pd], -1)], -2)
    M = np.stack([np.stack([m, 0 * m], -1), np.stack([0 * m, m], -1)], -2)
    return r, K, C, M


def rod_elastic(approach, q, l, EA, EI):
    """Exact internal force dU/dq and its tangent for an approach (hand-differentiated)."""
    f = element_fields(q, np.zeros_like(np.asarray(q, float)), l)
    u_x, v_x, v_xx = (f[k][..., None] for k in ("u_x", "v_x", "v_xx"))
    b_u, b_v, b_psi = f["B_u"], f["B_v"], f["B_psi"]
    ea, ei = _q(EA)[..., None], _q(EI)[..., None]
    if approach == "A":
        e = u_x + v_x**2 / 2
        g = b_u + v_x * b_v                                   # de/dq
        r_dens = ea * e * g + ei * v_xx * b_psi
        K_dens = ea[..., None] * (outer(g, g) + e[..., None] * outer(b_v, b_v))
    elif approach == "B":
        r_dens = ea * (u_x * b_u + v_x**2 / 2 * b_u + u_x * v_x * b_v) + ei * v_xx * b_psi
        K_dens = ea[..., None] * (outer(b_u, b_u)
                                  + v_x[..., None] * (outer(b_u, b_v) + outer(b_v, b_u))
                                  + u_x[..., None] * outer(b_v, b_v))
    else:
        r_dens = ea * u_x * b_u + ei * v_xx * b_psi
        K_dens = ea[..., None] * outer(b_u, b_u)
    K_dens = K_dens + ei[..., None] * outer(b_psi, b_psi)
    return integrate(r_dens, l, 1), integrate(K_dens, l, 2)


def kelvin_voigt(approach, q, qd, l, EA, EI, mu):
    """Strain-rate damping force dD/dqd and its tangents (r, K = dr/dq, C = dr/dqd)."""
    f = element_fields(q, qd, l)
    b_u, b_v, b_psi = f["B_u"], f["B_v"], f["B_psi"]
    c_ea = (_q(mu) * _q(EA))[..., None]
    c_ei = (_q(mu) * _q(EI))[..., None]
    vd_xx = f["vd_xx"][..., None]
    if approach == "C":
        g = b_u + 0 * b_v
        edot = f["ud_x"][..., None]
        K_dens = 0 * outer(g, g)
    else:
        v_x, vd_x = f["v_x"][..., None], f["vd_x"][..., None]
        g = b_u + v_x * b_v                                   # d edot / d qd
        edot = f["ud_x"][..., None] + v_x * vd_x
        # d/dq [edot g] = g (d edot/dq)^T + edot dg/dq, d edot/dq = vd_x B_v, dg/dq = B_v B_v^T
        K_dens = c_ea[..., None] * (outer(g, vd_x * b_v) + edot[..., None] * outer(b_v, b_v))
    r_dens = c_ea * edot * g + c_ei * vd_xx * b_psi
    C_dens = c_ea[..., None] * outer(g, g) + c_ei[..., None] * outer(b_psi, b_psi)
    return integrate(r_dens, l, 1), integrate(K_dens, l, 2), integrate(C_dens, l, 2)


# --------------------------------------------------------------------------------------------
# the printed matrix form (Appendix B), corrected as docs/errata.md says: B3 -> -rhoI phid N_psi,
# eq. 29 -> -d/dt m_s4
# --------------------------------------------------------------------------------------------

def printed_matrices(q, l, x0, rhoA, rhoI, EA, EI, a, theta, thetad, phi, phid, phidd):
    """m1, m2, m3, d/dt m3, m4, kuu, kpsipsi, kpvv, kvvv of one element (B1-B9) by quadrature."""
    f = element_fields(q, np.zeros_like(np.asarray(q, float)), l)
    n_u, n_v, n_psi = f["N_u"], f["N_v"], f["N_psi"]
    b_u, b_v, b_psi = f["B_u"], f["B_v"], f["B_psi"]
    x = (_q(l) * ZETA)[..., None]
    s2 = lambda v: _q(v)[..., None, None]          # scalar against (gauss, 8, 8)
    s1 = lambda v: _q(v)[..., None]                # scalar against (gauss, 8)
    rA, rI, pd, pdd = s1(rhoA), s1(rhoI), s1(phid), s1(phidd)
    crank = s1(a) * s1(thetad)
    tp = s1(theta) + s1(phi)
    X0 = s1(x0)
    trans = outer(n_u, n_u) + outer(n_v, n_v)
    pp = outer(n_psi, n_psi)
    m = {}
    m["m1"] = integrate(s2(rhoA) * trans + s2(rhoI) * pp, l, 2)
    m["m2"] = integrate(s2(phid) ** 2 * (s2(rhoA) * trans + s2(rhoI) * pp), l, 2)
    m["m3"] = integrate(rA * (crank * np.cos(tp) * n_v - pd * X0 * n_v - pd * x * n_v
                              - crank * np.sin(tp) * n_u) - rI * pd * n_psi, l, 1)
    # d/dt by hand: d(theta + phi)/dt = thetad + phid, thetadd = 0
    rate = s1(thetad) + pd
    m["m3dot"] = integrate(rA * (-crank * rate * np.sin(tp) * n_v - pdd * X0 * n_v
                                 - pdd * x * n_v - crank * rate * np.cos(tp) * n_u)
                           - rI * pdd * n_psi, l, 1)
    m["m4"] = integrate(rA * (-crank * pd * np.sin(tp) * n_v + pd**2 * X0 * n_u
                              + pd**2 * x * n_u - crank * pd * np.cos(tp) * n_u), l, 1)
    m["kuu"] = integrate(s2(EA) * outer(b_u, b_u), l, 2)
    m["kpsipsi"] = integrate(s2(EI) * outer(b_psi, b_psi), l, 2)
    # B_u is constant along the element: P_i = EA B_u^T q
    P = np.asarray(EA, float) * (np.asarray(q, float)[..., U1] - np.asarray(q, float)[..., U0]) \
        / np.asarray(l, float)
    m["P"] = P
    m["G"] = integrate(outer(b_v, b_v) + 0 * s2(l), l, 2)
    m["kpvv"] = P[..., None, None] * m["G"]
    slope = f["v_x"][..., None, None]
    m["kvvv"] = integrate(s2(EA) * slope**2 * outer(b_v, b_v) / 4, l, 2)
    return m


def printed_stiffness(approach, m):
    """(K_lin without -m2, K_non): A keeps k_pvv and 2 k_vvv, B drops k_vvv, C also k_pvv."""
    k_lin = m["kuu"] + m["kpsipsi"]
    k_non = np.zeros_like(k_lin)
    if approach in ("A", "B"):
        k_lin = k_lin + m["kpvv"]
    if approach == "A":
        k_non = 2 * m["kvvv"]
    return k_lin, k_non


def bstack(parts):
    """Stack on a new trailing axis after broadcasting the parts against each other."""
    return np.stack(np.broadcast_arrays(*parts), axis=-1)


def matvec(A, x):
    return np.einsum("...ij,...j->...i", A, x)


def paper_rod_inertia(q, qd, qdd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid, phidd):
    """m1 qdd - m2 q - (m4 - d/dt m3) and its tangents (K = -m2, C = 0, M = m1)."""
    m = printed_matrices(q, l, x0, rhoA, rhoI, 1.0, 1.0, a, theta, thetad, phi, phid, phidd)
    r = matvec(m["m1"], qdd) - matvec(m["m2"], q) - (m["m4"] - m["m3dot"])
    return r, -m["m2"], np.zeros_like(m["m1"]), m["m1"]


def paper_rod_elastic(approach, q, l, EA, EI):
    """(K_lin + K_non) q with P_i and k_vvv taken at q, the secant matrix and the exact tangent."""
    zero = np.zeros(np.shape(l))
    m = printed_matrices(q, l, zero, zero, zero, EA, EI, zero, zero, zero, zero, zero, zero)
    k_lin, k_non = printed_stiffness(approach, m)
    k_sec = k_lin + k_non
    r = matvec(k_sec, q)
    # exact tangent by hand: d/dq (P(q) G q) = P G + (G q) (dP/dq)^T, d/dq (2 kvvv(q) q) = 6 kvvv
    K = m["kuu"] + m["kpsipsi"]
    if approach in ("A", "B"):
        dP = np.zeros(np.shape(q))
        dP[..., U0] = -np.asarray(EA, float) / np.asarray(l, float)
        dP[..., U1] = np.asarray(EA, float) / np.asarray(l, float)
        K = K + m["kpvv"] + outer(matvec(m["G"], q), dP)
    if approach == "A":
        K = K + 6 * m["kvvv"]
    return r, K, k_sec


def paper_slider_inertia(qs, qsd, qsdd, ms, L, a, theta, thetad, phi, phid, phidd):
    """(B13)-(B16) restricted to (u, v) of the end node (zeta = 1): N_u -> (1, 0), N_v -> (0, 1)."""
    qs, qsdd = np.asarray(qs, float), np.asarray(qsdd, float)
    ms, L = np.asarray(ms, float), np.asarray(L, float)
    crank, tp = a * thetad, theta + phi
    ms3 = bstack([ms * (-crank * phid * np.cos(tp) + phid**2 * L),
                  ms * (-crank * phid * np.sin(tp))])
    ms4dot = bstack([ms * (-crank * (thetad + phid) * np.cos(tp)),
                     ms * (-crank * (thetad + phid) * np.sin(tp) - phidd * L)])
    msq = ms[..., None] if np.ndim(ms) else ms
    pd2 = (np.asarray(phid, float) ** 2)[..., None] if np.ndim(phid) else phid**2
    r = msq * qsdd - msq * pd2 * qs - (ms3 - ms4dot)
    shape = np.shape(r)[:-1]
    eye = np.broadcast_to(np.eye(2), shape + (2, 2))
    mm = np.broadcast_to(ms, shape)[..., None, None]
    p2 = np.broadcast_to(np.asarray(phid, float) ** 2, shape)[..., None, None]
    return r, -mm * p2 * eye, 0 * eye, mm * eye


def paper_damping(approach, q, qd, l, EA, EI, rhoA, rhoI, phid, mu):
    """mu (K_lin + K_non) qd with K_lin = k_uu + k_psipsi (+ k_pvv) - m2 (eqs. 22-24); (r, K, C)."""
    zero = np.zeros(np.shape(l))
    m = printed_matrices(q, l, zero, rhoA, rhoI, EA, EI, zero, zero, zero, zero, phid, zero)
    k_lin, k_non = printed_stiffness(approach, m)
    mu2 = np.asarray(mu, float)[..., None, None]
    c = mu2 * (k_lin - m["m2"] + k_non)
    # d r / d q by hand: k_pvv depends on q through P_i, k_vvv through the slope (B_v . q)^2
    K = np.zeros_like(c)
    if approach in ("A", "B"):
        dP = np.zeros(np.shape(q))
        dP[..., U0] = -np.asarray(EA, float) / np.asarray(l, float)
        dP[..., U1] = np.asarray(EA, float) / np.asarray(l, float)
        K = K + mu2 * outer(matvec(m["G"], qd), dP)
    if approach == "A":
        f = element_fields(q, qd, l)
        w = (_q(EA) * f["v_x"] * f["vd_x"])[..., None, None]
        K = K + mu2 * integrate(w * outer(f["B_v"], f["B_v"]), l, 2)
    return matvec(c, qd), K, c


def paper_slider_damping(qsd, ms, phid, mu):
    """-mu m_s2 qd on (u, v): (r, K, C)."""
    qsd = np.asarray(qsd, float)
    coef = np.asarray(mu * ms * phid**2, float)
    r = -coef[..., None] * qsd
    shape = np.shape(r)[:-1]
    eye = np.broadcast_to(np.eye(2), shape + (2, 2))
    return r, 0 * eye, -np.broadcast_to(coef, shape)[..., None, None] * eye


# --------------------------------------------------------------------------------------------
# finite differences (5-point central stencil: exact for polynomials up to degree 4)
# --------------------------------------------------------------------------------------------

def fd_derivative(f, x, h):
    """Central 5-point derivative of f at scalar/array x along a scalar parameter."""
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


def fd_jacobian(f, x, h):
    """d f / d x by 5-point central differences; x (..., m) -> result f-shape + (m,).

    The leading axes of x are independent problems (elements) perturbed simultaneously.
    """
    x = np.asarray(x, float)
    cols = []
    for j in range(x.shape[-1]):
        e = np.zeros_like(x)
        e[..., j] = 1.0
        cols.append(fd_derivative(lambda s: f(x + s * e), 0.0, h))
    return np.stack(cols, axis=-1)


# --------------------------------------------------------------------------------------------
# comparison
# --------------------------------------------------------------------------------------------

def assert_close(actual, expected, rtol, trailing, what, atol=0.0):
    """Per element (leading axes), |actual - expected| <= rtol |expected| + atol, with the
    Frobenius norm over the `trailing` axes (0: scalar per element, 1: vector, 2: matrix)."""
    actual, expected = np.asarray(actual, float), np.asarray(expected, float)
    assert actual.shape == expected.shape, f"{what}: shape {actual.shape} != {expected.shape}"
    assert np.all(np.isfinite(actual)) and np.all(np.isfinite(expected)), f"{what}: not finite"
    axes = tuple(range(actual.ndim - trailing, actual.ndim))
    if trailing:
        err = np.sqrt(np.sum((actual - expected) ** 2, axis=axes))
        scale = np.sqrt(np.sum(expected**2, axis=axes))
    else:
        err, scale = np.abs(actual - expected), np.abs(expected)
    bad = err > rtol * scale + atol
    if np.any(bad):
        idx = tuple(np.argwhere(bad)[0])
        diff = np.abs(actual[idx] - expected[idx])
        worst = np.unravel_index(np.argmax(diff), np.shape(diff)) if trailing else ()
        raise AssertionError(
            f"{what}: element {idx}: relative error {err[idx] / max(scale[idx], 1e-300):.3e} "
            f"> rtol {rtol:g}; worst entry {worst}: actual {np.asarray(actual[idx])[worst]!r}, "
            f"expected {np.asarray(expected[idx])[worst]!r}")


# --------------------------------------------------------------------------------------------
# random test data
# --------------------------------------------------------------------------------------------

def random_nodal(rng, shape):
    """Nodal vectors of realistic magnitude: axial ~1e-3, transverse ~1e-2..1e-1, slopes alike (the
    axial slopes chi like the axial strain, ~1e-3: no field of approaches A, B, C, which must
    ignore them)."""
    mag = np.array([1e-3, 5e-2, 5e-2, 1e-3, 1e-3, 5e-2, 5e-2, 1e-3])
    q = rng.uniform(-1, 1, shape + (NDOF,)) * mag
    q[..., TRANSVERSE] *= rng.uniform(0.2, 2.0, shape + (2,))
    return q


def random_elements(rng, n=7):
    """A batch of n unrelated elements with random geometry, state, material and kinematics."""
    shape = (n,)
    u = lambda lo, hi: rng.uniform(lo, hi, shape)
    d = dict(
        q=random_nodal(rng, shape), qd=3 * random_nodal(rng, shape), qdd=9 * random_nodal(rng, shape),
        l=u(0.05, 0.5), x0=u(0.0, 0.9),
        rhoA=u(0.5, 2.0), rhoI=u(0.01, 0.1), EA=u(10.0, 1000.0), EI=u(0.005, 0.05), mu=u(0.01, 0.5),
        a=u(0.05, 0.3), theta=u(0, 2 * np.pi), thetad=u(0.2, 3.0), phi=u(-0.3, 0.3),
        phid=u(-1.0, 1.0), phidd=u(-2.0, 2.0),
        ms=u(0.1, 1.0), L=u(0.8, 1.2),
    )
    d["qs"] = d["q"][:, END_UV].copy()
    d["qsd"] = d["qd"][:, END_UV].copy()
    d["qsdd"] = d["qdd"][:, END_UV].copy()
    return d


def pick(d, *names):
    return [d[k] for k in names]


KIN = ("a", "theta", "thetad", "phi", "phid", "phidd")
ROD_INERTIA_ARGS = ("q", "qd", "qdd", "l", "x0", "rhoA", "rhoI") + KIN
SLIDER_INERTIA_ARGS = ("qs", "qsd", "qsdd", "ms", "L") + KIN
ROD_T_ARGS = ("q", "qd", "l", "x0", "rhoA", "rhoI") + KIN[:-1]
SLIDER_T_ARGS = ("qs", "qsd", "ms", "L") + KIN[:-1]
