"""A motor's torque-speed curve (motion `motor`, parameter `torque_curve`), in per-unit:

    T_m(thetad) = T_stall f(s),   s = thetad / Omega_nl,   f(0) = 1,  f(1) = 0

T_stall is the torque at rest (stall_torque) and Omega_nl the speed where the torque vanishes
(no_load_speed); f is given as pairs (s_k, f_k), s increasing, among them (0, 1) and (1, 0).  A
table of speeds in rad/s and torques in N m (a data sheet's) is put in per-unit by `per_unit`.

f between the pairs is the piecewise cubic Hermite interpolant with Fritsch-Carlson slopes
(PCHIP): continuous with its first derivative (Newton's crank row is exact), and it keeps the
table's shape (a monotone stretch stays monotone, no overshoot past a peak torque).  Beyond the
first and last pairs f continues linearly with the end slopes.  The default, the two pairs (0, 1)
and (1, 0), is the linear law f = 1 - s of a DC motor that the generated crank equation holds
(derive/motions.py); any other curve enters the crank equation g at run time as its departure
from that law (crankgen.discrete.system.coordinate_equations, crankgen.engine.coordinates):

    g  +=  T_stall [(1 - s) - f(s)],     dg/dthetad  +=  -(T_stall / Omega_nl) [1 + f'(s)].

Continuation in stall_torque or no_load_speed scales the curve along its torque or speed axis,
as a DC motor's voltage or an inverter's frequency does.

A callable f (per-unit speed -> per-unit torque) is tabulated where a crank runs, s in [0, 1.2]:
an interval is bisected until the interpolant's error against f at its quarter points is below
half of TOLERANCE, which keeps it below TOLERANCE (1e-5 of the stall torque) everywhere in practice
(the interpolant's error falls as the square of the spacing: about 230 points for a curve with a
peak torque twice the stall torque).  The case holds that table, so that it is what the case's key, its
CSV row and its reproduction carry.
"""

import functools
import math

import numpy as np

from ..errors import ParameterError

LINEAR = ((0.0, 1.0), (1.0, 0.0))      # the default: T_m = T_stall (1 - s)
MAX_POINTS = 512
TOLERANCE = 1e-5                       # a callable's tabulation error, in units of T_stall
SPAN = (0.0, 1.2)                      # where a callable is tabulated (per-unit speed)
RANGE_TEXT = ("per-unit pairs S:F (S = thetad / Omega_nl increasing, F = T_m / T_stall) through 0:1 and 1:0, "
              "comma-separated, e.g. 0:1,0.8:2.2,1:0; or a callable F(S)")


def number_text(x):
    """x as short text that reads back to the same float."""
    short = f"{x:g}"
    return short if float(short) == x else repr(float(x))


def text(curve):
    """The canonical curve as the text the flag and a CSV cell take: "0:1,0.8:2.2,1:0"."""
    return ",".join(f"{number_text(s)}:{number_text(f)}" for s, f in curve)


def summary(curve, most=8):
    """The curve as titles and messages show it: its text, or for a long table (a tabulated
    callable) its count, ends and peak."""
    if len(curve) <= most:
        return text(curve)
    s, f = np.array(curve, dtype=float).T
    k = int(np.argmax(f))
    return (f"{len(curve)} pairs {text(curve[:1])} .. {text(curve[-1:])}, peak {number_text(round(float(f[k]), 4))} "
            f"at {number_text(round(float(s[k]), 4))}")


def _parse(label, value):
    pairs = []
    for part in value.replace(" ", "").split(","):
        if not part:
            continue
        bits = part.split(":")
        if len(bits) != 2:
            raise ParameterError(f"{label} must be {RANGE_TEXT}; {part!r} is not S:F")
        pairs.append(bits)
    return pairs


def _real(label, x):
    try:
        y = float(x)
    except (TypeError, ValueError):
        raise ParameterError(f"{label} must be {RANGE_TEXT}; {x!r} is not a number") from None
    if not math.isfinite(y):
        raise ParameterError(f"{label} must be {RANGE_TEXT}; got the non-finite value {x!r}")
    return 0.0 if y == 0 else y


def canonical(label, value):
    """The curve as a tuple of (s, f) float pairs, checked; value: such pairs, their text
    "0:1,0.8:2.2,1:0" or a callable f(s) (tabulated).  ParameterError names what is wrong."""
    if callable(value):
        return tabulate(value, label=label)
    if isinstance(value, str):
        value = _parse(label, value)
    if isinstance(value, (bytes, dict, set, frozenset)) or not hasattr(value, "__len__"):
        raise ParameterError(f"{label} must be {RANGE_TEXT}, got {value!r}")
    pairs = []
    for item in value:
        if isinstance(item, (str, bytes)) or not hasattr(item, "__len__") or len(item) != 2:
            raise ParameterError(f"{label} must be {RANGE_TEXT}; {item!r} is not a pair (S, F)")
        pairs.append((_real(label, item[0]), _real(label, item[1])))
    if not 2 <= len(pairs) <= MAX_POINTS:
        raise ParameterError(f"{label} takes 2 to {MAX_POINTS} pairs, got {len(pairs)}")
    s = [p[0] for p in pairs]
    if any(b <= a for a, b in zip(s, s[1:])):
        raise ParameterError(f"{label}: the per-unit speeds S must increase, got {', '.join(map(number_text, s))}")
    ends = dict(pairs)
    if ends.get(0.0) != 1.0 or ends.get(1.0) != 0.0:
        raise ParameterError(f"{label} must pass through 0:1 (the stall torque at rest) and 1:0 (no torque at the "
                             f"no-load speed): per-unit, F = T_m / T_stall at S = thetad / Omega_nl; got "
                             f"{text(pairs)} (crankgen.torque_curve.per_unit puts a table of speeds and torques in per-unit)")
    return tuple(pairs)


@functools.lru_cache(maxsize=64)
def _interpolant(curve):
    """(s, f, f' at the pairs, the PCHIP, its derivative) of a curve given as a tuple of pairs, built
    once per curve (the reference evaluates it at every residual)."""
    from scipy.interpolate import PchipInterpolator

    s, f = np.array(curve, dtype=float).T
    pchip = PchipInterpolator(s, f)
    slope = pchip.derivative()
    return s, f, slope(s), pchip, slope


def _pairs(curve):
    """The curve as a tuple of pairs (a key of _interpolant): a diagram's info holds lists."""
    return curve if isinstance(curve, tuple) else tuple(tuple(p) for p in curve)


def knot_slopes(curve):
    """(s, f, f') at the pairs: PCHIP's Fritsch-Carlson slopes (scipy)."""
    return _interpolant(_pairs(curve))[:3]


def of(case):
    """(curve, T_stall, Omega_nl, J) of a case whose crank a motor drives, by the names of the
    parameters its motion declares (records.Motion.characteristic); None for a prescribed crank."""
    names = case.motion_record.characteristic
    return tuple(getattr(case, n) for n in names) if names else None


def departure_table(case):
    """(n, 3) rows (thetad_k, D_k, D'_k) of the case's departure from the linear law in crankgen's
    units, D(thetad) = T_stall [f(s) - (1 - s)] at s = thetad / Omega_nl and D' = dD/dthetad at the
    knots: the engine's (engine/coordinates.py `hermite`: the cubic Hermite pieces of these rows are the
    curve's departure exactly, 1 - s being linear; linear beyond the ends).  (0, 3) for a
    prescribed crank or the linear law (the generated drive alone)."""
    law = of(case)
    if law is None or tuple(law[0]) == LINEAR:
        return np.zeros((0, 3))
    curve, stall, no_load, _ = law
    s, f, m = knot_slopes(curve)
    return np.column_stack([no_load * s, stall * (f - (1 - s)), stall / no_load * (m + 1)])


def step_hint(case, dt):
    """A sentence for a step of a motor-driven run that failed: when the motor's time constant
    J Omega_nl / (T_stall max |f'|) (the inertia it accelerates alone; the linkage adds more) is
    shorter than the step dt, the step cannot follow the motor; else ""."""
    law = of(case)
    if law is None:
        return ""
    curve, stall, no_load, inertia = law
    tau = inertia * no_load / (stall * steepest(curve))
    if tau >= dt:
        return ""
    return (f"; the motor's time constant J Omega_nl / (T_stall max|f'|) = {tau:.3g} is shorter than the step "
            f"{dt:.3g}: raise steps_per_rev above {math.ceil(case.steps_per_rev * dt / tau)}")


def batch_tables(cases):
    """(tables (cases, K, 3), counts (cases,)) of a batch's cases for the engine (engine/records.py
    Cases.curve, curve_n): each case's `departure_table` padded with zeros; count 0: none."""
    rows = [departure_table(c) for c in cases]
    out = np.zeros((len(rows), max([1] + [len(r) for r in rows]), 3))
    for k, r in enumerate(rows):
        out[k, :len(r)] = r
    return out, np.array([len(r) for r in rows], dtype=np.int64)


def evaluate(curve, s):
    """(f(s), f'(s)) of the curve (module docstring), NumPy arrays like s: the reference's
    arithmetic (scipy's PCHIP inside, the end slopes outside)."""
    knots, values, slopes, pchip, slope = _interpolant(_pairs(curve))
    s = np.asarray(s, dtype=float)
    inside = np.clip(s, knots[0], knots[-1])
    f, df = pchip(inside), slope(inside)
    below, above = s < knots[0], s > knots[-1]
    f = np.where(below, values[0] + slopes[0] * (s - knots[0]), f)
    f = np.where(above, values[-1] + slopes[-1] * (s - knots[-1]), f)
    df = np.where(below, slopes[0], np.where(above, slopes[-1], df))
    return f, df


def steepest(curve):
    """max |f'| of the curve (1 for the linear law): the fastest the motor's torque changes with
    speed, in per-unit."""
    s = np.array([x for x, _ in curve])
    fine = np.concatenate([np.linspace(a, b, 33) for a, b in zip(s, s[1:])])
    return float(np.max(np.abs(evaluate(curve, fine)[1])))


def departure(curve, s):
    """(f(s) - (1 - s), f'(s) + 1): the curve's departure from the linear law and its slope."""
    f, df = evaluate(curve, s)
    return f - (1.0 - np.asarray(s, dtype=float)), df + 1.0


def tabulate(func, span=SPAN, tol=TOLERANCE, label="torque_curve"):
    """The pairs of a per-unit curve func(s) on span, bisected until the interpolant matches func
    within tol / 2 at every interval's quarter points (module docstring)."""
    def value(s):
        try:
            y = float(func(float(s)))
        except Exception as exc:
            raise ParameterError(f"{label}: the callable failed at per-unit speed {s:g}: {exc}") from exc
        if not math.isfinite(y):
            raise ParameterError(f"{label}: the callable gave {y!r} at per-unit speed {s:g}")
        return y

    lo, hi = span
    s = sorted(set(np.linspace(lo, hi, 13).tolist()) | {0.0, 1.0})
    f = {x: value(x) for x in s}
    if abs(f[0.0] - 1.0) > 1e-12 or abs(f[1.0]) > 1e-12:
        raise ParameterError(f"{label}: a per-unit curve F(S) has F(0) = 1 (the stall torque) and F(1) = 0 (the "
                             f"no-load speed); the callable gives F(0) = {f[0.0]:g}, F(1) = {f[1.0]:g}")
    f[0.0], f[1.0] = 1.0, 0.0
    while True:
        knots = np.array(sorted(f))
        curve = tuple((x, f[x]) for x in knots)
        a, b = knots[:-1, None], knots[1:, None]
        probes = a + (b - a) * np.array([0.25, 0.5, 0.75])
        error = np.abs(evaluate(curve, probes)[0] - np.vectorize(value)(probes)).max(axis=1)
        failing = ((a + b)[:, 0] / 2)[error > tol / 2]
        if not len(failing):
            return canonical(label, curve)
        if len(knots) + len(failing) > MAX_POINTS:
            raise ParameterError(f"{label}: the callable could not be tabulated within {tol:g} of the stall torque "
                                 f"with {MAX_POINTS} points on per-unit speeds {lo:g}..{hi:g} (is it continuous?); "
                                 "give the pairs instead")
        for x in failing.tolist():
            f[x] = value(x)


def per_unit(speeds, torques):
    """(stall_torque, no_load_speed, curve) of a table of speeds and torques in any consistent
    units (rad/s and N m from a data sheet: give stall_torque and no_load_speed to an
    SIMechanism's motor; crankgen's units: to crankgen.Motor).  The table holds the speed 0 (its
    torque is the stall torque) and one speed of torque 0 above it (the no-load speed)."""
    w = np.asarray(speeds, dtype=float)
    T = np.asarray(torques, dtype=float)
    if w.ndim != 1 or w.shape != T.shape or len(w) < 2 or not (np.all(np.isfinite(w)) and np.all(np.isfinite(T))):
        raise ParameterError("per_unit takes two sequences of finite numbers of the same length (at least 2)")
    at_rest = np.flatnonzero(w == 0)
    if len(at_rest) != 1 or T[at_rest[0]] <= 0:
        raise ParameterError("per_unit: the table must hold the speed 0 once, with a positive torque (the stall "
                             "torque)")
    k0 = int(at_rest[0])
    zero = [k for k in range(k0 + 1, len(w)) if T[k] == 0]
    if not zero:
        raise ParameterError("per_unit: the table must hold a speed above 0 where the torque is 0 (the no-load "
                             "speed); add that point of the data sheet")
    stall, no_load = float(T[k0]), float(w[zero[0]])
    return stall, no_load, canonical("per_unit", tuple(zip(w / no_load, T / stall)))
