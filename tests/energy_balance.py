"""Power flows of a crankgen trajectory in the inertial frame (test helper).

The rod's material points are R = a e_r + (x + u - y psi) e_i + (y + v) e_j with
e_i = (cos phi, -sin phi), e_j = (sin phi, cos phi), psi = v_x (eq. 4, ERRATA conventions).  The
kinematics of the section is written out here by hand and integrated by Gauss quadrature: this
module does not use crankgen's energy or damping kernels (eq. 24 is written out from Appendix B).
It uses crankgen only for the element residuals of the unreduced system (to read the pin
reaction and the guide reaction), for the DOF layout (Mesh.gather) and for the rigid kinematics
(theta, its rates and phi with its rates; tests/test_four_bar.py and tests/test_crank_motions.py
check them against independent ones).  The rod's end is mapped here from its reduced co-ordinate:
a slider's displacement along the line, or the deviation of a four-bar's rocker angle from the
rigid one (the rigid rocker from tests/four_bar.py); the crank may accelerate (a run-up, a
fluctuating crank: the crank pin's tangential acceleration a thetadd enters the accelerations).

Along a solution of the Lagrange equations of T - U (T the inertial kinetic energy) with the
crank pin and the guide as the only constraints (a straight guide or a rocker pivoted on the
ground: either reaction is normal to the end's path, so it does no work),

    d(T + U)/dt = F_pin . V_pin  -  P_diss  +  phid Q_phi,

where Q_phi is the generalized force on the frame angle: the moment about the crank pin of the
inertia forces (rod and slider) minus that of the guide reaction, i.e. the residual of the rod's
equations in the direction of a rigid rotation of the deformed rod with its frame.  The frame
angle phi(t) is prescribed by the rigid mechanism, so the frame can do work on the rod; it does
none only if the discrete strain energy is invariant under that rotation.  Measured over two
revolutions at Omega* = 0.8 (work relative to the total |pin work|): approach C, whose linear
strain has no geometric stiffness, 0.9 % whatever the mesh (a property of the model); A 0.5 %,
0.4 %, 0.2 % with 2, 4, 8 elements and, with the element-mean membrane strain, 0.4 %, 0.13 %,
0.05 % (the finite elements cannot rotate a deformed rod exactly: a discretization effect).

The geometrically exact rod (approach "exact") has the same centre line; its section's director is
the unit vector d = -sin(theta) e_i + cos(theta) e_j, whose inertial angle is theta - phi, so its
rotary kinetic energy is rho I/2 int (theta' - phid)^2 dx and its part of the frame moment
rho I int (phidd - theta'') dx; its u is cubic in the nodal u and chi = u_x (typed in here like
v); theta, the strain energy and the dissipation are those of exact_reference.py (numpy.arctan2 of
the tangent, the strain pointwise, by the rule the model declares), theta' and theta'' by central
differences in time along the nodal motion.

Element vectors hold (u, v, psi, chi) of each of the element's two nodes (8 slots, reference.py's
layout); approaches A, B and C have no chi (their slots are the DOF map's dummy).
"""

import math

import numpy as np

import exact_reference as xr
from reference import AXIAL, END_UV, TRANSVERSE, U1, V1

N_GAUSS = 6
_XG, _WG = np.polynomial.legendre.leggauss(N_GAUSS)
ZETA, WEIGHTS = (_XG + 1) / 2, _WG / 2


def shapes(z, l, cubic_u=False):
    """N_u, N_u', N_v, N_v' , N_v'' rows (len(z), 8) at zeta = z (typed in by hand): Appendix A's
    (u linear; nodal vector (u, v, psi, chi) of each node), or (cubic_u) the exact rod's u, cubic
    Hermite in u and chi like v in v and psi."""
    z = np.asarray(z, float)
    o = 0 * z
    Nv = np.stack([o, 1 - 3 * z**2 + 2 * z**3, l * z * (z - 1) ** 2, o,
                   o, z**2 * (3 - 2 * z), l * z**2 * (z - 1), o], -1)
    Nvx = np.stack([o, (6 * z**2 - 6 * z) / l, 3 * z**2 - 4 * z + 1, o,
                    o, (6 * z - 6 * z**2) / l, 3 * z**2 - 2 * z, o], -1)
    Nvxx = np.stack([o, (12 * z - 6) / l**2, (6 * z - 4) / l, o, o, (6 - 12 * z) / l**2, (6 * z - 2) / l, o], -1)
    if cubic_u:               # v's rows moved from the (v, psi) slots to the (u, chi) slots
        move = [1, 0, 3, 2, 5, 4, 7, 6]
        return Nv[:, move], Nvx[:, move], Nv, Nvx, Nvxx
    Nu = np.stack([1 - z, o, o, o, z, o, o, o], -1)
    Nux = np.stack([-1 + o, o, o, o, 1 + o, o, o, o], -1) / l
    return Nu, Nux, Nv, Nvx, Nvxx


def frame(phi):
    """e_i, e_j on inertial X, Y; arrays (..., 2)."""
    phi = np.asarray(phi, float)
    return (np.stack([np.cos(phi), -np.sin(phi)], -1), np.stack([np.sin(phi), np.cos(phi)], -1))


def _col(x, like):
    """Time array (Nt,) as a column broadcasting against per-element arrays (Nt, n, k)."""
    x = np.asarray(x, float)
    return x.reshape(x.shape + (1,) * (np.ndim(like) - 1))


def point_kinematics(x, u, ud, udd, v, vd, vdd, kin, a):
    """Inertial velocity and acceleration of the centre-line point x on (e_i, e_j); kin arrays
    of shape (Nt,) (theta, thetad, thetadd, phi, phid, phidd), fields of shape (Nt, ...)."""
    ref = np.broadcast_arrays(u, v)[0]
    ph, phd, phdd = (_col(getattr(kin, k), ref) for k in ("phi", "phid", "phidd"))
    th, thd = _col(kin.theta, ref), _col(kin.thetad, ref)
    Ai, Aj = ud + v * phd, vd - (x + u) * phd                        # d/dt of (x+u) e_i + v e_j
    Bi = udd + vd * phd + v * phdd + Aj * phd                         # second derivative
    Bj = vdd - ud * phd - (x + u) * phdd - Ai * phd
    # crank pin a e_r: velocity a thd e_theta, acceleration -a thd^2 e_r, resolved on the frame
    # (e_r . e_i = cos(theta + phi), e_r . e_j = sin(theta + phi))
    # and, when the crank accelerates, a thdd e_theta (e_theta . e_i = -sin(theta + phi),
    # e_theta . e_j = cos(theta + phi))
    thdd = _col(kin.thetadd, ref)
    Vci, Vcj = -a * thd * np.sin(th + ph), a * thd * np.cos(th + ph)
    Aci = -a * thd**2 * np.cos(th + ph) - a * thdd * np.sin(th + ph)
    Acj = -a * thd**2 * np.sin(th + ph) + a * thdd * np.cos(th + ph)
    return (Vci + Ai, Vcj + Aj), (Aci + Bi, Acj + Bj)


def section_rates(psi, psid, psidd, kin):
    """Rotary part per unit y: first and second time derivatives of (-psi e_i + e_j) on (e_i, e_j)."""
    phd, phdd = _col(kin.phid, psi), _col(kin.phidd, psi)
    Ci, Cj = phd - psid, psi * phd
    Di = phdd - psidd + Cj * phd
    Dj = psid * phd + psi * phdd - Ci * phd
    return (Ci, Cj), (Di, Dj)


def rod_fields(model, q, qd, qdd):
    """Fields at the Gauss points (Nt, n, N_GAUSS): x, u, v, psi = v_x, u_x, v_xx and rates."""
    mesh = model.mesh
    l = mesh.length
    Nu, Nux, Nv, Nvx, Nvxx = shapes(ZETA, l, model.options["approach"] == "exact")
    f = {"x": mesh.x0[:, None] + l * ZETA[None, :], "l": l}
    for name, Q in (("", q), ("d", qd), ("dd", qdd)):
        for key, N in (("u", Nu), ("v", Nv), ("psi", Nvx), ("ux", Nux), ("vxx", Nvxx)):
            f[key + name] = Q @ N.T
    return f


def _integrate(f, density):
    """int_0^1 density dx for each time: (Nt,)."""
    return np.sum(density * WEIGHTS, axis=(-2, -1)) * f["l"]


def slider_state(s, sd, sdd, kin):
    """(u, v) of the slider end and their rates from its displacement s along the guide:
    (u, v) = s (cos phi, sin phi) on the frame (the guide is the X axis)."""
    c, sn, phd, phdd = np.cos(kin.phi), np.sin(kin.phi), kin.phid, kin.phidd
    u, v = s * c, s * sn
    ud, vd = sd * c - s * sn * phd, sd * sn + s * c * phd
    udd = sdd * c - 2 * sd * sn * phd - s * (c * phd**2 + sn * phdd)
    vdd = sdd * sn + 2 * sd * c * phd + s * (c * phdd - sn * phd**2)
    return np.stack([u, v], -1), np.stack([ud, vd], -1), np.stack([udd, vdd], -1)


def rocker_state(s, sd, sdd, kin, case):
    """(u, v) of the rod's end on a four-bar's rocker and their rates, from the deviation s of the
    rocker angle from the rigid one, beta + s (the rigid beta and its rates from the independent
    position analysis of four_bar.py): W = B(beta + s) - A - e_i on (e_i, e_j), B = D + c (cos,
    sin)(beta + s), differentiated by hand with de_i/dt = -phid e_j, de_j/dt = phid e_i.  Also the
    rocker's tangent at the end on the frame, (..., 2)."""
    import four_bar
    a, c, d, e = case.a, case.c, case.d, case.offset
    k = four_bar.four_bar(kin.theta, kin.thetad, kin.thetadd, a, c, d, e, case.branch)
    ph, phd, phdd = kin.phi, kin.phid, kin.phidd
    th, thd, thdd = kin.theta, kin.thetad, kin.thetadd
    ei = np.stack([np.cos(ph), -np.sin(ph)], -1)
    ej = np.stack([np.sin(ph), np.cos(ph)], -1)
    b, bd, bdd = k["beta"] + s, k["betad"] + sd, k["betadd"] + sdd
    ub = np.stack([np.cos(b), np.sin(b)], -1)
    tb = np.stack([-np.sin(b), np.cos(b)], -1)
    er = np.stack([np.cos(th), np.sin(th)], -1)
    et = np.stack([-np.sin(th), np.cos(th)], -1)
    col = lambda x: np.asarray(x, float)[..., None]                          # noqa: E731
    W = np.array([d, e]) + c * ub - a * er - ei
    Wd = c * col(bd) * tb - a * col(thd) * et + col(phd) * ej
    Wdd = (c * col(bdd) * tb - c * col(bd**2) * ub - a * col(thdd) * et + a * col(thd**2) * er
           + col(phdd) * ej + col(phd**2) * ei)
    dot = lambda x, y: np.sum(x * y, -1)                                      # noqa: E731
    u, v = dot(W, ei), dot(W, ej)
    ud, vd = dot(Wd, ei) - phd * v, dot(Wd, ej) + phd * u
    udd = dot(Wdd, ei) - 2 * phd * dot(Wd, ej) - phdd * v - phd**2 * u
    vdd = dot(Wdd, ej) + 2 * phd * dot(Wd, ei) + phdd * u - phd**2 * v
    tangent = np.stack([dot(tb, ei), dot(tb, ej)], -1)
    return np.stack([u, v], -1), np.stack([ud, vd], -1), np.stack([udd, vdd], -1), tangent


def end_state(model, kin, s, sd, sdd):
    """(u, v) of the rod's end and rates from its reduced co-ordinate on the case's guide, and the
    guide's tangent on the frame at the end."""
    case = model.case
    if case.guide == "line":
        out = slider_state(s, sd, sdd, kin)
        return out + (np.stack([np.cos(kin.phi), np.sin(kin.phi)], -1),)
    assert case.guide == "circle", case.guide
    return rocker_state(s, sd, sdd, kin, case)


def nodal_states(model, kin, d, v, a):
    """Element nodal vectors (Nt, n, 8) of reduced histories (Nt, N), the end mapped here."""
    mesh = model.mesh
    q, qd, qdd = mesh.gather(d), mesh.gather(v), mesh.gather(a)
    S = mesh.reduced_coordinates()[0]
    for Q, val in zip((q, qd, qdd), end_state(model, kin, d[:, S], v[:, S], a[:, S])[:3]):
        Q[:, -1, END_UV] = val
    return q, qd, qdd


def kinetic_energy(model, kin, q, qd):
    """T_rod + T_slider in the inertial frame, from the point kinematics above."""
    m = model.mechanism
    f = rod_fields(model, q, qd, 0 * q)
    (Vi, Vj), _ = point_kinematics(f["x"], f["u"], f["ud"], 0, f["v"], f["vd"], 0, kin, m.a)
    if model.options["approach"] == "exact":
        T = 0.5 * _integrate(f, m.rhoA * (Vi**2 + Vj**2))
        T = T + np.sum(xr.rotary_kinetic_energy(q, qd, model.mesh.length, m.rhoI, kin.phid[:, None]), -1)
    else:
        (Ci, Cj), _ = section_rates(f["psi"], f["psid"], 0, kin)
        T = 0.5 * _integrate(f, m.rhoA * (Vi**2 + Vj**2) + m.rhoI * (Ci**2 + Cj**2))
    (Vsi, Vsj), _ = point_kinematics(1.0, q[:, -1, U1], qd[:, -1, U1], 0, q[:, -1, V1], qd[:, -1, V1], 0, kin, m.a)
    return T + 0.5 * m.ms * (Vsi**2 + Vsj**2)


def _element_mean(g):
    return np.broadcast_to(np.sum(g * WEIGHTS, axis=-1, keepdims=True), g.shape)


def strain_energy(model, q, approach, averaged=False):
    """Eq. (2) for A; without the quartic term for B; linear strain for C.  averaged: the
    membrane strain uses the element mean of v_x^2 (A and B; the exact rod's strain is pointwise)."""
    m = model.mechanism
    if approach == "exact":
        return np.sum(xr.strain_energy(q, model.mesh.length, m.EA, m.EI), -1)
    f = rod_fields(model, q, 0 * q, 0 * q)
    vx2 = _element_mean(f["psi"] ** 2) if averaged else f["psi"] ** 2
    axial = {"A": (f["ux"] + vx2 / 2) ** 2, "B": f["ux"] ** 2 + f["ux"] * vx2, "C": f["ux"] ** 2}[approach]
    return 0.5 * _integrate(f, m.EA * axial + m.EI * f["vxx"] ** 2)


def kelvin_voigt_power(model, q, qd, approach, averaged=False):
    """2 D = mu int [EA (d/dt e)^2 + EI (d/dt v_xx)^2] dx, e the approach's axial strain."""
    m = model.mechanism
    if approach == "exact":
        return 2 * np.sum(xr.dissipation(q, qd, model.mesh.length, m.EA, m.EI, m.mu), -1)
    f = rod_fields(model, q, qd, 0 * q)
    vvd = f["psi"] * f["psid"]
    ed = f["uxd"] + ((_element_mean(vvd) if averaged else vvd) if approach in "AB" else 0)
    return m.mu * _integrate(f, m.EA * ed**2 + m.EI * f["vxxd"] ** 2)


def frame_moment(model, kin, q, qd, qdd):
    """int rho Rdd . dR/dphi dV + ms Rsdd . dRs/dphi, dR/dphi = v e_i - (x + u) e_j + y (e_i + psi e_j)."""
    m = model.mechanism
    f = rod_fields(model, q, qd, qdd)
    _, (Bi, Bj) = point_kinematics(f["x"], f["u"], f["ud"], f["udd"], f["v"], f["vd"], f["vdd"], kin, m.a)
    if model.options["approach"] == "exact":
        J = _integrate(f, m.rhoA * (Bi * f["v"] - Bj * (f["x"] + f["u"])))
        J = J + np.sum(m.rhoI * _exact_rotary_moment(model, kin, q, qd, qdd), -1)
    else:
        _, (Di, Dj) = section_rates(f["psi"], f["psid"], f["psidd"], kin)
        J = _integrate(f, m.rhoA * (Bi * f["v"] - Bj * (f["x"] + f["u"])) + m.rhoI * (Di + Dj * f["psi"]))
    us, vs = q[:, -1, U1], q[:, -1, V1]
    _, (Bsi, Bsj) = point_kinematics(1.0, us, qd[:, -1, U1], qdd[:, -1, U1], vs, qd[:, -1, V1], qdd[:, -1, V1], kin, m.a)
    return J + m.ms * (Bsi * vs - Bsj * (1.0 + us))


def _exact_rotary_moment(model, kin, q, qd, qdd, h=1e-3):
    """int (phidd - theta'') dx per element (Nt, n): d'' . dd/dphi of the unit director, whose
    inertial angle is theta - phi; theta'' = d^2/ds^2 theta(q + s qd + s^2/2 qdd) at s = 0 by a
    5-point central difference (theta measured from its value at s = 0: no branch of arctan2 is
    crossed), by the model's rule."""
    l = model.mesh.length
    z, w = xr.rule()

    def theta(s):
        return xr._turn(q + s * qd + s**2 / 2 * qdd, l, z, q, z)
    second = (-theta(2 * h) + 16 * theta(h) - 30 * theta(0.0) + 16 * theta(-h) - theta(-2 * h)) / (12 * h**2)
    return xr.integrate(kin.phidd[:, None, None] - second, l, w)


def damping_forces(model, kin, q, qd):
    """(rod (Nt, n, 8), slider (Nt, 2)) forces of the model's damping kernels."""
    r_d = _family_forces(model, kin, q, qd, 0 * q, "rod", {"dissipation"})
    r_sd = _family_forces(model, kin, q, qd, 0 * q, "end", {"slider_dissipation"})[:, END_UV]
    return r_d, r_sd


def _family_forces(model, kin, q, qd, qdd, part, names):
    """Sum of the residuals of the model's selected kernels of the named families on every element
    ('rod': (Nt, n, 8)) or on the last one ('end': (Nt, 8))."""
    geo, coef = model.geometry, model.coefficients
    if part == "rod":
        args, shape = (q, qd, qdd, geo, coef, kin.vector[:, None, :]), q.shape
    else:
        args, shape = (q[:, -1], qd[:, -1], qdd[:, -1], geo[-1], coef, kin.vector), q[:, -1].shape
    total = np.zeros(shape)
    for name, kernel in model.selection.vectorized(part):
        if name in names:
            total = total + kernel(*args)[0]
    return total


def printed_damping_forces(model, kin, q, qd, approach):
    """Eq. (24) written out here: C qd = mu (K_lin + K_non) qd with K_lin = k_uu + k_psipsi + k_pvv
    - m2 (eq. 22; k_pvv with P_i = EA u_x, the element's constant axial strain, A and B only),
    K_non = 2 k_vvv = (EA/2) v_x^2 B_v B_v^T (A only); at the slider -mu m_s2 qd (eq. 28)."""
    m = model.mechanism
    f = rod_fields(model, q, qd, 0 * q)
    Nu, Nux, Nv, Nvx, Nvxx = shapes(ZETA, f["l"])
    phd2 = _col(kin.phid, f["u"]) ** 2
    wl = WEIGHTS * f["l"]
    axial = m.EA * f["uxd"]
    transverse_slope = m.EA * f["ux"] * f["psid"] if approach in "AB" else 0 * f["psid"]
    if approach == "A":
        transverse_slope = transverse_slope + 0.5 * m.EA * f["psi"] ** 2 * f["psid"]
    r = ((axial * wl) @ Nux + (transverse_slope * wl) @ Nvx + (m.EI * f["vxxd"] * wl) @ Nvxx
         - (phd2 * m.rhoA * f["ud"] * wl) @ Nu - (phd2 * m.rhoA * f["vd"] * wl) @ Nv
         - (phd2 * m.rhoI * f["psid"] * wl) @ Nvx)
    r_s = -m.ms * kin.phid[:, None] ** 2 * qd[:, -1, END_UV]
    return m.mu * r, m.mu * r_s


def unreduced_residual(model, kin, q, qd, qdd):
    """Element residuals (Nt, n, 8) of the unreduced system from crankgen's kernels: the pinned
    rows (pin reaction) and the slider rows (guide reaction) are kept, nothing is projected."""
    r = _family_forces(model, kin, q, qd, qdd, "rod", {"inertia", "elastic", "gravity"})
    r_d, r_sd = damping_forces(model, kin, q, qd)
    r = r + r_d
    r[:, -1, END_UV] += _family_forces(model, kin, q, qd, qdd, "end", {"slider_inertia", "slider_gravity"})[:, END_UV]
    r[:, -1, END_UV] += r_sd
    return r


def power_history(model, t, d, v, a, averaged=False):
    """Along reduced histories (Nt, N): E = T + U and the powers of the balance
    dE/dt = P_pin - P_diss + P_frame + P_resultant (module docstring), each (Nt,).
    P_resultant = -(net damping force) . V_pin: zero for Kelvin-Voigt damping (internal forces),
    not for eq. (24), whose -mu m2 part has a net resultant that the pin must balance."""
    m, options = model.mechanism, model.options
    kin = model.kinematics(t)
    q, qd, qdd = nodal_states(model, kin, d, v, a)
    r = unreduced_residual(model, kin, q, qd, qdd)
    ei, ej = frame(kin.phi)
    V_pin = m.a * kin.thetad[:, None] * np.stack([-np.sin(kin.theta), np.cos(kin.theta)], -1)
    F_pin = r[:, 0, 0:1] * ei + r[:, 0, 1:2] * ej                  # force of the crank on the rod
    r_d, r_sd = damping_forces(model, kin, q, qd)
    if options["damping"] == "kelvin-voigt":
        P_diss = kelvin_voigt_power(model, q, qd, options["approach"], averaged)
    else:                           # eq. (24): qd . C qd, C written out here (not the kernels)
        r_d, r_sd = printed_damping_forces(model, kin, q, qd, options["approach"])
        P_diss = np.sum(r_d * qd, axis=(1, 2)) + np.sum(r_sd * qd[:, -1, END_UV], axis=1)
    net_i = np.sum(r_d[:, :, AXIAL], axis=(1, 2)) + r_sd[:, 0]
    net_j = np.sum(r_d[:, :, TRANSVERSE], axis=(1, 2)) + r_sd[:, 1]
    rs = r[:, -1, END_UV]                                           # guide reaction on (e_i, e_j)
    us, vs = q[:, -1, U1], q[:, -1, V1]
    Q_phi = frame_moment(model, kin, q, qd, qdd) - (rs[:, 0] * vs - rs[:, 1] * (1.0 + us))
    T = kinetic_energy(model, kin, q, qd)
    U = strain_energy(model, q, options["approach"], averaged)
    S = model.mesh.reduced_coordinates()[0]
    tangent = end_state(model, kin, d[:, S], v[:, S], a[:, S])[3]
    return {"E": T + U, "T": T, "U": U,
            "P_pin": np.sum(F_pin * V_pin, -1), "P_diss": P_diss, "P_frame": kin.phid * Q_phi,
            "P_resultant": -np.sum((net_i[:, None] * ei + net_j[:, None] * ej) * V_pin, -1),
            "guide": np.sum(rs * tangent, -1)}


def cumulative(t, p):
    """Trapezoidal running integral (the average-acceleration rule's own quadrature)."""
    return np.concatenate([[0.0], np.cumsum(0.5 * np.diff(t) * (p[1:] + p[:-1]))])
