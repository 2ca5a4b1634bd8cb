"""Every CSV crankgen writes parses with pandas.read_csv into numbers, words and empty fields under
a header; units are in the column names (theta_deg, u0_L, psi0_rad); responses carry the theory
flags (crankgen.theory).  The reproduce tables are checked in test_reproduce.py."""

import math

import numpy as np
import pytest

import crankgen
from crankgen import theory
from crankgen.cli import main
from helpers import check_csv

TINY = ["--elements", "2", "--steps-per-rev", "20", "--quiet"]


def test_simulate_writes_units_a_time_column_and_the_theory_flags(tmp_path):
    out = tmp_path / "s"
    assert main(["simulate", "--revolutions", "1", "--nodes", "--out", str(out), *TINY]) == 0
    sim = check_csv(out / "simulation.csv")
    step_outputs = ["crank_speed", "slider_position", "end_height", "chord_angle", "chord_rate",
                    "chord_elongation", "slider_velocity", "torque", "crank_on_rod_x", "crank_on_rod_y",
                    "rod_on_slider_x", "rod_on_slider_y", "guide_on_slider_x", "guide_on_slider_y"]
    reductions = ["kinetic_energy", "strain_energy"]
    assert list(sim.columns) == (["t", "theta_deg", "v_mid", "u_end", "extension"] + step_outputs
                                 + reductions + ["deflection_over_L", "axial_strain", "beyond_theory", "status"])
    ref = crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20, revolutions=1,
                            formulation="lagrange", damping="kelvin-voigt", membrane="averaged")
    np.testing.assert_allclose(sim["theta_deg"], np.degrees(ref.theta), rtol=1e-15)
    for name in step_outputs + reductions:    # the declared outputs of the same run, per step
        np.testing.assert_allclose(sim[name], getattr(ref, name), rtol=1e-14, atol=1e-15, err_msg=name)
    np.testing.assert_allclose(sim["deflection_over_L"], 0.01 * np.abs(ref.v_mid), rtol=1e-15)
    nodes = check_csv(out / "nodes.csv")
    assert list(nodes.columns[:5]) == ["t", "theta_deg", "u0_L", "v0_L", "psi0_rad"]
    assert list(nodes.columns[-9:-6]) == ["u2_L", "v2_L", "psi2_rad"] and len(nodes) == len(sim)
    assert list(nodes.columns[-6:]) == ["X0_L", "Y0_L", "X1_L", "Y1_L", "X2_L", "Y2_L"]   # inertial
    np.testing.assert_allclose(nodes["t"], sim["t"])


def test_a_four_bar_writes_its_rocker_and_a_run_up_is_drawn_against_the_crank_speed(tmp_path):
    out = tmp_path / "fb"
    assert main(["simulate", "--guide", "circle", "--crank", "runup", "--omega0", "0.2", "--ramp", "1",
                 "--revolutions", "1", "--out", str(out), *TINY]) == 0
    sim = check_csv(out / "simulation.csv")
    assert {"rocker_angle", "transmission_angle", "torque"} <= set(sim.columns)
    # the run-up's crank speed rises from Omega0 = 0.2 to Omega* = 0.8 over the ramp
    assert sim["crank_speed"].iloc[0] == pytest.approx(0.2) and sim["crank_speed"].iloc[-1] == pytest.approx(0.8)
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
    assert math.isnan(last["v_mid"]) and sim["status"].iloc[:-1].eq("ok").all()


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
