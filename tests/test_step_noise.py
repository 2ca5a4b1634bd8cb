"""Forces free of step noise on default settings: the README's steel mechanism in SI (8 elements,
3 revolutions, no damping: its first axial mode, about 18,000 rad/s, is far above what 100 steps
per revolution resolve, omega dt = 7.6).

The step-to-step alternation of a sequence f_k is measured by its fourth difference over 16,
|f_{k-2} - 4 f_{k-1} + 6 f_k - 4 f_{k+1} + f_{k+2}| / 16: the amplitude A of an alternation
+-A, and sin^4(omega dt / 2) of a resolved oscillation (the rod's first bending mode, 12 steps per
period here: 0.5 % of its amplitude).  The rigid mechanism's driving torque is computed here from
its kinetic energy, tau Omega = dT/dt (the crank turns at constant speed, no gravity)."""

import math
import warnings

import numpy as np
import pytest

import crankgen
from crankgen.discrete.time_scheme import StepWarning

L, A_CRANK, E, RHO, AREA, INERTIA, M_SLIDER, OMEGA = 0.3, 0.15, 2e11, 7870.0, 6.4e-5, 3.41e-10, 0.0756, 150.0
STEEL = crankgen.SIMechanism(L=L, a=A_CRANK, E=E, rho=RHO, A=AREA, I=INERTIA, slider_mass=M_SLIDER,
                             crank_speed=OMEGA)
FORCES = ("torque", "crank_on_rod_x", "crank_on_rod_y", "rod_on_slider_x", "rod_on_slider_y",
          "guide_on_slider_x", "guide_on_slider_y")


def rigid_torque(theta):
    """Driving torque (N m) of the rigid slider-crank at constant crank speed: T = Omega^2 f(theta) / 2
    with f = m |dG/dtheta|^2 + J (dphi/dtheta)^2 + m_s (dX_B/dtheta)^2, so tau = Omega^2 f'(theta) / 2
    (a uniform rod of mass m = rho A L and moment of inertia m L^2/12 + rho I L about its centre G)."""
    m = RHO * AREA * L
    J = m * L ** 2 / 12 + RHO * INERTIA * L

    def positions(th):
        ax, ay = A_CRANK * np.cos(th), A_CRANK * np.sin(th)
        bx = ax + np.sqrt(L ** 2 - ay ** 2)
        return np.array([(ax + bx) / 2, ay / 2, np.arctan2(-ay, bx - ax), bx])

    def f(th, h=1e-6):
        d = (positions(th + h) - positions(th - h)) / (2 * h)
        return m * (d[0] ** 2 + d[1] ** 2) + J * d[2] ** 2 + M_SLIDER * d[3] ** 2

    h = 1e-4
    return 0.5 * OMEGA ** 2 * (f(theta + h) - f(theta - h)) / (2 * h)


def alternation(f):
    return np.abs(f[4:] - 4 * f[3:-1] + 6 * f[2:-2] - 4 * f[1:-3] + f[:-4]) / 16


@pytest.fixture(scope="module")
def runs():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        default = crankgen.simulate(STEEL, units="si", n_elements=8, revolutions=3)
        quiet = list(caught)
        newmark = crankgen.simulate(STEEL, units="si", n_elements=8, revolutions=3, rho_inf=1.0)
        loud = [w for w in caught[len(quiet):] if issubclass(w.category, StepWarning)]
    return default, newmark, quiet, loud


def test_default_forces_carry_no_step_to_step_alternation(runs):
    """Every force and torque output, over the last revolution: alternation below 1 % of the force's
    peak (measured: 0.04 % for the torque, 0.06 % at most); the peak torque within 3 % of the rigid
    mechanism's (measured 0.19 %: 69.52 against 69.65 N m), the torque within 10 % of its peak at
    every step (measured 5.5 %: the rod's vibration)."""
    r = runs[0]
    assert r.case.rho_inf == 0.8 and r.case.model == "consistent"
    spr = r.case.steps_per_rev
    last = slice(-spr - 1, None)
    for name in FORCES:
        f = r.si.quantity(name)[last]
        other = name[:-1] + ("y" if name.endswith("x") else "x") if name != "torque" else name
        peak = max(np.max(np.abs(f)), np.max(np.abs(r.si.quantity(other)[last])))   # a force's size
        assert peak > 0, name
        assert np.max(alternation(f)) < 0.01 * peak, name
    tau = r.si.torque[last]
    rigid = rigid_torque(r.theta[last])
    assert np.max(np.abs(rigid)) == pytest.approx(70.0, rel=0.05)                # about +-70 N m
    assert np.max(np.abs(tau)) == pytest.approx(np.max(np.abs(rigid)), rel=0.03)
    assert np.max(np.abs(tau - rigid)) < 0.1 * np.max(np.abs(rigid))           # the rod's vibration


def test_newmark_leaves_the_axial_mode_ringing_and_says_so_once(runs):
    """The trapezoidal rule (rho_inf = 1, the paper's) does not damp the unresolved axial mode: the
    torque alternates by tens of percent of its peak, and the run warns once, in one line, naming
    the mode; the default run does not warn."""
    default, newmark, quiet, loud = runs
    assert not [w for w in quiet if issubclass(w.category, StepWarning)]
    assert len(loud) == 1
    text = str(loud[0].message)
    assert "\n" not in text and "axial" in text and "omega dt = 7.58" in text and "1.81e+04 rad/s" in text
    spr = newmark.case.steps_per_rev
    tau = newmark.si.torque[-spr - 1:]
    assert np.max(alternation(tau)) > 0.2 * np.max(np.abs(tau))
