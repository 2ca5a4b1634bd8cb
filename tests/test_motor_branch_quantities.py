"""The physical quantities of a motor-driven crank's continuation branches (bifurcation/quantities.py)
against a simulation started on a branch point's state over one revolution (the same steps, its
declared outputs computed here), against the motor's law, and in the SI files."""

import csv
import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

import crankgen
from crankgen.analyses.bifurcation import BifurcationDiagram
from crankgen.analyses.bifurcation.mechanism import AutonomousMap as MotorMap
from crankgen.analyses.bifurcation.quantities import motor_orbit, motor_orbit_quantities
from crankgen.analyses.section import CrankSection
from crankgen.notices import BeyondTheoryWarning

MOTOR = dict(stall_torque=0.05, inertia=0.05, load_torque=0.002)
# Newmark (rho_inf = 1): a branch point's state (d, v, thetad) is all a simulation needs to march
# the same steps (generalized-alpha's algorithmic accelerations would restart with its starter)
RUN = dict(n_elements=2, steps_per_rev=40, rho_inf=1.0)
SECTION = crankgen.sections.rectangle(0.01, 0.01)


def _continue(stop=0.8, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondTheoryWarning)
        return crankgen.continuation(parameter="no_load_speed", start=0.7, stop=stop, dp_max=0.05, max_period=1,
                                     crank=crankgen.Motor(no_load_speed=0.7, **MOTOR), **RUN, **options)


@pytest.fixture(scope="module")
def branch():
    lines = []
    d = _continue(section=SECTION, progress=lines.append)
    assert any(line.startswith("branch 0: the physical quantities of its") for line in lines)
    return d, d.branches[0]


def _revolution(br, i):
    """The simulation from point i's state on the section, its steps before the revolution time T
    and the state at T (simulate's landing on a requested time): the revolution's steps."""
    p = float(br.parameter[i])
    case = crankgen.Case(motion="motor", no_load_speed=p, **MOTOR, **RUN)
    X, V, _ = CrankSection(case).full(br.states[i])
    T = float(br.quantities["revolution_time"][i])
    r = crankgen.simulate(case=case, initial=(X[0], V[0]), times=[T], tol=1e-12)
    return r, r.t < T, T


def _integral(f, t):
    """The trapezoidal rule's integral of f at the times t (NumPy 1.24 has no trapezoid)."""
    return sum(0.5 * (f[k] + f[k + 1]) * (t[k + 1] - t[k]) for k in range(len(t) - 1))


def _along(r, inside, name, x=None, **arguments):
    value = r.quantity(name) if x is None else r.quantity(name, x, **arguments)
    end = r.at_times.quantity(name) if x is None else r.at_times.quantity(name, x, **arguments)
    return np.concatenate([np.asarray(value)[inside], np.asarray(end)])


def test_a_point_has_the_quantities_of_its_simulated_revolution(branch):
    _, br = branch
    i = len(br) // 2
    r, inside, T = _revolution(br, i)
    assert r.at_times.theta[0] == pytest.approx(r.theta[0] + 2 * math.pi, abs=1e-10)   # one revolution
    xs = np.linspace(0.0, 1.0, 5)                 # n = 2: the nodes and the element midpoints
    torque = _along(r, inside, "torque")
    axial = _along(r, inside, "axial_force", xs)
    fibre = math.sqrt(3.0)
    speed = np.concatenate([r.crank[inside, 1], r.at_times.crank[:, 1]])
    t = np.append(r.t[inside], T)
    motor = MOTOR["stall_torque"] * (1 - speed / float(br.parameter[i]))         # the linear law
    expected = dict(
        peak_v=np.max(np.abs(_along(r, inside, "v_mid"))),
        peak_torque=torque[np.argmax(np.abs(torque))],
        peak_pin_force_A=np.max(np.hypot(_along(r, inside, "crank_on_rod_x"), _along(r, inside, "crank_on_rod_y"))),
        peak_pin_force_B=np.max(np.hypot(_along(r, inside, "rod_on_slider_x"), _along(r, inside, "rod_on_slider_y"))),
        peak_support_force=np.max(np.hypot(_along(r, inside, "guide_on_slider_x"),
                                           _along(r, inside, "guide_on_slider_y"))),
        peak_axial_force=axial.ravel()[np.argmax(np.abs(axial))],
        peak_strain=max(np.max(np.abs(_along(r, inside, "surface_strain", xs, fiber=f))) for f in (fibre, -fibre)),
        peak_stress=max(abs(crankgen.stress(r, SECTION).largest.value),
                        abs(crankgen.stress(r.at_times, SECTION).largest.value)),
        min_crank_speed=speed.min(), max_crank_speed=speed.max(), mean_speed=2 * math.pi / T,
        rms_motor_torque=math.sqrt(_integral(motor ** 2, t) / T), mean_motor_power=_integral(motor * speed, t) / T)
    for name, value in expected.items():
        got = br.quantities[name][i]
        if name == "peak_stress":
            got = abs(got)
        assert got == pytest.approx(value, rel=1e-10, abs=1e-14), name
    assert br.quantities["min_crank_speed"][i] < br.quantities["mean_speed"][i] < br.quantities["max_crank_speed"][i]


def test_the_peak_motor_torque_is_the_law_at_the_slowest_speed(branch):
    _, br = branch
    law = MOTOR["stall_torque"] * (1 - br.quantities["min_crank_speed"] / br.parameter)    # T_m decreases
    assert np.all(np.isfinite(law)) and np.all(law > 0)
    assert np.max(np.abs(br.quantities["peak_motor_torque"] - law)) < 1e-14
    # the crank's equation along the simulated revolution: T_m = J thetadd + T_load + T_rod (torque)
    i = len(br) // 3
    r, inside, _ = _revolution(br, i)
    speed = np.concatenate([r.crank[inside, 1], r.at_times.crank[:, 1]])
    assert br.quantities["min_crank_speed"][i] == pytest.approx(speed.min(), rel=1e-10)
    balance = (MOTOR["inertia"] * np.concatenate([r.crank[inside, 2], r.at_times.crank[:, 2]])
               + MOTOR["load_torque"] + _along(r, inside, "torque"))
    assert br.quantities["peak_motor_torque"][i] == pytest.approx(balance.max(), rel=1e-10)


def test_two_revolutions_of_a_period_one_orbit_have_its_quantities(branch):
    d, br = branch
    i = len(br) - 1
    p = float(br.parameter[i])
    fmap = MotorMap(crankgen.Case(motion="motor", no_load_speed=p, **MOTOR, **RUN), "no_load_speed")
    one, T1 = motor_orbit(fmap, br.states[i], p, 1)
    two, T2 = motor_orbit(fmap, br.states[i], p, 2)
    assert T2 == pytest.approx(2 * T1, rel=1e-9) and two.t[-1] == pytest.approx(T2, rel=1e-12)
    assert len(two.t) == 2 * len(one.t) - 1 and np.all(np.diff(two.theta) > 0)
    assert two.theta[-1] - two.theta[0] == pytest.approx(4 * math.pi, abs=1e-10)
    a, b = motor_orbit_quantities(one, T1, 1), motor_orbit_quantities(two, T2, 2)
    for name, value in a.items():
        assert b[name] == pytest.approx(value, rel=1e-7), name
        assert br.quantities[name][i] == value, name          # the branch's own, from the same march


def test_a_torque_curve_s_peak_is_the_motor_torque_along_the_orbit(branch):
    # a curve with its peak torque inside (crankgen.torque_curve): one revolution from a branch
    # point's state (not periodic for this motor: the crank's equation holds along any motion)
    from scipy.interpolate import PchipInterpolator
    _, br = branch
    i = len(br) // 2
    p = float(br.parameter[i])
    curve = ((0.0, 1.0), (0.9, 1.5), (1.0, 0.0), (1.1, -1.2))
    fmap = MotorMap(crankgen.Case(motion="motor", no_load_speed=p, torque_curve=curve, **MOTOR, **RUN),
                    "no_load_speed")
    orbit, T = motor_orbit(fmap, br.states[i], p, 1)
    got = motor_orbit_quantities(orbit, T, 1)["peak_motor_torque"]
    balance = MOTOR["inertia"] * orbit.crank[:, 2] + MOTOR["load_torque"] + np.asarray(orbit.torque)
    assert got == pytest.approx(balance[np.argmax(np.abs(balance))], rel=1e-10)
    s = orbit.crank[:, 1] / p                       # inside the table: scipy's PCHIP is the curve
    assert 0.9 < s.min() and s.max() < 1.1
    law = MOTOR["stall_torque"] * PchipInterpolator(*zip(*curve))(s)
    assert got == pytest.approx(law[np.argmax(np.abs(law))], rel=1e-12)
    assert got != pytest.approx(br.quantities["peak_motor_torque"][i], rel=0.05)   # not the linear law's


def test_the_motor_s_work_over_an_undamped_orbit_is_the_load_s():
    # no damping, no gravity: over a periodic revolution the rod's and the crank's energies return,
    # so the motor's work T <T_m thetad> is the load's, 2 pi T_load, but for the work of the rod's
    # moving frame on the rod (README, "A motor instead of a prescribed crank": the elements cannot
    # rotate a deformed rod exactly; measured 2.4e-4 of it at 40 and at 80 steps per revolution: not
    # the trapezoidal rule's error)
    case = crankgen.Case(motion="motor", no_load_speed=0.75, mu=0.0, **MOTOR, **RUN)
    st = crankgen.steady_state(case=case)
    assert st.status == "periodic"
    orbit, T = motor_orbit(MotorMap(case, "no_load_speed"), st.section_state, 0.75, 1)
    q = motor_orbit_quantities(orbit, T, 1)
    assert q["revolution_time"] == pytest.approx(st.period, rel=1e-9)
    assert q["mean_motor_power"] * T == pytest.approx(2 * math.pi * MOTOR["load_torque"], rel=1e-3)
    assert abs(q["peak_motor_torque"]) > q["rms_motor_torque"] > q["mean_motor_power"] / q["max_crank_speed"]


def test_the_files_read_back_and_quantities_false_keeps_the_speeds(branch, tmp_path):
    d, br = branch
    back = BifurcationDiagram.read_csv(d.to_csv(tmp_path / "csv")[0].parent, info=d.info)
    assert set(back.branches[0].quantities) == set(br.quantities)
    for name, value in br.quantities.items():
        assert np.array_equal(back.branches[0].quantities[name], value), name
    assert br.quantity_units["peak_motor_torque"] == "rhoA L^3 omega_b^2"
    assert br.quantity_units["min_crank_speed"] == "omega_b" and br.quantity_units["revolution_time"] == "1/omega_b"
    assert br.quantity_units["mean_motor_power"] == "rhoA L^3 omega_b^3"
    bare = _continue(quantities=False, stop=0.72).branches[0]
    assert set(bare.quantities) == {"mean_speed", "revolution_time"}
    assert bare.quantities["mean_speed"][0] == br.quantities["mean_speed"][0]


def test_the_si_files_have_them_in_si(tmp_path):
    # what `crankgen continue --si FILE --parameter no_load_speed ...` writes (diagram.si.to_csv): a 0.5 m
    # aluminium rod, 20 mm x 5 mm, its motor in SI
    si = crankgen.SIMechanism(L=0.5, E=7.0e10, rho=2700.0, A=1.0e-4, I=0.02 * 0.005 ** 3 / 12, a=0.05,
                              slider_mass=0.0675, damping=0.0017, motion="motor", stall_torque=140.0,
                              no_load_speed=200.0, inertia=0.0017, load_torque=5.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondTheoryWarning)
        d = crankgen.continuation(si, "no_load_speed", 200.0, 205.0, units="si", dp_max=2.0, max_period=1, **RUN)
    with open(d.si.to_csv(tmp_path)[0], newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) >= 3
    for row in rows:
        low, high = float(row["min_crank_speed_rad_per_s"]), float(row["max_crank_speed_rad_per_s"])
        mean, T = float(row["mean_speed_rad_per_s"]), float(row["revolution_time_s"])
        assert low < mean < high < float(row["no_load_speed_rad_per_s"]) and mean * T == pytest.approx(2 * math.pi)
        law = 140.0 * (1 - low / float(row["no_load_speed_rad_per_s"]))            # N m
        assert float(row["peak_motor_torque_N_m"]) == pytest.approx(law, rel=1e-10)
        assert float(row["peak_pin_force_A_N"]) > 0 and float(row["peak_torque_N_m"]) != 0
        # W = N m rad/s: the mean power against the SI rms torque and mean speed's bound
        assert 0 < float(row["mean_motor_power_W"]) < float(row["rms_motor_torque_N_m"]) * high


def test_a_point_of_a_motor_branch_animates_its_orbit(branch):
    """BifurcationDiagram.orbit of a motor-driven point: the run from its section state (its crank
    speed the point's) over its revolution time, to the nearest step: one crank revolution, the
    crank-speed range the point's."""
    d, br = branch
    i = len(br) // 2
    r = d.orbit(0, i)
    T = float(br.quantities["revolution_time"][i])
    dt = r.t[1] - r.t[0]
    assert abs(r.t[-1] - T) <= dt / 2 + 1e-12
    speed = r.crank_speed
    N = (len(br.states[i]) - 1) // 2                 # Newmark's section state (d, v, thetad)
    assert speed[0] == br.states[i][2 * N]
    assert abs(r.theta[-1] - r.theta[0] - 2 * math.pi) <= np.max(speed) * dt / 2 + 1e-9
    assert np.min(speed) == pytest.approx(br.quantities["min_crank_speed"][i], rel=1e-9)
    assert np.max(speed) == pytest.approx(br.quantities["max_crank_speed"][i], rel=1e-3)
