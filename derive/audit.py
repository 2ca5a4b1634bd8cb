"""Symbolic audit: energies by order, Euler-Lagrange terms by kind, the printed matrix form
(eqs. 17-29, Appendix B) against the derivation, and the transcription problems of the printed
equations (docs/errata.md).

Two levels are used throughout.
- Field level: densities in the field symbols below (u, v, psi, their rates and x-derivatives,
  the abscissa x).  Readable; this is what the report prints.  An element equation is written as a
  weak form, one density per virtual quantity ("slot"): the element vector is
      r = int_0^l ( N_u f_u + N_v f_v + N_psi f_psi + B_u f_{u_x} + B_v f_{v_x} + B_psi f_{v_xx} ) dx.
- Element level: 6-vectors in {q}, {qd}, {qdd} of eq. (14), what the kernels and the printed
  matrices are.  `element_vector` maps a weak form to this level, so each field-level statement is
  checked where the printed matrices live.
Everything returns SymPy objects or frozen records; expensive results are cached (treat them as
read-only).  crankgen.audit turns them into the report.
"""

from dataclasses import dataclass
from functools import lru_cache
from types import MappingProxyType

import sympy as sp

from . import printed
from . import symbols as s
from .energies import (
    fields, kelvin_voigt_dissipation, moving_frame_velocity, rod_kinetic_energy,
    slider_kinetic_energy, strain_energy,
)
from .euler_lagrange import gradient, jacobian, kinetic_residual, total_time_derivative
from .groups import (  # noqa: F401  (re-exported: the audit names them)
    ELEMENT_VARS, GROUPS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, Variables, _degree, _terms,
    classify, group_vector,
)
from .shape_functions import B_PSI, B_U, B_V, N_PSI, N_U, N_V, integrate_element

APPROACHES = ("A", "B", "C")

# ---------------------------------------------------------------------------------------------
# Field symbols
# ---------------------------------------------------------------------------------------------
u, v, psi = sp.symbols("u v psi", real=True)
ud, vd, psid = sp.symbols("ud vd psid", real=True)
udd, vdd, psidd = sp.symbols("udd vdd psidd", real=True)
u_x, v_x, v_xx, v_xxx = sp.symbols("u_x v_x v_xx v_xxx", real=True)
ud_x, vd_x, vd_xx = sp.symbols("ud_x vd_x vd_xx", real=True)
x = sp.Symbol("x", real=True)      # abscissa along the undeformed rod: x0 + l zeta in an element
y = sp.Symbol("y", real=True)      # cross-section co-ordinate of eq. (1)
P = sp.Symbol("P", real=True)      # axial force of eq. (3) and (B9)

COORDS, RATES, ACCELS = (u, v, psi), (ud, vd, psid), (udd, vdd, psidd)
GRADIENTS, GRADIENT_RATES = (u_x, v_x, v_xx), (ud_x, vd_x, vd_xx)
RATE_OF = dict(zip(COORDS + GRADIENTS, RATES + GRADIENT_RATES))

_NODES = (("u", "i"), ("v", "i"), (r"\psi", "i"), ("u", "{i+1}"), ("v", "{i+1}"), (r"\psi", "{i+1}"))
_SLIDER_NODES = (("u", "{n+1}"), ("v", "{n+1}"))


def _node_names(syms, nodes, accent):
    """LaTeX names of nodal symbols, e.g. accent 'dot' -> \\dot{u}_{i+1}."""
    return {sym: (rf"\{accent}{{{base}}}" if accent else base) + "_" + index
            for sym, (base, index) in zip(syms, nodes)}


LATEX_NAMES = {
    s.rhoA: r"\rho A", s.rhoI: r"\rho I", s.EA: "EA", s.EI: "EI", s.mu: r"\mu", s.ms: "m_s",
    s.L: "L", s.l: "l", s.x0: "x_0", s.a: "a", s.zeta: r"\zeta",
    s.theta: r"\theta", s.thetad: r"\dot{\theta}", s.phi: r"\phi", s.phid: r"\dot{\phi}",
    s.phidd: r"\ddot{\phi}",
    u: "u", v: "v", psi: r"\psi", ud: r"\dot{u}", vd: r"\dot{v}", psid: r"\dot{\psi}",
    udd: r"\ddot{u}", vdd: r"\ddot{v}", psidd: r"\ddot{\psi}",
    u_x: "u_{,x}", v_x: "v_{,x}", v_xx: "v_{,xx}", v_xxx: "v_{,xxx}",
    ud_x: r"\dot{u}_{,x}", vd_x: r"\dot{v}_{,x}", vd_xx: r"\dot{v}_{,xx}", x: "x", y: "y", P: "P",
}
for _syms, _nodes in ((s.q, _NODES), (s.qs, _SLIDER_NODES)):
    LATEX_NAMES.update(_node_names(_syms, _nodes, ""))
for _syms, _nodes in ((s.qd, _NODES), (s.qsd, _SLIDER_NODES)):
    LATEX_NAMES.update(_node_names(_syms, _nodes, "dot"))
for _syms, _nodes in ((s.qdd, _NODES), (s.qsdd, _SLIDER_NODES)):
    LATEX_NAMES.update(_node_names(_syms, _nodes, "ddot"))


def order_split(expr, variables):
    """{total degree in `variables`: part of expr}, ascending degree (terms of each order)."""
    parts = {}
    for term in _terms(expr):
        k = _degree(term, variables)
        parts[k] = parts.get(k, sp.Integer(0)) + term
    return dict(sorted(parts.items()))


# ---------------------------------------------------------------------------------------------
# Weak forms (slots) and the map to the element level
# ---------------------------------------------------------------------------------------------
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
    total = sp.zeros(6, 1)
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


# ---------------------------------------------------------------------------------------------
# Section 1: energies (eqs. 1-7) and dissipation functions by order
# ---------------------------------------------------------------------------------------------
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


# ---------------------------------------------------------------------------------------------
# Section 2: Euler-Lagrange terms grouped by kind (classification: the derive stage groups.py)
# ---------------------------------------------------------------------------------------------
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


# ---------------------------------------------------------------------------------------------
# Element-level residuals of each formulation
#   lagrange: exact Euler-Lagrange equations; paper: printed form, errata applied; printed: as printed
# ---------------------------------------------------------------------------------------------
FORMULATIONS = ("lagrange", "paper", "printed")


@lru_cache(maxsize=None)
def rod_T():
    """Element kinetic energy T_i of energies.py (eqs. 4-5), cached."""
    return rod_kinetic_energy()


@lru_cache(maxsize=None)
def rod_U(approach):
    """Element strain energy U_i of energies.py for an approach, cached."""
    return strain_energy(approach)


@lru_cache(maxsize=None)
def printed_set(corrected):
    """printed.printed_matrices(corrected), cached."""
    return MappingProxyType(printed.printed_matrices(corrected=corrected))


def _matrices(formulation):
    return printed_set(formulation != "printed")


@lru_cache(maxsize=None)
def rod_inertia(formulation):
    """Inertia forces of a rod element: d/dt dT/dqd - dT/dq, or m1 qdd - m2 q - (m4 - d/dt m3)."""
    if formulation == "lagrange":
        r = kinetic_residual(rod_T(), s.q, s.qd, s.qdd)
    else:
        r = printed.rod_kinetic_residual(_matrices(formulation))
    return sp.ImmutableMatrix(r)


@lru_cache(maxsize=None)
def rod_elastic(formulation, approach):
    """Elastic force of a rod element: dU/dq, or (k_uu + k_psipsi + k_pvv + k_non) q (eq. 20)."""
    if formulation == "lagrange":
        return sp.ImmutableMatrix(gradient(rod_U(approach), s.q))
    return sp.ImmutableMatrix(printed.rod_elastic_residual(approach, _matrices(formulation))[0])


@lru_cache(maxsize=None)
def rod_damping(model, approach):
    """Damping force of a rod element: eq. (24) c qd ('eq24') or dD/dqd (Kelvin-Voigt)."""
    if model == "eq24":
        return sp.ImmutableMatrix(printed.rod_damping_residual(approach, printed_set(True)))
    return sp.ImmutableMatrix(gradient(kelvin_voigt_dissipation(approach), s.qd))


@lru_cache(maxsize=None)
def slider_inertia(formulation):
    """Slider forces on (u, v)_{n+1}: exact Lagrange, or m_s1 qdd - m_s2 q - (m_s3 - [d/dt] m_s4)."""
    if formulation == "lagrange":
        r = kinetic_residual(slider_kinetic_energy(), s.qs, s.qsd, s.qsdd)
    else:
        corrected = formulation == "paper"
        r = printed.slider_kinetic_residual(printed_set(corrected), corrected=corrected)
    return sp.ImmutableMatrix(r)


@lru_cache(maxsize=None)
def rod_inertia_weak(formulation):
    """Field-level weak form of rod_inertia(formulation)."""
    if formulation == "lagrange":
        return kinetic_weak_form(kinetic_density())
    return kinetic_weak_form(eq17_density(corrected=formulation == "paper"))


@lru_cache(maxsize=None)
def rod_elastic_weak(formulation, approach):
    """Field-level weak form of rod_elastic(formulation, approach)."""
    if formulation == "lagrange":
        return potential_weak_form(strain_density(approach))
    return printed_elastic_weak_form(approach)


@lru_cache(maxsize=None)
def rod_damping_weak(model, approach):
    """Field-level weak form of rod_damping(model, approach)."""
    return dissipation_weak_form(dissipation_density(model, approach))


# ---------------------------------------------------------------------------------------------
# Which formulation / approach keeps each group
# ---------------------------------------------------------------------------------------------
ROD_COLUMNS = (("lagrange", "A"), ("lagrange", "B"), ("lagrange", "C"),
               ("paper", "A"), ("paper", "B"), ("paper", "C"), ("printed", "A"))
DAMPING_COLUMNS = tuple((m, ap) for m in DAMPING_MODELS for ap in APPROACHES)


def _status(candidate, reference):
    """'kept' (equal to the reference), 'dropped' (absent), 'differs', '' (in neither)."""
    if candidate is None:
        return "" if reference is None else "dropped"
    if reference is not None and sp.expand(candidate - reference) == sp.zeros(*candidate.shape):
        return "kept"
    return "differs"


@dataclass(frozen=True)
class KeepRow:
    group: str
    status: tuple        # one entry per column of the table


@lru_cache(maxsize=None)
def rod_keep_table():
    """Rod element groups of each (formulation, approach) of ROD_COLUMNS against the exact
    Lagrange equations of eq. (2) (lagrange, A)."""
    vectors = {col: group_vector(rod_inertia(col[0]) + rod_elastic(col[0], col[1])) for col in ROD_COLUMNS}
    reference = vectors[("lagrange", "A")]
    rows = []
    for g in GROUPS[:9]:
        rows.append(KeepRow(g, tuple(_status(vectors[c].get(g), reference.get(g)) for c in ROD_COLUMNS)))
    return tuple(rows)


@lru_cache(maxsize=None)
def slider_keep_table():
    """Slider groups of each formulation (columns FORMULATIONS) against the exact equations."""
    vectors = {f: group_vector(slider_inertia(f), SLIDER_VARS, SLIDER_AXIAL_ROWS) for f in FORMULATIONS}
    reference = vectors["lagrange"]
    return tuple(KeepRow(g, tuple(_status(vectors[f].get(g), reference.get(g)) for f in FORMULATIONS))
                 for g in GROUPS[:5])


@lru_cache(maxsize=None)
def damping_keep_table():
    """Damping groups present ('present' or '') in each (model, approach) of DAMPING_COLUMNS
    (from the field-level weak forms, which equal the element forces: see the tests)."""
    groups = {col: group_weak_form(rod_damping_weak(*col)) for col in DAMPING_COLUMNS}
    return tuple(KeepRow(g, tuple("present" if g in groups[c] else "" for c in DAMPING_COLUMNS))
                 for g in GROUPS[9:])


# ---------------------------------------------------------------------------------------------
# Section 3: the printed form against the exact Lagrange equations
# ---------------------------------------------------------------------------------------------
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


# ---------------------------------------------------------------------------------------------
# Dimensions (mass, length, time exponents) for the units checks
# ---------------------------------------------------------------------------------------------
_LEN, _ONE = (0, 1, 0), (0, 0, 0)
DIMENSIONS = {
    s.l: _LEN, s.x0: _LEN, s.L: _LEN, s.a: _LEN, x: _LEN, y: _LEN, s.zeta: _ONE,
    s.rhoA: (1, -1, 0), s.rhoI: (1, 1, 0), s.EA: (1, 1, -2), s.EI: (1, 3, -2), s.mu: (0, 0, 1),
    s.ms: (1, 0, 0), P: (1, 1, -2), s.theta: _ONE, s.phi: _ONE, s.thetad: (0, 0, -1),
    s.phid: (0, 0, -1), s.phidd: (0, 0, -2),
    u: _LEN, v: _LEN, psi: _ONE, u_x: _ONE, v_x: _ONE, v_xx: (0, -1, 0), v_xxx: (0, -2, 0),
}
for _base, _rate, _accel in zip(COORDS, RATES, ACCELS):
    d0 = DIMENSIONS[_base]
    DIMENSIONS[_rate], DIMENSIONS[_accel] = (d0[0], d0[1], -1), (d0[0], d0[1], -2)
for _base, _rate in zip(GRADIENTS, GRADIENT_RATES):
    DIMENSIONS[_rate] = DIMENSIONS[_base][:2] + (-1,)
for _k in range(6):
    _node = _ONE if _k in (2, 5) else _LEN             # psi slots are slopes
    DIMENSIONS[s.q[_k]] = _node
    DIMENSIONS[s.qd[_k]] = (_node[0], _node[1], -1)
    DIMENSIONS[s.qdd[_k]] = (_node[0], _node[1], -2)
for _k in range(2):
    DIMENSIONS[s.qs[_k]], DIMENSIONS[s.qsd[_k]], DIMENSIONS[s.qsdd[_k]] = _LEN, (0, 1, -1), (0, 1, -2)
FORCE, MOMENT, MOMENTUM, ANGULAR_MOMENTUM, ENERGY = (1, 1, -2), (1, 2, -2), (1, 1, -1), (1, 2, -1), (1, 2, -2)


def monomial_dimension(term):
    """(M, L, T) exponents of one monomial; function arguments must be dimensionless."""
    if term.is_Number:
        return _ONE
    if term.is_Symbol:
        return DIMENSIONS[term]
    if term.is_Pow:
        base = monomial_dimension(term.base)
        return tuple(int(term.exp * e) for e in base)
    if term.is_Mul:
        dims = [monomial_dimension(f) for f in term.args]
        return tuple(sum(c) for c in zip(*dims))
    if isinstance(term, sp.Function):
        for arg in term.args:
            if dimensions(arg) != (_ONE,):
                raise ValueError(f"dimensional argument in {term}")
        return _ONE
    raise ValueError(f"cannot give a dimension to {term}")


def dimensions(expr):
    """Sorted distinct (M, L, T) exponents of the terms of expr: one entry iff homogeneous."""
    return tuple(sorted({monomial_dimension(t) for t in _terms(expr) if t != 0}))


# ---------------------------------------------------------------------------------------------
# Transcription problems of the printed equations (docs/errata.md) and the conventions that
# follow from eq. (7)
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Evidence:
    label: str       # what was computed (plain text, may hold $...$ LaTeX)
    value: object    # SymPy expression, tuple of dimensions, bool or number


@dataclass(frozen=True)
class Verdict:
    item: str        # "eq. (1)", ...
    key: str         # identifier: "eq1", "B3", "eq29", "eq37", "eq39", "B15/B16"
    evidence: tuple
    verdict: str     # "confirmed", "refuted", "confirmed (typesetting only)"


def _verdict(ok):
    return "confirmed" if ok else "refuted"


def erratum_eq1():
    """Eq. (1): only the bending term -y v_xx reproduces eq. (2); -y v_xxx is not even a strain."""
    with_vxx = sp.expand(section_strain_energy(v_xx) - eq2_density())
    with_vxxx = sp.expand(section_strain_energy(v_xxx) - eq2_density())
    strain_dims, printed_dims = dimensions(u_x), dimensions(y * v_xxx)
    ok = with_vxx == 0 and with_vxxx != 0 and printed_dims != strain_dims and dimensions(y * v_xx) == strain_dims
    return Verdict("eq. (1)", "eq1", (
        Evidence(r"$\frac{E}{2}\int_A e_{xx}^2\,dA$ - eq. (2), bending term $-y v_{,xx}$", with_vxx),
        Evidence(r"$\frac{E}{2}\int_A e_{xx}^2\,dA$ - eq. (2), bending term $-y v_{,xxx}$ (as printed)", with_vxxx),
        Evidence(r"(M, L, T) exponents of $u_{,x}$ (a strain)", strain_dims),
        Evidence(r"(M, L, T) exponents of $y\,v_{,xxx}$", printed_dims),
    ), _verdict(ok))


def erratum_b3():
    """(B3): T's term linear in {qd} is the exact {m3}; its rotary part is -rho I phid {N_psi}."""
    exact_m3 = gradient(rod_T(), s.qd).xreplace({c: 0 for c in tuple(s.q) + tuple(s.qd)})
    d_corrected = (exact_m3 - printed_set(True)["m3"]).applyfunc(sp.expand)
    d_printed = (exact_m3 - printed_set(False)["m3"]).applyfunc(sp.expand)
    psid_coefficient = sp.expand(kinetic_parts()["m3"]).coeff(psid)
    rows_printed = tuple(dimensions(e) for e in printed_set(False)["m3"])
    rows_corrected = tuple(dimensions(e) for e in printed_set(True)["m3"])
    ok = (d_corrected == sp.zeros(6, 1) and d_printed != sp.zeros(6, 1)
          and all(len(r) <= 1 for r in rows_corrected) and any(len(r) > 1 for r in rows_printed))
    return Verdict("(B3)", "B3", (
        Evidence(r"coefficient of $\dot\psi$ in the kinetic energy density (terms linear in rates)", psid_coefficient),
        Evidence(r"exact $\{m_3\} = \partial T_i/\partial\{\dot q\}$ at $\{q\}=\{\dot q\}=0$, minus (B3) corrected", sp.ImmutableMatrix(d_corrected)),
        Evidence(r"exact $\{m_3\}$ minus (B3) as printed", sp.ImmutableMatrix(d_printed)),
        Evidence("(M, L, T) exponents of the rows of (B3) as printed", rows_printed),
        Evidence("(M, L, T) exponents of the rows of (B3) corrected", rows_corrected),
    ), _verdict(ok))


def erratum_eq29():
    """Eq. (29): the exact slider equations need -d/dt {m_s4}; -{m_s4} mixes momentum and force."""
    exact = slider_inertia("lagrange")
    d_corrected = (exact - slider_inertia("paper")).applyfunc(sp.expand)
    d_printed = (exact - slider_inertia("printed")).applyfunc(sp.expand)
    groups_corrected = tuple(group_vector(d_corrected, SLIDER_VARS, SLIDER_AXIAL_ROWS))
    rows_printed = tuple(dimensions(e) for e in slider_inertia("printed"))
    rows_corrected = tuple(dimensions(e) for e in slider_inertia("paper"))
    ok = (set(groups_corrected) <= {"gyroscopic", "phidd"} and "forcing" in group_vector(d_printed, SLIDER_VARS, SLIDER_AXIAL_ROWS)
          and all(r == (FORCE,) for r in rows_corrected) and any(len(r) > 1 for r in rows_printed))
    return Verdict("eq. (29)", "eq29", (
        Evidence("exact slider equations minus eqs. (27)-(29) with $-\\{\\dot m_{s4}\\}$", sp.ImmutableMatrix(d_corrected)),
        Evidence("groups of that difference", groups_corrected),
        Evidence("exact slider equations minus eqs. (27)-(29) as printed ($-\\{m_{s4}\\}$)", sp.ImmutableMatrix(d_printed)),
        Evidence("(M, L, T) exponents of the slider rows, as printed", rows_printed),
        Evidence("(M, L, T) exponents of the slider rows, corrected", rows_corrected),
    ), _verdict(ok))


# Scalar stand-ins of eq. (30) for the Newmark checks, the predictors of eqs. (35)-(36), and the
# derivatives d_k = d^(k)(t_m) of a smooth motion with step h = dt.
NM_M, NM_C, NM_K, NM_F, NM_DT, NM_BETA, NM_GAMMA = sp.symbols("M C K F dt beta gamma", positive=True)
D_PRED, V_PRED, V_PRED_PREV = sp.symbols("d_pred v_pred v_pred_prev", real=True)
H = sp.Symbol("h", positive=True)
DERIVS = sp.symbols("d0:7", real=True)
LATEX_NAMES.update({NM_DT: r"\Delta t", NM_BETA: r"\beta", NM_GAMMA: r"\gamma", D_PRED: r"\tilde{d}_{m+1}",
                    V_PRED: r"\tilde{v}_{m+1}", V_PRED_PREV: r"\tilde{v}_{m}"})
LATEX_NAMES.update({d: "d^{(%d)}" % k for k, d in enumerate(DERIVS)})


def newmark_eq37_residual(corrector_velocity):
    """R = M a + C v + K d - F at t_{m+1} for the a of eq. (37), with d from eq. (38) and the
    given velocity corrector ('corrected': v~_{m+1} + gamma dt a; 'printed': v~_m + gamma dt a)."""
    M, C, K, F, dt, beta, gamma = NM_M, NM_C, NM_K, NM_F, NM_DT, NM_BETA, NM_GAMMA
    d_pred, v_pred, v_pred_prev = D_PRED, V_PRED, V_PRED_PREV
    a = (F - C * v_pred - K * d_pred) / (M + gamma * dt * C + beta * dt**2 * K)       # eq. (37)
    d_new = d_pred + beta * dt**2 * a                                                  # eq. (38)
    v_base = v_pred if corrector_velocity == "corrected" else v_pred_prev
    v_new = v_base + gamma * dt * a                                                    # eq. (39)
    return sp.simplify(M * a + C * v_new + K * d_new - F)


def _taylor(derivs, k, shift, h):
    """Taylor series of the k-th derivative of a smooth motion at t + shift h (derivs: d^(j)(t))."""
    return sum(derivs[k + j] * (shift * h) ** j / sp.factorial(j) for j in range(len(derivs) - k))


def newmark_defects(gamma=sp.Rational(1, 2), beta=sp.Rational(1, 4)):
    """Local defects (exact motion inserted) of the corrected and printed velocity correctors
    (eq. 39, with the predictor of eq. 36) and of the displacement corrector (eqs. 35, 38)."""
    h, derivs = H, DERIVS
    disp, vel, acc = (lambda c, k=k: _taylor(derivs, k, c, h) for k in range(3))
    corrected = vel(1) - (vel(0) + h * (1 - gamma) * acc(0) + gamma * h * acc(1))
    printed_ = vel(1) - (vel(-1) + h * (1 - gamma) * acc(-1) + gamma * h * acc(1))
    displacement = disp(1) - (disp(0) + h * vel(0) + h**2 / 2 * (1 - 2 * beta) * acc(0) + beta * h**2 * acc(1))
    return {name: sp.expand(expr) for name, expr in
            (("velocity, corrected", corrected), ("velocity, as printed", printed_),
             ("displacement, eq. (38)", displacement))}, h


def _leading_order(expr, h):
    poly = sp.Poly(expr, h)
    return min(m[0] for m in poly.monoms())


def erratum_eq37():
    """Eq. (37) (brace aside) is the equation of motion at t_{m+1} under eqs. (38) and corrected (39)."""
    residual = newmark_eq37_residual("corrected")
    ok = residual == 0
    return Verdict("eq. (37)", "eq37", (
        Evidence(r"$M a + C v + K d - F$ at $t_{m+1}$ with $a$ from (37), $d$ from (38), $v$ from corrected (39)", residual),
    ), "confirmed (typesetting only)" if ok else "refuted")


def erratum_eq39():
    """Eq. (39): the printed corrector is inconsistent with eq. (37) and with the motion (defect O(dt))."""
    printed_residual = newmark_eq37_residual("printed")
    defects, h = newmark_defects()
    orders = {name: _leading_order(d, h) for name, d in defects.items()}
    ok = (newmark_eq37_residual("corrected") == 0 and printed_residual != 0
          and orders["velocity, as printed"] <= 1 and orders["velocity, corrected"] >= 3)
    return Verdict("eq. (39)", "eq39", (
        Evidence(r"$M a + C v + K d - F$ at $t_{m+1}$ with the printed corrector $\tilde v_m + \gamma\Delta t\,a$", printed_residual),
        Evidence(r"local defect of the corrected velocity update ($\gamma = 1/2$; $d^{(k)}$ the $k$-th "
                 r"derivative of the motion at $t_m$, $h = \Delta t$)", defects["velocity, corrected"]),
        Evidence(r"local defect of the printed velocity update", defects["velocity, as printed"]),
        Evidence(r"local defect of the displacement update (35), (38) ($\beta = 1/4$)", defects["displacement, eq. (38)"]),
        Evidence("leading power of h in each defect", tuple(sorted(orders.items()))),
    ), _verdict(ok))


def erratum_b15_b16():
    """(B15)/(B16): the slider's (u, v) are the element's end-node values only at zeta = 1."""
    e_u, e_v = sp.zeros(6, 1), sp.zeros(6, 1)
    e_u[3], e_v[4] = 1, 1
    roots = sp.solve(list(N_U - e_u) + list(N_V - e_v), s.zeta, dict=True)
    end_abscissa = (s.x0 + s.l * s.zeta).subs({s.zeta: 1, s.x0: s.L - s.l})
    ok = roots == [{s.zeta: 1}] and end_abscissa == s.L
    return Verdict("(B15)/(B16)", "B15/B16", (
        Evidence(r"solutions $\zeta$ of $\{N_u\}(\zeta) = e_{u_{i+1}}$, $\{N_v\}(\zeta) = e_{v_{i+1}}$", tuple(r[s.zeta] for r in roots)),
        Evidence(r"$x_0 + l\zeta$ of element $n$ ($x_0 = L - l$) at $\zeta = 1$, the $L$ in (B15)-(B16)", end_abscissa),
    ), _verdict(ok))


@lru_cache(maxsize=None)
def errata_verdicts():
    """One Verdict per transcription problem of the printed equations (docs/errata.md, same order)."""
    return (erratum_eq1(), erratum_b3(), erratum_eq29(), erratum_eq37(), erratum_eq39(), erratum_b15_b16())


def convention_checks():
    """Conventions of the derivation (docs/errata.md): basis rates, eq. (7) from R = a e_r + xi e_i + eta e_j, the rigid rod
    angle sin phi = (a/L) sin theta and eq. (26), both from the slider staying on the X axis."""
    t = sp.Symbol("t", real=True)
    xi, eta, xid, etad = sp.symbols("xi eta xid etad", real=True)
    u_s, v_s = s.qs
    th, ph, xi_t, eta_t = (sp.Function(n, real=True)(t) for n in ("theta", "phi", "xi", "eta"))
    to_symbols = {th.diff(t): s.thetad, ph.diff(t): s.phid, xi_t.diff(t): xid, eta_t.diff(t): etad}
    to_plain = {th: s.theta, ph: s.phi, xi_t: xi, eta_t: eta}
    flat = lambda e: sp.simplify(sp.expand_trig(e.subs(to_symbols).subs(to_plain)))

    e_r = sp.Matrix([sp.cos(th), sp.sin(th)])
    e_i, e_j = sp.Matrix([sp.cos(ph), -sp.sin(ph)]), sp.Matrix([sp.sin(ph), sp.cos(ph)])
    basis_i = (e_i.diff(t) + ph.diff(t) * e_j).applyfunc(flat)
    basis_j = (e_j.diff(t) - ph.diff(t) * e_i).applyfunc(flat)

    R_dot = (s.a * e_r + xi_t * e_i + eta_t * e_j).diff(t)
    frame_i, frame_j = moving_frame_velocity(xi, eta, xid, etad)
    velocity = (flat((R_dot.T * e_i)[0] - frame_i), flat((R_dot.T * e_j)[0] - frame_j))

    eq7_i = -s.a * s.thetad * sp.sin(s.theta + s.phi) + ud + v * s.phid                 # eq. (7)
    eq7_j = s.a * s.thetad * sp.cos(s.theta + s.phi) - (s.L + u) * s.phid + vd
    slider_i, slider_j = moving_frame_velocity(s.L + u, v, ud, vd)
    eq7 = (sp.expand(slider_i - eq7_i), sp.expand(slider_j - eq7_j))

    slider_Y = (s.a * e_r + (s.L + u_s) * e_i + v_s * e_j)[1].subs(to_plain)
    rigid_Y = slider_Y.subs({u_s: 0, v_s: 0})
    rigid = sp.solve(rigid_Y, sp.sin(s.phi))
    flexible = sp.solve(sp.expand(slider_Y - rigid_Y), v_s)
    return (
        Evidence(r"$\dot e_i + \dot\phi\, e_j$", sp.ImmutableMatrix(basis_i)),
        Evidence(r"$\dot e_j - \dot\phi\, e_i$", sp.ImmutableMatrix(basis_j)),
        Evidence(r"$\dot R\cdot e_i$, $\dot R\cdot e_j$ of $R = a e_r + \xi e_i + \eta e_j$ minus the "
                 "derivation's moving-frame velocity", velocity),
        Evidence("derivation's slider velocity ($\\xi = L + u$, $\\eta = v$) minus eq. (7) as printed", eq7),
        Evidence(r"rigid rod, slider on the $X$ axis: $\sin\phi$", tuple(rigid)),
        Evidence(r"flexible rod, slider end on the $X$ axis: $v_{n+1}$ in terms of $u_{n+1}$ (eq. 26)",
                 tuple(flexible)),
    )
