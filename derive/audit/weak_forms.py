"""Weak forms, one density per virtual quantity (slot), their exact map to the element level
(`element_vector`, an exact rational quadrature), and their split by term group (groups.classify)."""

from dataclasses import dataclass
from functools import lru_cache
from types import MappingProxyType

import sympy as sp

from .. import symbols as s
from ..energies import fields
from ..euler_lagrange import total_time_derivative
from ..groups import GROUPS, _terms, classify, Variables
from ..shape_functions import B_PSI, B_U, B_V, N_PSI, N_U, N_V
from .field_symbols import (
    ACCELS, COORDS, GRADIENTS, GRADIENT_RATES, RATES, RATE_OF, psi, psid, psidd, u, u_x, ud, ud_x, udd, v,
    v_x, v_xx, vd, vd_x, vd_xx, vdd, x,
)


@dataclass(frozen=True)
class Slot:
    """A virtual quantity of the weak form, its field symbol and its element column."""

    name: str
    field: sp.Symbol
    shape: sp.ImmutableMatrix
    axial: bool          # True: enters the axial equation (u dofs), False: the transverse one


SLOTS = (
    Slot("u", u, sp.ImmutableMatrix(N_U), True),
    Slot("v", v, sp.ImmutableMatrix(N_V), False),
    Slot("psi", psi, sp.ImmutableMatrix(N_PSI), False),
    Slot("u_x", u_x, sp.ImmutableMatrix(B_U), True),
    Slot("v_x", v_x, sp.ImmutableMatrix(B_V), False),
    Slot("v_xx", v_xx, sp.ImmutableMatrix(B_PSI), False),
)
SLOT = {sl.name: sl for sl in SLOTS}


def weak_form(entries):
    """Read-only {slot name: density}, slots in the fixed order of SLOTS, zero densities dropped."""
    out = {}
    for sl in SLOTS:
        density = sp.expand(entries.get(sl.name, 0))
        if density != 0:
            out[sl.name] = density
    return MappingProxyType(out)


def add_weak(*forms, signs=None):
    """Slot-wise signed sum of weak forms."""
    signs = signs or (1,) * len(forms)
    total = {}
    for sign, form in zip(signs, forms):
        for name, density in form.items():
            total[name] = total.get(name, 0) + sign * density
    return weak_form(total)


@lru_cache(maxsize=None)
def interpolation():
    """Field symbol -> element interpolation (eqs. 8-10, B10-B12) and x -> x0 + l zeta."""
    f, acc = fields(s.q, s.qd), fields(s.qdd, s.qdd)
    names = {u: "u", v: "v", psi: "psi", ud: "ud", vd: "vd", psid: "psid", u_x: "u_x",
             v_x: "v_x", v_xx: "v_xx", ud_x: "ud_x", vd_x: "vd_x", vd_xx: "vd_xx"}
    table = {sym: f[key] for sym, key in names.items()}
    table.update({udd: acc["u"], vdd: acc["v"], psidd: acc["psi"], x: s.x0 + s.l * s.zeta})
    return MappingProxyType(table)


def element_interpolated(expr):
    """A field-level expression with the fields replaced by their element interpolation."""
    return sp.expand(expr.xreplace(dict(interpolation())))


@lru_cache(maxsize=None)
def _newton_cotes(degree):
    """Nodes zeta_k = k / p and weights of the closed rule on [0, 1] that integrates every
    polynomial of the given degree exactly (p = max(degree, 1), exact rational weights)."""
    p = max(degree, 1)
    nodes = [sp.Rational(k, p) for k in range(p + 1)]
    weights = []
    for k, node in enumerate(nodes):
        basis = sp.Poly(sp.Mul(*[(s.zeta - other) / (node - other) for j, other in enumerate(nodes) if j != k]), s.zeta)
        antiderivative = basis.integrate()
        weights.append(antiderivative.eval(1) - antiderivative.eval(0))
    return tuple(nodes), tuple(weights)


@lru_cache(maxsize=None)
def _interpolation_at(node):
    """interpolation() at zeta = node."""
    return {sym: sp.expand(expr.subs(s.zeta, node)) for sym, expr in interpolation().items()}


@lru_cache(maxsize=None)
def _field_zeta_degrees():
    return {sym: sp.degree(expr, s.zeta) for sym, expr in interpolation().items()}


def _zeta_degree(density):
    """Degree in zeta of the interpolated density (an upper bound, term by term)."""
    degrees = _field_zeta_degrees()
    return max((sum(sp.degree(term, f) * d for f, d in degrees.items() if f in term.free_symbols)
                for term in _terms(density)), default=0)


def _quadrature(density, column):
    """int_0^l column * density dx, exactly, by the rule of _newton_cotes of the right degree."""
    degree = _zeta_degree(density) + max(sp.degree(e, s.zeta) for e in column)
    total = sp.zeros(column.shape[0], 1)
    for node, weight in zip(*_newton_cotes(degree)):
        value = sp.expand(density.xreplace(_interpolation_at(node)))
        total += (weight * s.l * value) * column.subs(s.zeta, node)
    return total.applyfunc(sp.expand)


def element_integral(density):
    """int_0^l density dx of a field-level density over one element (exact)."""
    return _quadrature(sp.sympify(density), sp.Matrix([1]))[0, 0]


def element_vector(form):
    """Element vector int_0^l sum_k {N_k} f_k dx of a weak form (k over SLOTS), exact.

    Evaluated by an exact rational quadrature, not by the symbolic integration of
    shape_functions.integrate_element, so comparing the two is a real cross-check."""
    total = sp.zeros(s.ELEMENT_DOFS, 1)
    for name, density in form.items():
        total += _quadrature(density, sp.Matrix(SLOT[name].shape))
    return sp.ImmutableMatrix(total.applyfunc(sp.expand))


def kinetic_weak_form(T):
    """Lagrange weak form d/dt dT/d(fdot) - dT/df, f = u, v, psi, of a kinetic energy density."""
    return weak_form({
        sl.name: total_time_derivative(sp.diff(T, RATE_OF[sl.field]), COORDS, RATES, ACCELS)
        - sp.diff(T, sl.field)
        for sl in SLOTS[:3]
    })


def potential_weak_form(U):
    """Weak form dU/dg, g = u_x, v_x, v_xx, of a strain energy density."""
    return weak_form({sl.name: sp.diff(U, sl.field) for sl in SLOTS[3:]})


def dissipation_weak_form(D):
    """Weak form dD/d(gdot) of a Rayleigh dissipation density, over all six slots."""
    return weak_form({sl.name: sp.diff(D, RATE_OF[sl.field]) for sl in SLOTS})


FIELD_VARS = Variables(frozenset(COORDS + GRADIENTS), frozenset(RATES + GRADIENT_RATES), frozenset(ACCELS))


def group_weak_form(form):
    """{group: weak form} of a field-level weak form (groups in GROUPS order, empty ones left out)."""
    split = {}
    for name, density in form.items():
        for term in _terms(density):
            group = classify(term, FIELD_VARS, SLOT[name].axial)
            split.setdefault(group, {}).setdefault(name, 0)
            split[group][name] += term
    return MappingProxyType({g: weak_form(split[g]) for g in GROUPS if g in split})
