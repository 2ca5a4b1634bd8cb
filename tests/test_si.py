"""SI in and out: simulate(units="si") with a crankgen.SIMechanism, result.si (every declared output
converted by its declared units), SI times and initial states, and `crankgen simulate --si`.

Each SI value is checked against physics computed here from the SI data (E I v'', E A u', the
torque of the pin force about the crank pivot, the slider's rigid position), not against the
conversion table."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

import crankgen
from crankgen.cli import main as cli_main
from crankgen.declaration.units import Scales, parse

L, A_CRANK, E, RHO, SIDE, OMEGA = 0.3, 0.15, 2.0e11, 7870.0, 0.008, 150.0
AREA, INERTIA = SIDE**2, SIDE**4 / 12
SI = crankgen.SIMechanism(L=L, a=A_CRANK, E=E, rho=RHO, A=AREA, I=INERTIA, slider_mass=0.075552,
                          crank_speed=OMEGA)
OMEGA_B = (math.pi / L) ** 2 * math.sqrt(E * INERTIA / (RHO * AREA))


def _bent_si():
    """A bent rod, in SI: 0.5 mm first-mode deflection moving at 0.3 m/s (x in metres)."""
    return crankgen.InitialState(v=lambda x: 5e-4 * np.sin(np.pi * x / L), v_t=lambda x: 0.3 * np.sin(np.pi * x / L))


@pytest.fixture(scope="module")
def run():
    return crankgen.simulate(SI, units="si", approach="C", n_elements=6, steps_per_rev=200, revolutions=0.3,
                             initial=_bent_si(), store_nodes=True, times=[0.004])


def test_time_angle_and_rigid_start_in_si(run):
    si = run.si
    assert si.t[-1] == pytest.approx(0.3 * 2 * math.pi / OMEGA, rel=1e-12)
    np.testing.assert_allclose(si.theta, OMEGA * si.t, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(si.crank_speed, OMEGA, rtol=1e-12)
    assert si.slider_position[0] == pytest.approx(A_CRANK + L, rel=1e-12)     # rod straight along X
    assert si.chord_deflection(L / 2)[0] == pytest.approx(5e-4, rel=1e-12)
    assert si.at_times.t[0] == pytest.approx(0.004, rel=1e-12)
    with pytest.raises(crankgen.ParameterError, match="position along the rod, m"):
        si.chord_deflection(0.5)                                         # metres: beyond the 0.3 m rod


def test_section_forces_in_si_are_e_i_v_xx_and_e_a_u_x_from_the_si_nodes(run):
    si, n = run.si, 6
    h = L / n
    for k in (5, 40, 60):
        nodes = si.nodes[k]
        u, v, psi = nodes[0::4], nodes[1::4], nodes[2::4]             # (u, v, psi, chi) a node
        e, z = 2, 0.3                                       # x = (2 + 0.3) h, inside element 2
        x = (e + z) * h
        curvature = ((12 * z - 6) * v[e] + h * (6 * z - 4) * psi[e] + (6 - 12 * z) * v[e + 1]
                     + h * (6 * z - 2) * psi[e + 1]) / h**2                    # v'' of the Hermite cubic
        assert si.bending_moment(x)[k] == pytest.approx(E * INERTIA * curvature, rel=1e-9)
        assert si.axial_force(x)[k] == pytest.approx(E * AREA * (u[e + 1] - u[e]) / h, rel=1e-9)
        assert si.v_mid[k] == pytest.approx(v[n // 2], rel=1e-12)              # the midpoint is node 3
        assert si.u_end[k] == pytest.approx(u[n], rel=1e-12)


def test_torque_in_si_is_the_pin_force_moment_about_the_crank_pivot(run):
    si = run.si
    th = si.theta
    fx, fy = si.crank_on_rod_x, si.crank_on_rod_y
    np.testing.assert_allclose(si.torque, A_CRANK * (np.cos(th) * fy - np.sin(th) * fx), rtol=1e-10,
                               atol=1e-12 * np.max(np.abs(si.torque)))
    assert np.max(np.abs(fx)) > 1.0                                     # newtons, not rho A L^2 omega_b^2
    np.testing.assert_allclose(si.slider_velocity, run.slider_velocity * L * OMEGA_B, rtol=1e-12)
    np.testing.assert_allclose(si.chord_rate, run.chord_rate * OMEGA_B, rtol=1e-12)


def test_unit_names_follow_from_the_declared_units(run):
    si = run.si
    names = dict(t="s", theta="rad", v_mid="m", u_end="m", extension="1", slider_position="m",
                 chord_angle="rad", chord_rate="rad/s", slider_velocity="m/s", torque="N m", crank_on_rod_x="N",
                 axial_force="N", bending_moment="N m", surface_strain="1", chord_deflection="m")
    for name, unit in names.items():
        assert si.units(name) == unit, name
    assert parse("r^2/L") == {"r": 2, "L": -1} and parse("1") == {}
    for bad in ("furlong", "L^x", "L/omega_b/r", ""):
        with pytest.raises(ValueError):
            parse(bad)
    scales = Scales(L=2.0, eps=0.1, omega_b=3.0, rhoA=5.0)
    assert scales.factor("r^2/L") == pytest.approx(0.2**2 / 2.0)


def test_si_inputs_equal_the_same_state_and_times_in_crankgen_units():
    """The SI initial state and times give the run of the dimensionless ones."""
    si_run = crankgen.simulate(SI, units="si", approach="C", n_elements=4, steps_per_rev=100, initial=_bent_si(),
                               times=[0.004])
    mech, omega = SI.mechanism, SI.omega
    ini = crankgen.InitialState(v=lambda x: 5e-4 / L * np.sin(np.pi * x),
                                v_t=lambda x: 0.3 / (L * OMEGA_B) * np.sin(np.pi * x))
    plain = crankgen.simulate(mech, omega=omega, approach="C", n_elements=4, steps_per_rev=100, initial=ini,
                              times=[0.004 * OMEGA_B])
    np.testing.assert_allclose(si_run.states, plain.states, rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(si_run.at_times.states, plain.at_times.states, rtol=1e-10, atol=1e-16)
    with pytest.raises(crankgen.ParameterError, match="result.si"):
        plain.si
    assert plain.si_view(SI).slider_position[0] == pytest.approx(A_CRANK + L)


@pytest.mark.parametrize("kwargs, words", [
    (dict(mech=crankgen.Mechanism(), units="si"), "SIMechanism"),
    (dict(mech=SI), "units='si'"),
    (dict(mech=SI, units="si", omega=0.5), "crank_speed"),
    (dict(mech=SI, units="furlongs"), "units"),
])
def test_si_misuse_is_refused(kwargs, words):
    with pytest.raises(crankgen.ParameterError) as exc:
        crankgen.simulate(n_elements=2, revolutions=0.1, **kwargs)
    assert words in str(exc.value)


def test_cli_si_file_in_and_si_columns_out(tmp_path):
    path = tmp_path / "mechanism.json"
    path.write_text(json.dumps(dict(L=L, a=A_CRANK, E=E, rho=RHO, A=AREA, I=INERTIA, slider_mass=0.075552,
                                    crank_speed=OMEGA)))
    out = tmp_path / "run"
    rc = cli_main(["simulate", "--si", str(path), "--approach", "C", "--elements", "4", "--steps-per-rev", "50",
                   "--revolutions", "0.5", "--out", str(out), "--quiet", "--nodes"])
    assert rc == 0
    import pandas
    data = pandas.read_csv(out / "simulation.csv")
    assert list(data.columns[:5]) == ["t_s", "theta_rad", "v_mid_m", "u_end_m", "extension"]
    assert {"slider_position_m", "chord_angle_rad", "torque_N_m", "crank_on_rod_x_N", "guide_on_slider_y_N",
            "rod_on_slider_x_N",
            "slider_velocity_m_per_s", "crank_speed_rad_per_s"} <= set(data.columns)
    assert data["t_s"].iloc[-1] == pytest.approx(0.5 * 2 * math.pi / OMEGA, rel=1e-12)
    assert data["crank_speed_rad_per_s"].to_numpy() == pytest.approx(OMEGA, rel=1e-12)
    assert data["slider_position_m"].iloc[0] == pytest.approx(A_CRANK + L, rel=1e-12)
    assert data["slider_position_m"].iloc[-1] == pytest.approx(L - A_CRANK, rel=1e-3)   # half a turn: the pin at -a
    proc = subprocess.run([sys.executable, "-m", "crankgen.cli", "simulate", "--si", str(path), "--eps", "0.1",
                           "--out", str(tmp_path / "x"), "--quiet"], capture_output=True, text=True)
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1 and "--eps" in proc.stderr
    path.write_text('{"L": 0.3}')
    assert cli_main(["simulate", "--si", str(path), "--out", str(tmp_path / "y"), "--quiet"]) == 2
    assert not (tmp_path / "y").exists()
