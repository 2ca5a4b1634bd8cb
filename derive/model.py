"""The model's ingredients, declared once as data: what crankgen can combine, and how each is built.

This is the one place to read every ingredient of the flexible slider-crank model:

- OPTIONS: the model options a case chooses (formulation, approach, membrane, damping,
  rotary_inertia), with their choices and defaults.
- PARAMETERS: the mechanism's physical parameters (a, eps, ms, mu, gravity, offset) and
  COEFFICIENTS: the values every element kernel receives, each a formula in the parameters and
  options (rotary_inertia=False is rho*I = 0; a switched-off term group has weight 0).
- FAMILIES: the term families of the equations of motion, each a set of mutually exclusive
  variants selected by option values (`when`); a variant builds its element residual from the
  energies (derive/energies.py) or the printed form (derive/printed.py).  `part` says where it
  acts: "rod" on every element, "end" on the last element (the slider, rows 3-4: u, v of the last
  node).  The residual convention is  r = d/dt dT/dqd - dT/dq + dU/dq + dV/dq + dD/dqd.
- GUIDE: the end constraint, a straight guide Y = e; derive/guide.py derives the kinematics.
- OUTPUTS: the quantities a result can give, per step or as fields of x*.

From this declaration derive/kernels.py makes the kernel specifications (one calling convention
per kernel kind), derive/dispatch.py the generated dispatch table, and the runtime reads that table:
it never names a kernel or a family.  To add an ingredient, declare it here (a Family variant, an
Option, a Parameter/Coefficient or an Output) with its builder, then `make derive`.
"""

from dataclasses import dataclass, field
from typing import Callable

import sympy as sp

from . import energies as en
from . import printed
from . import symbols as s
from .euler_lagrange import gradient, kinetic_residual
from .groups import ELEMENT_VARS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector


# ----------------------------------------------------------------------------------------------
# Options, parameters, coefficients
# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Option:
    name: str
    choices: tuple
    default: object
    doc: str


OPTIONS = (
    Option("formulation", ("lagrange", "paper"), "lagrange",
           "lagrange: the exact Euler-Lagrange equations of T_c + T_s - U_c; paper: the printed "
           "matrix form, eqs. (17)-(29) and Appendix B with its transcription problems corrected"),
    Option("approach", ("A", "B", "C"), "A",
           "strain energy: A full non-linear (eq. 2), B without the quartic v_x^4 term, C linear strain"),
    Option("membrane", ("pointwise", "averaged"), "pointwise",
           "membrane strain of approaches A and B: pointwise (eq. 1) or its element mean "
           "(u_x + <v_x^2>/2, no membrane locking); no effect on approach C or on printed matrices"),
    Option("damping", ("paper", "kelvin-voigt"), "paper",
           "paper: C = mu (K_lin + K_non), eq. (24) as printed; kelvin-voigt: strain-rate damping "
           "from the Rayleigh function of the approach's strain"),
    Option("rotary_inertia", (True, False), True,
           "keep the rho*I (section rotation) terms of the kinetic energy, eq. (5)"),
)


@dataclass(frozen=True)
class Parameter:
    name: str
    doc: str
    default: object
    low: float = None            # allowed range (open ends) of each component
    high: float = None


PARAMETERS = (
    Parameter("a", "crank length over rod length a* = a/L", 0.1, 0.0, 1.0),
    Parameter("eps", "slenderness eps = r/L (r: radius of gyration)", 0.01, 0.0, None),
    Parameter("ms", "slider mass ms* = m_s/(rho A L)", 0.5, None, None),
    Parameter("mu", "damping mu* = omega_b mu", 0.5, None, None),
    Parameter("gravity", "gravity (gX, gY) in the inertial frame, units of L omega_b^2", (0.0, 0.0)),
    Parameter("offset", "guide offset e: the slider moves on the line Y = e (units of L)", 0.0),
)

# indicator of an option value, usable in coefficient formulas
with_rotary_inertia = sp.Symbol("with_rotary_inertia")
eps = sp.Symbol("eps", positive=True)
switched_off = {g: sp.Symbol(f"off_{g}") for g in s.SWITCHABLE_GROUPS}

# crankgen's units: length L, mass rho A L, time 1/omega_b with omega_b = (pi/L)^2 sqrt(EI/(rho A)),
# so rho A = 1, E I = 1/pi^4, E A = E I / r^2 = 1/(pi^4 eps^2), rho I = rho A r^2 = eps^2.
COEFFICIENTS = {
    s.rhoA: sp.Integer(1),
    s.rhoI: with_rotary_inertia * eps**2,
    s.EA: 1 / (sp.pi**4 * eps**2),
    s.EI: 1 / sp.pi**4,
    s.mu: s.mu,
    s.ms: s.ms,
    s.gX: s.gX,
    s.gY: s.gY,
    **{w: 1 - switched_off[g] for g, w in s.WEIGHT.items()},
}
assert tuple(COEFFICIENTS) == s.COEFFICIENTS


# ----------------------------------------------------------------------------------------------
# Term families
# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Term:
    """An element residual (6-vector in q, qd, qdd of eq. 14) and, where the printed one-pass scheme
    of eq. (37) iterates with another stiffness than the exact tangent, that `printed_stiffness`
    ("exact": dr/dq; "none": no stiffness; a 6x6 Matrix: the printed secant)."""

    residual: sp.Matrix
    printed_stiffness: object = "exact"


@dataclass(frozen=True)
class Variant:
    name: str                    # kernel name: <family>_<name>
    when: dict                   # option values that select it (absent options: any value)
    build: Callable              # () -> Term
    doc: str
    groups: tuple = ()           # switchable groups it carries, each multiplied by its weight w_<group>
    energy: str = None           # the energy kernel (derive/kernels.energy_kernels) it derives from


@dataclass(frozen=True)
class Family:
    name: str
    part: str                    # "rod": every element; "end": the slider, on the last element
    doc: str
    energy_kind: str             # what its variants' energy kernels give: "kinetic", "potential", "dissipation"
    variants: tuple = field(default_factory=tuple)
    vanishes_with: tuple = ()    # coefficients that scale the whole family: all zero -> left out of a case



def _weighted(residual, variables, axial_rows, groups):
    """residual with each switchable group's part multiplied by its weight (derive/groups.py)."""
    parts = group_vector(sp.Matrix(residual), variables, axial_rows)
    total = sp.zeros(residual.shape[0], 1)
    for group, part in parts.items():
        total += (s.WEIGHT[group] if group in groups else 1) * sp.Matrix(part)
    return total.applyfunc(sp.expand)


SLIDER_ROWS = (3, 4)             # u, v of the last node in the last element's nodal vector
_ON_LAST_ELEMENT = {**dict(zip(s.qs, s.q[3:5])), **dict(zip(s.qsd, s.qd[3:5])),
                    **dict(zip(s.qsdd, s.qdd[3:5])), s.L: s.x0 + s.l}


def on_last_element(vector2):
    """A slider vector on (u, v)_{n+1} as a 6-vector of the last element (L = x0 + l)."""
    out = sp.zeros(6, 1)
    for k, row in enumerate(SLIDER_ROWS):
        out[row] = sp.expand(vector2[k].subs(_ON_LAST_ELEMENT))
    return out


INERTIA_GROUPS = ("gyroscopic", "phidd", "centrifugal")
ELASTIC_GROUPS = ("cubic_axial", "cubic_transverse", "quartic")


def rod_inertia_lagrange():
    r = kinetic_residual(en.rod_kinetic_energy(), s.q, s.qd, s.qdd)
    return Term(_weighted(r, ELEMENT_VARS, ROD_AXIAL_ROWS, INERTIA_GROUPS))


def rod_inertia_paper():
    return Term(printed.rod_kinetic_residual(printed.printed_matrices(corrected=True)))


def elastic_lagrange(approach, averaged):
    U = en.strain_energy_averaged(approach) if averaged else en.strain_energy(approach)
    groups = ELASTIC_GROUPS if approach == "A" else ()
    return lambda: Term(_weighted(gradient(U, s.q), ELEMENT_VARS, ROD_AXIAL_ROWS, groups))


def elastic_paper(approach):
    def build():
        r, k_secant = printed.rod_elastic_residual(approach, printed.printed_matrices(corrected=True))
        return Term(r, k_secant)
    return build


def kelvin_voigt(approach, averaged):
    D = (en.kelvin_voigt_dissipation_averaged if averaged else en.kelvin_voigt_dissipation)(approach)
    return lambda: Term(gradient(D, s.qd), "none")


def damping_paper(approach):
    return lambda: Term(printed.rod_damping_residual(approach, printed.printed_matrices(corrected=True)),
                        "none")


def rod_gravity():
    return Term(gradient(en.rod_gravity_potential(), s.q))


def slider_inertia_lagrange():
    r = kinetic_residual(en.slider_kinetic_energy(), s.qs, s.qsd, s.qsdd)
    return Term(on_last_element(_weighted(r, SLIDER_VARS, SLIDER_AXIAL_ROWS, INERTIA_GROUPS)))


def slider_inertia_paper():
    return Term(on_last_element(printed.slider_kinetic_residual(printed.printed_matrices(corrected=True))))


def slider_damping_paper():
    return Term(on_last_element(printed.slider_damping_residual(printed.printed_matrices(corrected=True))),
                "none")


def slider_gravity():
    return Term(on_last_element(gradient(en.slider_gravity_potential(), s.qs)))


def _elastic_variants():
    out = []
    for ap in ("A", "B"):
        for membrane, averaged in (("pointwise", False), ("averaged", True)):
            suffix = "_averaged" if averaged else ""
            out.append(Variant(f"lagrange_{ap}{suffix}",
                               {"formulation": "lagrange", "approach": ap, "membrane": membrane},
                               elastic_lagrange(ap, averaged),
                               f"dU/dq of approach {ap}, {membrane} membrane strain",
                               ELASTIC_GROUPS if ap == "A" else (), f"strain_energy_{ap}{suffix}"))
    out.append(Variant("lagrange_C", {"formulation": "lagrange", "approach": "C"},
                       elastic_lagrange("C", False), "dU/dq of approach C (linear strain)",
                       energy="strain_energy_C"))
    for ap in ("A", "B", "C"):
        out.append(Variant(f"paper_{ap}", {"formulation": "paper", "approach": ap}, elastic_paper(ap),
                           f"printed (k_uu + k_psipsi + k_pvv + k_non) q of approach {ap}, P_i of "
                           "eq. (B9) taken at q; printed secant for eq. (37)",
                           energy=f"strain_energy_{ap}"))     # nominal: the printed form has no potential
    return tuple(out)


def _damping_variants():
    out = []
    for ap in ("A", "B"):
        for membrane, averaged in (("pointwise", False), ("averaged", True)):
            suffix = "_averaged" if averaged else ""
            out.append(Variant(f"kelvin_voigt_{ap}{suffix}",
                               {"damping": "kelvin-voigt", "approach": ap, "membrane": membrane},
                               kelvin_voigt(ap, averaged),
                               f"dD/dqd, strain-rate damping of approach {ap}, {membrane} membrane strain",
                               energy=f"dissipation_{ap}{suffix}"))
    out.append(Variant("kelvin_voigt_C", {"damping": "kelvin-voigt", "approach": "C"},
                       kelvin_voigt("C", False), "dD/dqd, strain-rate damping of approach C",
                       energy="dissipation_C"))
    for ap in ("A", "B", "C"):
        out.append(Variant(f"paper_{ap}", {"damping": "paper", "approach": ap}, damping_paper(ap),
                           f"printed damping mu (K_lin + K_non) qd of approach {ap}, eq. (24)"))
    return tuple(out)


FAMILIES = (
    Family("inertia", "rod", "inertia forces of the rod element, from T_c of eqs. (4)-(5)", "kinetic", (
        Variant("lagrange", {"formulation": "lagrange"}, rod_inertia_lagrange,
                "d/dt dT/dqd - dT/dq, exact", INERTIA_GROUPS, "rod_kinetic_energy"),
        Variant("paper", {"formulation": "paper"}, rod_inertia_paper,
                "printed m1 qdd - m2 q - (m4 - d/dt m3), eqs. (20)-(25)", energy="rod_kinetic_energy"),
    )),
    Family("elastic", "rod", "internal elastic force of the rod element, from U_c of eq. (2)", "potential",
           _elastic_variants()),
    Family("dissipation", "rod", "damping force of the rod element", "dissipation", _damping_variants()),
    Family("gravity", "rod", "weight of the rod element, dV/dq with V = -int rho A g.R dx", "potential", (
        Variant("uniform", {}, rod_gravity, "consistent load vector of a uniform gravity field",
                energy="rod_gravity_potential"),
    ), vanishes_with=("gX", "gY")),
    Family("slider_inertia", "end", "inertia forces of the slider on (u, v) of the last node, eqs. (6)-(7)", "kinetic", (
        Variant("lagrange", {"formulation": "lagrange"}, slider_inertia_lagrange,
                "d/dt dT_s/dqd - dT_s/dq, exact", INERTIA_GROUPS, "slider_kinetic_energy"),
        Variant("paper", {"formulation": "paper"}, slider_inertia_paper,
                "printed m_s1, m_s2, m_s3, m_s4 terms of eqs. (27)-(29)", energy="slider_kinetic_energy"),
    )),
    Family("slider_dissipation", "end", "damping force of the slider", "dissipation", (
        Variant("paper", {"damping": "paper"}, slider_damping_paper,
                "printed -mu m_s2 qd of eqs. (24), (28)"),
    )),
    Family("slider_gravity", "end", "weight of the slider, dV_s/dq with V_s = -m_s g.R_s", "potential", (
        Variant("uniform", {}, slider_gravity, "gravity on the slider; the guide carries its normal part",
                energy="slider_gravity_potential"),
    ), vanishes_with=("gX", "gY")),
)
FAMILY = {f.name: f for f in FAMILIES}

# The option values under which the paper's one-pass scheme (eqs. 34-39) iterates with the printed
# matrices of eq. (37) (K_printed of the variants that declare one) instead of the exact tangent.
PRINTED_ITERATION = {"formulation": "paper"}


# ----------------------------------------------------------------------------------------------
# The end constraint (guide) and the outputs
# ----------------------------------------------------------------------------------------------

GUIDE = ("straight guide Y = e: the slider end of the rod is (u, v)_{n+1} = s (cos phi, sin phi), s the "
         "slider's displacement along the guide (eq. 26 holds identically); the crank pin removes "
         "u_1 = v_1 = 0.  Kinematics: derive/guide.py.")


@dataclass(frozen=True)
class Output:
    name: str
    kind: str                    # "step": one value per stored step; "field": per step at any x* in [0, 1]
    doc: str
    build: Callable = None       # field: (options) -> expression in q, zeta, l, coefficients [, fiber]
    arguments: tuple = ()        # extra arguments of a field, e.g. ("fiber",)


fiber = sp.Symbol("fiber", real=True)


def membrane_strain(options, q=s.q):
    """The membrane strain of the approach in use: u_x + v_x^2/2 for A and B (pointwise or element
    mean), u_x for C."""
    f = en.fields(q, q)
    if options["approach"] == "C":
        return f["u_x"]
    if options["membrane"] == "averaged":
        return f["u_x"] + en.mean_over_element(f["v_x"] ** 2) / 2
    return f["u_x"] + f["v_x"] ** 2 / 2


def _curvature(q=s.q):
    return en.fields(q, q)["v_xx"]


# N* = N L^2/EI = EA e / EI = e / eps^2 = e EA/EI;  M* = M L / EI = v_xx (L = 1).
OUTPUTS = (
    Output("v_mid", "step", "v* = v/r at x* = 1/2 (shape-function interpolation)"),
    Output("u_end", "step", "u*(1) = L u(L) / r^2"),
    Output("extension", "step", "delta* = u(L)/L + (1/2) int (dv/dx)^2 dx / L, eq. (40)"),
    Output("slider_position", "step", "X/L of the slider: rigid a cos theta + cos phi plus s"),
    Output("axial_force", "field", "N* = N L^2 / EI, N = EA times the approach's membrane strain",
           lambda o: membrane_strain(o) * s.EA / s.EI),
    Output("bending_moment", "field", "M* = M L / EI = v_xx (M = EI v_xx)",
           lambda o: _curvature()),
    Output("surface_strain", "field",
           "axial strain of the fibre at distance fiber*r from the neutral axis (towards e_j), "
           "e_m - fiber r v_xx (eq. 1 with y = fiber r)",
           lambda o: membrane_strain(o) - fiber * sp.sqrt(s.EI / s.EA) * _curvature(),
           ("fiber",)),
)
