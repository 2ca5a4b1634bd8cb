"""Reductions over time of the declared outputs (schema.REDUCTIONS, declared once in
derive/outputs.py): a peak, extreme, range, mean or RMS of an output along a steady revolution, a
continuation point's orbit or a run's last revolution.  The steady and sweep tables, their SI
columns and every branch point's quantities read them from here; a new one is a declaration.

Over the stored steps t_0 .. t_n of the orbit:
    peak   the value of largest magnitude, signed          max, min, range = max - min
    mean   (1/T) int v dt,   rms = sqrt((1/T) int v^2 dt), T = t_n - t_0, by the trapezoidal rule
(a steady revolution's steps close the orbit: its last is its first again, one revolution later).
"""

import math

import numpy as np

from ..declaration import schema

KINDS = ("peak", "max", "min", "range", "mean", "rms")


def declared(case):
    """The declared reductions that exist for the case (their output's guides)."""
    guide = case.guide_record.name
    return [r for r in schema.REDUCTIONS if r.guides is None or guide in r.guides]


def series(result, reduction, steps=slice(None)):
    """(t, values) of the reduction's output over a result's stored steps (those at `steps`)."""
    o = schema.OUTPUTS[reduction.output]
    if o.kind == "field":
        values = result.quantity(o.name, reduction.at, **dict(reduction.arguments))
    else:
        values = result.quantity(o.name)
    return np.asarray(result.t, dtype=float)[steps], np.asarray(values, dtype=float)[steps]


def reduce(kind, t, values):
    """The reduction `kind` (module docstring) of values at the times t."""
    v = np.asarray(values, dtype=float)
    if kind == "peak":
        return float(v[int(np.argmax(np.abs(v)))])
    if kind == "max":
        return float(np.max(v))
    if kind == "min":
        return float(np.min(v))
    if kind == "range":
        return float(np.max(v) - np.min(v))
    t = np.asarray(t, dtype=float)
    span = t[-1] - t[0]
    dt = np.diff(t)
    if kind == "mean":
        return float(np.sum(0.5 * (v[1:] + v[:-1]) * dt) / span)
    if kind == "rms":
        return math.sqrt(float(np.sum(0.5 * (v[1:] ** 2 + v[:-1] ** 2) * dt) / span))
    raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")


def value(result, reduction, steps=slice(None)):
    """The reduction of a result (its stored steps, or those at `steps`); None where the result
    holds no states or the value is not finite."""
    if getattr(result, "states", None) is None:
        return None
    x = reduce(reduction.kind, *series(result, reduction, steps))
    return x if math.isfinite(x) else None


def values(result, steps=slice(None)):
    """{name: value} of every declared reduction of the result's case (module docstring)."""
    return {r.name: value(result, r, steps) for r in declared(result.case)}


def last_revolution(result):
    """The steps of a run's last revolution (a slice of its stored steps): the last steps_per_rev
    steps of a periodic crank's run; for a driven crank, from the last step whose crank angle lies a
    turn before the final one (at least two steps)."""
    theta = np.asarray(result.theta, dtype=float)
    if result.case.motion_record.coordinates:
        first = int(np.searchsorted(theta, theta[-1] - 2 * math.pi, side="right")) - 1
        return slice(max(0, min(first, len(theta) - 2)), None)
    return slice(max(0, len(theta) - 1 - result.case.steps_per_rev), None)


def units(name):
    """The units of a declared reduction (its output's), None for another name."""
    r = next((r for r in schema.REDUCTIONS if r.name == name), None)
    return None if r is None else r.units


def meaning(name):
    """What a declared reduction is, in words ("" for another name)."""
    r = next((r for r in schema.REDUCTIONS if r.name == name), None)
    return "" if r is None else r.doc
