"""Every CSV crankgen writes parses with pandas.read_csv into numbers, words and empty fields under
a header; units are in the column names (theta_deg, u0_L, psi0_rad); responses carry the theory
flags (crankgen.analyses.theory).  The reproduce tables are checked in test_reproduce.py."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.analyses import theory
from crankgen.cli import main
from helpers import check_csv

TINY = ["--elements", "2", "--steps-per-rev", "20", "--quiet"]


def test_simulate_writes_units_a_time_column_and_the_theory_flags(tmp_path):
    out = tmp_path / "s"
    assert main(["simulate", "--revolutions", "1", "--nodes", "--out", str(out), *TINY]) == 0
    sim = check_csv(out / "simulation.csv")
    # every column named with its unit (crankgen's units: r = eps L, L, omega_b, rho A)
    step_outputs = {"crank_speed": "crank_speed_omega_b", "slider_position": "slider_position_L",
                    "end_height": "end_height_L", "chord_angle": "chord_angle_rad",
                    "chord_rate": "chord_rate_omega_b", "chord_elongation": "chord_elongation_L",
                    "slider_velocity": "slider_velocity_L_omega_b", "torque": "torque_rhoA_L3_omega_b2",
                    "crank_on_rod_x": "crank_on_rod_x_rhoA_L2_omega_b2",
                    "crank_on_rod_y": "crank_on_rod_y_rhoA_L2_omega_b2",
                    "rod_on_slider_x": "rod_on_slider_x_rhoA_L2_omega_b2",
                    "rod_on_slider_y": "rod_on_slider_y_rhoA_L2_omega_b2",
                    "guide_on_slider_x": "guide_on_slider_x_rhoA_L2_omega_b2",
                    "guide_on_slider_y": "guide_on_slider_y_rhoA_L2_omega_b2",
                    "ground_on_crank_x": "ground_on_crank_x_rhoA_L2_omega_b2",
                    "ground_on_crank_y": "ground_on_crank_y_rhoA_L2_omega_b2"}
    reductions = {"kinetic_energy": "kinetic_energy_rhoA_L3_omega_b2",     # the rod's energies, per step
                  "strain_energy": "strain_energy_rhoA_L3_omega_b2"}
    fields = {"axial_force": "axial_force_at_0.5_EI_per_L2", "bending_moment": "bending_moment_at_0.5_EI_per_L",
              "chord_deflection": "chord_deflection_at_0.5_L"}
    joints = [f"{j}_{q}" for j in ("crank_on_rod", "rod_on_slider", "guide_on_slider", "ground_on_crank")  # bearings
              for q in ("magnitude_rhoA_L2_omega_b2", "angle_deg")]
    along = [f"axial_force_at_{x:g}_EI_per_L2" for x in (0, 1)]     # at every node (2 elements; 1/2 above)
    assert list(sim.columns) == (["t_per_omega_b", "theta_deg", "v_mid_r", "u_end_r2_per_L", "extension"]
                                 + list(step_outputs.values()) + list(reductions.values()) + joints
                                 + list(fields.values()) + along
                                 + ["deflection_over_L", "axial_strain", "beyond_theory", "status"])
    ref = crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20, revolutions=1,
                            formulation="lagrange", damping="kelvin-voigt", membrane="averaged")
    np.testing.assert_allclose(sim["theta_deg"], np.degrees(ref.theta), rtol=1e-15)
    for name, col in {**step_outputs, **reductions}.items():    # the declared outputs of the same run, per step
        np.testing.assert_allclose(sim[col], getattr(ref, name), rtol=1e-14, atol=1e-15, err_msg=name)
    for name, col in fields.items():              # the fields at mid-span
        np.testing.assert_allclose(sim[col], getattr(ref, name)(0.5), rtol=1e-14, atol=1e-15, err_msg=name)
    for x, col in zip((0, 1), along):             # the axial force along the rod
        np.testing.assert_allclose(sim[col], ref.axial_force(x), rtol=1e-14, atol=1e-15, err_msg=col)
    np.testing.assert_allclose(sim["deflection_over_L"], 0.01 * np.abs(ref.v_mid), rtol=1e-15)
    nodes = check_csv(out / "nodes.csv")
    assert list(nodes.columns[:5]) == ["t_per_omega_b", "theta_deg", "u0_L", "v0_L", "psi0_rad"]
    assert list(nodes.columns[-9:-6]) == ["u2_L", "v2_L", "psi2_rad"] and len(nodes) == len(sim)
    assert list(nodes.columns[-6:]) == ["X0_L", "Y0_L", "X1_L", "Y1_L", "X2_L", "Y2_L"]   # inertial
    np.testing.assert_allclose(nodes["t_per_omega_b"], sim["t_per_omega_b"])


def test_a_four_bar_writes_its_rocker_and_a_run_up_is_drawn_against_the_crank_speed(tmp_path):
    out = tmp_path / "fb"
    assert main(["simulate", "--guide", "circle", "--crank", "runup", "--omega0", "0.2", "--ramp", "1",
                 "--revolutions", "1", "--out", str(out), *TINY]) == 0
    sim = check_csv(out / "simulation.csv")
    assert {"rocker_angle_rad", "transmission_angle_rad", "torque_rhoA_L3_omega_b2"} <= set(sim.columns)
    # the run-up's crank speed rises from Omega0 = 0.2 to Omega* = 0.8 over the ramp
    assert sim["crank_speed_omega_b"].iloc[0] == pytest.approx(0.2)
    assert sim["crank_speed_omega_b"].iloc[-1] == pytest.approx(0.8)
    assert (out / "v_mid.png").stat().st_size > 0


def test_the_axial_strain_of_one_averaged_element_is_the_extension(tmp_path):
    """With one element and the averaged membrane strain (the consistent model), the rod's axial
    strain is one number per step, the mean strain: the extension delta* of eq. (40)."""
    out = tmp_path / "one"
    assert main(["simulate", "--revolutions", "1", "--elements", "1", "--steps-per-rev", "20",
                 "--eps", "0.1", "--out", str(out), "--quiet"]) == 0
    sim = check_csv(out / "simulation.csv")
    np.testing.assert_allclose(sim["axial_strain"], sim["extension"].abs(), rtol=1e-9, atol=1e-15)
    assert sim["axial_strain"].max() > 1e-4


def test_a_failed_simulation_keeps_numbers_and_says_ill_posed(tmp_path):
    out = tmp_path / "b"
    rc = main(["simulate", "--approach", "B", "--elements", "4", "--revolutions", "3",
               "--out", str(out), "--quiet"])
    assert rc == 1
    sim = check_csv(out / "simulation.csv")
    last = sim.iloc[-1]
    assert last["status"].startswith("failed: ") and "unbounded below" in last["status"]
    assert "ill-posed" in last["status"] and "not an instability" in last["status"]
    assert math.isnan(last["v_mid_r"]) and sim["status"].iloc[:-1].eq("ok").all()


def test_steady_csv_is_flat_and_flags_large_strain(tmp_path, capsys):
    """`steady --omega 0.8 --eps 0.1` (the issue's case): |v|/L about 0.15 and an axial strain of
    about 0.13 (delta* up to 0.13) are both beyond the theory, and said so."""
    out = tmp_path / "st"
    assert main(["steady", "--omega", "0.8", "--eps", "0.1", "--elements", "4", "--out", str(out),
                 "--quiet"]) == 0
    printed = capsys.readouterr().out
    row = check_csv(out / "steady.csv").iloc[0]
    assert "gravity" not in row and row["gravity_x"] == 0.0 and row["gravity_y"] == 0.0
    assert "groups_off" not in row
    assert row["status"] == "periodic" and row["beyond_theory"] == "yes"
    orbit = check_csv(out / "orbit.csv")
    assert orbit["theta_deg"].iloc[-1] == pytest.approx(360.0)
    assert row["axial_strain"] == pytest.approx(orbit["axial_strain"].max())
    assert row["axial_strain"] > theory.STRAIN_LIMIT
    # the mean axial strain delta* bounds the largest one from below
    assert row["axial_strain"] >= orbit["extension"].abs().max() * (1 - 1e-9)
    assert row["deflection_over_L"] == pytest.approx(0.1 * row["amplitude"])
    assert "BEYOND THE THEORY" in printed and "axial strain" in printed


def test_steady_with_one_pass_says_it_marches(tmp_path, capsys):
    assert main(["steady", "--integrator", "one-pass", "--out", str(tmp_path / "o"), *TINY[:4]]) == 0
    err = capsys.readouterr().err
    assert "marching revolution by revolution" in err and "shooting needs --integrator newton" in err
    assert "shooting (" not in err


def test_sweep_csv_is_flat(tmp_path):
    out = tmp_path / "sw"
    assert main(["sweep", "--omega", "0.4,0.8", "--out", str(out), *TINY]) == 0
    table = check_csv(out / "sweep.csv")
    assert {"gravity_x", "gravity_y"} <= set(table.columns)
    assert "gravity" not in table.columns and "groups_off" not in table.columns


def test_continuation_and_poincare_csv(tmp_path):
    out = tmp_path / "c"
    assert main(["poincare", "--from", "0.5", "--to", "0.6", "--values", "2", "--transient", "3",
                 "--samples", "4", "--with-continuation", "--max-period", "1", "--direction", "up",
                 "--out", str(out), *TINY]) == 0
    summary = check_csv(out / "poincare_summary.csv")
    assert summary["lyapunov"].isna().any() or summary["classification"].ne("period-1").all()
    check_csv(out / "poincare_samples.csv")
    branches = check_csv(out / "branches.csv")
    np.testing.assert_allclose(branches["deflection_over_L"], 0.01 * branches["amplitude"])
    assert set(branches["beyond_theory"]) <= {"yes", "no"}
    check_csv(out / "special_points.csv")
    check_csv(out / "multipliers.csv")


def test_the_python_api_writers(tmp_path):
    res = crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20, revolutions=1)
    res.to_csv(tmp_path / "run.csv")
    run = check_csv(tmp_path / "run.csv")
    np.testing.assert_allclose(run["theta_deg"], np.degrees(res.theta))


def test_every_csv_of_the_si_commands_parses_into_numbers(tmp_path):
    """steady, sweep, continue and poincare with --si, and the Python API's to_csv of a result and
    of its SI view: every file crankgen writes parses into numbers, words and empty fields."""
    import json
    path = tmp_path / "rod.json"
    path.write_text(json.dumps({"L": 0.3, "a": 0.03, "E": 2e11, "rho": 7870, "A": 6.4e-5, "I": 3.41e-10,
                                "slider_mass": 0.0756, "crank_speed": 900, "damping": 2e-4,
                                "gravity": [0, -9.81]}))
    si = ["--si", str(path), *TINY]
    assert main(["steady", *si, "--out", str(tmp_path / "st")]) == 0
    assert main(["sweep", *si, "--omega", "600,900", "--out", str(tmp_path / "sw")]) == 0
    assert main(["continue", *si, "--from", "600", "--to", "900", "--max-period", "1",
                 "--out", str(tmp_path / "c")]) == 0
    assert main(["poincare", *si, "--from", "600", "--to", "900", "--values", "2", "--transient", "2",
                 "--samples", "2", "--with-continuation", "--max-period", "1", "--direction", "up",
                 "--out", str(tmp_path / "p")]) == 0
    st = crankgen.steady_state(crankgen.Mechanism(), omega=0.5, n_elements=2, steps_per_rev=20)
    st.to_csv(tmp_path / "st" / "api.csv")
    rod = crankgen.SIMechanism(L=0.3, a=0.03, E=2e11, rho=7870, A=6.4e-5, I=6.4e-5 * 0.003 ** 2, slider_mass=1,
                               crank_speed=1)                    # eps = sqrt(I/A)/L = 0.01, the case's
    st.si_view(rod).to_csv(tmp_path / "st" / "api_si.csv")
    files = sorted(tmp_path.rglob("*.csv"))
    assert len(files) == 16                  # 4 steady, 2 sweep, 4 continue, 6 poincare
    for f in files:
        check_csv(f)
    branches = check_csv(tmp_path / "c" / "branches.csv")
    assert branches["crank_speed_rad_per_s"].iloc[0] == pytest.approx(600.0)
    assert check_csv(tmp_path / "p" / "poincare_samples.csv").columns[-1] == "value_m"
