"""A motor's torque-speed curve (crankgen.torque_curve, motion `motor`'s torque_curve): the engine's
Hermite evaluation against scipy's PCHIP, the curve's checks, a callable's tabulation against the
callable, a data sheet's table put in per-unit, and the motor-driven mechanism with a curve against
the rigid slider-crank's one-degree-of-freedom equation integrated here with the same curve."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.interpolate import PchipInterpolator

import crankgen
from crankgen.declaration import torque_curve
from crankgen.engine.coordinates import hermite
from crankgen.errors import ParameterError

# an induction motor's shape: locked-rotor torque 1, breakdown torque 2.2 near synchronous speed 1,
# a generator's braking beyond it
INDUCTION = ((0.0, 1.0), (0.3, 1.15), (0.6, 1.5), (0.85, 2.2), (0.95, 1.3), (1.0, 0.0), (1.2, -3.0))


def _scipy_curve(curve):
    """f(s) of the module docstring written with scipy: PCHIP inside, the end slopes outside."""
    s, f = np.array(curve).T
    p = PchipInterpolator(s, f)
    d = p.derivative()
    lo, hi = float(d(s[0])), float(d(s[-1]))

    def value(x):
        x = np.asarray(x, dtype=float)
        return np.where(x < s[0], f[0] + lo * (x - s[0]), np.where(x > s[-1], f[-1] + hi * (x - s[-1]),
                                                                   p(np.clip(x, s[0], s[-1]))))
    return value


def test_the_engine_s_hermite_pieces_are_scipy_s_pchip():
    """The engine's table of a case is the curve's departure from the linear law in crankgen's
    units: T_stall [f(thetad / Omega_nl) - (1 - thetad / Omega_nl)], f scipy's PCHIP here."""
    stall, no_load = 0.05, 0.8
    case = crankgen.Case(motion="motor", stall_torque=stall, no_load_speed=no_load, torque_curve=INDUCTION)
    tab = torque_curve.departure_table(case)
    f = _scipy_curve(INDUCTION)
    w = no_load * np.concatenate([np.linspace(-0.3, 1.5, 997), [s for s, _ in INDUCTION]])
    got = np.array([hermite(tab, len(tab), x) for x in w])
    want = stall * (f(w / no_load) - (1 - w / no_load))
    assert np.max(np.abs(got[:, 0] - want)) < 1e-13 * stall * 10
    h = 1e-6                                     # the slope against differences of the scipy curve
    fd = stall * ((f((w + h) / no_load) - f((w - h) / no_load)) / (2 * h) + 1 / no_load)
    inner = np.all(np.abs(w[:, None] / no_load - np.array([s for s, _ in INDUCTION])) > 2 * h, axis=1)
    assert np.max(np.abs(got[inner, 1] - fd[inner])) < 1e-6 * stall
    # the shape is kept: no overshoot above the breakdown torque between its neighbours
    assert np.max(got[:, 0] / stall + 1 - w / no_load) <= 2.2 + 1e-12
    assert len(torque_curve.departure_table(crankgen.Case(motion="motor"))) == 0      # the linear law: none


def test_a_curve_is_checked_and_reads_back_from_its_text():
    c = crankgen.Case(motion="motor", torque_curve="0:1, 0.85:2.2 ,1:0")
    assert c.torque_curve == ((0.0, 1.0), (0.85, 2.2), (1.0, 0.0))
    assert torque_curve.canonical("x", torque_curve.text(INDUCTION)) == INDUCTION
    assert crankgen.Case.from_dict(c.as_dict()) == c
    for bad, match in (("0:1,1:0.2", "through 0:1"), ("0:1,0.5:2,0.5:1,1:0", "must increase"),
                       ("0:1;1:0", "not S:F"), ("0:1,x:2,1:0", "not a number"), ([(0, 1)], "2 to"),
                       ("0:1,0.5:nan,1:0", "non-finite")):
        with pytest.raises(ParameterError, match=match):
            crankgen.Case(motion="motor", torque_curve=bad)
    with pytest.raises(ParameterError, match="motor"):       # only the motor reads it
        crankgen.Case(torque_curve=INDUCTION)


def test_a_callable_is_tabulated_within_its_tolerance():
    def shape(s):                                # peak torque 2.4 at s = 0.8, zero at 1
        return (1 - s) * (1 + 6 * s ** 3) / (1 + 0.5 * s)
    c = crankgen.Case(motion="motor", torque_curve=shape)
    xs = np.linspace(0.0, 1.2, 20001)
    err = np.abs(torque_curve.evaluate(c.torque_curve, xs)[0] - shape(xs))
    assert 20 < len(c.torque_curve) <= torque_curve.MAX_POINTS
    assert err.max() < torque_curve.TOLERANCE
    with pytest.raises(ParameterError, match=r"F\(0\) = 1"):
        crankgen.Case(motion="motor", torque_curve=lambda s: 2 * (1 - s))


def test_a_data_sheet_table_in_per_unit():
    speeds = [0.0, 50.0, 100.0, 140.0, 157.0, 170.0]       # rad/s
    torques = [12.0, 13.0, 18.0, 26.0, 0.0, -20.0]         # N m
    stall, no_load, curve = torque_curve.per_unit(speeds, torques)
    assert (stall, no_load) == (12.0, 157.0)
    assert curve[0] == (0.0, 1.0) and (1.0, 0.0) in curve and curve[3] == (140 / 157, 26 / 12)
    with pytest.raises(ParameterError, match="no-load"):
        torque_curve.per_unit(speeds[:4], torques[:4])


def _rigid_speed(a, ms, J, stall, no_load, law, t):
    """theta, thetad of the rigid slider-crank (rod of unit mass and length, end mass ms on the line
    Y = 0) from rest under T_m = stall law(thetad / no_load): (J + I) thetadd + I' thetad^2 / 2 = T_m."""
    def inertia(th):
        s, c = np.sin(th), np.cos(th)
        A1 = np.array([-a * s, a * c])
        B1 = np.array([-a * s - a * a * s * c / np.sqrt(1 - (a * s) ** 2), 0.0])
        D = B1 - A1
        return A1 @ A1 + A1 @ D + D @ D / 3 + ms * B1[0] ** 2

    def rhs(_, y):
        th, w = y
        h = 1e-6
        dI = (inertia(th + h) - inertia(th - h)) / (2 * h)
        return [w, (stall * float(law(w / no_load)) - 0.5 * dI * w * w) / (J + inertia(th))]
    return solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-11, atol=1e-13).y


@pytest.mark.slow
def test_stiff_rod_limit_with_a_curve_is_the_rigid_slider_crank():
    """Slow against the rod (Omega_nl = 0.05): the run-up from rest through the curve's breakdown
    peak and the speed's swing per revolution follow the rigid mechanism's equation with the same
    curve (scipy's PCHIP here); the linear law would give another run-up (the check can fail)."""
    no_load, stall = 0.05, 0.0001
    motor = crankgen.Motor(stall_torque=stall, no_load_speed=no_load, inertia=0.01, torque_curve=INDUCTION)
    r = crankgen.simulate(crank=motor, n_elements=4, steps_per_rev=200, revolutions=3)
    th, w = _rigid_speed(0.1, 0.5, 0.01, stall, no_load, _scipy_curve(INDUCTION), r.t)
    _, w_linear = _rigid_speed(0.1, 0.5, 0.01, stall, no_load, lambda s: 1 - s, r.t)
    late = slice(200, None)
    error = np.max(np.abs(r.crank_speed[late] - w[late])) / no_load
    assert np.max(np.abs(w_linear[late] - w[late])) / no_load > 0.05      # the curve matters here
    assert error < 5e-4, error
    assert np.max(np.abs(r.theta - th)) < 0.01


def test_engines_agree_and_a_straight_curve_is_the_linear_law():
    kw = dict(n_elements=4, revolutions=0.5)
    motor = dict(stall_torque=0.05, no_load_speed=0.8, inertia=0.05, load_torque=0.002)
    a = crankgen.simulate(crank=crankgen.Motor(**motor, torque_curve=INDUCTION), engine="numpy", **kw)
    b = crankgen.simulate(crank=crankgen.Motor(**motor, torque_curve=INDUCTION), **kw)
    assert np.array_equal(a.iterations, b.iterations)
    assert np.max(np.abs(a.states - b.states)) < 1e-11 and np.max(np.abs(a.crank - b.crank)) < 1e-11
    straight = crankgen.simulate(crank=crankgen.Motor(**motor, torque_curve=((0, 1), (0.4, 0.6), (1, 0), (1.5, -0.5))),
                                 **kw)
    linear = crankgen.simulate(crank=crankgen.Motor(**motor), **kw)
    assert np.max(np.abs(straight.crank - linear.crank)) < 1e-12
    assert np.max(np.abs(b.crank[:, 1] - linear.crank[:, 1])) > 1e-3      # and a curved one is not


def test_a_run_s_motor_torque_is_the_crank_equation_s(tmp_path):
    """result.motor_torque (the curve, evaluated by the reference's scipy PCHIP) equals what the
    compiled engine's step solved for, J thetadd + T_load + T_rod (the output torque), through the
    breakdown peak; the per-step CSV carries it."""
    J, load = 0.05, 0.002
    r = crankgen.simulate(crank=crankgen.Motor(stall_torque=0.05, no_load_speed=0.8, inertia=J, load_torque=load,
                                               torque_curve=INDUCTION), n_elements=4, revolutions=1)
    balance = J * r.crank_acceleration + load + np.asarray(r.torque)
    assert np.max(r.crank_speed) / 0.8 > 0.85                  # past the breakdown torque
    assert np.max(np.abs(r.motor_torque - balance)) < 1e-8 * np.max(np.abs(r.motor_torque))
    from crankgen.results.exports import per_step
    columns, values = per_step(r)
    assert np.array_equal(values[columns.index("motor_torque_rhoA_L3_omega_b2")], r.motor_torque)
    assert crankgen.simulate(omega=0.8, n_elements=2, revolutions=0.1).motor_torque is None
