"""Checks of user input: every failure names the parameter and its allowed range.

One check per kind of input, used wherever that kind enters (docs/howto/input-checks.md):

    finite_number   a real number: a Python or NumPy scalar or a 0-d array (text, booleans, complex
                    numbers and one-element arrays are refused)
    sequence        an ordered collection of items: a list, tuple, range, array or generator (text, a
                    mapping, a set, a scalar are refused)
    numbers_array   a number or a sequence of numbers, as a 1-d float array
    angle           a number taken modulo 2 pi (angle_value: reduced exactly, refused beyond
                    ANGLE_LIMIT)
    integer         a whole number >= a minimum; a count with a bound: crankgen.limits.count
"""

import math
import numbers

import numpy as np

from ..errors import ParameterError

# what is never a number, though Python or NumPy would turn it into one: text ("0.8" -> 0.8) and
# truth values (True -> 1, numpy.bool_ included)
NOT_NUMBERS = (bool, np.bool_, str, bytes, bytearray)


def not_a_number(value):
    """True for text and booleans (Python's or NumPy's), which crankgen never reads as numbers."""
    return isinstance(value, NOT_NUMBERS)


def finite_number(name, value):
    """value as a float; it must be a real, finite number: a Python or NumPy real scalar or a 0-d
    array of one.  Text and booleans are refused, even "0.8" and numpy.True_: a number given as a
    string is a mistake to report, not to guess (the command line parses its own)."""
    if isinstance(value, np.ndarray):
        if value.shape != ():
            raise ParameterError(f"{name} must be a number, got an array of shape {value.shape}")
        value = value[()]
    if not_a_number(value) or isinstance(value, (complex, np.complexfloating)) \
            or not isinstance(value, (numbers.Real, np.generic)):
        raise ParameterError(f"{name} must be a number, got {value!r}"[:200])
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"{name} must be finite, got {value!r}")
    return x


def sequence(name, values, what="values"):
    """The items of an ordered collection as a list: a list, tuple, range, array of one or more
    dimensions (its first axis), a generator or an iterator (consumed once).  Text, a mapping, a
    set (its order is not the caller's), a scalar or a 0-d array are refused, naming `name`."""
    items = ordered(values)
    if items is None:
        raise ParameterError(f"{name} must be a sequence of {what} (a list, a tuple, an array or a generator), "
                             f"got {type(values).__name__} {values!r}"[:240])
    return items


def angle(name, value):
    """value as an angle in rad (a number): reduced modulo 2 pi exactly beyond one turn, refused
    beyond ANGLE_LIMIT, where a float no longer names a position (angle_value)."""
    return angle_value(name, finite_number(name, value))


def in_range(name, value, low=None, high=None, low_open=False, high_open=False):
    """value as a float, checked against [low, high] (or open ends); the message states the range."""
    x = finite_number(name, value)
    bad_low = low is not None and (x <= low if low_open else x < low)
    bad_high = high is not None and (x >= high if high_open else x > high)
    if bad_low or bad_high:
        left = "-inf" if low is None else f"{low:g}"
        right = "inf" if high is None else f"{high:g}"
        bracket = ("(" if low_open or low is None else "[") + f"{left}, {right}" + (
            ")" if high_open or high is None else "]")
        raise ParameterError(f"{name} must be in {bracket}, got {x:g}")
    return x


def integer(name, value, minimum, maximum=None):
    """value as an int >= minimum (integral floats such as 16.0 are accepted; a 0-d array of one
    too); maximum: the largest accepted (crankgen.limits.count gives a bound the caller can lift)."""
    if isinstance(value, np.ndarray) and value.shape == ():
        value = value[()]
    if isinstance(value, numbers.Integral) and not not_a_number(value):
        n = int(value)
    elif isinstance(value, (float, np.floating)) and float(value).is_integer():
        n = int(value)
    else:
        raise ParameterError(f"{name} must be an integer >= {minimum}, got {value!r}"[:200])
    if n < minimum:
        raise ParameterError(f"{name} must be an integer >= {minimum}, got {n}")
    if maximum is not None and n > maximum:
        raise ParameterError(f"{name} must be an integer from {minimum} to {maximum}, got {n}")
    return n


def choice(name, value, allowed):
    """value, which must be one of allowed."""
    if value not in allowed:
        options = ", ".join(repr(a) for a in allowed)
        raise ParameterError(f"{name} must be one of {options}, got {value!r}")
    return value


def numbers_array(name, values):
    """values (a number or a sequence of them: a list, tuple, array or generator) as a 1-d float
    array; text, booleans and other non-numbers are refused anywhere in it (NumPy would read "0.5"
    and True as numbers)."""
    if isinstance(values, np.ndarray) and values.dtype.kind in "iuf":
        return values.astype(float).ravel()              # numbers already: no look at each one
    if isinstance(values, np.ndarray) and values.shape == () or isinstance(values, (numbers.Number, np.generic)) \
            or not_a_number(values):
        return np.array([finite_number(name, values)])
    items = sequence(name, values, "numbers")
    if any(isinstance(v, np.ndarray) and v.ndim > 0 for v in items):
        items = [x for v in items for x in np.ravel(v)]
    bad = ParameterError(f"{name} must be a number or a sequence of numbers, got {values!r}"[:200])
    try:
        return np.array([finite_number(name, v) for v in items], dtype=float)
    except ParameterError as exc:
        raise (bad if "must be a number" in str(exc) else exc) from None


# Angles (a crank angle, a guide's inclination, ...: every float crankgen uses modulo 2 pi).  An
# angle up to ANGLE_LIMIT rad from zero is reduced modulo 2 pi exactly; beyond it the float has lost
# the digits of the position it names (floats near 1e7 are 1.9e-9 rad apart, near 1e17 16 rad
# apart: more than a turn) and it is refused.  docs/howto/input-checks.md states the rule.
ANGLE_LIMIT = 1e7


def reduced_angle(x):
    """An angle beyond one turn either way, reduced to (-pi, pi]: the angle of the same crank
    position.  The reduction is exact (the sine and cosine reduce their argument by 2 pi to full
    precision), so the run's theta0 + Omega* t keeps every digit of its time.  Angles within one
    turn are kept as given."""
    return math.atan2(math.sin(x), math.cos(x)) + 0.0


def angle_value(label, x):
    """A finite float x taken as an angle (rad): refused beyond ANGLE_LIMIT (its crank position is
    lost to rounding), reduced modulo 2 pi exactly beyond one turn, kept as given within one."""
    if abs(x) > ANGLE_LIMIT:
        raise ParameterError(f"{label} = {x:g} rad is too far from 0 to name an angle: floats that large are "
                             f"{math.ulp(x):.2g} rad apart, so the position it means is lost to rounding; "
                             f"angles are taken within {ANGLE_LIMIT:g} rad of 0 (reduced modulo 2 pi "
                             "exactly): give it modulo 2 pi")
    return reduced_angle(x) if abs(x) > 2 * math.pi else x


def ordered(value):
    """The items of an ordered collection (a list, tuple, range, array of one or more dimensions, a
    generator or iterator: consumed once) as a list, or None for what is not one: text, a mapping,
    a set (unordered), a scalar, a 0-d array."""
    if isinstance(value, (str, bytes, bytearray, dict, set, frozenset)) or not hasattr(value, "__iter__") \
            or (type(value).__module__ == "numpy" and getattr(value, "ndim", 1) == 0):
        return None
    try:
        return list(value)
    except TypeError:
        return None
