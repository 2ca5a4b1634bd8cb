"""The steady motion of a motor-driven crank (crankgen.analyses.section, CrankSection): an autonomous periodic orbit
found by shooting on the section theta = theta0 (mod 2 pi), checked against marching, against
another section and against the flow's monodromy matrix (its trivial multiplier)."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.analyses import section as motor_steady

MOTOR = dict(stall_torque=0.05, no_load_speed=0.8, inertia=0.05, load_torque=0.002)


@pytest.fixture(scope="module")
def steady():
    return crankgen.steady_state(crank=crankgen.Motor(**MOTOR), n_elements=4)


def test_shooting_finds_the_motion_marching_settles_on(steady):
    assert steady.status == "periodic" and steady.residual < 1e-8
    T = steady.period
    assert steady.t[-1] == pytest.approx(T, rel=1e-12)
    assert steady.theta[-1] - steady.theta[0] == pytest.approx(2 * math.pi, abs=1e-12)
    # marched from rest long enough: the time between two late passages of theta0 + 2 pi k is T
    r = crankgen.simulate(crank=crankgen.Motor(**MOTOR), n_elements=4, revolutions=60)
    k = np.arange(int(r.theta[-1] / (2 * math.pi)) - 2, int(r.theta[-1] / (2 * math.pi)))
    passages = np.interp(2 * math.pi * k, r.theta, r.t)
    assert np.diff(passages)[-1] == pytest.approx(T, rel=1e-4)
    assert steady.mean_speed == pytest.approx(2 * math.pi / T)
    w = steady.crank_speed
    assert steady.speed_fluctuation == pytest.approx((w.max() - w.min()) / steady.mean_speed)
    assert 0.0 < steady.speed_fluctuation < 0.5
    # the crank equation holds along the orbit: the motor's torque less the load and the rod's
    # demand accelerates the crank's inertia (the rod's demand, the output torque, from the states)
    motor_torque = MOTOR["stall_torque"] * (1 - w / MOTOR["no_load_speed"]) - MOTOR["load_torque"]
    J = MOTOR["inertia"]
    assert np.max(np.abs(J * steady.crank[:, 2] - (motor_torque - steady.torque))) < 1e-9


def test_the_orbit_does_not_depend_on_the_section(steady):
    other = crankgen.steady_state(crank=crankgen.Motor(theta0=2.0, **MOTOR), n_elements=4)
    assert other.status == "periodic"
    assert other.period == pytest.approx(steady.period, rel=1e-6)
    # the map's multipliers are the flow's, to the time scheme's error: sections sample the orbit on
    # different time grids (measured: 3.6e-4 apart at 100 steps per no-load revolution, 9.6e-5 at 200)
    assert other.multiplier == pytest.approx(steady.multiplier, rel=1e-3)
    # the same motion sampled from another angle: the crank speed at equal angles agrees
    a = np.interp(np.linspace(2.5, 6.0, 50), steady.theta, steady.crank_speed)
    b = np.interp(np.linspace(2.5, 6.0, 50), other.theta, other.crank_speed)
    assert np.max(np.abs(a - b)) < 1e-3 * steady.mean_speed


def test_the_flow_has_the_trivial_multiplier_and_the_map_the_others(steady):
    m = motor_steady.CrankSection(steady.case)
    M = motor_steady.monodromy(m, steady.section_state, steady.period)
    mu = np.linalg.eigvals(M)
    trivial = mu[np.argmin(np.abs(mu - 1.0))]
    assert abs(trivial - 1.0) < 1e-5
    rest = np.delete(mu, np.argmin(np.abs(mu - 1.0)))
    top = np.sort(np.abs(rest))[::-1]
    # the map's last step adapts its length to land on the section, the flow's is fixed: their
    # dominant multipliers agree to the time scheme's error (measured 2.5e-4 apart)
    assert np.allclose(top[:2], np.abs(steady.multipliers[:2]), rtol=1e-3)
    assert top[2] < 1e-3 and abs(steady.multipliers[2]) < 1e-3
    assert steady.multiplier == pytest.approx(abs(steady.multipliers[0]))


def test_a_stalled_motor_is_a_failure_not_a_hang():
    s = crankgen.steady_state(crank=crankgen.Motor(stall_torque=0.01, load_torque=0.02), n_elements=2)
    assert s.status == "failed" and "held back" in s.message


def test_a_weak_motor_on_a_heavy_crank_runs_up_until_it_settles():
    """The run-up before shooting lasts until the crank's mean speed settles (a weak motor takes
    (J + the linkage's inertia) Omega_nl / T_stall, here hundreds of time units, far more than 30
    no-load revolutions), not a fixed count that would call the crank held back."""
    s = crankgen.steady_state(crank=crankgen.Motor(stall_torque=0.0022, no_load_speed=6.0, inertia=0.3), n_elements=2)
    assert s.status in ("periodic", "unstable"), s.message
    assert s.periods > 30 and 0.5 < s.mean_speed < 6.0


def test_the_orbit_figure_draws_the_crank_speed_of_a_driven_crank(steady):
    """A motor's steady motion: the orbit figure's torque panel carries the crank speed on a
    right-hand axis, the state's own samples against the crank angle in degrees."""
    import matplotlib.pyplot as plt

    from crankgen.plots.figures import orbit_figure
    fig = orbit_figure(steady)
    speed_axes = [ax for ax in fig.axes if ax.get_ylabel() == "crank speed Omega*"]
    assert len(speed_axes) == 1
    x, y = speed_axes[0].lines[0].get_data()
    np.testing.assert_array_equal(y, steady.crank_speed)
    np.testing.assert_allclose(x, np.degrees(steady.theta))
    assert np.ptp(y) > 0                                      # the speed fluctuates
    plt.close(fig)


def test_a_sweep_takes_motor_driven_cases_beside_prescribed_ones(steady):
    """crankgen.sweep of a motor-driven case gives its steady_state's motion (the same revolution
    time, amplitude and multiplier) with the motor's columns; a prescribed case in the same sweep
    has its own steady state and leaves the motor's columns empty."""
    prescribed = crankgen.Case(omega=0.6, n_elements=4)
    table = crankgen.sweep([steady.case, prescribed])
    motor_row, other_row = table.rows
    assert motor_row["status"] == "periodic"
    assert motor_row["revolution_time"] == pytest.approx(steady.period, rel=1e-9)
    assert motor_row["amplitude"] == pytest.approx(steady.amplitude, rel=1e-9)
    assert motor_row["multiplier"] == pytest.approx(steady.multiplier, rel=1e-6)
    alone = crankgen.steady_state(case=prescribed)
    assert other_row["amplitude"] == pytest.approx(alone.amplitude, rel=1e-12)
    assert other_row.get("revolution_time") is None and other_row.get("mean_speed") is None


def test_a_poincare_sweep_of_a_motor_finds_the_steady_motion(steady):
    """crankgen.poincare of a motor-driven crank (its section map, from the run-up from rest): at
    the steady state's no-load speed the sweep settles on a period-1 motion of the same amplitude
    (measured 2e-5 apart: the sweep's transient revolutions against shooting to 1e-8)."""
    d = crankgen.poincare(crank=crankgen.Motor(**MOTOR), parameter="no_load_speed",
                          values=[0.7, MOTOR["no_load_speed"]], n_elements=4, direction="up")
    assert [p.classification for p in d.points] == ["period-1", "period-1"]
    assert d.points[-1].amplitude == pytest.approx(steady.amplitude, rel=1e-4)
    assert d.points[0].amplitude < 0.8 * d.points[-1].amplitude         # a slower motor, a smaller response


def test_a_steady_motor_motion_gives_what_sizes_the_motor():
    """The peak and RMS motor torque and the mean power of a steady revolution (SteadyState.motor_duty,
    the steady.csv columns): the motor's torque along the orbit is the crank's equation's,
    J thetadd + T_load + T_rod (the output torque), and the time means are the trapezoidal rule's
    of the law written here; the motor's mean power exceeds the load's by what the rod dissipates."""
    stall, no_load, J, load = 0.05, 0.8, 0.05, 0.002
    st = crankgen.steady_state(crank=crankgen.Motor(stall_torque=stall, no_load_speed=no_load, inertia=J,
                                                    load_torque=load), n_elements=4)
    assert st.ok
    w, wdot, t = st.crank[:, 1], st.crank[:, 2], st.t
    law = stall * (1 - w / no_load)
    balance = J * wdot + load + np.asarray(st.quantity("torque"))
    assert np.max(np.abs(law - balance)) < 1e-7 * np.max(np.abs(law))
    duty = st.motor_duty

    def mean(f):
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)) / (t[-1] - t[0]))
    assert duty["peak_motor_torque"] == pytest.approx(law[np.argmax(np.abs(law))], rel=1e-12)
    assert duty["rms_motor_torque"] == pytest.approx(np.sqrt(mean(law ** 2)), rel=1e-12)
    assert duty["mean_motor_power"] == pytest.approx(mean(law * w), rel=1e-12)
    assert load * st.mean_speed < duty["mean_motor_power"] < 1.5 * load * st.mean_speed
    row = st.row()
    assert all(row[k] == v for k, v in duty.items())
