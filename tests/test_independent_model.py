"""crankgen's lagrange formulation against an independent second model (independent_model.py:
all nodal co-ordinates free, pin and guide as Lagrange multipliers, d'Alembert with the inertial
accelerations, scipy DOP853), same finite elements (3, so that x* = 1/2 lies inside an element).

Both sides are converged in time: crankgen's Newmark (trapezoidal, error even in dt) is
Richardson-extrapolated from 1000 and 2000 steps per revolution (the 2000-step run alone is off by
about 1e-5), the DAE is integrated at rtol 1e-9.  The trajectories from rest (v*, u*(1) and the
extension over 7.85 time units: one revolution at Omega* = 0.8, 5/8 at 0.5) must agree to 1e-6
of each signal's largest value; with damping they agree to 5e-9 (undamped: 5e-8).
"""

import math

import numpy as np
import pytest

import crankgen
from independent_model import SliderCrank

A, EPS, MS = 0.1, 0.05, 0.5
N_EL = 3
WINDOW = 2 * math.pi / 0.8
SPR = 1000


def crankgen_extrapolated(omega, approach, mu, spr0=SPR, **extra):
    revs = WINDOW * omega / (2 * math.pi)
    runs = []
    for spr in (spr0, 2 * spr0):
        r = crankgen.simulate(crankgen.Mechanism(a=A, eps=EPS, ms=MS, mu=mu), omega=omega,
                              approach=approach, formulation="lagrange", damping="kelvin-voigt",
                              membrane="pointwise", n_elements=N_EL, steps_per_rev=spr, revolutions=revs,
                              **extra)
        runs.append(np.stack([r.v_mid, r.u_end, r.extension], -1))
    coarse, fine = runs[0], runs[1][::2]
    t = np.arange(len(coarse)) * (2 * math.pi / omega / spr0)
    return t, (4 * fine - coarse) / 3, np.abs(fine - coarse) / 3


def compare(omega, approach, mu, rotary_inertia=True, spr0=SPR):
    extra = {} if rotary_inertia else {"rotary_inertia": False}
    t, ref, estimate = crankgen_extrapolated(omega, approach, mu, spr0, **extra)
    sample = slice(None, None, 25 * spr0 // SPR)
    model = SliderCrank(A, EPS, MS, mu, omega, N_EL, approach, rotary_inertia=rotary_inertia)
    out, drift = model.simulate(t[sample], rtol=1e-9, atol=1e-12)
    scale = np.max(np.abs(ref), axis=0)
    assert drift < 1e-12                                      # the multipliers hold the constraints
    assert np.all(np.max(estimate, axis=0) / scale < 1e-4)   # Newmark error, not extrapolated
    return np.max(np.abs(out - ref[sample]), axis=0) / scale


@pytest.mark.parametrize("approach", ["A", "C"])
@pytest.mark.parametrize("omega", [0.5, 0.8])
def test_trajectories_agree_with_an_independent_model(omega, approach):
    """Kelvin-Voigt damping mu* = 0.2, rotary inertia included: v*, u*(1), extension."""
    err = compare(omega, approach, 0.2)
    assert np.all(err < 1e-6), err


def test_undamped_trajectory_agrees_with_an_independent_model():
    """No damping: the axial modes ring on, so crankgen takes twice the steps."""
    err = compare(0.8, "A", 0.0, spr0=2 * SPR)
    assert np.all(err < 1e-6), err


@pytest.mark.parametrize("approach", ["A", "C"])
def test_trajectories_agree_without_rotary_inertia(approach):
    err = compare(0.8, approach, 0.2, rotary_inertia=False)
    assert np.all(err < 1e-6), err
