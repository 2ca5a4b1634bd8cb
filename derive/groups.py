"""Stage 3b: the terms of an equation of motion classified by kind (inertia, gyroscopic, phidd,
centrifugal, forcing, stiffness, cubic and quartic elastic terms, damping by order).

The classification is a derivation stage of its own: the kernel specifications use it to weight the
switchable groups (term masks, derive/declaration.py) and the symbolic audit uses it to report what each
formulation keeps.
"""

from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

from . import symbols as s

ROD_AXIAL_ROWS = s.element_slots(0, ("u",)) + s.element_slots(1, ("u",))   # u_i, u_{i+1} of the element
SLIDER_AXIAL_ROWS = (0,)       # u_{n+1} row of the slider vector


def _terms(expr):
    """Additive terms of the expanded expression, in SymPy's canonical order."""
    return sp.Add.make_args(sp.expand(expr))


def _degree(term, variables):
    """Total degree of a monomial in the given symbols."""
    present = term.free_symbols
    return sum(sp.degree(term, var) for var in variables if var in present)


GROUPS = (
    "inertia", "gyroscopic", "phidd", "centrifugal", "forcing", "stiffness", "cubic_axial",
    "cubic_transverse", "quartic", "damping_linear", "damping_centrifugal", "damping_q1", "damping_q2",
)


@dataclass(frozen=True)
class Variables:
    """Displacement, rate and acceleration symbols of one level (field, element, slider)."""

    disp: frozenset
    rates: frozenset
    accels: frozenset


ELEMENT_VARS = Variables(frozenset(s.q), frozenset(s.qd), frozenset(s.qdd))
SLIDER_VARS = Variables(frozenset(s.qs), frozenset(s.qsd), frozenset(s.qsdd))


def classify(term, variables, axial):
    """Group (one of GROUPS) of one monomial of an equation of motion.

    Damping: carries mu; then by degree in the displacements (0: linear or, with phid, the
    centrifugal part of eq. 24; 1, 2).  Inertia: an acceleration.  Elastic: EA or EI, by degree in
    the displacements (1: linear stiffness, 2: the cubic energy term u_x v_x^2, split by the
    equation it enters, 3: the quartic term).  Otherwise kinetic: no displacement or rate ->
    kinematic forcing; a rate -> gyroscopic/Coriolis; phidd -> phidd coupling; phid -> centrifugal.
    """
    syms = term.free_symbols
    degree = _degree(term, variables.disp)
    if s.mu in syms:
        if degree == 0:
            return "damping_centrifugal" if s.phid in syms else "damping_linear"
        kinds = {1: "damping_q1", 2: "damping_q2"}
    elif syms & variables.accels:
        return "inertia"
    elif syms & {s.EA, s.EI}:
        if degree == 2:
            return "cubic_axial" if axial else "cubic_transverse"
        kinds = {1: "stiffness", 3: "quartic"}
    elif not syms & (variables.disp | variables.rates):
        return "forcing"
    elif syms & variables.rates:
        return "gyroscopic"
    elif s.phidd in syms:
        return "phidd"
    elif s.phid in syms:
        return "centrifugal"
    else:
        kinds = {}
    if degree not in kinds:
        raise ValueError(f"unclassified term of an equation of motion: {term}")
    return kinds[degree]


def group_vector(vector, variables=ELEMENT_VARS, axial_rows=ROD_AXIAL_ROWS):
    """{group: vector} of an element (or slider) residual vector, groups in GROUPS order."""
    split = {}
    for i in range(vector.shape[0]):
        for term in _terms(vector[i]):
            group = classify(term, variables, i in axial_rows)
            split.setdefault(group, sp.zeros(vector.shape[0], 1))[i] += term
    return MappingProxyType({g: sp.ImmutableMatrix(split[g]) for g in GROUPS if g in split})


