"""Section 2 of the audit: element residuals of each formulation, their field-level weak forms, and
which formulation / approach keeps each term group.

lagrange: the exact Euler-Lagrange equations; paper: the printed form with its transcription
problems corrected; printed: as printed."""

from dataclasses import dataclass
from functools import lru_cache
from types import MappingProxyType

import sympy as sp

from .. import printed
from .. import symbols as s
from ..energies import kelvin_voigt_dissipation, rod_kinetic_energy, slider_kinetic_energy, strain_energy
from ..euler_lagrange import gradient, kinetic_residual
from ..groups import GROUPS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from .densities import (
    DAMPING_MODELS, dissipation_density, eq17_density, kinetic_density, printed_elastic_weak_form,
    strain_density,
)
from .field_symbols import APPROACHES
from .weak_forms import dissipation_weak_form, group_weak_form, kinetic_weak_form, potential_weak_form


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
