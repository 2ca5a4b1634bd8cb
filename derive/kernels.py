"""Stage 4: kernel specifications (name, ordered inputs, outputs, expressions), made from the
declaration in derive/model.py, grouped by generated module.

One calling convention per kernel kind:
- element kernels (one per family variant, module `elements`):
      name(q, qd, qdd, geo, coef, kin) -> r, K, C, M [, K_printed]
  q, qd, qdd: the element's nodal vector and rates (eq. 14); geo = (l, x0); coef = the coefficients
  of derive/model.py (rho A, rho I, E A, E I, mu, m_s, gX, gY, the term weights); kin = (a, theta,
  thetad, phi, phid, phidd).  r is the element residual, K, C, M its exact derivatives with respect
  to q, qd, qdd; K_printed, where a variant declares one, is the stiffness the printed one-pass
  scheme of eq. (37) iterates with.
- energy kernels (module `energy`): name(q, qd, geo, coef, kin) -> scalar.
- field kernels (module `fields`): name(q, zeta, geo, coef[, fiber]) -> value at zeta = x / l.
- the kinematics kernel (module `guide`): crank_kinematics(t, omega, a, e) -> kin.
- shape kernels (module `shape`): shape functions and the slope Gram matrix.
- audit group kernels (module `groups`): the consistent model's element forces split by kind, in
  the element convention (used by the audit to weigh each group along trajectories).
"""

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import energies as en
from . import guide
from . import model
from . import symbols as s
from .euler_lagrange import gradient, jacobian, kinetic_residual
from .groups import ELEMENT_VARS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from .shape_functions import B_V, N_PSI, N_U, N_V, integrate_element


@dataclass(frozen=True)
class Input:
    name: str
    symbols: tuple      # the SymPy symbols it carries: one for a scalar, n for a trailing axis of n


@dataclass(frozen=True)
class Output:
    name: str
    expr: sp.Matrix     # column (vector output), square matrix, or 1x1 (scalar output)
    doc: str


@dataclass(frozen=True)
class Kernel:
    name: str
    doc: str
    inputs: tuple
    outputs: tuple


def scalar(sym):
    return Input(sym.name, (sym,))


def vector(name, column):
    return Input(name, tuple(column))


Q, QD, QDD = vector("q", s.q), vector("qd", s.qd), vector("qdd", s.qdd)
GEO = vector("geo", s.GEOMETRY)
COEF = vector("coef", s.COEFFICIENTS)
KIN = vector("kin", s.KINEMATICS)
ELEMENT_INPUTS = (Q, QD, QDD, GEO, COEF, KIN)


def _residual_outputs(r, printed_stiffness="exact"):
    K = jacobian(r, s.q)
    outs = [Output("r", r, "element residual"), Output("K", K, "d r / d q"),
            Output("C", jacobian(r, s.qd), "d r / d qd"), Output("M", jacobian(r, s.qdd), "d r / d qdd")]
    if not (isinstance(printed_stiffness, str) and printed_stiffness == "exact"):
        Kp = sp.zeros(6, 6) if isinstance(printed_stiffness, str) else printed_stiffness
        outs.append(Output("K_printed", Kp.applyfunc(sp.expand), "stiffness of the printed eq. (37)"))
    return tuple(outs)


def element_kernel_name(family, variant):
    return f"{family.name}_{variant.name}"


@lru_cache(maxsize=None)
def element_kernels():
    kernels = []
    for family in model.FAMILIES:
        for variant in family.variants:
            term = variant.build()
            kernels.append(Kernel(
                element_kernel_name(family, variant),
                f"{family.doc}: {variant.doc}.",
                ELEMENT_INPUTS, _residual_outputs(sp.Matrix(term.residual), term.printed_stiffness)))
    return tuple(kernels)


def energy_kernels():
    element = (Q, QD, GEO, COEF, KIN)
    kernels = [
        Kernel("rod_kinetic_energy", "Element kinetic energy T_i of the rod, eqs. (4)-(5).", element,
               (Output("T", sp.Matrix([en.rod_kinetic_energy()]), "kinetic energy"),)),
        Kernel("slider_kinetic_energy", "Kinetic energy T_s of the slider, eqs. (6)-(7), on the last element.",
               element, (Output("T", sp.Matrix([en.slider_kinetic_energy().subs(model._ON_LAST_ELEMENT)]),
                                "kinetic energy"),)),
        Kernel("rod_gravity_potential", "Element potential of gravity V_i.", element,
               (Output("V", sp.Matrix([en.rod_gravity_potential()]), "potential energy"),)),
        Kernel("slider_gravity_potential", "Potential of gravity on the slider, on the last element.",
               element, (Output("V", sp.Matrix([en.slider_gravity_potential().subs(model._ON_LAST_ELEMENT)]),
                                "potential energy"),)),
    ]
    for ap in en.APPROACHES:
        for averaged in ((False, True) if ap != "C" else (False,)):
            suffix = "_averaged" if averaged else ""
            U = (en.strain_energy_averaged if averaged else en.strain_energy)(ap)
            D = (en.kelvin_voigt_dissipation_averaged if averaged else en.kelvin_voigt_dissipation)(ap)
            kernels.append(Kernel(f"strain_energy_{ap}{suffix}",
                                  f"Element strain energy U_i of approach {ap}{', element-mean membrane strain' if averaged else ''}.",
                                  element, (Output("U", sp.Matrix([U]), "strain energy"),)))
            kernels.append(Kernel(f"dissipation_{ap}{suffix}",
                                  f"Kelvin-Voigt Rayleigh dissipation function D of approach {ap}"
                                  f"{', element-mean membrane strain rate' if averaged else ''}.",
                                  element, (Output("D", sp.Matrix([D]), "dissipation function"),)))
    return tuple(kernels)


def field_kernel_name(output, options):
    """Name of the field kernel of an output for the option values (equal expressions share one)."""
    if output.name == "bending_moment":
        return "field_bending_moment"
    if options["approach"] == "C":
        key = "linear"
    else:
        key = "averaged" if options["membrane"] == "averaged" else "pointwise"
    return f"field_{output.name}_{key}"


FIELD_OPTION_CASES = ({"approach": "A", "membrane": "pointwise"}, {"approach": "A", "membrane": "averaged"},
                      {"approach": "C", "membrane": "pointwise"})


def field_kernels():
    kernels = {}
    for out in model.OUTPUTS:
        if out.kind != "field":
            continue
        extra = tuple(scalar(model.fiber) for a in out.arguments if a == "fiber")
        for options in FIELD_OPTION_CASES:
            name = field_kernel_name(out, options)
            if name in kernels:
                continue
            expr = sp.expand(out.build(options))
            kernels[name] = Kernel(name, f"{out.doc} (at zeta = x / l of the element).",
                                   (Q, scalar(s.zeta), GEO, COEF) + extra,
                                   (Output("value", sp.Matrix([expr]), out.name),))
    return tuple(kernels.values())


def guide_kernels():
    theta, thetad, phi, phid, phidd, x_slider = guide.kinematics()
    inputs = (scalar(guide.t), scalar(guide.omega), scalar(s.a), scalar(s.e))
    return (
        Kernel("crank_kinematics", "Rigid kinematics kin = (a, theta, thetad, phi, phid, phidd) at time t "
               "(constant crank speed omega, guide Y = e; derive/guide.py).", inputs,
               (Output("kin", sp.Matrix([s.a, theta, thetad, phi, phid, phidd]), "kinematics"),)),
        Kernel("slider_rigid_position", "X / L of the slider of the rigid mechanism at time t.", inputs,
               (Output("X", sp.Matrix([x_slider]), "slider abscissa"),)),
    )


def shape_kernels():
    return (
        Kernel("shape_functions", "Shape functions N_u, N_v, N_psi of Appendix A at zeta = x / l.",
               (scalar(s.zeta), scalar(s.l)),
               (Output("N_u", N_U, "eq. (11)"), Output("N_v", N_V, "eq. (12)"),
                Output("N_psi", N_PSI, "eq. (13)"))),
        Kernel("slope_gram", "int_0^l {B_v}{B_v}^T dx, so that int v_x^2 dx = q^T G q (eq. 40).",
               (scalar(s.l),),
               (Output("G", (B_V * B_V.T).applyfunc(integrate_element), "slope Gram matrix"),)),
    )


def group_kernels():
    """The consistent model's element forces (approach A: lagrange inertia, elastic force and
    Kelvin-Voigt damping, pointwise and averaged membrane) split by kind (derive/groups.py), in the
    element convention; the slider's inertia groups act on the last element."""
    sources = [
        ("rod_inertia", kinetic_residual(en.rod_kinetic_energy(), s.q, s.qd, s.qdd), False),
        ("slider_inertia", kinetic_residual(en.slider_kinetic_energy(), s.qs, s.qsd, s.qsdd), True),
        ("rod_elastic_A", gradient(en.strain_energy("A"), s.q), False),
        ("rod_elastic_A_averaged", gradient(en.strain_energy_averaged("A"), s.q), False),
        ("kelvin_voigt_A", gradient(en.kelvin_voigt_dissipation("A"), s.qd), False),
        ("kelvin_voigt_A_averaged", gradient(en.kelvin_voigt_dissipation_averaged("A"), s.qd), False),
    ]
    kernels = []
    for name, residual, slider in sources:
        variables, rows = (SLIDER_VARS, SLIDER_AXIAL_ROWS) if slider else (ELEMENT_VARS, ROD_AXIAL_ROWS)
        for group, part in group_vector(sp.Matrix(residual), variables, rows).items():
            r = model.on_last_element(part) if slider else sp.Matrix(part)
            kernels.append(Kernel(
                f"{name}__{group}", f"The '{group}' part of {name} (consistent model, approach A).",
                ELEMENT_INPUTS, _residual_outputs(r)))
    return tuple(kernels)


MODULES = {
    "shape": ("Shape functions of Appendix A.", shape_kernels),
    "guide": ("Rigid kinematics of the crank, the rod's chord and the slider on its guide.", guide_kernels),
    "elements": ("Element kernels of every term family variant declared in derive/model.py.", element_kernels),
    "energy": ("Element energies T_i, T_s, U_i, V_i and the Kelvin-Voigt dissipation function.", energy_kernels),
    "fields": ("Section quantities along the rod (the field outputs of derive/model.py).", field_kernels),
    "groups": ("Element forces of the consistent model split by kind (symbolic audit).", group_kernels),
}
# modules whose element kernels also get the accumulating one-element variants (emit.py)
ACCUMULATING = ("elements",)
# modules whose kernels also get a one-element `_into` variant (compiled by the engine)
SCALAR = ("guide", "shape")
