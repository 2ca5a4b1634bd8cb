"""Section 3 of the audit: the printed matrix form (eqs. 17-29, Appendix B) against the exact
Lagrange equations."""

from dataclasses import dataclass
from functools import lru_cache
from types import MappingProxyType

import sympy as sp

from .. import printed
from .. import symbols as s
from ..euler_lagrange import gradient, jacobian
from ..groups import ELEMENT_VARS, GROUPS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from ..shape_functions import B_U, B_V, integrate_element
from .densities import eq24_density, kinetic_parts, printed_elastic_weak_form
from .field_symbols import APPROACHES, GRADIENTS, GRADIENT_RATES, RATE_OF, v_x
from .residuals import (
    printed_set, rod_U, rod_elastic, rod_elastic_weak, rod_inertia, rod_inertia_weak, slider_inertia,
)
from .weak_forms import (
    SLOT, add_weak, element_integral, element_interpolated, element_vector, group_weak_form, weak_form,
)


@dataclass(frozen=True)
class Difference:
    """A term of the exact equations missing from (or different in) a printed form.

    element = exact - printed for one group, element level; weak = its field-level weak form
    (rod only; None for the slider, whose equations are already point equations)."""

    component: str           # "rod inertia", "rod elastic", "slider inertia"
    formulation: str         # "paper" (errata applied) or "printed" (as printed, extra items only)
    approaches: tuple        # approaches the difference applies to
    group: str
    element: sp.ImmutableMatrix
    weak: object


def _group_differences(exact, candidate, variables, axial_rows):
    ge, gc = group_vector(exact, variables, axial_rows), group_vector(candidate, variables, axial_rows)
    out = {}
    for g in GROUPS:
        zero = sp.zeros(exact.shape[0], 1)
        d = (ge.get(g, zero) - gc.get(g, zero)).applyfunc(sp.expand)
        if d != zero:
            out[g] = sp.ImmutableMatrix(d)
    return out


def _weak_difference(exact_form, candidate_form, group):
    ge, gc = group_weak_form(exact_form), group_weak_form(candidate_form)
    empty = weak_form({})
    return add_weak(ge.get(group, empty), gc.get(group, empty), signs=(1, -1))


@lru_cache(maxsize=None)
def differences():
    """Every group in which a printed form differs from the exact Lagrange equations.

    'paper' items compare the errata-applied form; 'printed' items list only what the printed text
    adds on top of them.  Field-level weak forms are checked against the element level here."""
    out = []
    paper_items = {}
    for formulation in ("paper", "printed"):
        rod = _group_differences(rod_inertia("lagrange"), rod_inertia(formulation), ELEMENT_VARS, ROD_AXIAL_ROWS)
        for g, d in rod.items():
            if formulation == "printed" and paper_items.get(("rod inertia", g)) == d:
                continue
            weak = _weak_difference(rod_inertia_weak("lagrange"), rod_inertia_weak(formulation), g)
            assert element_vector(weak) == d, ("rod inertia", formulation, g)
            out.append(Difference("rod inertia", formulation, APPROACHES, g, d, weak))
            paper_items[("rod inertia", g)] = d
        slider = _group_differences(slider_inertia("lagrange"), slider_inertia(formulation),
                                    SLIDER_VARS, SLIDER_AXIAL_ROWS)
        for g, d in slider.items():
            if formulation == "printed" and paper_items.get(("slider inertia", g)) == d:
                continue
            out.append(Difference("slider inertia", formulation, APPROACHES, g, d, None))
            paper_items[("slider inertia", g)] = d
    elastic = {}
    for ap in APPROACHES:
        diffs = _group_differences(rod_elastic("lagrange", ap), rod_elastic("paper", ap),
                                   ELEMENT_VARS, ROD_AXIAL_ROWS)
        for g, d in diffs.items():
            elastic.setdefault((g, d), []).append(ap)
    for (g, d), aps in elastic.items():
        weak = _weak_difference(rod_elastic_weak("lagrange", aps[0]), rod_elastic_weak("paper", aps[0]), g)
        assert element_vector(weak) == d, ("rod elastic", g)
        out.append(Difference("rod elastic", "paper", tuple(aps), g, d, weak))
    order = {"rod inertia": 0, "rod elastic": 1, "slider inertia": 2}
    out.sort(key=lambda item: (item.formulation != "paper", order[item.component], GROUPS.index(item.group)))
    return tuple(out)


def linear_parts(vector, rates, coords):
    """(d vector / d rates, d vector / d coords) of a vector linear in rates and coords."""
    return (sp.ImmutableMatrix(jacobian(sp.Matrix(vector), rates)),
            sp.ImmutableMatrix(jacobian(sp.Matrix(vector), coords)))


def common_factor(matrix):
    """The product of the symbols common to all non-zero entries (lowest powers), for display."""
    factor = None
    for entry in matrix:
        if entry == 0:
            continue
        powers = {b: e for b, e in sp.factor_terms(entry).as_powers_dict().items() if b.is_Symbol}
        factor = powers if factor is None else {b: min(e, powers[b]) for b, e in factor.items() if b in powers}
    return sp.Mul(*[b**e for b, e in sorted((factor or {}).items(), key=lambda kv: kv[0].name)])


@lru_cache(maxsize=None)
def eq17_checks():
    """{quantity: exact - printed} for eq. (17): 1/2 qd^T m1 qd, 1/2 q^T m2 q, qd^T m3 (errata
    and as printed), q^T m4 against the element integrals of the kinetic-energy terms they stand
    for, and the bilinear terms, which eq. (17) has no place for."""
    parts = {k: element_integral(d) for k, d in kinetic_parts().items()}
    corrected, as_printed = printed_set(True), printed_set(False)
    quad = lambda m, w: sp.expand((w.T * m * w)[0, 0] / 2)
    lin = lambda m, w: sp.expand((w.T * m)[0, 0])
    return MappingProxyType({
        "m1": sp.expand(parts["m1"] - quad(corrected["m1"], s.qd)),
        "m2": sp.expand(parts["m2"] - quad(corrected["m2"], s.q)),
        "m3": sp.expand(parts["m3"] - lin(corrected["m3"], s.qd)),
        "m3 as printed": sp.expand(parts["m3"] - lin(as_printed["m3"], s.qd)),
        "m4": sp.expand(parts["m4"] - lin(corrected["m4"], s.q)),
        "bilinear": parts["bilinear"],
    })


@lru_cache(maxsize=None)
def eq18_checks():
    """{approach: U_i of eq. (18) - U_i of the approach} with P = EA {B_u}^T {q} (B9)."""
    m = printed_set(True)
    out = {}
    for ap in APPROACHES:
        k_lin, k_non = printed.stiffness_matrices(ap, m)
        u_18 = (s.q.T * (k_lin + k_non / 2) * s.q)[0, 0] / 2      # eq. (18): k_non = 2 k_vvv
        out[ap] = sp.expand(u_18 - rod_U(ap))
    return MappingProxyType(out)


@lru_cache(maxsize=None)
def elastic_asymmetry(formulation, approach):
    """K - K^T of the elastic force's Jacobian (zero iff the force is a gradient, i.e. conservative)."""
    K = jacobian(rod_elastic(formulation, approach), s.q)
    return sp.ImmutableMatrix((K - K.T).applyfunc(sp.expand))


def bilinear_matrix():
    """[W] with {qd}^T [W] {q} the element integral of T's bilinear term rho A phid (ud v - u vd);
    its Lagrange forces are (W - W^T) qd + (dW/dt) q = 2 [W] qd + (phidd / phid) [W] q."""
    bilinear = element_integral(kinetic_parts()["bilinear"])
    return sp.ImmutableMatrix(jacobian(gradient(bilinear, s.qd), s.q))


def frozen_force_asymmetry():
    """EA int_0^l v_x ({B_v}{B_u}^T - {B_u}{B_v}^T) dx: K - K^T of a force whose P_i is held fixed
    in the variation (the d P / d q that (B7) omits, on one side of the diagonal only)."""
    slope = element_interpolated(v_x)
    matrix = (s.EA * slope * (B_V * B_U.T - B_U * B_V.T)).applyfunc(integrate_element)
    return sp.ImmutableMatrix(matrix)


def tangent_minus_secant(approach):
    """Weak form of (K_tan - K_sec){qd}: the rate of eq. (20)'s elastic force minus the rate that
    the printed iteration matrix of eq. (37), K_lin + K_non with K_non frozen, gives for it."""
    out = {}
    for name, density in printed_elastic_weak_form(approach).items():
        own = SLOT[name].field
        rate = sum(sp.diff(density, g) * RATE_OF[g] for g in GRADIENTS)
        out[name] = rate - sp.cancel(density / own) * RATE_OF[own]
    return weak_form(out)


def slope_gram():
    """[S] = int_0^l {B_v}{B_v}^T dx, so that int v_x^2 dx = {q}^T [S] {q}."""
    return sp.ImmutableMatrix((B_V * B_V.T).applyfunc(integrate_element))


def axial_force_vector():
    """(EA/2) ({q}^T [S] {q}) {B_u}: the element vector of the weak density EA v_x^2 / 2 in the
    axial slot u_x ({B_u} is constant in an element, so the integral factorises)."""
    quadratic = sp.expand((s.q.T * slope_gram() * s.q)[0, 0])
    return sp.ImmutableMatrix((s.EA / 2 * quadratic * B_U).applyfunc(sp.expand))


def eq24_rigid_dissipation(approach):
    """Eq. (24)'s dissipation density for a velocity field with zero strain rates (u_x, v_x, v_xx
    rates zero): what remains is -mu/2 phid^2 (rho A (ud^2 + vd^2) + rho I psid^2)."""
    return sp.expand(eq24_density(approach).xreplace({r: 0 for r in GRADIENT_RATES}))


def slider_eq24_dissipation():
    """1/2 qsd^T c_s qsd of the slider part of eq. (24) (c_s = -mu m_s2, eq. 28)."""
    c = jacobian(printed.slider_damping_residual(printed_set(True)), s.qsd)
    return sp.expand((s.qsd.T * c * s.qsd)[0, 0] / 2)


def slider_eq24_guide_force():
    """Slider damping of eq. (24) along the guide: (u, v)_{n+1} = s (cos phi, sin phi) (eq. 26),
    force projected on (cos phi, sin phi); s and its rate are the symbols s_g, sd_g."""
    s_g, sd_g = sp.symbols("s_g sd_g", real=True)
    direction = sp.Matrix([sp.cos(s.phi), sp.sin(s.phi)])
    normal = sp.Matrix([-sp.sin(s.phi), sp.cos(s.phi)])
    rates = direction * sd_g + normal * s.phid * s_g
    force = printed.slider_damping_residual(printed_set(True)).xreplace(dict(zip(s.qsd, rates)))
    return sp.simplify((direction.T * force)[0, 0]), s_g, sd_g
