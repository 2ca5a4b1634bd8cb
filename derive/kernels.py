"""Stage 4: kernel specifications (name, ordered inputs, outputs, expressions), grouped by module.

Every runtime quantity that needs the element equations comes from one of these specifications.
Residual kernels return the residual and its exact derivatives with respect to q (K), qd (C) and
qdd (M), so Newton's method gets exact tangents.
"""

from dataclasses import dataclass

import sympy as sp

from . import symbols as s
from .energies import (
    APPROACHES, kelvin_voigt_dissipation, kelvin_voigt_dissipation_averaged, rod_kinetic_energy,
    slider_kinetic_energy, strain_energy, strain_energy_averaged,
)
from .euler_lagrange import gradient, jacobian, kinetic_residual
from . import printed
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
QS, QSD, QSDD = vector("qs", s.qs), vector("qsd", s.qsd), vector("qsdd", s.qsdd)
ELEMENT = (scalar(s.l), scalar(s.x0))
KINEMATICS = tuple(scalar(sym) for sym in s.KINEMATICS)
INERTIA = (scalar(s.rhoA), scalar(s.rhoI))
STIFFNESS = (scalar(s.EA), scalar(s.EI))
AVERAGED_APPROACHES = ("A", "B")     # C has no membrane coupling: its averaged element is the plain one


def _residual_outputs(r, coords, rates=None, accels=None, what="residual"):
    outs = [Output("r", r, what), Output("K", jacobian(r, coords), "d r / d q")]
    if rates is not None:
        outs.append(Output("C", jacobian(r, rates), "d r / d qd"))
    if accels is not None:
        outs.append(Output("M", jacobian(r, accels), "d r / d qdd"))
    return tuple(outs)


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


def energy_kernels():
    kernels = [
        Kernel("rod_kinetic_energy", "Element kinetic energy T_i of the rod, eqs. (4)-(5).",
               (Q, QD) + ELEMENT + INERTIA + KINEMATICS[:-1],
               (Output("T", sp.Matrix([rod_kinetic_energy()]), "kinetic energy"),)),
        Kernel("slider_kinetic_energy", "Kinetic energy T_s of the slider, eqs. (6)-(7).",
               (QS, QSD, scalar(s.ms), scalar(s.L)) + KINEMATICS[:-1],
               (Output("T", sp.Matrix([slider_kinetic_energy()]), "kinetic energy"),)),
    ]
    for ap in APPROACHES:
        kernels.append(Kernel(
            f"strain_energy_{ap}", f"Element strain energy U_i of approach {ap} (eq. 2 and reductions).",
            (Q, scalar(s.l)) + STIFFNESS,
            (Output("U", sp.Matrix([strain_energy(ap)]), "strain energy"),)))
        kernels.append(Kernel(
            f"dissipation_{ap}", f"Kelvin-Voigt Rayleigh dissipation function D of approach {ap}.",
            (Q, QD, scalar(s.l)) + STIFFNESS + (scalar(s.mu),),
            (Output("D", sp.Matrix([kelvin_voigt_dissipation(ap)]), "dissipation function"),)))
    for ap in AVERAGED_APPROACHES:
        kernels.append(Kernel(
            f"strain_energy_{ap}_averaged", f"Element strain energy of approach {ap}, element-mean membrane strain.",
            (Q, scalar(s.l)) + STIFFNESS,
            (Output("U", sp.Matrix([strain_energy_averaged(ap)]), "strain energy"),)))
        kernels.append(Kernel(
            f"dissipation_{ap}_averaged", f"Kelvin-Voigt dissipation function of approach {ap}, element-mean membrane strain rate.",
            (Q, QD, scalar(s.l)) + STIFFNESS + (scalar(s.mu),),
            (Output("D", sp.Matrix([kelvin_voigt_dissipation_averaged(ap)]), "dissipation function"),)))
    return tuple(kernels)


def lagrange_kernels():
    rod_T, slider_T = rod_kinetic_energy(), slider_kinetic_energy()
    kernels = [
        Kernel("rod_inertia", "Exact Lagrange inertia forces of a rod element: d/dt dT/dqd - dT/dq.",
               (Q, QD, QDD) + ELEMENT + INERTIA + KINEMATICS,
               _residual_outputs(kinetic_residual(rod_T, s.q, s.qd, s.qdd), s.q, s.qd, s.qdd)),
        Kernel("slider_inertia", "Exact Lagrange inertia forces of the slider on (u, v) of the last node.",
               (QS, QSD, QSDD, scalar(s.ms), scalar(s.L)) + KINEMATICS,
               _residual_outputs(kinetic_residual(slider_T, s.qs, s.qsd, s.qsdd), s.qs, s.qsd, s.qsdd)),
    ]
    for ap in APPROACHES:
        kernels.append(Kernel(
            f"rod_elastic_{ap}", f"Internal force dU/dq of approach {ap}, exact gradient, and its tangent.",
            (Q, scalar(s.l)) + STIFFNESS,
            _residual_outputs(gradient(strain_energy(ap), s.q), s.q)))
    for ap in AVERAGED_APPROACHES:
        kernels.append(Kernel(
            f"rod_elastic_{ap}_averaged",
            f"Internal force dU/dq of approach {ap} with the element-mean membrane strain, and its tangent.",
            (Q, scalar(s.l)) + STIFFNESS,
            _residual_outputs(gradient(strain_energy_averaged(ap), s.q), s.q)))
    return tuple(kernels)


def paper_kernels():
    m = printed.printed_matrices(corrected=True)
    kernels = [
        Kernel("rod_inertia", "Printed inertia terms of eq. (20): m1 qdd - m2 q - (m4 - d/dt m3).",
               (Q, QD, QDD) + ELEMENT + INERTIA + KINEMATICS,
               _residual_outputs(printed.rod_kinetic_residual(m), s.q, s.qd, s.qdd)),
        Kernel("slider_inertia", "Printed slider terms of eqs. (27)-(29), errata applied.",
               (QS, QSD, QSDD, scalar(s.ms), scalar(s.L)) + KINEMATICS,
               _residual_outputs(printed.slider_kinetic_residual(m), s.qs, s.qsd, s.qsdd)),
    ]
    for ap in APPROACHES:
        r, k_secant = printed.rod_elastic_residual(ap, m)
        kernels.append(Kernel(
            f"rod_elastic_{ap}",
            f"Printed elastic force (k_uu + k_psipsi + k_pvv + k_non) q of approach {ap}, its exact "
            "tangent K and the printed secant matrix K_sec (P_i of eq. B9 taken at q).",
            (Q, scalar(s.l)) + STIFFNESS,
            _residual_outputs(r, s.q) + (Output("K_sec", k_secant, "k_uu + k_psipsi + k_pvv + k_non"),)))
    return tuple(kernels)


def damping_kernels():
    m = printed.printed_matrices(corrected=True)
    kernels = []
    for ap in APPROACHES:
        kernels.append(Kernel(
            f"kelvin_voigt_{ap}", f"Strain-rate damping force dD/dqd of approach {ap} and its tangents.",
            (Q, QD, scalar(s.l)) + STIFFNESS + (scalar(s.mu),),
            _residual_outputs(gradient(kelvin_voigt_dissipation(ap), s.qd), s.q, s.qd)))
    for ap in AVERAGED_APPROACHES:
        kernels.append(Kernel(
            f"kelvin_voigt_{ap}_averaged",
            f"Strain-rate damping force of approach {ap} with the element-mean membrane strain rate.",
            (Q, QD, scalar(s.l)) + STIFFNESS + (scalar(s.mu),),
            _residual_outputs(gradient(kelvin_voigt_dissipation_averaged(ap), s.qd), s.q, s.qd)))
    for ap in APPROACHES:
        kernels.append(Kernel(
            f"paper_{ap}", f"Printed damping force mu (K_lin + K_non) qd of approach {ap} (eq. 24).",
            (Q, QD, scalar(s.l)) + STIFFNESS + INERTIA + (scalar(s.phid), scalar(s.mu)),
            _residual_outputs(printed.rod_damping_residual(ap, m), s.q, s.qd)))
    kernels.append(Kernel(
        "paper_slider", "Printed slider damping force -mu m_s2 qd (eqs. 24, 28).",
        (QSD, scalar(s.ms), scalar(s.phid), scalar(s.mu)),
        _residual_outputs(printed.slider_damping_residual(m), s.qs, s.qsd)))
    return tuple(kernels)


def group_kernels():
    """The consistent model's element forces split by kind (derive/audit.py classification) for
    approach A: the rod and slider inertia terms of the lagrange formulation, the elastic force and
    the Kelvin-Voigt damping force (pointwise and averaged membrane).  Used by the audit to weigh
    each group along real trajectories and to switch groups off one at a time."""
    from . import audit

    sources = [
        ("rod_inertia", (Q, QD, QDD) + ELEMENT + INERTIA + KINEMATICS,
         kinetic_residual(rod_kinetic_energy(), s.q, s.qd, s.qdd), audit.ELEMENT_VARS,
         audit.ROD_AXIAL_ROWS, (s.q, s.qd, s.qdd)),
        ("slider_inertia", (QS, QSD, QSDD, scalar(s.ms), scalar(s.L)) + KINEMATICS,
         kinetic_residual(slider_kinetic_energy(), s.qs, s.qsd, s.qsdd), audit.SLIDER_VARS,
         audit.SLIDER_AXIAL_ROWS, (s.qs, s.qsd, s.qsdd)),
        ("rod_elastic_A", (Q, scalar(s.l)) + STIFFNESS, gradient(strain_energy("A"), s.q),
         audit.ELEMENT_VARS, audit.ROD_AXIAL_ROWS, (s.q, None, None)),
        ("rod_elastic_A_averaged", (Q, scalar(s.l)) + STIFFNESS,
         gradient(strain_energy_averaged("A"), s.q), audit.ELEMENT_VARS, audit.ROD_AXIAL_ROWS,
         (s.q, None, None)),
        ("kelvin_voigt_A", (Q, QD, scalar(s.l)) + STIFFNESS + (scalar(s.mu),),
         gradient(kelvin_voigt_dissipation("A"), s.qd), audit.ELEMENT_VARS, audit.ROD_AXIAL_ROWS,
         (s.q, s.qd, None)),
        ("kelvin_voigt_A_averaged", (Q, QD, scalar(s.l)) + STIFFNESS + (scalar(s.mu),),
         gradient(kelvin_voigt_dissipation_averaged("A"), s.qd), audit.ELEMENT_VARS,
         audit.ROD_AXIAL_ROWS, (s.q, s.qd, None)),
    ]
    kernels = []
    for name, inputs, residual, variables, axial_rows, (coords, rates, accels) in sources:
        for group, part in audit.group_vector(sp.Matrix(residual), variables, axial_rows).items():
            kernels.append(Kernel(
                f"{name}__{group}", f"The '{group}' part of {name} (consistent model, approach A).",
                inputs, _residual_outputs(sp.Matrix(part), coords, rates, accels)))
    return tuple(kernels)


MODULES = {
    "shape": ("Shape functions of Appendix A.", shape_kernels),
    "energy": ("Element energies T_i, T_s, U_i and the Kelvin-Voigt dissipation function.", energy_kernels),
    "lagrange": ("Exact Euler-Lagrange terms of T_c + T_s - U_c (the `lagrange` formulation).", lagrange_kernels),
    "paper": ("The printed matrix form, eqs. (17)-(29) and Appendix B with errata (the `paper` formulation).",
              paper_kernels),
    "damping": ("Damping forces: Kelvin-Voigt strain-rate damping and the printed eq. (24).", damping_kernels),
    "groups": ("Element forces of the consistent model split by kind (symbolic audit).", group_kernels),
}
# modules whose residual kernels also get the accumulating Newton-Newmark variants (emit.py)
ACCUMULATING = ("lagrange", "paper", "damping")
