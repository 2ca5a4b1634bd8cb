"""Checks of user input: every failure names the parameter and its allowed range."""

import math
import numbers

from .errors import ParameterError


def finite_number(name, value):
    """value as a float; it must be a real, finite number.  Text is refused, even "0.8": a number
    given as a string is a mistake to report, not to guess (the command line parses its own)."""
    if isinstance(value, (bool, str, bytes, bytearray)):
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
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        n = int(value)
    elif isinstance(value, float) and value.is_integer():
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
