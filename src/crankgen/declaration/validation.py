"""Checks of user input: every failure names the parameter and its allowed range."""

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
    """value as a float; it must be a real, finite number.  Text and booleans are refused, even
    "0.8" and numpy.True_: a number given as a string is a mistake to report, not to guess (the
    command line parses its own)."""
    if not_a_number(value) or isinstance(value, (complex, np.complexfloating)):
        raise ParameterError(f"{name} must be a number, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(x):
        raise ParameterError(f"{name} must be finite, got {value!r}")
    return x


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


def integer(name, value, minimum):
    """value as an int >= minimum (integral floats such as 16.0 are accepted)."""
    if isinstance(value, numbers.Integral) and not not_a_number(value):
        n = int(value)
    elif isinstance(value, (float, np.floating)) and float(value).is_integer():
        n = int(value)
    else:
        raise ParameterError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if n < minimum:
        raise ParameterError(f"{name} must be an integer >= {minimum}, got {n}")
    return n


def choice(name, value, allowed):
    """value, which must be one of allowed."""
    if value not in allowed:
        options = ", ".join(repr(a) for a in allowed)
        raise ParameterError(f"{name} must be one of {options}, got {value!r}")
    return value


def numbers_array(name, values):
    """values (a number or a sequence of them) as a 1-d float array; text, booleans and other
    non-numbers are refused anywhere in it (NumPy would read "0.5" and True as numbers)."""
    bad = ParameterError(f"{name} must be a number or a sequence of numbers, got {values!r}"[:200])
    if not_a_number(values):
        raise bad
    if isinstance(values, np.ndarray) and values.dtype.kind in "iuf":
        return values.astype(float).ravel()              # numbers already: no look at each one
    try:
        items = np.asarray(values, dtype=object).ravel()  # each item as given (NumPy would turn
    except (TypeError, ValueError):                       # [numpy.True_, 1.0] into [1.0, 1.0])
        raise bad from None
    if any(not_a_number(v) or isinstance(v, (list, tuple, dict, set)) for v in items):
        raise bad
    try:
        return np.array([finite_number(name, v) if not isinstance(v, (float, int)) else v for v in items],
                        dtype=float)
    except ParameterError:
        raise bad from None
