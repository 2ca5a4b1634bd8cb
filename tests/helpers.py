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
