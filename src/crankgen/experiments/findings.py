"""Numbers of the findings, computed from sweep data (pure functions of arrays, no I/O).

Every function takes plain sequences, treats NaN as "no value" (a case without a periodic steady
state), and returns plain Python numbers, None when the quantity cannot be computed.
"""

import math

import numpy as np


def _arr(x):
    return np.asarray(x, dtype=float)


def ratio(numerator, denominator):
    """Element-wise numerator / denominator; NaN where either is missing or the denominator is 0."""
    n, d = _arr(numerator), _arr(denominator)
    out = np.full(np.broadcast(n, d).shape, math.nan)
    ok = np.isfinite(n) & np.isfinite(d) & (d != 0)
    np.divide(n, d, out=out, where=ok)
    return out


def relative_difference(value, reference):
    """|value / reference - 1| element-wise (NaN where either is missing)."""
    return np.abs(ratio(value, reference) - 1.0)


def first_exceedance(x, y, threshold):
    """Lowest x at which y rises above threshold, linearly interpolated between the last sweep
    point at or below it and the first one above it.  x increasing; NaN points of y are skipped.
    Returns None if y never exceeds the threshold; x of the first valid point if that point is
    already above it (the crossing is then at or below the start of the sweep)."""
    x, y = _arr(x), _arr(y)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    above = np.flatnonzero(y > threshold)
    if above.size == 0:
        return None
    i = int(above[0])
    if i == 0:
        return float(x[0])
    x0, x1, y0, y1 = x[i - 1], x[i], y[i - 1], y[i]
    return float(x0 + (threshold - y0) * (x1 - x0) / (y1 - y0))


def first_where(x, flags):
    """Lowest x whose flag is true (None if none)."""
    x, flags = _arr(x), np.asarray(flags, dtype=bool)
    idx = np.flatnonzero(flags)
    return float(np.min(x[idx])) if idx.size else None


def loglog_slope(x, y):
    """Least-squares slope of log y against log x over the points where both are positive and
    finite.  Returns dict(slope, intercept, points, max_residual) (max_residual: largest |error| of
    the fit in log y, i.e. how far the data are from a power law), or None with fewer than 2 points."""
    x, y = _arr(x), _arr(y)
    ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    if np.count_nonzero(ok) < 2:
        return None
    lx, ly = np.log(x[ok]), np.log(y[ok])
    slope, intercept = np.polyfit(lx, ly, 1)
    resid = ly - (slope * lx + intercept)
    return dict(slope=float(slope), intercept=float(intercept), points=int(ok.sum()),
                max_residual=float(np.max(np.abs(resid))))


def successive_changes(values):
    """|v[k+1] - v[k]| / |v[k+1]| for consecutive entries (NaN where either is missing)."""
    v = _arr(values)
    if v.size < 2:
        return np.array([])
    return relative_difference(v[:-1], v[1:])


def converged_count(ns, amplitudes, tol):
    """Smallest element count n of a ladder (increasing) whose amplitude differs from that of the
    next count by less than tol (relative to the finer one): "converged to tol between n and the
    next count".  None if no pair of the ladder qualifies."""
    ns = list(ns)
    changes = successive_changes(amplitudes)
    for k, c in enumerate(changes):
        if np.isfinite(c) and c < tol:
            return int(ns[k])
    return None


def _periodic_grid(theta_deg, curves):
    """Drop a closing point at theta_0 + 360 (periodic data), return (theta, curves)."""
    th, Y = _arr(theta_deg), np.atleast_2d(_arr(curves))
    if th.size > 2 and math.isclose(th[-1] - th[0], 360.0, abs_tol=1e-9):
        th, Y = th[:-1], Y[:, :-1]
    return th, Y


def extension_crossings(theta_deg, curves, rel_tol=0.05, resolution_deg=0.01):
    """Crank angles where all curves (rows of `curves`, over one revolution `theta_deg`, periodic)
    meet: local minima of the spread (max - min across curves), refined by linear interpolation of
    every curve on a fine grid between the neighbouring sweep points, kept when the refined spread
    is at most rel_tol times the largest spread over the revolution.
    Returns a list of dict(angle (degrees in [0, 360)), spread, relative_spread), by angle."""
    th, Y = _periodic_grid(theta_deg, curves)
    if Y.shape[0] < 2 or th.size < 3 or not np.all(np.isfinite(Y)):
        return []
    spread = Y.max(axis=0) - Y.min(axis=0)
    scale = float(spread.max())
    if scale == 0.0:
        return []
    m = th.size
    period = 360.0
    found = []
    for i in range(m):
        prev, nxt = spread[(i - 1) % m], spread[(i + 1) % m]
        if not (spread[i] <= prev and spread[i] < nxt):
            continue
        # fine grid on [theta_{i-1}, theta_{i+1}] (unwrapped), curves linear between points
        idx = [(i - 1) % m, i, (i + 1) % m]
        t_loc = np.array([th[i] - ((th[i] - th[idx[0]]) % period), th[i],
                          th[i] + ((th[idx[2]] - th[i]) % period)])
        fine = np.arange(t_loc[0], t_loc[2] + resolution_deg / 2, resolution_deg)
        Yf = np.stack([np.interp(fine, t_loc, Y[k, idx]) for k in range(Y.shape[0])])
        s = Yf.max(axis=0) - Yf.min(axis=0)
        j = int(np.argmin(s))
        if s[j] <= rel_tol * scale:
            found.append(dict(angle=float(fine[j] % period), spread=float(s[j]),
                              relative_spread=float(s[j] / scale)))
    return sorted(found, key=lambda d: d["angle"])


def slider_acceleration_zeros(a, points=72000):
    """Crank angles (degrees) where the rigid mechanism's slider acceleration vanishes
    (rod length 1, crank a*, x_s = a cos theta + sqrt(1 - a^2 sin^2 theta), constant crank speed)."""
    th = np.linspace(0.0, 2 * math.pi, points, endpoint=False)
    s, c = np.sin(th), np.cos(th)
    w = np.sqrt(1.0 - (a * s) ** 2)
    # d^2 x_s / d theta^2 in closed form
    acc = -a * c - (a ** 2) * (c ** 2 - s ** 2) / w - (a ** 4) * (s ** 2) * (c ** 2) / w ** 3
    nxt = np.roll(acc, -1)
    idx = np.flatnonzero(np.sign(acc) != np.sign(nxt))
    out = []
    h = th[1] - th[0]
    for i in idx:
        frac = acc[i] / (acc[i] - nxt[i])
        out.append(math.degrees((th[i] + frac * h) % (2 * math.pi)))
    return sorted(out)


def max_relative_difference(x, values, reference):
    """Largest |values / reference - 1| over points where both exist: dict(value, at, points) or None."""
    d = relative_difference(values, reference)
    ok = np.isfinite(d)
    if not ok.any():
        return None
    k = int(np.nanargmax(np.where(ok, d, -np.inf)))
    return dict(value=float(d[k]), at=float(_arr(x)[k]), points=int(ok.sum()))


def max_abs_difference(a, b):
    """Largest |a - b| over points where both are finite (None if none)."""
    a, b = _arr(a), _arr(b)
    ok = np.isfinite(a) & np.isfinite(b)
    return float(np.max(np.abs(a[ok] - b[ok]))) if ok.any() else None


def ranges_text(values, fmt="{:g}"):
    """Compact text of a sorted list of sweep values: "0.35-1.6 (26 values)" or "0.1, 0.8"."""
    v = sorted(values)
    if not v:
        return ""
    if len(v) <= 3:
        return ", ".join(fmt.format(x) for x in v)
    return f"{fmt.format(v[0])}-{fmt.format(v[-1])} ({len(v)} values)"
