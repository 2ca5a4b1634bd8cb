"""Public API, bad input, failure reporting and the command line."""

import math
import subprocess
import sys

import numpy as np
import pytest

import crankgen
from crankgen.cli import main as cli_main


@pytest.mark.parametrize("kwargs, name", [
    (dict(a=1.0), "a"), (dict(a=0.0), "a"), (dict(a=-0.2), "a"), (dict(eps=0.0), "eps"),
    (dict(eps=-1), "eps"), (dict(ms=-0.1), "ms"), (dict(mu=-1e-3), "mu"),
    (dict(a=float("nan")), "a"), (dict(eps=float("inf")), "eps"), (dict(ms="heavy"), "ms"),
])
def test_invalid_mechanism_names_parameter_and_range(kwargs, name):
    with pytest.raises(crankgen.ParameterError) as exc:
        crankgen.Mechanism(**kwargs)
    assert str(exc.value).startswith(name)
    assert "must be" in str(exc.value)


@pytest.mark.parametrize("kwargs, name", [
    (dict(omega=-0.5), "omega"), (dict(omega=0.0), "omega"), (dict(omega=float("nan")), "omega"),
    (dict(n_elements=0), "n_elements"), (dict(n_elements=2.5), "n_elements"),
    (dict(steps_per_rev=3), "steps_per_rev"), (dict(revolutions=0), "revolutions"),
    (dict(approach="D"), "approach"), (dict(formulation="exact"), "formulation"),
    (dict(integrator="rk4"), "integrator"), (dict(damping="viscous"), "damping"),
])
def test_invalid_run_options_raise_clear_errors(kwargs, name):
    with pytest.raises(crankgen.ParameterError) as exc:
        crankgen.simulate(crankgen.Mechanism(), **kwargs)
    assert str(exc.value).startswith(name)


def test_result_arrays_and_units():
    r = crankgen.simulate(crankgen.Mechanism(), omega=0.8, n_elements=3, steps_per_rev=20,
                          revolutions=1.5)
    assert len(r.t) == len(r.theta) == len(r.v_mid) == len(r.u_end) == len(r.extension) == 31
    assert r.t[-1] == pytest.approx(1.5 * 2 * math.pi / 0.8)
    assert r.theta[-1] == pytest.approx(3 * math.pi)          # unwrapped crank angle
    assert r.v_mid[0] == 0 and np.all(np.isfinite(r.v_mid)) and np.any(r.v_mid != 0)


def test_non_converging_newton_names_step_time_and_residual():
    """The consistent approach B (no quartic term: energy unbounded below) blows up at Omega* = 0.8;
    the failure must surface as an error, never as NaN in a result."""
    with pytest.raises(crankgen.ConvergenceError) as exc:
        crankgen.simulate(crankgen.Mechanism(), omega=0.8, approach="B", formulation="lagrange",
                          n_elements=4, revolutions=3)
    err = exc.value
    assert err.step is not None and err.time is not None and err.residual is not None
    assert f"step {err.step}" in str(err) and "t* =" in str(err) and "residual" in str(err)


def test_si_constructor_converts_to_paper_parameters():
    L, r, E, rho = 0.3, 0.003, 2.0e11, 7800.0
    A = math.pi * (2 * r) ** 2                      # solid circle of radius 2r has r_g = r
    I = math.pi * (2 * r) ** 4 / 4
    omega_b = (math.pi / L) ** 2 * math.sqrt(E * I / (rho * A))
    si = crankgen.SIMechanism(L=L, a=0.03, E=E, rho=rho, A=A, I=I, slider_mass=0.5 * rho * A * L,
                              crank_speed=0.8 * omega_b, damping=0.5 / omega_b)
    mech, omega = si.mechanism, si.omega
    assert mech.a == pytest.approx(0.1) and mech.eps == pytest.approx(0.01)
    assert mech.ms == pytest.approx(0.5) and mech.mu == pytest.approx(0.5)
    assert omega == pytest.approx(0.8)
    with pytest.raises(crankgen.ParameterError):
        crankgen.SIMechanism(L=-1, a=0.03, E=E, rho=rho, A=A, I=I, slider_mass=1, crank_speed=1)


def test_cli_writes_csv_and_png(tmp_path):
    rc = cli_main(["simulate", "--elements", "2", "--revolutions", "1", "--steps-per-rev", "20",
                   "--out", str(tmp_path), "--quiet", "--nodes"])
    assert rc == 0
    data = np.loadtxt(tmp_path / "simulation.csv", delimiter=",", skiprows=1, usecols=range(5))
    assert data.shape == (21, 5) and np.all(np.isfinite(data))
    assert (tmp_path / "simulation.csv").read_text().splitlines()[0].endswith(",status")
    assert (tmp_path / "v_mid.png").stat().st_size > 1000
    assert np.loadtxt(tmp_path / "nodes.csv", delimiter=",", skiprows=1).shape == (21, 2 + 9 + 6)   # + X, Y


@pytest.mark.parametrize("args, word", [
    (["--a", "2"], "a (crank"), (["--elements", "0"], "n_elements"), (["--eps", "nan"], "eps"),
    (["--steps-per-rev", "2"], "steps_per_rev"), (["--omega", "-1"], "omega"),
])
def test_cli_bad_input_is_one_line_without_traceback(tmp_path, args, word):
    proc = subprocess.run([sys.executable, "-m", "crankgen.cli", "simulate", "--out", str(tmp_path),
                           "--quiet"] + args, capture_output=True, text=True)
    assert proc.returncode != 0
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and word in lines[0] and "Traceback" not in proc.stderr


def test_cli_help_explains_every_option():
    proc = subprocess.run([sys.executable, "-m", "crankgen.cli", "simulate", "--help"],
                          capture_output=True, text=True)
    assert proc.returncode == 0
    for option in ("--a", "--eps", "--ms", "--mu", "--omega", "--approach", "--formulation",
                   "--damping", "--elements", "--steps-per-rev", "--revolutions", "--integrator",
                   "--out"):
        assert option in proc.stdout


def test_cli_audit_writes_the_report(tmp_path):
    rc = cli_main(["audit", "--out", str(tmp_path), "--sections", "1", "--quiet"])
    assert rc == 0
    text = (tmp_path / "report.md").read_text(encoding="utf-8")
    assert "## 1. Energies and dissipation functions by order" in text and "## 2." not in text
    with pytest.raises(SystemExit) as exc:                  # argparse: usage and a one-line error
        cli_main(["audit", "--out", str(tmp_path), "--sections", "9", "--quiet"])
    assert exc.value.code == 2


def test_public_names_are_the_functions_whatever_was_imported_first():
    """The public names load on first use; a submodule imported earlier must not shadow one."""
    import subprocess
    import sys
    code = ("import crankgen.analyses.sweeps, crankgen.analyses.simulation, crankgen.analyses.steady, crankgen.analyses.bifurcation, types; "
            "from crankgen import sweep, simulate, steady_state, continuation, Case; "
            "assert not any(isinstance(f, types.ModuleType) for f in (sweep, simulate, steady_state, "
            "continuation, Case)); import crankgen; assert callable(crankgen.sweep)")
    subprocess.run([sys.executable, "-c", code], check=True)
