"""Stage 1: shape functions of Appendix A and their x-derivatives (eqs. 8-13, B10-B12), as columns
over the element's nodal vector (u, v, psi, chi of its two nodes: symbols.NODE); and the exact rod's
cubic axial field."""

from functools import lru_cache

import sympy as sp

from . import symbols as s
from .symbols import l, zeta


def _column(**by_component):
    """A column over the nodal vector from {component: (its function at node 0, at node 1)}."""
    col = sp.zeros(s.ELEMENT_DOFS, 1)
    for component, (first, second) in by_component.items():
        col[s.element_slots(0, (component,))[0]] = first
        col[s.element_slots(1, (component,))[0]] = second
    return col


# The cubic Hermite functions of a value and its x-derivative at the two nodes.
HERMITE_VALUE = (1 - 3 * zeta**2 + 2 * zeta**3, zeta**2 * (3 - 2 * zeta))
HERMITE_SLOPE = (zeta * (zeta - 1) ** 2 * l, zeta**2 * (zeta - 1) * l)

# Appendix A, as printed.
N_U = _column(u=(1 - zeta, zeta))
N_V = _column(v=HERMITE_VALUE, psi=HERMITE_SLOPE)
N_PSI = _column(v=(6 * zeta / l * (zeta - 1), -6 * zeta / l * (zeta - 1)),
                psi=(1 - 4 * zeta + 3 * zeta**2, 3 * zeta**2 - 2 * zeta))


def d_dx(column):
    """d/dx = (1/l) d/dzeta of a column of shape functions."""
    return (column.diff(zeta) / l).applyfunc(sp.expand)


B_U = d_dx(N_U)       # eq. (B10)
B_V = d_dx(N_V)       # eq. (B11)
B_PSI = d_dx(N_PSI)   # eq. (B12)

# The printed slope functions are the x-derivatives of the cubic ones, so psi = v_x exactly
# (a consistency check of the transcription, not an assumption).
assert (B_V - N_PSI).applyfunc(sp.simplify) == sp.zeros(s.ELEMENT_DOFS, 1)

# The geometrically exact rod interpolates u as v is: cubic in u and chi = u_x at the nodes (the
# absolute-slope coordinates of an ANCF cable element, in the moving frame), so that its tangent
# r' = (1 + u_x, v_x) is continuous along the rod.
N_U_CUBIC = _column(u=HERMITE_VALUE, chi=HERMITE_SLOPE)
B_U_CUBIC = d_dx(N_U_CUBIC)


@lru_cache(maxsize=None)
def integrate_element(expr):
    """Exact element integral  int_0^l expr dx = l int_0^1 expr dzeta  of a polynomial in zeta:
    each term c zeta^k of the expanded integrand gives c / (k + 1) (term by term: much faster than
    a Poly of the large element energies).  Cached: the same energy is integrated for a variant,
    its energy kernel and the audit's groups."""
    total = []
    for term in sp.Add.make_args(sp.expand(expr)):
        coeff, power = term.as_coeff_exponent(zeta)
        if coeff.has(zeta) or not (power.is_Integer and power >= 0):
            raise ValueError(f"integrate_element: {term} is not a polynomial term in zeta")
        total.append(coeff / (power + 1))
    return sp.expand(l * sp.Add(*total))
