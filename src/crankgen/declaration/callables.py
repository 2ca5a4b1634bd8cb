"""User functions handed to crankgen (a motor's torque curve F(S), an initial state's fields u(x),
...): one rule for all of them.

A callable is never trusted blindly; crankgen samples it where the method uses it:

1. every sample must be one real, finite number (a Python or NumPy real, a 0-d array of one):
   text, booleans, None, complex numbers, containers and NaN or infinity are refused, and so is a
   call that raises;
2. where the method relies on a bound of its slope (a Lipschitz bound: the torque curve's slope
   enters the crank's Newton row and the step-size advice), the function must be continuous
   with a bounded slope there: sampled closer and closer (`tabulate`'s bisection), a stretch
   narrower than NARROWEST that still changes by more than the tabulation's tolerance is a jump
   (or a slope no motor has) and is refused, naming where.

Each refusal is a ParameterError of one line naming the field ("torque_curve: ..."), the point
and what the function gave.  docs/howto/input-checks.md states the rule.
"""

import math
import numbers

import numpy as np

from ..errors import ParameterError
from .validation import not_a_number

# a stretch of the argument narrower than this (per-unit speed, ...) on which a function still
# departs from its interpolant by the tolerance is a jump, not a steep stretch
NARROWEST = 1e-6


def _what(value):
    """What a function returned, in words: "values of shape (3, 2)", "str 'a text'", ..."""
    if isinstance(value, np.ndarray) and value.ndim > 0:
        return f"values of shape {value.shape} ({value.dtype})"
    return f"{type(value).__name__} {value!r}"[:80]


def _is_real(value):
    value = value[()] if isinstance(value, np.ndarray) and value.shape == () else value
    return not not_a_number(value) and isinstance(value, (numbers.Real, np.integer, np.floating))


def sample(who, fn, x, where="x"):
    """fn(x) at one point x, checked: one real finite number (rule 1), else ParameterError naming
    the function (`who`: "torque_curve: F(S)"), the point and what came back."""
    try:
        y = fn(x)
    except ParameterError:
        raise
    except Exception as exc:
        raise ParameterError(f"{who} failed at {where} = {x:g}: {type(exc).__name__}: {exc}"[:300]) from None
    if not _is_real(y):
        raise ParameterError(f"{who} must return one real number, got {_what(y)} at {where} = {x:g}")
    value = float(y)
    if not math.isfinite(value):
        raise ParameterError(f"{who} is not finite at {where} = {x:g} (it gave {value!r})")
    return value


def check_values(who, values, x, where="x"):
    """A function's values at the points x (from one vectorized call, or a list of one call per
    point), checked as `sample` checks one: real (not text, booleans, containers or complex with
    an imaginary part), finite, one per point; returned as a float array shaped like x."""
    shape = np.shape(x)
    if isinstance(values, (list, tuple)):
        bad = [v for v in values if not (_is_real(v) or isinstance(v, (complex, np.complexfloating)))]
        if bad or len(values) != np.size(x):
            got = _what(bad[0]) if bad else f"{len(values)} values"
            raise ParameterError(f"{who} must return one real number per {where}, got {got}")
        values = np.array(values)
    arr = np.asarray(values) if isinstance(values, np.ndarray) or _is_real(values) else None
    if arr is None or arr.dtype.kind not in "iufc" or arr.shape not in (shape, ()):
        raise ParameterError(f"{who} must return one real number per {where} (an array shaped like {where} for an "
                             f"array of them), got {_what(values)}")
    if np.iscomplexobj(arr):
        if np.any(arr.imag != 0):
            raise ParameterError(f"{who} must return one real number per {where}, got complex values")
        arr = arr.real
    arr = np.broadcast_to(arr.astype(float), shape).copy()
    bad = ~np.isfinite(arr)
    if bad.any():
        k = int(np.argmax(bad))
        raise ParameterError(f"{who} is not finite at {where} = {np.ravel(x)[k]:g} (it gave {arr.flat[k]!r})")
    return arr


def check_continuous(who, a, b, fa, fb, where="x"):
    """Rule 2 on one stretch [a, b] the bisection could not resolve within its tolerance: refused
    when it is narrower than NARROWEST (a jump from fa to fb there, or a slope no bound holds)."""
    if b - a <= NARROWEST:
        raise ParameterError(f"{who} is not continuous with a bounded slope near {where} = {0.5 * (a + b):.9g} "
                             f"(from {fa:.6g} to {fb:.6g} within {b - a:.2g}); crankgen uses its slope (a "
                             "Lipschitz bound), so it must be continuous: give a continuous function or the table "
                             "of points")
