"""crankgen's lagrange formulation against an independent second model (independent_model.py:
all nodal co-ordinates free, pin and guide as Lagrange multipliers, d'Alembert with the inertial
accelerations, scipy DOP853), same finite elements (3, so that x* = 1/2 lies inside an element).

Both sides are converged in time: crankgen's Newmark (trapezoidal, rho_inf = 1: its error is even
in dt, as Richardson's extrapolation needs) is
Richardson-extrapolated from 1000 and 2000 steps per revolution (the 2000-step run alone is off by
about 1e-5), the DAE is integrated at rtol 1e-9.  The trajectories from rest (v*, u*(1) and the
extension over 7.85 time units: one revolution at Omega* = 0.8, 5/8 at 0.5) must agree to 1e-6
of each signal's largest value; with damping they agree to 5e-9 (undamped: 5e-8).

The four-bar (the end on the rocker's circle: a multiplier constraint non-linear in the
co-ordinates there, the end map in crankgen), a fluctuating crank on it and a run-up of an offset
slider-crank (the crank's rate law integrated with the rod there, closed forms in crankgen) are
compared the same way, with the reactions too: the multipliers are the forces of the crank pin and
of the guide, so the torque, the pin force and the end reaction (crankgen: the residual rows of
the constrained DOFs, Model.reactions) must agree as well.  Measured: 3e-9 at most (each force's
components on one scale); required 1e-7.  A 1e-4 relative error in the four-bar's phidd (a local
mutation of the compiled kinematics) shows as 5e-5 to 8e-5.
"""

import math

import numpy as np
import pytest

import crankgen
import four_bar
from crankgen.discrete.kinematics import case_state
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
                              rho_inf=1.0, **extra)
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


# ---- the four-bar and crank motions that are not constant ----------------------------------------

FOUR_BAR = dict(guide="circle", c=0.9, d=1.1, offset=0.2, branch=1)


def crankgen_forces_extrapolated(mech, window, spr0=SPR, **kw):
    """crankgen's v*, u*(1), extension and reactions (torque, pin X, Y, end X, Y) from rest over
    [0, window], Richardson-extrapolated from spr0 and 2 spr0 steps per (fastest) revolution."""
    runs = []
    for spr in (spr0, 2 * spr0):
        case = crankgen.Case.from_mechanism(mech, steps_per_rev=spr, n_elements=N_EL, rho_inf=1.0, **kw)
        revs = float(case_state(case, window).theta) / (2 * math.pi) + 0.01
        r = crankgen.simulate(case=case, revolutions=revs)
        keep = r.t <= window * (1 + 1e-12)
        end = "guide_on_slider" if case.guide == "line" else "rocker_on_tip"
        runs.append((r.t[keep], np.stack([r.v_mid, r.u_end, r.extension, r.torque, r.crank_on_rod_x,
                                          r.crank_on_rod_y, r.quantity(end + "_x"), r.quantity(end + "_y")],
                                         -1)[keep]))
    (t, coarse), (_, fine) = runs
    n = min(len(coarse), (len(fine) + 1) // 2)
    t, coarse, fine = t[:n], coarse[:n], fine[::2][:n]
    return t, (4 * fine - coarse) / 3, np.abs(fine - coarse) / 3


def compare_with_forces(mech, guide, rate_law, window=WINDOW, **kw):
    """kw: crankgen's run settings; guide and rate_law: the independent model's guide and crank
    motion (tests/four_bar.py; None: constant omega)."""
    t, ref, estimate = crankgen_forces_extrapolated(mech, window, formulation="lagrange",
                                                    damping="kelvin-voigt", membrane="pointwise", **kw)
    sample = slice(None, None, 25)
    model = SliderCrank(mech.a, mech.eps, mech.ms, mech.mu, kw.get("omega", 0.0), N_EL,
                        kw.get("approach", "A"), guide=guide, motion=rate_law)
    out, drift = model.simulate(t[sample], rtol=1e-9, atol=1e-12, forces=True)
    scale = np.max(np.abs(ref), axis=0)
    for first in (3, 5):                   # a force's two components on one scale
        scale[first:first + 2] = np.max(scale[first:first + 2])
    assert drift < 1e-11                                       # the multipliers hold the constraints
    assert np.all(np.max(estimate, axis=0) / scale < 1e-4)     # Newmark error, not extrapolated
    return np.max(np.abs(out - ref[sample]), axis=0) / scale


@pytest.mark.slow
def test_four_bar_agrees_with_an_independent_model():
    """The rod's end on the rocker's circle, a multiplier constraint non-linear in the co-ordinates
    in the independent model, the end map in crankgen: v*, u*(1), extension, torque, pin force and
    the rocker's force."""
    mech = crankgen.Mechanism(a=A, eps=EPS, ms=MS, mu=0.2, **FOUR_BAR)
    guide = ("circle", FOUR_BAR["c"], FOUR_BAR["d"], FOUR_BAR["offset"], FOUR_BAR["branch"])
    err = compare_with_forces(mech, guide, None, omega=0.8)
    assert np.all(err < 1e-7), err


@pytest.mark.slow
def test_fluctuating_crank_on_a_four_bar_agrees_with_an_independent_model():
    mech = crankgen.Mechanism(a=A, eps=EPS, ms=MS, mu=0.2, **FOUR_BAR)
    guide = ("circle", FOUR_BAR["c"], FOUR_BAR["d"], FOUR_BAR["offset"], FOUR_BAR["branch"])
    err = compare_with_forces(mech, guide, four_bar.Fluctuation(0.8, 0.3, 2),
                              motion=crankgen.Fluctuation(omega=0.8, amplitude=0.3, order=2))
    assert np.all(err < 1e-7), err


@pytest.mark.slow
def test_run_up_of_an_offset_slider_crank_agrees_with_an_independent_model():
    mech = crankgen.Mechanism(a=A, eps=EPS, ms=MS, mu=0.2, offset=0.05)
    err = compare_with_forces(mech, ("line", 0.05), four_bar.RunUp(0.3, 1.0, 1),
                              motion=crankgen.RunUp(start=0.3, stop=1.0, revolutions=1))
    assert np.all(err < 1e-7), err
