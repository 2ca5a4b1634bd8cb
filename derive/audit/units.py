"""(M, L, T) exponents of the audit's symbols and of expressions, for the units checks."""

import sympy as sp

from .. import symbols as s
from ..groups import _terms
from .field_symbols import (
    ACCELS, COORDS, GRADIENTS, GRADIENT_RATES, P, RATES, psi, u, u_x, v, v_x, v_xx, v_xxx, x, y,
)


_LEN, _ONE = (0, 1, 0), (0, 0, 0)
DIMENSIONS = {
    s.l: _LEN, s.x0: _LEN, s.L: _LEN, s.a: _LEN, x: _LEN, y: _LEN, s.zeta: _ONE,
    s.rhoA: (1, -1, 0), s.rhoI: (1, 1, 0), s.EA: (1, 1, -2), s.EI: (1, 3, -2), s.mu: (0, 0, 1),
    s.ms: (1, 0, 0), P: (1, 1, -2), s.theta: _ONE, s.phi: _ONE, s.thetad: (0, 0, -1),
    s.phid: (0, 0, -1), s.phidd: (0, 0, -2), s.thetadd: (0, 0, -2),
    u: _LEN, v: _LEN, psi: _ONE, u_x: _ONE, v_x: _ONE, v_xx: (0, -1, 0), v_xxx: (0, -2, 0),
}
for _base, _rate, _accel in zip(COORDS, RATES, ACCELS):
    d0 = DIMENSIONS[_base]
    DIMENSIONS[_rate], DIMENSIONS[_accel] = (d0[0], d0[1], -1), (d0[0], d0[1], -2)
for _base, _rate in zip(GRADIENTS, GRADIENT_RATES):
    DIMENSIONS[_rate] = DIMENSIONS[_base][:2] + (-1,)
for _k in range(s.ELEMENT_DOFS):
    _node = _ONE if s.NODE[_k % len(s.NODE)] in ("psi", "chi") else _LEN     # the slopes' slots
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
