"""Stage 3: Euler-Lagrange terms of the discrete Lagrangian T_c + T_s - U_c (eq. 19) and tangents.

For one element with coordinates q, rates qd, accelerations qdd the equation of motion is
    d/dt dT/dqd - dT/dq + dU/dq + dD/dqd = 0,
each part of which is a separate residual vector here.  The time derivative is total: it runs
through q, qd and the rigid-body kinematics (theta, thetad, phi, phid).
"""

from functools import lru_cache

import sympy as sp

from . import symbols as s


def total_time_derivative(expr, coords, rates, accels):
    """d/dt of expr(coords, rates, kinematics) along a motion (constant crank speed)."""
    result = sp.Integer(0)
    for c, cd in zip(coords, rates):
        result += sp.diff(expr, c) * cd
    for cd, cdd in zip(rates, accels):
        result += sp.diff(expr, cd) * cdd
    for sym, rate in s.TIME_DERIVATIVE.items():
        result += sp.diff(expr, sym) * rate
    return sp.expand(result)


def kinetic_residual(T, coords, rates, accels):
    """Inertia force vector  d/dt dT/dqd - dT/dq  (every inertia, gyroscopic, phidd, centrifugal
    and kinematic-forcing term of the exact Lagrange equations)."""
    return sp.Matrix([
        total_time_derivative(sp.diff(T, cd), coords, rates, accels) - sp.diff(T, c)
        for c, cd in zip(coords, rates)
    ]).applyfunc(sp.expand)


def gradient(expr, variables):
    """Column of partial derivatives d expr / d variables."""
    return sp.Matrix([sp.expand(sp.diff(expr, v)) for v in variables])


def jacobian(vector, variables):
    """Matrix d vector_i / d variable_j, entries expanded.  An entry that is expanded and polynomial
    in the variables differentiates term by term into expanded terms (a power of a variable loses
    one degree, the other factors untouched): it is expanded once, not each of its derivatives."""
    variables = list(variables)
    rows = []
    for entry in vector:
        termwise = entry.is_polynomial(*variables) and _is_expanded(entry)
        rows.append([entry.diff(v) if termwise else sp.expand(entry.diff(v)) for v in variables])
    return sp.Matrix(rows)


@lru_cache(maxsize=None)
def _is_expanded(expr):
    """expr is its own expansion (asked once per residual entry, for its three tangents)."""
    return sp.expand(expr) == expr
