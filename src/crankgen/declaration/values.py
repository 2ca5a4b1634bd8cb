"""The values of the declared parameters and options: their checks, canonical forms and text.

The records (crankgen.declaration.records) are data only; what a value of a parameter may be, and how titles
and messages write it, is the runtime's, here: `canonical(p, value)` (a Python float, int, str or
tuple of floats, -0.0 made 0.0, or a ParameterError naming the parameter and its allowed values),
`text(p, value)`, `range_text(p)`, and `option_value(option, value)`.
"""

import math
import numbers

from . import torque_curve
from ..errors import ParameterError
from .validation import ANGLE_LIMIT, angle_value as angle, ordered, reduced_angle  # noqa: F401  (the rules' home)


def _bracket(low, high, low_open, high_open):
    left = "-inf" if low is None else f"{low:g}"
    right = "inf" if high is None else f"{high:g}"
    return ("(" if low_open or low is None else "[") + f"{left}, {right}" + (")" if high_open or high is None else "]")


def _scalar(value):
    """A 0-d NumPy array as the scalar it holds (NumPy and SciPy take one as a number)."""
    if type(value).__name__ == "ndarray" and getattr(value, "shape", None) == ():
        return value[()]
    return value


def is_number(value):
    """A real number: a Python or NumPy integer or float, or a 0-d array of one (a boolean, a
    complex number or a string is none; NumPy's scalars register as numbers.Real, its booleans
    and complex numbers do not)."""
    value = _scalar(value)
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def real(label, value):
    if not is_number(value):
        raise ParameterError(f"{label} must be a number, got {value!r}")
    x = float(_scalar(value))
    if not math.isfinite(x):
        raise ParameterError(f"{label} must be finite, got {value!r}")
    return x + 0.0                     # -0.0 -> 0.0: one canonical zero


def plain(value):
    """A NumPy scalar as the Python value it holds."""
    return value.item() if type(value).__module__ == "numpy" and hasattr(value, "item") else value


def option_value(option, value):
    """value checked against a model option's choices (records.Option), in canonical form."""
    value = plain(value)
    if value not in option.choices or type(value) is not type(option.choices[0]):
        allowed = ", ".join(repr(c) for c in option.choices)
        raise ParameterError(f"{option.name} must be one of {allowed}, got {value!r}")
    return value


def range_text(p):
    """The allowed values of a parameter (records.Parameter), as messages show them."""
    if p.kind == "real":
        return _bracket(p.low, p.high, p.low_open, p.high_open)
    if p.kind == "count":
        return f"an integer >= {p.low}"
    if p.kind == "sign":
        return "+1 or -1"
    if p.kind == "choice":
        return " or ".join(repr(c) for c in p.choices)
    if p.kind == "curve":
        return torque_curve.RANGE_TEXT
    return "two finite numbers"


_CANONICAL = {}            # (parameter, type, value) -> canonical value, of values seen before
_CANONICAL_SIZE = 4096


def canonical(p, value):
    """value checked and in canonical form (a Python float, int, str or a tuple of floats; -0.0
    is 0.0), or ParameterError naming the parameter and its allowed values.  A value seen before
    (of the same types, item by item: 1, 1.0 and True differ) is looked up: a case is rebuilt for every point of
    a continuation, with all but one of its values unchanged."""
    try:
        key = (p.name, _typed(value))
        known = _CANONICAL.get(key)
    except TypeError:                   # unhashable (a list, an array): checked every time
        return _canonical(p, value)
    if known is None:
        known = _canonical(p, value)
        if len(_CANONICAL) >= _CANONICAL_SIZE:
            _CANONICAL.clear()
        _CANONICAL[key] = known
    return known


def _typed(value):
    """value with the type of every item beside it (True == 1 == 1.0 as keys; not as values)."""
    if type(value) is tuple:
        return (tuple, tuple(_typed(v) for v in value))
    hash(value)                         # TypeError for an unhashable value
    return (type(value), value)


def _canonical(p, value):
    label = p.label
    if p.kind == "real":
        x = real(label, value)
        bad_low = p.low is not None and (x <= p.low if p.low_open else x < p.low)
        bad_high = p.high is not None and (x >= p.high if p.high_open else x > p.high)
        if bad_low or bad_high:
            raise ParameterError(f"{label} must be in {range_text(p)}, got {x:g}")
        return angle(label, x) if p.units == "rad" else x
    if p.kind == "pair":
        items = ordered(value)
        if items is None or len(items) != 2:
            raise ParameterError(f"{label} must be a sequence of two numbers ({p.metavar or 'X,Y'}), "
                                 f"got {value!r}")
        return tuple(real(f"{label}[{k}]", items[k]) for k in range(2))
    if p.kind == "curve":
        return torque_curve.canonical(label, value)
    if p.kind in ("count", "sign"):
        if not is_number(value):
            raise ParameterError(f"{label} must be {range_text(p)}, got {value!r}")
        x = float(_scalar(value))
        if not (math.isfinite(x) and x.is_integer()):
            raise ParameterError(f"{label} must be {range_text(p)}, got {value!r}")
        n = int(x)
        if (p.kind == "sign" and n not in (1, -1)) or (p.kind == "count" and n < p.low):
            raise ParameterError(f"{label} must be {range_text(p)}, got {n}")
        return n
    value = plain(value)
    if not isinstance(value, str) or value not in p.choices:
        raise ParameterError(f"{label} must be {range_text(p)}, got {value!r}")
    return value


def text(p, value):
    """A value of the parameter as titles and messages show it."""
    if p.kind == "pair":
        return "(" + ", ".join(f"{x:g}" for x in value) + ")"
    if p.kind == "sign":
        return f"{value:+d}"
    if p.kind == "curve":
        return torque_curve.summary(value)
    return f"{value:g}" if p.kind in ("real", "count") else str(value)
