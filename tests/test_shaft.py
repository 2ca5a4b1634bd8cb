"""A motor driving the crank through a torsionally flexible shaft (motion `shaft`: the motor rotor's
angle a second declared co-ordinate of the DOF map, with its own equation), against independent
truths built here: the two-inertia torsional natural frequency at rest, and the rigid slider-crank
with the same two-inertia drive integrated by scipy's solve_ivp (the rod made effectively stiff:
slow against its first bending frequency)."""

import numpy as np
from scipy.integrate import solve_ivp

import crankgen

A, MS = 0.1, 0.5          # the default crank length a* and end mass ms*


def linkage_inertia(theta, a=A, ms=MS):
    """The rigid slider-crank's inertia reflected to the crank, I(theta) = T / (thetad^2 / 2): the rod
    (unit mass and length) and the end mass ms on the line Y = 0, the crank massless."""
    s, c = np.sin(theta), np.cos(theta)
    A1 = np.array([-a * s, a * c])                                                  # d(crank pin)/d theta
    B1 = np.array([-a * s - a * a * s * c / np.sqrt(1 - (a * s) ** 2), 0.0])        # d(end)/d theta
    D = B1 - A1
    return A1 @ A1 + A1 @ D + D @ D / 3 + ms * B1[0] ** 2


def test_the_shaft_s_torsional_frequency_at_rest():
    """Held at rest by a load equal to the stall torque, the shaft starts untwisted and swings about
    its static twist T / k at the two-inertia frequency sqrt(k (1/J_rotor + 1/(J + I(theta0)))), I
    the linkage's reflected inertia.  The rod is far stiffer (the torsional frequency 0.074 of its
    first bending one), the motor's slope damps the swing by a damping ratio of 1e-3 (its speed
    stays 400 times below the no-load speed), Newmark's step shortens the period by (w dt)^2 / 12
    ~ 2e-5."""
    J, Jm, k, T, theta0, no_load = 0.04, 0.03, 1e-4, 1e-6, 0.7, 0.3
    case = crankgen.Case(motion="shaft", stall_torque=T, load_torque=T, no_load_speed=no_load, inertia=J,
                         rotor_inertia=Jm, shaft_stiffness=k, theta0=theta0, n_elements=4, steps_per_rev=100,
                         rho_inf=1.0)
    omega = np.sqrt(k * (1 / Jm + 1 / (J + linkage_inertia(theta0))))
    period = 2 * np.pi / omega
    r = crankgen.simulate(case=case, revolutions=3 * period / (2 * np.pi / no_load), history=False)
    twist = r.coordinates["rotor"][:, 0] - r.coordinates["theta"][:, 0]
    static = T / k
    assert abs(np.max(twist) - 2 * static) < 0.02 * static          # from 0 to twice the static twist and back
    x = twist - static
    up = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))                 # upward zero crossings, interpolated
    times = r.t[up] - x[up] * (r.t[up + 1] - r.t[up]) / (x[up + 1] - x[up])
    measured = np.mean(np.diff(times))
    assert len(times) >= 3
    assert abs(measured / period - 1) < 2e-3, (measured, period)
    # the crank hardly moves: the linkage's inertia is the one at theta0
    assert np.max(np.abs(r.theta - theta0)) < 1e-2


def _rigid_two_inertia(J, Jm, k, c, stall, no_load, t):
    """(theta, thetad, phi_m, phid_m) of the rigid slider-crank driven from rest through the shaft:
    (J + I) thetadd + I' thetad^2 / 2 = T_s,  Jm phidd_m = stall (1 - phid_m / no_load) - T_s,
    T_s = k (phi_m - theta) + c (phid_m - thetad)."""
    def rhs(_, y):
        th, w, ph, wm = y
        h = 1e-6
        dI = (linkage_inertia(th + h) - linkage_inertia(th - h)) / (2 * h)
        ts = k * (ph - th) + c * (wm - w)
        return [w, (ts - 0.5 * dI * w * w) / (J + linkage_inertia(th)), wm, (stall * (1 - wm / no_load) - ts) / Jm]
    return solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0, 0.0, 0.0], t_eval=t, rtol=1e-11, atol=1e-13, method="DOP853").y


def test_a_slow_run_up_through_the_shaft_is_the_rigid_two_inertia_drive():
    """Slow against the rod's first bending frequency (no-load speed 0.05; stall torque scaled by its
    square), a soft damped shaft (its torsional frequency about 0.45 of the rod's first bending one,
    far above the crank's speed: the twist rings and settles): after the first revolution (the
    start from an undeformed rod at rest rings its modes) the crank's and the rotor's speeds follow
    the rigid mechanism's two-inertia equations to 0.15 % of the no-load speed (measured 0.06 and
    0.08 %); a rigid shaft (one inertia J + J_rotor) would be 1.9 % off."""
    no_load = 0.05
    stall = 0.0004 * (no_load / 0.1) ** 2
    J, Jm, k, c = 0.01, 0.01, 1e-3, 2e-4
    r = crankgen.simulate(crank=crankgen.ShaftMotor(stall_torque=stall, no_load_speed=no_load, inertia=J,
                                                    rotor_inertia=Jm, shaft_stiffness=k, shaft_damping=c),
                          n_elements=4, steps_per_rev=200, revolutions=3)
    th, w, ph, wm = _rigid_two_inertia(J, Jm, k, c, stall, no_load, r.t)
    late = slice(200, None)
    crank_speed = r.coordinates["theta"][:, 1]
    rotor_speed = r.coordinates["rotor"][:, 1]
    assert np.ptp(rotor_speed[late] - crank_speed[late]) > 0.01 * no_load       # the shaft really twists
    assert np.max(np.abs(crank_speed[late] - w[late])) < 1.5e-3 * no_load
    assert np.max(np.abs(rotor_speed[late] - wm[late])) < 1.5e-3 * no_load
    assert np.max(np.abs(r.theta - th)) < 0.01
    assert np.max(np.abs(r.coordinates["rotor"][:, 0] - ph)) < 0.01
