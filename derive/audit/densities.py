"""Section 1 of the audit: energies (eqs. 1-7) and dissipation functions, by order."""

from types import MappingProxyType

import sympy as sp

from .. import symbols as s
from ..energies import moving_frame_velocity
from ..groups import _degree, _terms
from .field_symbols import (
    COORDS, GRADIENTS, GRADIENT_RATES, P, RATES, RATE_OF, order_split, psi, psid, u, u_x, ud, ud_x, v,
    v_x, v_xx, vd, vd_x, vd_xx, x, y,
)
from .weak_forms import SLOT, potential_weak_form, weak_form


def eq2_density():
    """Strain energy per unit length as printed in eq. (2)."""
    return sp.expand((s.EA * (u_x**2 + u_x * v_x**2 + v_x**4 / 4) + s.EI * v_xx**2) / 2)


def section_strain_energy(bending, nonlinear=True):
    """(E/2) int_A e_xx^2 dA with e_xx = u_x [+ v_x^2/2] - y * bending (eq. 1 with the given
    bending term) and centroidal axes: int dA = A, int y dA = 0, int y^2 dA = I."""
    strain = u_x + (v_x**2 / 2 if nonlinear else 0) - y * bending
    moments = {0: s.EA, 1: sp.Integer(0), 2: s.EI}       # E times the section moments
    poly = sp.Poly(sp.expand(strain**2 / 2), y)
    return sp.expand(sum(coeff * moments[k] for (k,), coeff in poly.terms()))


STRAIN_ORDERS = {"A": (2, 3, 4), "B": (2, 3), "C": (2,)}


def strain_orders():
    """Eq. (2) split by total order in the displacement gradients u_x, v_x, v_xx: {2, 3, 4}."""
    return order_split(eq2_density(), GRADIENTS)


def strain_density(approach):
    """Strain energy density of an approach: the orders of eq. (2) it keeps (STRAIN_ORDERS)."""
    parts = strain_orders()
    return sp.expand(sum(parts.get(k, 0) for k in STRAIN_ORDERS[approach]))


def membrane_square_check():
    """(A's membrane energy) - EA/2 (u_x + v_x^2/2)^2 (zero: A is a square, eq. 1 -> eq. 2), and
    the minimum over u_x of B's membrane energy EA/2 (u_x^2 + u_x v_x^2) (unbounded below in v_x)."""
    membrane_b = s.EA * (u_x**2 + u_x * v_x**2) / 2
    stationary = sp.solve(sp.diff(membrane_b, u_x), u_x)[0]
    square = sp.expand(eq2_density() - s.EI * v_xx**2 / 2 - s.EA * (u_x + v_x**2 / 2) ** 2 / 2)
    return square, sp.expand(membrane_b.subs(u_x, stationary))


def kinetic_density():
    """Kinetic energy per unit length of the rod, eqs. (4)-(5) integrated over the section:
    centre line (rho A) plus rotary inertia of the section y (-psi e_i + e_j) (rho I)."""
    vel_i, vel_j = moving_frame_velocity(x + u, v, ud, vd)
    rot_i, rot_j = s.phid - psid, psi * s.phid
    return sp.expand((s.rhoA * (vel_i**2 + vel_j**2) + s.rhoI * (rot_i**2 + rot_j**2)) / 2)


# Which eq. (17) quantity a kinetic-energy term builds, by (degree in u, v, psi; degree in rates).
EQ17_PART = {(0, 0): "constant", (0, 2): "m1", (2, 0): "m2", (0, 1): "m3", (1, 0): "m4",
             (1, 1): "bilinear"}


def kinetic_parts(T=None):
    """Kinetic density split by the eq. (17) quantity each term belongs to (EQ17_PART values);
    'bilinear' (terms in both {q} and {qd}) has no counterpart in eq. (17)."""
    T = kinetic_density() if T is None else T
    parts = {name: sp.Integer(0) for name in EQ17_PART.values()}
    for term in _terms(T):
        parts[EQ17_PART[(_degree(term, COORDS), _degree(term, RATES))]] += term
    return MappingProxyType(parts)


def eq17_density(corrected=True):
    """Kinetic density that eq. (17) represents: T without its bilinear (gyroscopic) term.
    corrected=False puts the printed (B3) rotary term -rho I phid^2 psid in place of -rho I phid psid."""
    parts = kinetic_parts()
    density = sum(parts[k] for k in ("constant", "m1", "m2", "m3", "m4"))
    if not corrected:
        exact_term = -s.rhoI * s.phid * psid
        assert exact_term in _terms(parts["m3"])
        density += -exact_term - s.rhoI * s.phid**2 * psid
    return sp.expand(density)


def kelvin_voigt_density(approach):
    """Kelvin-Voigt dissipation density mu/2 [EA edot^2 + EI vd_xx^2]: edot = ud_x + v_x vd_x (A, B,
    the rate of eq. 1's axial strain) or ud_x (C, linear strain)."""
    rate = ud_x if approach == "C" else ud_x + v_x * vd_x
    return sp.expand(s.mu * (s.EA * rate**2 + s.EI * vd_xx**2) / 2)


def eq18_density(approach):
    """Eq. (18) per unit length with P of (B9) a given symbol: 1/2 [EA u_x^2 + EI v_xx^2 + P v_x^2]
    (eq. 3, k_uu + k_psipsi + k_pvv) plus for A 1/2 (EA/4) v_x^4 (k_vvv); C has no k_pvv."""
    density = s.EA * u_x**2 + s.EI * v_xx**2
    if approach in ("A", "B"):
        density += P * v_x**2
    if approach == "A":
        density += s.EA * v_x**4 / 4
    return sp.expand(density / 2)


def printed_elastic_weak_form(approach):
    """Weak form of eq. (20)'s elastic force: variation of eq. (18) with P held fixed, then P = EA u_x."""
    form = potential_weak_form(eq18_density(approach))
    return weak_form({k: d.subs(P, s.EA * u_x) for k, d in form.items()})


def eq24_density(approach):
    """Rayleigh function of eq. (24), D = 1/2 {qd}^T [c] {qd}, c = mu (K_lin + K_non), per unit
    length: K_lin + K_non is the printed secant matrix (each slot density coefficient * its own
    gradient, coefficient frozen) and K_lin contains -m2 (eq. 22)."""
    secant = sp.Integer(0)
    for name, density in printed_elastic_weak_form(approach).items():
        gradient_sym = SLOT[name].field
        coefficient = sp.cancel(density / gradient_sym)
        assert sp.denom(coefficient) == 1, (name, density)
        secant += coefficient * RATE_OF[gradient_sym] ** 2 / 2
    centrifugal = kinetic_parts()["m2"].xreplace({c: RATE_OF[c] for c in COORDS})
    return sp.expand(s.mu * (secant - centrifugal))


def dissipation_density(model, approach):
    """Dissipation density of a damping model: 'eq24' (printed) or 'kelvin-voigt'."""
    return eq24_density(approach) if model == "eq24" else kelvin_voigt_density(approach)


DAMPING_MODELS = ("eq24", "kelvin-voigt")


def dissipation_orders(model, approach):
    """Dissipation density split by total order in the displacements, gradients and their rates."""
    return order_split(dissipation_density(model, approach), COORDS + GRADIENTS + RATES + GRADIENT_RATES)
