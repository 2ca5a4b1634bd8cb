"""Unit mistakes named before any work (crankgen.declaration.plausibility), and speeds in rpm.

Each likely mistake is made on a real mechanism (a steel press rod, 0.25 m, 10 x 10 mm, 3000 rpm)
and must be refused in one line that names the field and the unit it was likely given in, before
anything is computed or created; the right numbers pass.  rpm is checked against rad/s by the
definition rpm = rad/s x 60 / (2 pi), written out here."""

import json
import math

import pytest

import crankgen
from crankgen.cli.main import main

ROD = dict(L=0.25, E=2.1e11, rho=7850.0, A=1e-4, I=1e-2 ** 4 / 12)      # steel, 10 x 10 mm, m / Pa / kg/m^3
PRESS = dict(ROD, a=0.05, slider_mass=0.5, crank_speed=3000 * 2 * math.pi / 60, damping=2e-4)


def test_the_right_numbers_pass():
    si = crankgen.SIMechanism(**PRESS)
    assert 0.13 < si.omega < 0.14                     # 314 rad/s over omega_b = 2358 rad/s


@pytest.mark.parametrize("field, value, unit, words", [
    ("E", 210.0, "GPa", "210 GPa = 2.1e+11 Pa"),                     # a modulus in GPa: 10^9
    ("E", 2.1e5, "MPa (N/mm^2)", "= 2.1e+11 Pa"),                    # in N/mm^2: 10^6
    ("rho", 7.85, "g/cm^3", "7.85 g/cm^3 = 7850 kg/m^3"),            # a density in g/cm^3: 10^3
    ("rho", 7.85e-9, "t/mm^3", "t/mm^3"),                            # an FE code's t/mm^3: 10^12
    ("rho", 7.85e-6, "kg/mm^3", "kg/mm^3"),                          # 10^9
    ("L", 250.0, "mm", "250 mm = 0.25 m"),                           # a length in mm: 10^3
    ("A", 100.0, "mm^2", "100 mm^2 = 0.0001 m^2"),                   # an area in mm^2: 10^6
    ("I", 1e4 / 12, "mm^4", "mm^4"),                                 # in mm^4: 10^12
    ("slider_mass", 500.0, "g", "500 g = 0.5 kg"),                   # a mass in grams: 10^3
])
def test_each_likely_unit_mistake_is_named(field, value, unit, words):
    with pytest.raises(crankgen.ParameterError) as info:
        crankgen.SIMechanism(**dict(PRESS, **{field: value}))
    text = str(info.value)
    assert "\n" not in text and f"{field} = " in text and f"in {unit}?" in text and words in text, text


def test_lengths_of_the_section_in_mm_are_named_by_the_slenderness():
    """A and I in mm^2 and mm^4 but small enough for their own ranges: sqrt(I/A)/L gives it away."""
    wire = dict(PRESS, A=1.0, I=1.0 / 12, slider_mass=0.01)      # a 1 x 1 mm wire's section in mm^2, mm^4
    with pytest.raises(crankgen.ParameterError, match=r"slenderness sqrt\(I/A\)/L = 1.15 .*no rod's.*A in "
                                                      r"mm\^2 and I in mm\^4"):
        crankgen.SIMechanism(**wire)
    crankgen.SIMechanism(**dict(wire, A=1e-6, I=1e-12 / 12))                 # in m^2, m^4 it passes


def test_a_speed_far_beyond_the_rods_frequency_is_named():
    """All the rod's fields right, the crank speed 60 omega_b: a speed no mechanism runs at."""
    omega_b = crankgen.SIMechanism(**PRESS).omega_b
    with pytest.raises(crankgen.ParameterError, match=r"crank_speed = .* rad/s is 60 times the rod's first "
                                                      r"bending frequency.*crank_speed_rpm takes rpm"):
        crankgen.SIMechanism(**dict(PRESS, crank_speed=60 * omega_b))


def test_rad_per_s_passed_as_omega_star_is_named():
    """The issue's case: rad/s passed to the dimensionless run."""
    with pytest.raises(crankgen.ParameterError, match=r"omega \(crank speed Omega\*\) = 4200 .*are your "
                                                      r"inputs in SI\?"):
        crankgen.simulate(crankgen.Mechanism(), omega=4200, revolutions=1)
    with pytest.raises(crankgen.ParameterError, match="no_load_speed"):
        crankgen.Case(motion=crankgen.Motor(no_load_speed=314.0))
    crankgen.Case(omega=50.0)                                                 # the limit itself passes


def test_a_value_meant_as_given_passes_when_named_unchecked():
    rubber = dict(PRESS, E=5e5, crank_speed=1.0)
    with pytest.raises(crankgen.ParameterError, match="E = 5e"):
        crankgen.SIMechanism(**rubber)
    assert crankgen.SIMechanism(**rubber, unchecked=["E"]).E == 5e5
    with pytest.raises(crankgen.ParameterError, match="unchecked names no check 'Young'"):
        crankgen.SIMechanism(**PRESS, unchecked=["Young"])


def test_the_command_line_names_the_mistake_before_anything_is_made(tmp_path, capsys):
    path = tmp_path / "press.json"
    path.write_text(json.dumps(dict(PRESS, E=210)))
    assert main(["steady", "--si", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "in GPa? 210 GPa = 2.1e+11 Pa" in err and len(err) < 300, err
    assert not (tmp_path / "o").exists()
    assert main(["simulate", "--omega", "4200", "--out", str(tmp_path / "o")]) == 2
    assert "are your inputs in SI?" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_a_json_typo_gets_did_you_mean(tmp_path, capsys):
    path = tmp_path / "press.json"
    data = dict(PRESS)
    data["crank_sped"] = data.pop("crank_speed")
    path.write_text(json.dumps(data))
    assert main(["steady", "--si", str(path), "--out", str(tmp_path / "o")]) == 2
    assert "unknown field 'crank_sped'; did you mean 'crank_speed'?" in capsys.readouterr().err


def test_a_crank_at_rest_from_a_file_names_the_files_field(tmp_path, capsys):
    """The error named --omega where the file said crank_speed."""
    path = tmp_path / "press.json"
    path.write_text(json.dumps(dict(PRESS, crank_speed=0)))
    assert main(["steady", "--si", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert f'"crank_speed": 0 in {path}' in err and "--omega" not in err, err


# ---- rpm ------------------------------------------------------------------------------------------

def test_rpm_is_rad_per_s_times_60_over_2_pi():
    for field in ("crank_speed", "omega0"):
        rpm = crankgen.SIMechanism(**dict(PRESS, crank_speed=None, crank_speed_rpm=3000.0, motion="runup",
                                          omega0=None, omega0_rpm=600.0, ramp=2))
        assert getattr(rpm, field) == pytest.approx({"crank_speed": 3000.0, "omega0": 600.0}[field] * 2 * math.pi / 60,
                                                    rel=1e-15)
    assert rpm.crank_speed_rpm is None                     # converted into crank_speed on construction
    same = crankgen.SIMechanism(**dict(PRESS, crank_speed=3000.0 * 2 * math.pi / 60))
    assert crankgen.SIMechanism(**dict(PRESS, crank_speed=None, crank_speed_rpm=3000.0)).omega == same.omega
    with pytest.raises(crankgen.ParameterError, match="give one"):
        crankgen.SIMechanism(**dict(PRESS, crank_speed_rpm=3000.0))
    motor = crankgen.SIMechanism(**dict(ROD, a=0.05, slider_mass=0.5, motion="motor", stall_torque=40.0,
                                        no_load_speed_rpm=3000.0, inertia=0.01))
    assert motor.no_load_speed == pytest.approx(100 * math.pi, rel=1e-15)


def test_rpm_on_the_command_line(tmp_path, capsys):
    rod = tmp_path / "rod.json"                        # the rod alone: the speed on the command line
    rod.write_text(json.dumps({k: v for k, v in PRESS.items() if k != "crank_speed"}))
    press = tmp_path / "press.json"
    press.write_text(json.dumps(PRESS))
    tiny = ["--elements", "2", "--steps-per-rev", "20", "--quiet"]
    assert main(["steady", "--si", str(rod), "--rpm", "3000", "--out", str(tmp_path / "r"), *tiny]) == 0
    assert main(["steady", "--si", str(press), "--out", str(tmp_path / "s"), *tiny]) == 0
    capsys.readouterr()
    import pandas as pd
    r, s = (pd.read_csv(tmp_path / k / "steady.csv") for k in "rs")
    assert r["crank_speed_rad_per_s"][0] == pytest.approx(3000 * 2 * math.pi / 60, rel=1e-15)
    assert r["amplitude_m"][0] == pytest.approx(s["amplitude_m"][0], rel=1e-12)
    assert main(["steady", "--si", str(press), "--rpm", "3000", "--out", str(tmp_path / "x")]) == 2
    assert "same crank speed" in capsys.readouterr().err
    assert main(["steady", "--rpm", "3000", "--out", str(tmp_path / "x")]) == 2
    assert "needs the rod in SI" in capsys.readouterr().err
    assert main(["sweep", "--si", str(press), "--rpm", "1500,3000", "--out", str(tmp_path / "w"), *tiny]) == 0
    w = pd.read_csv(tmp_path / "w" / "sweep.csv")
    assert list(w["crank_speed_rad_per_s"]) == pytest.approx([50 * math.pi, 100 * math.pi], rel=1e-15)
