"""Stage 1: shape functions of Appendix A and their x-derivatives (eqs. 8-13, B10-B12)."""

from functools import lru_cache

import sympy as sp

from .symbols import l, zeta

# Appendix A, as printed.
N_U = sp.Matrix([1 - zeta, 0, 0, zeta, 0, 0])
N_V = sp.Matrix([
    0,
    1 - 3 * zeta**2 + 2 * zeta**3,
    zeta * (zeta - 1) ** 2 * l,
    0,
    zeta**2 * (3 - 2 * zeta),
    zeta**2 * (zeta - 1) * l,
])
N_PSI = sp.Matrix([
    0,
    6 * zeta / l * (zeta - 1),
    1 - 4 * zeta + 3 * zeta**2,
    0,
    -6 * zeta / l * (zeta - 1),
    3 * zeta**2 - 2 * zeta,
])


def d_dx(column):
    """d/dx = (1/l) d/dzeta of a column of shape functions."""
    return (column.diff(zeta) / l).applyfunc(sp.expand)


B_U = d_dx(N_U)       # eq. (B10)
B_V = d_dx(N_V)       # eq. (B11)
B_PSI = d_dx(N_PSI)   # eq. (B12)

# The printed slope functions are the x-derivatives of the cubic ones, so psi = v_x exactly
# (a consistency check of the transcription, not an assumption).
assert (B_V - N_PSI).applyfunc(sp.simplify) == sp.zeros(6, 1)


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
