"""The rigid crank's own mass, centre of mass and moment of inertia (crank_mass, crank_centre,
crank_inertia): under a prescribed crank they change the driving torque and the main bearing's force
only; a motor turns them (its equation reads the torque the crank's load demands).

Independent truths:
- a rigid body turning about a fixed axis O: the torque that turns it is J_O thetadd, J_O = J_G +
  m (k a)^2, and its weight's moment about O is that of m g at G = k a e_r; its bearing force is
  m a_G - m g plus the force the rod's pin takes from it (Newton's second law for the crank), with
  thetadd and a_G by central differences along the run (not from crankgen's kernels);
- a motor-driven crank's energy: (J + J_O) thetad^2 / 2 - m g . G changes by the work of the motor,
  the load and the rod's pin force (its torque a (e_r x F_pin) from the output crank_on_rod), to the
  trapezoidal rule's second order.
"""

import numpy as np
import pytest

import crankgen

CRANK = dict(crank_mass=4.0, crank_centre=0.7, crank_inertia=0.01)     # a heavy crank (the rod: 1)
GRAVITY = (0.003, -0.01)                 # the rod sags about 0.01 L


def _J_O(a, m, k, J):
    return J + m * (k * a) ** 2


def _central(t, y, order=1):
    """Central differences of y(t) at the interior samples (uniform steps)."""
    h = t[1] - t[0]
    if order == 1:
        return (y[2:] - y[:-2]) / (2 * h)
    return (y[2:] - 2 * y[1:-1] + y[:-2]) / h**2


@pytest.fixture(scope="module")
def run_up():
    """A slider-crank under gravity accelerating (a run-up), with and without the crank's mass."""
    kw = dict(crank=crankgen.RunUp(start=0.2, stop=0.5, revolutions=0.5), n_elements=2, steps_per_rev=400,
              revolutions=0.8)
    plain = crankgen.simulate(crankgen.Mechanism(gravity=GRAVITY), **kw)
    heavy = crankgen.simulate(crankgen.Mechanism(gravity=GRAVITY, **CRANK), **kw)
    return plain, heavy


def test_a_prescribed_crank_s_mass_leaves_the_rod_s_motion_alone(run_up):
    plain, heavy = run_up
    for name in ("v_mid", "u_end", "crank_on_rod_x", "crank_on_rod_y", "slider_position"):
        assert np.array_equal(plain.quantity(name), heavy.quantity(name)), name
    # with no crank mass the main bearing carries the pin's force, bit for bit
    assert np.array_equal(plain.ground_on_crank_x, plain.crank_on_rod_x)
    assert np.array_equal(plain.ground_on_crank_y, plain.crank_on_rod_y)


def test_the_driving_torque_turns_the_crank_and_holds_its_weight(run_up):
    """torque(heavy) - torque(plain) = J_O thetadd + m k a (gX sin theta - gY cos theta), thetadd by
    central differences of the crank speed; the crank accelerates, so both terms take part."""
    plain, heavy = run_up
    a, m, k, J = 0.1, CRANK["crank_mass"], CRANK["crank_centre"], CRANK["crank_inertia"]
    t, theta = heavy.t, heavy.theta
    thetadd = _central(t, heavy.crank_speed)
    gX, gY = GRAVITY
    weight = m * k * a * (gX * np.sin(theta) - gY * np.cos(theta))
    expected = _J_O(a, m, k, J) * thetadd + weight[1:-1]
    measured = (heavy.torque - plain.torque)[1:-1]
    assert np.max(np.abs(_J_O(a, m, k, J) * thetadd)) > 0.3 * np.max(np.abs(weight))
    assert np.max(np.abs(measured - expected)) < 1e-4 * np.max(np.abs(expected))


def test_the_main_bearing_carries_the_crank_s_inertia_and_weight(run_up):
    """ground_on_crank = m a_G - m g + crank_on_rod, a_G by second central differences of the crank's
    centre of mass k a (cos theta, sin theta) along the run."""
    _, heavy = run_up
    a, m, k = 0.1, CRANK["crank_mass"], CRANK["crank_centre"]
    t, theta = heavy.t, heavy.theta
    for axis, (centre, g, on_rod, ground) in enumerate((
            (k * a * np.cos(theta), GRAVITY[0], heavy.crank_on_rod_x, heavy.ground_on_crank_x),
            (k * a * np.sin(theta), GRAVITY[1], heavy.crank_on_rod_y, heavy.ground_on_crank_y))):
        expected = m * (_central(t, centre, 2) - g) + on_rod[1:-1]
        own = m * (_central(t, centre, 2) - g)
        assert np.max(np.abs(own)) > 1e-3 * np.max(np.abs(on_rod))          # the crank's part shows
        assert np.max(np.abs(ground[1:-1] - expected)) < 1e-4 * np.max(np.abs(own)), axis


def _motor(mech, inertia=0.05, spr=100):
    return crankgen.simulate(mech, crank=crankgen.Motor(stall_torque=0.05, no_load_speed=0.9, inertia=inertia,
                                                        load_torque=0.005),
                             n_elements=2, steps_per_rev=spr, revolutions=1, rho_inf=1.0)


def test_a_motor_turns_the_crank_s_inertia_as_its_own():
    """Without gravity, the crank's J_O = J_G + m (k a)^2 is the same as as much more motor inertia."""
    m, k, J = CRANK["crank_mass"], CRANK["crank_centre"], CRANK["crank_inertia"]
    heavy = _motor(crankgen.Mechanism(**CRANK))
    lumped = _motor(crankgen.Mechanism(), inertia=0.05 + _J_O(0.1, m, k, J))
    plain = _motor(crankgen.Mechanism())
    for name in ("crank_speed", "v_mid", "crank_on_rod_x"):
        x, y = heavy.quantity(name), lumped.quantity(name)
        assert np.max(np.abs(x - y)) <= 1e-9 * np.max(np.abs(y)), name
    assert np.max(np.abs(heavy.crank_speed - plain.crank_speed)) > 1e-3 * np.max(plain.crank_speed)


def test_a_motor_driven_unbalanced_crank_s_energy_balance():
    """(J + J_O) thetad^2 / 2 - m g . G changes by the work of the motor, the load and the rod's pin
    force (its torque a (e_r x F_pin) from crank_on_rod): second order in the step."""
    a, m, k, J = 0.1, CRANK["crank_mass"], CRANK["crank_centre"], CRANK["crank_inertia"]
    gX, gY = GRAVITY
    defects = []
    for spr in (100, 200):
        r = _motor(crankgen.Mechanism(gravity=(gX, gY), **CRANK), spr=spr)
        w, theta = r.crank_speed, r.theta
        pin = a * (np.cos(theta) * r.crank_on_rod_y - np.sin(theta) * r.crank_on_rod_x)
        power = (0.05 * (1 - w / 0.9) - 0.005 - pin) * w
        work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(r.t))])
        energy = 0.5 * (0.05 + _J_O(a, m, k, J)) * w**2 - m * k * a * (gX * np.cos(theta) + gY * np.sin(theta))
        weight = m * k * a * np.hypot(gX, gY)
        assert weight > 0.05 * 0.05          # the weight's moment against the stall torque
        defects.append(np.max(np.abs(work - (energy - energy[0]))) / np.max(np.abs(energy - energy[0])))
    assert defects[0] < 5e-3 and 3.0 < defects[0] / defects[1] < 5.0, defects


def test_the_peak_loads_name_the_main_bearing_of_a_heavy_crank(run_up):
    plain, heavy = run_up
    names = [load.name for load in crankgen.peak_loads(heavy)]
    bearing = next(load for load in crankgen.peak_loads(heavy) if load.name.startswith("main bearing"))
    assert bearing.value == pytest.approx(np.max(np.hypot(heavy.ground_on_crank_x, heavy.ground_on_crank_y)))
    assert "pin force at A (crank on rod)" in names
    assert not any(load.name.startswith("main bearing") for load in crankgen.peak_loads(plain))


def test_the_command_line_takes_the_crank_s_mass(tmp_path, capsys):
    from crankgen.cli.main import main
    assert main(["simulate", "--crank-mass", "2", "--crank-inertia", "0.01", "--gravity", "0,-0.01", "--elements",
                 "2", "--revolutions", "0.2", "--out", str(tmp_path / "run"), "--quiet"]) == 0
    header = (tmp_path / "run" / "simulation.csv").read_text().splitlines()[0]
    assert "ground_on_crank_x" in header
    assert main(["simulate", "--crank-mass", "-1", "--elements", "2", "--revolutions", "0.2",
                 "--out", str(tmp_path / "bad"), "--quiet"]) != 0
    assert "crank_mass" in capsys.readouterr().err and not (tmp_path / "bad").exists()
