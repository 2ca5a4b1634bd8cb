"""Small helpers shared by the runtime tests (not a reference implementation of the physics)."""

import math

import numpy as np

from crankgen.audit.backbone import mode_state as bending_mode_state   # noqa: F401  (v = A sin(pi x))


def zero_crossing_frequency(t, y):
    """Angular frequency from the mean spacing of linearly interpolated zero crossings."""
    idx = np.where(np.sign(y[:-1]) * np.sign(y[1:]) < 0)[0]
    tz = t[idx] - y[idx] * (t[idx + 1] - t[idx]) / (y[idx + 1] - y[idx])
    assert len(tz) >= 4, "too few zero crossings to measure a frequency"
    return math.pi / np.mean(np.diff(tz))


def observed_order(h, err):
    """Slope of log(err) against log(h) (least squares)."""
    return np.polyfit(np.log(h), np.log(err), 1)[0]


BAD_CELLS = {"nan", "NaN", "inf", "-inf", "Infinity", "-Infinity", "None", "null", "NULL"}


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def check_csv(path):
    """A CSV crankgen writes: a header of names (none a number), and columns that are either all
    numbers or all words, with empty fields for what does not exist: no 'nan', 'inf', 'None',
    and no Python values such as '[0.0, 0.0]'.  pandas.read_csv parses the numeric columns as
    numbers.  Returns the DataFrame."""
    import pandas as pd

    raw = pd.read_csv(path, dtype=str, keep_default_na=False)
    assert len(raw.columns) and not any(_is_number(c) for c in raw.columns), (path, list(raw.columns))
    assert not any(c.startswith("Unnamed") for c in raw.columns), (path, list(raw.columns))
    numeric = []
    for c in raw.columns:
        cells = [x for x in raw[c] if x != ""]
        bad = [x for x in cells if x.strip() in BAD_CELLS or x.strip()[:1] in "[({"]
        assert not bad, (path, c, bad[:3])
        kinds = {_is_number(x) for x in cells}
        assert len(kinds) <= 1, (path, c, "numbers and words mixed", cells[:5])
        if kinds == {True}:
            numeric.append(c)
    frame = pd.read_csv(path)
    for c in numeric:
        assert pd.api.types.is_numeric_dtype(frame[c]), (path, c, frame[c].dtype)
    return frame


def fake_steady_states(calls):
    """Instant synthetic steady_states (for sweep plumbing tests) that records the cases it is given."""
    from crankgen import SteadyState

    def fake(cases, tol=1e-8, max_revolutions=400, progress=None, parallel=None):
        cases = list(cases)
        calls.extend(cases)
        return [SteadyState(c, "periodic", 2 * c.omega, c.omega, 3, 0, 1e-9, "", 0.01) for c in cases]
    return fake


def true_angle(x):
    """x rad reduced to (-pi, pi] with 2 pi to 50 digits (mpmath): the crank position of x."""
    import mpmath

    with mpmath.workdps(50):
        r = mpmath.fmod(mpmath.mpf(x), 2 * mpmath.pi)
        if r > mpmath.pi:
            r -= 2 * mpmath.pi
        elif r <= -mpmath.pi:
            r += 2 * mpmath.pi
        return float(r)
