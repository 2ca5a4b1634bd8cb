"""Stage 2: element energies from eqs. (2)-(7), with the reduced strain energies of approaches B, C.

Kinematic convention (docs/errata.md): e_i = (cos phi, -sin phi), e_j = (sin phi, cos phi) in the inertial
frame, so de_i/dt = -phid e_j and de_j/dt = phid e_i.  The crank pin is at a e_r, e_r = (cos theta,
sin theta); e_r . e_i = cos(theta + phi), e_theta . e_i = -sin(theta + phi).
"""

import sympy as sp

from . import symbols as s
from .shape_functions import B_PSI, B_U, B_V, N_PSI, N_U, N_V, integrate_element

APPROACHES = ("A", "B", "C")


def _dot(column, vector):
    return (column.T * vector)[0, 0]


def fields(q, qd):
    """Interpolated fields (eqs. 8-10) and gradients of one element."""
    return {
        "u": _dot(N_U, q), "v": _dot(N_V, q), "psi": _dot(N_PSI, q),
        "ud": _dot(N_U, qd), "vd": _dot(N_V, qd), "psid": _dot(N_PSI, qd),
        "u_x": _dot(B_U, q), "v_x": _dot(B_V, q), "v_xx": _dot(B_PSI, q),
        "ud_x": _dot(B_U, qd), "vd_x": _dot(B_V, qd), "vd_xx": _dot(B_PSI, qd),
    }


def moving_frame_velocity(xi, eta, xid, etad):
    """Components along (e_i, e_j) of the velocity of the point a e_r + xi e_i + eta e_j (eqs. 4, 7)."""
    crank = s.a * s.thetad
    vel_i = -crank * sp.sin(s.theta + s.phi) + xid + eta * s.phid
    vel_j = crank * sp.cos(s.theta + s.phi) - xi * s.phid + etad
    return vel_i, vel_j


def rod_kinetic_energy_density(q=s.q, qd=s.qd):
    """Kinetic energy per unit length, eq. (5) integrated over the cross-section (eq. 4).

    With int y dA = 0 and int y^2 dA = I the section integral splits into the centre-line part
    (rho A) and the rotary-inertia part (rho I) of the rotating section, R = ... + y (-psi e_i + e_j).
    """
    f = fields(q, qd)
    x = s.x0 + s.l * s.zeta
    vel_i, vel_j = moving_frame_velocity(x + f["u"], f["v"], f["ud"], f["vd"])
    rotary_i = s.phid - f["psid"]          # d/dt(-psi e_i + e_j) . e_i
    rotary_j = f["psi"] * s.phid           # d/dt(-psi e_i + e_j) . e_j
    return (s.rhoA * (vel_i**2 + vel_j**2) + s.rhoI * (rotary_i**2 + rotary_j**2)) / 2


def rod_kinetic_energy(q=s.q, qd=s.qd):
    """Element kinetic energy T_i, eq. (5) over one element."""
    return integrate_element(rod_kinetic_energy_density(q, qd))


def slider_kinetic_energy(qs=s.qs, qsd=s.qsd):
    """Slider kinetic energy T_s, eqs. (6)-(7); (qs0, qs1) = (u, v) of the rod's last node."""
    vel_i, vel_j = moving_frame_velocity(s.L + qs[0], qs[1], qsd[0], qsd[1])
    return sp.expand(s.ms * (vel_i**2 + vel_j**2) / 2)


def axial_strain(approach, q=s.q):
    """Axial strain of the neutral axis: non-linear (eq. 1) for A and B, linear for C."""
    f = fields(q, q)
    if approach == "C":
        return f["u_x"]
    return f["u_x"] + f["v_x"] ** 2 / 2


def strain_energy_density(approach, q=s.q):
    """Strain energy per unit length: eq. (2) for A, without 1/4 v_x^4 for B, linear strain for C."""
    f = fields(q, q)
    u_x, v_x = f["u_x"], f["v_x"]
    membrane = {
        "A": u_x**2 + u_x * v_x**2 + v_x**4 / 4,
        "B": u_x**2 + u_x * v_x**2,
        "C": u_x**2,
    }[approach]
    return (s.EA * membrane + s.EI * f["v_xx"] ** 2) / 2


def strain_energy(approach, q=s.q):
    """Element strain energy U_i of the approach."""
    return integrate_element(strain_energy_density(approach, q))


def strain_rate(approach, q=s.q, qd=s.qd):
    """Time derivative of the approach's axial strain measure.

    B keeps the non-linear strain of eq. (1) (it only truncates the energy), so it shares A's
    strain rate; C uses the linear strain.  Using a full square keeps D >= 0 in every approach.
    """
    f = fields(q, qd)
    if approach == "C":
        return f["ud_x"]
    return f["ud_x"] + f["v_x"] * f["vd_x"]


def kelvin_voigt_dissipation_density(approach, q=s.q, qd=s.qd):
    """Rayleigh dissipation per unit length, D = mu/2 [EA edot^2 + EI (d/dt v_xx)^2]."""
    f = fields(q, qd)
    return s.mu * (s.EA * strain_rate(approach, q, qd) ** 2 + s.EI * f["vd_xx"] ** 2) / 2


def kelvin_voigt_dissipation(approach, q=s.q, qd=s.qd):
    """Element Rayleigh dissipation function of the strain-rate (Kelvin-Voigt) damping model."""
    return integrate_element(kelvin_voigt_dissipation_density(approach, q, qd))


# ----------------------------------------------------------------------------------------------
# Element option: membrane strain averaged over the element (assumed strain, no membrane locking)
# ----------------------------------------------------------------------------------------------
#
# With linear u and cubic v, u_x is constant in an element while v_x^2 / 2 is a quartic in x, so
# the membrane strain u_x + v_x^2/2 cannot vanish for an inextensional bending shape: the element
# stores spurious membrane energy (and, with strain-rate damping, dissipates spuriously) when it
# bends, and converges slowly (membrane locking).  The cure used here replaces v_x^2 in the
# membrane strain by its element mean <v_x^2> = (1/l) int v_x^2 dx, which the linear u can match;
# bending (EI v_xx^2) is unchanged, and so is approach C (linear strain).

MEMBRANE_OPTIONS = ("pointwise", "averaged")


def mean_over_element(expr):
    """(1/l) int_0^l expr dx."""
    return sp.expand(integrate_element(expr) / s.l)


def strain_energy_averaged(approach, q=s.q):
    """Element strain energy with the element-mean membrane strain e = u_x + <v_x^2>/2."""
    f = fields(q, q)
    u_x = f["u_x"]                               # constant in the element
    m = mean_over_element(f["v_x"] ** 2)
    membrane = {
        "A": (u_x + m / 2) ** 2,
        "B": u_x**2 + u_x * m,
        "C": u_x**2,
    }[approach]
    return sp.expand(s.l * s.EA * membrane / 2 + integrate_element(s.EI * f["v_xx"] ** 2 / 2))


def kelvin_voigt_dissipation_averaged(approach, q=s.q, qd=s.qd):
    """Kelvin-Voigt dissipation with the element-mean membrane strain rate u_x' + <v_x v_x'>."""
    f = fields(q, qd)
    rate = f["ud_x"] if approach == "C" else f["ud_x"] + mean_over_element(f["v_x"] * f["vd_x"])
    return sp.expand(s.mu * (s.l * s.EA * rate**2 + integrate_element(s.EI * f["vd_xx"] ** 2)) / 2)


# ----------------------------------------------------------------------------------------------
# Gravity: potential energy of the rod and the slider in a uniform field g = (gX, gY)
# ----------------------------------------------------------------------------------------------
#
# Inertial frame: X along the guide towards the slider, Y perpendicular, crank pin at
# a (cos theta, sin theta); e_i = (cos phi, -sin phi), e_j = (sin phi, cos phi) (module docstring).

def inertial_position(xi, eta):
    """Inertial (X, Y) of the point a e_r + xi e_i + eta e_j of the moving frame (eq. 4)."""
    X = s.a * sp.cos(s.theta) + xi * sp.cos(s.phi) + eta * sp.sin(s.phi)
    Y = s.a * sp.sin(s.theta) - xi * sp.sin(s.phi) + eta * sp.cos(s.phi)
    return X, Y


def rod_gravity_potential(q=s.q):
    """Element potential of gravity, V_i = -int rho A g . R dx (the rotary part y(-psi e_i + e_j)
    of eq. 4 integrates to zero over the section, int y dA = 0)."""
    f = fields(q, q)
    X, Y = inertial_position(s.x0 + s.l * s.zeta + f["u"], f["v"])
    return integrate_element(-s.rhoA * (s.gX * X + s.gY * Y))


def slider_gravity_potential(qs=s.qs):
    """Potential of gravity on the slider, V_s = -m_s g . R_s (R_s: eq. 7's point at x = L)."""
    X, Y = inertial_position(s.L + qs[0], qs[1])
    return sp.expand(-s.ms * (s.gX * X + s.gY * Y))
