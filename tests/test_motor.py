"""The motor-driven crank (its angle a declared co-ordinate of the DOF map: crankgen.discrete.newmark, engine/coordinates.py): its limits against independent truths
(the rigid slider-crank's one-degree-of-freedom equation integrated here by scipy; the constant-speed
crank as the motor stiffens), its energy balance, and the two engines against each other."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import crankgen
from crankgen.errors import ParameterError
from crankgen.discrete.system import Model
from crankgen.discrete.kinematics import crank_state

import energy_balance as eb


def _rigid_speed(a, ms, J, stall, no_load, load, t):
    """theta, thetad of the rigid slider-crank (rod of unit mass and length, end mass ms on the line
    Y = 0) driven by T_m = stall (1 - thetad / no_load) - load from rest: T = I(theta) thetad^2 / 2,
    (J + I) thetadd + I'(theta) thetad^2 / 2 = T_m."""
    def inertia(th):
        s, c = np.sin(th), np.cos(th)
        A1 = np.array([-a * s, a * c])                                  # d(crank pin)/d theta
        B1 = np.array([-a * s - a * a * s * c / np.sqrt(1 - (a * s) ** 2), 0.0])   # d(slider)/d theta
        D = B1 - A1
        return A1 @ A1 + A1 @ D + D @ D / 3 + ms * B1[0] ** 2          # int_0^1 |A' + x D|^2 dx + ms X'^2

    def rhs(_, y):
        th, w = y
        h = 1e-6
        dI = (inertia(th + h) - inertia(th - h)) / (2 * h)
        return [w, (stall * (1 - w / no_load) - load - 0.5 * dI * w * w) / (J + inertia(th))]
    return solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-11, atol=1e-13).y


@pytest.mark.slow
def test_stiff_rod_limit_is_the_rigid_slider_crank():
    """Slow against the rod's first bending frequency (Omega_nl = 0.1, 0.05: the rod's dynamic
    deflection ~ Omega^2), with the stall torque scaled by Omega^2 (the same rigid motion in
    Omega t), a light flywheel (J comparable to the linkage's reflected inertia: the speed swings
    by about 22 % per revolution); after the first revolution (the start from an undeformed rod at
    rest rings its modes) the crank speed matches the rigid mechanism's, and closer at the slower speed."""
    errors = []
    for no_load in (0.1, 0.05):
        stall = 0.0004 * (no_load / 0.1) ** 2
        r = crankgen.simulate(crank=crankgen.Motor(stall_torque=stall, no_load_speed=no_load, inertia=0.01),
                              n_elements=4, steps_per_rev=200, revolutions=3)
        th, w = _rigid_speed(0.1, 0.5, 0.01, stall, no_load, 0.0, r.t)
        assert np.ptp(w[200:]) > 0.2 * no_load                   # a crank speed that really swings
        late = slice(200, None)
        errors.append(np.max(np.abs(r.crank_speed[late] - w[late])) / no_load)
        assert np.max(np.abs(r.theta - th)) < 0.01
    assert errors[0] < 4e-3 and errors[1] < 1.5e-3, errors
    assert errors[1] < 0.5 * errors[0], errors


def test_stiff_motor_limit_is_the_constant_speed_crank():
    """T_stall -> infinity at Omega_nl fixed, starting at Omega_nl: the crank speed stays at
    Omega_nl to O(1 / T_stall) and the rod's response tends to the constant-speed crank's."""
    omega = 0.6
    ref = crankgen.simulate(omega=omega, n_elements=4, revolutions=2)
    gaps, wobbles = [], []
    for stall in (1.0, 100.0):
        r = crankgen.simulate(crank=crankgen.Motor(stall_torque=stall, no_load_speed=omega, inertia=0.01,
                                                   initial_speed=omega), n_elements=4, revolutions=2)
        assert np.allclose(r.t, ref.t, rtol=0, atol=1e-12)
        wobbles.append(np.max(np.abs(r.crank_speed - omega)))
        gaps.append(np.max(np.abs(r.v_mid - ref.v_mid)) / np.max(np.abs(ref.v_mid)))
    assert wobbles[1] < wobbles[0] / 50 and wobbles[1] < 1e-4 * omega, wobbles
    assert gaps[1] < gaps[0] / 30 and gaps[1] < 2e-3, gaps


class _Driven:
    """The model of a motor run with the crank's history as its kinematics (energy_balance.py
    reads model.kinematics(t))."""

    def __init__(self, model, kin):
        self._model, self._kin = model, kin

    def __getattr__(self, name):
        return getattr(self._model, name)

    def kinematics(self, t):
        return self._kin


def _balance_defect(spr, J, stall, no_load, load, frame=True):
    """max over one no-load revolution of |E(t) - E(0) - (motor and load work - dissipated energy +
    the frame's work)| / the motor's |work|, E the kinetic energy of crank, rod and end mass plus the
    strain energy, every term from tests/energy_balance.py (the inertial kinematics and energies
    written out there; crankgen's residual only for the reactions)."""
    r = crankgen.simulate(crank=crankgen.Motor(stall_torque=stall, no_load_speed=no_load, inertia=J,
                                               load_torque=load), n_elements=4, steps_per_rev=spr,
                          revolutions=1, rho_inf=1.0, eps=0.05)
    w = r.crank_speed
    kin = crank_state(r.case, np.stack([r.theta, w, r.crank_acceleration], -1))
    p = eb.power_history(_Driven(Model(r.case), kin), r.t, r.states, r.rates, r.accelerations, averaged=True)
    drive = (stall * (1 - w / no_load) - load) * w
    E = p["E"] + 0.5 * J * w ** 2
    rhs = eb.cumulative(r.t, drive - p["P_diss"] + p["P_resultant"] + (p["P_frame"] if frame else 0.0))
    scale = eb.cumulative(r.t, np.abs(drive))[-1]
    assert eb.cumulative(r.t, p["P_diss"])[-1] > 1e-3 * scale          # the damping takes part
    return np.max(np.abs(E - E[0] - rhs)) / scale


@pytest.mark.filterwarnings("ignore::crankgen.notices.BeyondTheoryWarning")
@pytest.mark.slow
def test_energy_balance_of_the_motor_run():
    """Motor and load work = change of the kinetic energy of crank, rod and end mass and of the
    strain energy + dissipated energy - the work of the rod's moving frame on it (energy_balance.py:
    the frame's angle is the rigid mechanism's, and the finite elements of approaches A-C cannot
    rotate a deformed rod exactly, so the frame does a little work, about 0.1 % of the motor's here),
    closing at the trapezoidal rule's second order: measured 1.0e-3, 2.6e-4 of the work at 100 and
    200 steps per no-load revolution.  Without the frame's work the defect stays at 0.1 %."""
    J, stall, no_load, load = 0.05, 0.05, 0.9, 0.005
    coarse, fine = (_balance_defect(spr, J, stall, no_load, load) for spr in (100, 200))
    assert fine < 5e-4 and 3.5 < coarse / fine < 4.5, (coarse, fine)
    assert _balance_defect(200, J, stall, no_load, load, frame=False) > 2 * fine


def test_the_crank_s_own_balance_is_second_order():
    """J thetad^2 / 2 changes by the work of the motor, the load and the torque the rod demands (the
    output `torque`, from the stored states): the crank's equation as integrated, to the
    trapezoidal rule's second order (step halved: the defect falls about fourfold)."""
    J, stall, no_load, load = 0.05, 0.05, 0.9, 0.005
    defects = []
    for spr in (100, 200):
        r = crankgen.simulate(crank=crankgen.Motor(stall_torque=stall, no_load_speed=no_load, inertia=J,
                                                   load_torque=load), n_elements=4, steps_per_rev=spr,
                              revolutions=1, rho_inf=1.0)
        w = r.crank_speed
        power = (stall * (1 - w / no_load) - load - r.torque) * w
        work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(r.t))])
        defects.append(np.max(np.abs(work - 0.5 * J * (w ** 2 - w[0] ** 2))) / np.max(0.5 * J * w ** 2))
    assert defects[0] < 2e-3 and 3.0 < defects[0] / defects[1] < 5.0, defects


def test_compiled_and_numpy_engines_agree():
    kw = dict(crank=crankgen.Motor(stall_torque=0.05, no_load_speed=0.8, inertia=0.05, load_torque=0.002),
              n_elements=4, revolutions=1, times=[1.0, 2.05])
    a = crankgen.simulate(engine="numpy", **kw)
    b = crankgen.simulate(**kw)
    assert np.array_equal(a.iterations, b.iterations)
    assert np.max(np.abs(a.states - b.states)) < 1e-11
    assert np.max(np.abs(a.crank - b.crank)) < 1e-11
    assert np.max(np.abs(a.at_times.crank_speed - b.at_times.crank_speed)) < 1e-11
    # a requested time between steps is one step of the remaining length: the speed there lies
    # between its neighbours' (the crank runs up monotonically over the first revolution)
    k = int(2.05 // (b.t[1] - b.t[0]))
    assert min(b.crank_speed[k], b.crank_speed[k + 1]) < b.at_times.crank_speed[1] < max(
        b.crank_speed[k], b.crank_speed[k + 1])
    assert np.allclose(b.at_times.crank_angle, b.at_times.theta)
    # the crank starts from rest with the motor's whole torque on the crank and the linkage
    assert b.crank_speed[0] == 0.0 and b.crank_acceleration[0] > 0.0


def test_a_motor_run_refuses_what_it_cannot_take():
    with pytest.raises(ParameterError, match="n_elements >= 2"):
        crankgen.simulate(crank=crankgen.Motor(), n_elements=1, revolutions=0.1)
    with pytest.raises(ParameterError, match="one-pass scheme has no bordered form"):
        crankgen.simulate(crank=crankgen.Motor(), integrator="one-pass", n_elements=2, revolutions=0.1)
    with pytest.raises(ParameterError, match="stall_torque"):
        crankgen.simulate(crank=crankgen.Motor(stall_torque=-1.0), revolutions=0.1)
    with pytest.raises(ParameterError, match="one-pass"):                # a sweep checks the shooting's rules
        crankgen.sweep([crankgen.Case(motion="motor", integrator="one-pass", n_elements=2)])
    with pytest.raises(crankgen.NoResultError, match="held back"):          # a poincare sweep needs a turning crank
        crankgen.poincare(parameter="no_load_speed", values=[1.0], n_elements=2,
                          crank=crankgen.Motor(stall_torque=0.01, load_torque=0.02))


def test_simulate_many_runs_motor_driven_cases_beside_prescribed_ones():
    """simulate_many of a motor-driven case gives simulate's run of it, bit for bit (one path: its
    own batch, its state the DOF map's), and a prescribed case in the same list keeps its batched
    run; the progress counts the case-steps of both."""
    motor = crankgen.Case(motion="motor", stall_torque=0.05, no_load_speed=0.8, inertia=0.05, n_elements=2)
    prescribed = crankgen.Case(omega=0.8, n_elements=2)
    seen = []
    runs = crankgen.simulate_many([motor, prescribed], 1, progress=lambda done, total: seen.append((done, total)))
    alone = crankgen.simulate(case=motor, revolutions=1)
    np.testing.assert_array_equal(runs[0].crank_speed, alone.crank_speed)
    np.testing.assert_array_equal(runs[0].v_mid, alone.v_mid)
    assert runs[0].crank_speed[-1] > 0.5                      # it ran up
    batched = crankgen.simulate_many([prescribed], 1)[0]
    np.testing.assert_array_equal(runs[1].v_mid, batched.v_mid)
    assert seen[-1] == (200, 200)
