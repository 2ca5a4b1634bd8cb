"""SI everywhere (issue 28 item 1): a mechanism given in SI with every parameter (gravity in m/s^2, a
four-bar's rocker and pivot in m, a run-up's speeds in rad/s and ramp in revolutions, the damping
in s), run by every analysis, converted back, equals the run of its dimensionless twin, built here
from the SI numbers by the definitions of crankgen's units (omega_b = (pi/L)^2 sqrt(EI/(rho A)),
lengths over L, masses over rho A L, times times omega_b), not by crankgen's conversion."""

import dataclasses
import json
import math

import numpy as np
import pytest

import crankgen
from crankgen.cli import main
from helpers import check_csv

# an aluminium coupler 20 mm x 5 mm, 0.5 m long
L, E, RHO, B, H = 0.5, 7.0e10, 2700.0, 0.020, 0.005
AREA, INERTIA = B * H, B * H ** 3 / 12
OMEGA_B = (math.pi / L) ** 2 * math.sqrt(E * INERTIA / (RHO * AREA))        # rad/s
MASS = RHO * AREA * L                                                        # rho A L, kg
ROD = dict(L=L, E=E, rho=RHO, A=AREA, I=INERTIA)


def _four_bar_si():
    return crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, damping=3e-4, gravity=(0.0, -9.81),
                                guide="circle", c=0.4, d=0.5, offset=0.02, branch=-1,
                                motion="runup", omega0=0.2 * OMEGA_B, crank_speed=0.6 * OMEGA_B, ramp=2.0,
                                theta0=0.3)


def _four_bar_scaled():
    mech = crankgen.Mechanism(a=0.1 / L, eps=math.sqrt(INERTIA / AREA) / L, ms=0.05 / MASS, mu=3e-4 * OMEGA_B,
                              gravity=(0.0, -9.81 / (L * OMEGA_B ** 2)),
                              guide=crankgen.Circle(center=(0.5 / L, 0.02 / L), radius=0.4 / L, branch=-1))
    return mech, crankgen.RunUp(start=0.2, stop=0.6, revolutions=2.0, theta0=0.3)


SETTINGS = dict(n_elements=4, steps_per_rev=60, revolutions=3)


@pytest.fixture(scope="module")
def four_bar_runs():
    si = crankgen.simulate(_four_bar_si(), units="si", **SETTINGS)
    mech, crank = _four_bar_scaled()
    return si, crankgen.simulate(mech, crank=crank, **SETTINGS)


def test_a_four_bar_with_gravity_and_a_run_up_in_si_is_its_dimensionless_twin(four_bar_runs):
    si, scaled = four_bar_runs
    assert si.case == scaled.case
    np.testing.assert_array_equal(si.states, scaled.states)           # the same run, bit for bit
    view = si.si
    np.testing.assert_allclose(view.t, scaled.t / OMEGA_B, rtol=1e-14)
    np.testing.assert_allclose(view.crank_speed[[0, -1]], [0.2 * OMEGA_B, 0.6 * OMEGA_B], rtol=1e-12)
    force, torque = MASS * L * OMEGA_B ** 2, MASS * L ** 2 * OMEGA_B ** 2       # rho A L^2 omega_b^2, ...
    np.testing.assert_allclose(view.torque, scaled.torque * torque, rtol=1e-12)
    np.testing.assert_allclose(view.rocker_on_tip_y, scaled.rocker_on_tip_y * force, rtol=1e-12)
    np.testing.assert_allclose(view.slider_position, scaled.slider_position * L, rtol=1e-12)
    np.testing.assert_allclose(view.rocker_angle, scaled.rocker_angle, rtol=1e-12)
    # the rocker tip stays on its circle of c = 0.4 m about D = (0.5 m, 0.02 m), in metres
    np.testing.assert_allclose(np.hypot(view.slider_position - 0.5, view.end_height - 0.02), 0.4, rtol=1e-9)


def test_the_si_mechanism_comes_back_from_its_case(four_bar_runs):
    """The case of the SI run, converted back to SI on the same rod, is the SIMechanism given
    (every field, the run-up's ramp and the start angle included), and its .mechanism and .crank are the
    dimensionless mechanism and the run-up's record."""
    si, _ = four_bar_runs
    given = _four_bar_si()
    back = crankgen.SIMechanism.of_case(given, si.case)
    for name, value in given.si_values().items():
        got = getattr(back, name)
        assert (got == pytest.approx(value, rel=1e-12)) if not isinstance(value, str) else got == value, name
    rebuilt = crankgen.SIMechanism(**ROD, **given.si_values())
    mech, crank = rebuilt.mechanism, rebuilt.crank
    twin, twin_crank = _four_bar_scaled()
    assert mech.c == pytest.approx(twin.c, rel=1e-14) and mech.gravity[1] == pytest.approx(twin.gravity[1], rel=1e-12)
    assert type(crank) is crankgen.RunUp
    assert crank.values["omega0"] == pytest.approx(0.2) and crank.values["ramp"] == 2.0


def test_each_field_is_checked_in_si_and_named():
    with pytest.raises(crankgen.ParameterError, match=r"missing c \(m"):
        crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=100.0, guide="circle", d=0.5)
    with pytest.raises(crankgen.ParameterError, match=r"missing omega0 \(rad/s"):
        crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=100.0, motion="runup")
    with pytest.raises(crankgen.ParameterError, match=r"a = 0.6 m is 1.2 in crankgen's units"):
        crankgen.SIMechanism(**ROD, a=0.6, slider_mass=0.05, crank_speed=100.0)
    with pytest.raises(crankgen.ParameterError, match="gravity"):
        crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=100.0, gravity=9.81)
    si = crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=100.0)
    assert si.mechanism.mu == 0.0 and si.mechanism.gravity == (0.0, 0.0)     # undamped unless given
    with pytest.raises(crankgen.ParameterError, match="crank_speed"):
        crankgen.steady_state(si, omega=0.5, units="si")
    with pytest.raises(crankgen.ParameterError, match="theta0"):
        crankgen.simulate(dataclasses.replace(si, theta0=0.2), units="si", theta0=0.1)


@pytest.fixture(scope="module")
def heavy_slider():
    """A slider-crank in SI with gravity and an offset guide, and its dimensionless twin."""
    si = crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, damping=3e-4, gravity=(2.0, -9.81), offset=0.01,
                              crank_speed=0.5 * OMEGA_B)
    mech = crankgen.Mechanism(a=0.2, eps=math.sqrt(INERTIA / AREA) / L, ms=0.05 / MASS, mu=3e-4 * OMEGA_B,
                              gravity=(2.0 / (L * OMEGA_B ** 2), -9.81 / (L * OMEGA_B ** 2)), offset=0.01 / L)
    return si, mech


def test_a_steady_state_in_si_is_the_scaled_one_with_every_output(heavy_slider, tmp_path):
    si, mech = heavy_slider
    settings = dict(n_elements=4, steps_per_rev=60)
    st = crankgen.steady_state(si, units="si", **settings)
    twin = crankgen.steady_state(mech, omega=0.5, **settings)
    assert st.status == twin.status == "periodic"
    np.testing.assert_allclose(st.states, twin.states, rtol=1e-9, atol=1e-12 * np.abs(twin.states).max())
    force = MASS * L * OMEGA_B ** 2
    np.testing.assert_allclose(st.si.crank_on_rod_x, twin.crank_on_rod_x * force, rtol=1e-8,
                               atol=1e-9 * force * np.abs(twin.crank_on_rod_x).max())
    assert st.si.v_mid.max() == pytest.approx(twin.v_mid.max() * math.sqrt(INERTIA / AREA), rel=1e-8)
    # torque and forces are discoverable, and every declared step output is in its CSV, with units
    assert {"torque", "crank_on_rod_x", "guide_on_slider_y", "axial_force"} <= set(dir(st)) & set(dir(st.si))
    st.si.to_csv(tmp_path / "orbit_si.csv")
    twin.to_csv(tmp_path / "orbit.csv")
    orbit_si, orbit = check_csv(tmp_path / "orbit_si.csv"), check_csv(tmp_path / "orbit.csv")
    np.testing.assert_allclose(orbit_si["torque_N_m"], twin.torque * force * L, rtol=1e-8,
                               atol=1e-9 * force * L * np.abs(twin.torque).max())
    np.testing.assert_allclose(orbit["torque_rhoA_L3_omega_b2"], twin.torque, rtol=1e-15)
    np.testing.assert_allclose(orbit["slider_position_L"], twin.slider_position, rtol=1e-15)
    assert orbit_si["t_s"].iloc[-1] == pytest.approx(2 * math.pi / (0.5 * OMEGA_B), rel=1e-12)
    for table in (orbit, orbit_si):
        assert {"deflection_over_L", "axial_strain", "beyond_theory"} <= set(table.columns)


def test_steady_and_sweep_on_the_command_line_in_si(heavy_slider, tmp_path, capsys):
    si, mech = heavy_slider
    path = tmp_path / "rod.json"
    path.write_text(json.dumps(dict(ROD, **si.si_values())))
    run = ["--elements", "4", "--steps-per-rev", "60", "--quiet"]
    assert main(["steady", "--si", str(path), "--out", str(tmp_path / "st"), *run]) == 0
    row = check_csv(tmp_path / "st" / "steady.csv").iloc[0]
    orbit = check_csv(tmp_path / "st" / "orbit.csv")
    twin = crankgen.steady_state(mech, omega=0.5, n_elements=4, steps_per_rev=60)
    assert row["crank_speed_rad_per_s"] == pytest.approx(0.5 * OMEGA_B) and row["gravity_y_m_per_s2"] == -9.81
    assert row["amplitude_m"] == pytest.approx(twin.amplitude * math.sqrt(INERTIA / AREA), rel=1e-8)
    assert row["peak_torque_N_m"] == pytest.approx(np.abs(orbit["torque_N_m"]).max(), rel=1e-12)
    assert math.isnan(row["c"]) and math.isnan(row["omega0"])           # a slider has no rocker, no run-up
    printed = capsys.readouterr().out                                   # the summary names the peak loads
    assert f"peak loads: torque {row['peak_torque_N_m']:.4g} N m" in printed
    # a sweep of the crank speed given in rad/s: the file's crank speed replaced
    speeds = [0.3 * OMEGA_B, 0.5 * OMEGA_B]
    assert main(["sweep", "--si", str(path), "--omega", ",".join(f"{w!r}" for w in speeds),
                 "--out", str(tmp_path / "sw"), *run]) == 0
    table = check_csv(tmp_path / "sw" / "sweep.csv")
    np.testing.assert_allclose(table["crank_speed_rad_per_s"], speeds, rtol=1e-12)
    np.testing.assert_allclose(table["omega"], [0.3, 0.5], rtol=1e-12)
    assert table["amplitude_m"].iloc[1] == pytest.approx(row["amplitude_m"], rel=1e-8)
    docs = check_csv(tmp_path / "sw" / "sweep_columns.csv")
    assert list(docs["column"]) == list(table.columns)
    units = dict(zip(docs["column"], docs["units"].fillna("")))
    assert units["crank_speed_rad_per_s"] == "rad/s" and units["amplitude_m"] == "m"
    assert units["peak_torque_N_m"] == "N m" and units["omega"] == "omega_b"
    for bad, words in ((["--a", "0.05"], "in the file's SI"), (["--eps", "0.01"], "section")):
        capsys.readouterr()
        assert main(["sweep" if "--eps" in bad else "steady", "--si", str(path), *bad,
                     "--out", str(tmp_path / "x"), *run]) == 2
    assert not (tmp_path / "x").exists()
    # a refused range is named as given, in SI
    capsys.readouterr()
    assert main(["continue", "--si", str(path), "--from", "0", "--to", "100", "--out", str(tmp_path / "x")]) == 2
    assert "got --from 0 --to 100" in capsys.readouterr().err
    assert main(["continue", "--si", str(path), "--parameter", "a", "--from", "0.1", "--to", "0.6",
                 "--out", str(tmp_path / "x")]) == 2
    assert f"(with --si: --from 0.1 --to 0.6 m is {0.1 / L:g} to {0.6 / L:g} in crankgen's units)" in \
        capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_a_continuation_in_si_finds_the_scaled_special_points_in_rad_per_s(tmp_path):
    """The SI mechanism of the README's steel rod with a short crank: its continuation over the
    crank speed in rad/s finds the dimensionless one's folds at Omega* omega_b."""
    steel = crankgen.SIMechanism(L=0.3, a=0.03, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10, slider_mass=0.0756,
                                 crank_speed=1000.0, damping=2e-4)
    omega_b = (math.pi / 0.3) ** 2 * math.sqrt(2e11 * 3.41e-10 / (7870 * 6.4e-5))
    run = dict(n_elements=2, steps_per_rev=40, max_period=1)
    d = crankgen.continuation(steel, "omega", 600.0, 1300.0, units="si", **run)
    twin = crankgen.continuation(steel.mechanism, "omega", 600.0 / omega_b, 1300.0 / omega_b, **run)
    got = [(s.kind, s.parameter) for s in d.si.special_points]
    assert [k for k, _ in got] == [s.kind for s in twin.special_points] and got
    np.testing.assert_allclose([p for _, p in got], [s.parameter * omega_b for s in twin.special_points],
                               rtol=1e-9)
    d.si.to_csv(tmp_path)
    branches = check_csv(tmp_path / "branches.csv")
    assert {"crank_speed_rad_per_s", "amplitude_m"} <= set(branches.columns)
    assert branches["crank_speed_rad_per_s"].iloc[0] == pytest.approx(600.0)
    assert branches["stop_reason"].iloc[-1].startswith("reached crank_speed = 1300 rad/s")
    # every branch point's quantities in SI: torque, forces, deflection, stress (a section given)
    rhoA, r = 7870 * 6.4e-5, math.sqrt(3.41e-10 / 6.4e-5)
    q = {k: np.concatenate([b.quantities[k] for b in d.branches]) for k in d.branches[0].quantities}
    np.testing.assert_allclose(branches["peak_torque_N_m"], q["peak_torque"] * rhoA * 0.3 ** 3 * omega_b ** 2,
                               rtol=1e-12)
    np.testing.assert_allclose(branches["peak_pin_force_A_N"], q["peak_pin_force_A"] * rhoA * 0.3 ** 2 * omega_b ** 2,
                               rtol=1e-12)
    np.testing.assert_allclose(branches["peak_v_m"], q["peak_v"] * r, rtol=1e-12)
    assert "peak_strain" in branches.columns
    square = crankgen.sections.rectangle(0.008, 0.008)                      # A = 6.4e-5, I = 3.41e-10
    stressed = crankgen.continuation(steel, "omega", 600.0, 700.0, units="si", section=square, **run)
    stressed.si.to_csv(tmp_path / "stressed")
    table = check_csv(tmp_path / "stressed" / "branches.csv")
    np.testing.assert_allclose(table["peak_stress_Pa"],
                               np.concatenate([b.quantities["peak_stress"] for b in stressed.branches]) * 2e11,
                               rtol=1e-12)
    # a branch's origin names the parameter in SI, with the digits it was printed with
    assert d.si.text("period-doubling of branch 0 at omega = 0.9352908; merged at omega = 1.1") == \
        f"period-doubling of branch 0 at crank_speed = {0.9352908 * omega_b:.7g} rad/s; " \
        f"merged at crank_speed = {round(1.1 * omega_b)} rad/s"           # its whole digits, not 1.4e+03
    # a marching sweep in SI: its amplitudes in m, and in mm where it is drawn over the branches
    pc = crankgen.poincare(steel, "omega", [700.0], units="si", transient=2, samples=2, n_elements=2,
                           steps_per_rev=40)
    assert pc.si.points[0].parameter == pytest.approx(700.0)
    assert pc.si.points[0].amplitude == pytest.approx(pc.points[0].amplitude * r, rel=1e-12)
    drawn = pc.si._converted(1e3, {})
    assert drawn.points[0].amplitude == pytest.approx(pc.points[0].amplitude * r * 1e3, rel=1e-12)
    with pytest.raises(crankgen.ParameterError, match="section"):
        crankgen.continuation(steel, "eps", 0.01, 0.02, units="si", **run)


def test_a_guide_declared_later_has_its_si_fields():
    """The inclined guide and the cam were declared after SIMechanism was written: their parameters
    are SI fields by their declared units (the inclination in rad, the cam's height and wavelength
    in m), and a run in SI is its dimensionless twin's."""
    si = crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, damping=3e-4, crank_speed=0.5 * OMEGA_B,
                              guide="incline", inclination=0.3, offset=0.01)
    twin = crankgen.Mechanism(a=0.2, eps=math.sqrt(INERTIA / AREA) / L, ms=0.05 / MASS, mu=3e-4 * OMEGA_B,
                              guide="incline", inclination=0.3, offset=0.01 / L)
    settings = dict(n_elements=2, steps_per_rev=20, revolutions=0.5)
    run, ref = crankgen.simulate(si, units="si", **settings), crankgen.simulate(twin, omega=0.5, **settings)
    np.testing.assert_array_equal(run.states, ref.states)
    np.testing.assert_allclose(run.si.torque, ref.torque * MASS * L ** 2 * OMEGA_B ** 2, rtol=1e-12)
    cam = crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=100.0, guide="cam", cam_height=0.005,
                               cam_wavelength=0.2)
    assert cam.mechanism.cam_height == pytest.approx(0.005 / L) and cam.mechanism.cam_wavelength == pytest.approx(0.2 / L)
    with pytest.raises(crankgen.ParameterError, match=r"missing cam_wavelength \(m"):
        crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=100.0, guide="cam", cam_height=0.005)


def test_a_step_warning_of_an_analysis_in_si_gives_the_mode_in_rad_per_s():
    """steady_state (and so continuation's first point) with units="si": the StepWarning names the
    unresolved mode's frequency in omega_b and in rad/s, the latter omega_b's value in SI times it."""
    import re

    from crankgen.discrete.time_scheme import StepWarning
    si = crankgen.SIMechanism(**ROD, a=0.1, slider_mass=0.05, crank_speed=0.5 * OMEGA_B)
    with pytest.warns(StepWarning) as caught:
        crankgen.steady_state(si, units="si", rho_inf=1.0, n_elements=4, steps_per_rev=60)
    text = str(caught[0].message)
    found = re.search(r"omega = ([0-9.e+]+) omega_b = ([0-9.e+]+) rad/s", text)
    assert found, text
    assert float(found[2]) == pytest.approx(float(found[1]) * OMEGA_B, rel=1e-2)     # 3 digits each


def test_si_unit_names_follow_the_dimensions():
    """The SI name of a declared unit, from its dimensions worked out by hand here: a moment of
    inertia rho A L^3 (kg/m m^3) is kg m^2, a torque rho A L^3 omega_b^2 N m, a force N, a speed
    L omega_b m/s."""
    from crankgen.declaration.units import Scales
    assert Scales.si_name("rhoA L^3") == "kg m^2"
    assert Scales.si_name("rhoA L^3 omega_b^2") == "N m"
    assert Scales.si_name("rhoA L^2 omega_b^2") == "N"
    assert Scales.si_name("L omega_b") == "m/s"
