"""Approach A against the exact strain of the rod (audit section 7): the series of the exact
stretch and curvature in the moderate-rotation ordering, and the terms A drops.

Ordering (the von Karman ordering of eq. 1): slopes and curvatures of the transverse field are of
order delta, the axial strain of order delta^2,

    v_x, v_xx ~ delta,    u_x, u_xx, <v_x^2> ~ delta^2,    var(v_x^2) ~ delta^4,

with <.> and var(.) an element's mean and variance.  A's membrane strain is u_x + v_x^2/2 (order
delta^2) and its curvature v_xx (order delta); the exact rod's (derive/energies.py):

- the stretch  e = sqrt((1 + u_x)^2 + v_x^2) - 1, pointwise;
- the curvature, the rate of the section's rotation theta = atan2(v_x, 1 + u_x),
  kappa = ((1 + u_x) v_xx - v_x u_xx) / ((1 + u_x)^2 + v_x^2) (Reissner's measure per undeformed
  length).
"""

import functools

import sympy as sp

from .field_symbols import FIELD_LATEX_NAMES, u_x, v_x, v_xx
from .. import symbols as s

u_xx = sp.Symbol("u_xx", real=True)
m2 = sp.Symbol("m2", nonnegative=True)       # <v_x^2>, the element's mean of the squared slope
var = sp.Symbol("var2", nonnegative=True)    # var(v_x^2), its variance over the element
delta = sp.Symbol("delta", positive=True)    # the bookkeeping parameter of the ordering
ORDER = {v_x: 1, v_xx: 1, u_x: 2, u_xx: 2, m2: 2, var: 4}
LATEX_NAMES = {u_xx: "u_{,xx}", m2: r"\langle v_{,x}^2\rangle", var: r"\operatorname{var}(v_{,x}^2)",
               delta: r"\delta"}
FIELD_LATEX_NAMES.update(LATEX_NAMES)


# name -> (the exact measure, A's, words)
MEASURES = {
    "stretch": (sp.sqrt((1 + u_x) ** 2 + v_x ** 2) - 1, u_x + v_x ** 2 / 2,
                "membrane strain: $|r'| - 1$ against $u_{,x} + v_{,x}^2/2$"),
    "curvature": ((((1 + u_x) * v_xx - v_x * u_xx) / ((1 + u_x) ** 2 + v_x ** 2)), v_xx,
                  "curvature: $\\frac{d}{dx}\\operatorname{atan2}(v_{,x}, 1 + u_{,x})$ "
                  "against $v_{,xx}$"),
}


def ordered(expr):
    """expr with every field symbol scaled by delta to its order (ORDER)."""
    return expr.subs({k: delta ** n * k for k, n in ORDER.items()}, simultaneous=True)


@functools.lru_cache(maxsize=None)
def dropped(name, terms=2):
    """[(order in delta, the part of exact - A of that order)], the first `terms` non-zero orders
    of what A drops from the exact measure `name` (MEASURES)."""
    exact, approx = MEASURES[name][:2]
    lowest = a_order(name)
    series = sp.expand(sp.series(ordered(exact - approx), delta, 0, lowest + 2 * terms + 1).removeO())
    out = []
    for k in range(lowest, lowest + 2 * terms + 1):
        part = sp.factor_terms(sp.expand(sp.cancel(series.coeff(delta, k))))
        if part != 0:
            out.append((k, part))
        if len(out) == terms:
            break
    return out


def a_order(name):
    """The order in delta of A's own measure (2 for a membrane strain, 1 for a curvature)."""
    return 1 if name == "curvature" else 2


@functools.lru_cache(maxsize=None)
def energy_difference():
    """The leading part of the exact strain-energy density less A's, (EA/2)(e^2 - e_A^2) +
    (EI/2)(kappa^2 - v_xx^2), pointwise, by order."""
    ee, ea = MEASURES["stretch"][:2]
    ke, ka = MEASURES["curvature"][:2]
    diff = s.EA / 2 * (ee ** 2 - ea ** 2) + s.EI / 2 * (ke ** 2 - ka ** 2)
    series = sp.expand(sp.series(ordered(diff), delta, 0, 7).removeO())
    by_order = {k: sp.factor_terms(sp.expand(sp.cancel(series.coeff(delta, k)))) for k in range(0, 7)}
    return {k: p for k, p in by_order.items() if p != 0}
