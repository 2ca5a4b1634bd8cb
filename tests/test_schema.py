"""The model as data: presets, one default model for the Python API and the command line,
canonical parameter values, every parameter and option stated once (the schema), and the
guards that a run is a result only when it is one."""

import csv
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import crankgen
from crankgen.declaration import schema
from crankgen.declaration.cases import Case
from crankgen.cli import main as cli_main_function
from crankgen.cli.options import _float_grid
from crankgen.errors import ConvergenceError, ParameterError

TINY = dict(n_elements=2, steps_per_rev=20)


def test_the_api_and_the_command_line_default_to_the_same_model(tmp_path):
    """The same call without model options gives the same numbers through both doors."""
    api = crankgen.simulate(crankgen.Mechanism(), omega=0.8, revolutions=1, **TINY)
    assert api.case.model == schema.DEFAULT_PRESET == "consistent"
    code = cli_main_function(["simulate", "--elements", "2", "--steps-per-rev", "20", "--revolutions", "1",
                          "--out", str(tmp_path), "--quiet"])
    assert code == 0
    with open(tmp_path / "simulation.csv", newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    header, rows = rows[0], rows[1:]
    column = next(i for i, name in enumerate(header) if name.startswith("v_mid"))
    cli = np.array([float(r[column]) for r in rows if r[column]])
    np.testing.assert_allclose(cli, api.v_mid[:len(cli)], rtol=1e-12, atol=1e-15)
    assert len(cli) == len(api.v_mid)


def test_a_preset_sets_options_and_explicit_options_override_it():
    paper = Case(model="paper")
    assert paper.options == schema.resolve_options("paper")
    assert (paper.formulation, paper.damping, paper.membrane) == ("paper", "paper", "pointwise")
    mixed = Case(model="paper", damping="kelvin-voigt")
    assert (mixed.formulation, mixed.damping) == ("paper", "kelvin-voigt") and mixed.model is None
    assert Case() == Case(model="consistent") and Case().model == "consistent"
    with pytest.raises(ParameterError, match="model must be one of"):
        Case(model="rigid")


def test_parameters_have_one_canonical_form():
    with pytest.raises(ParameterError, match="gravity"):
        Case(gravity={0: 1e-3, 1: 2e-3})                 # a dict's keys are not a pair
    with pytest.raises(ParameterError, match="gravity"):
        Case(gravity={1e-3, 2e-3})                       # a set has no order
    with pytest.raises(ParameterError, match="gravity"):
        Case(gravity=(1e-3, 2e-3, 0.0))
    a, b = Case(offset=-0.0), Case(offset=0.0)
    assert a == b and hash(a) == hash(b) and a.key() == b.key()
    assert math.copysign(1.0, a.offset) == 1.0
    assert Case(gravity=(0.0, -0.0)).key() == Case().key()
    assert Case(gravity=[np.float32(0.5), 1]).gravity == (0.5, 1.0)
    assert Case(branch=-1.0, guide="circle").branch == -1
    with pytest.raises(ParameterError, match="branch"):
        Case(branch=0.5, guide="circle")


def test_grid_values_are_rounded_to_the_places_the_range_is_written_with():
    values = _float_grid("-0.3:0.3:0.1")
    assert values == [-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3]
    assert math.copysign(1.0, values[3]) == 1.0                  # 0.0, not -0.0 or 5.55e-17
    assert _float_grid("0,-0") == [0.0]


def test_a_parameter_of_another_guide_or_motion_is_refused_by_name():
    with pytest.raises(ParameterError, match=r"^c \(rocker length"):
        Case(c=0.5)                                              # the line guide has no rocker
    with pytest.raises(ParameterError, match=r"^omega0 \(run-up start speed\)"):
        Case(omega0=0.3)
    with pytest.raises(ParameterError, match="unknown case parameter 'rocker'"):
        crankgen.simulate(crankgen.Mechanism(), rocker=0.5)


def test_every_parameter_and_option_has_a_flag_from_the_schema():
    from crankgen.cli.main import build_parser
    text = build_parser()._subparsers._group_actions[0].choices["simulate"].format_help()
    for p in schema.PARAMETERS.values():
        assert f"--{p.cli}" in text, p.name
    for o in schema.OPTIONS.values():
        assert f"--{o.cli}" in text, o.name
    for preset in schema.PRESETS:
        assert preset in text


def test_a_blow_up_is_a_failure_whatever_the_integrator(tmp_path, capsys):
    """The paper's one-pass scheme with 10 steps per revolution diverges; every row of its run
    used to say ok with v* = 1e48."""
    with pytest.raises(ConvergenceError, match="diverged") as exc:
        crankgen.simulate(crankgen.Mechanism(), integrator="one-pass", steps_per_rev=10, n_elements=4,
                          revolutions=5)
    partial = exc.value.partial
    assert partial is not None and np.max(np.abs(partial.states)) < 10
    code = cli_main_function(["simulate", "--integrator", "one-pass", "--steps-per-rev", "10", "--elements",
                          "4", "--revolutions", "5", "--out", str(tmp_path), "--quiet"])
    assert code == 1
    text = (tmp_path / "simulation.csv").read_text()
    assert "diverged" in text and "e+48" not in text


@pytest.mark.slow
def test_the_engine_runs_with_numba_switched_off(tmp_path):
    """NUMBA_DISABLE_JIT=1 (what a user tries first when debugging numba code) runs the same engine
    as plain Python: the same numbers as compiled."""
    code = ("import crankgen; m = crankgen.Mechanism(); "
            "r = crankgen.simulate(m, omega=0.8, n_elements=2, steps_per_rev=20, revolutions=1); "
            "s = crankgen.steady_state(m, omega=0.8, n_elements=2, steps_per_rev=20); "
            "print(repr(float(r.v_mid[-1])), repr(float(s.amplitude)), s.status)")
    env = dict(os.environ, NUMBA_DISABLE_JIT="1", CRANKGEN_CACHE_DIR=str(tmp_path))
    plain = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                           timeout=900)
    assert plain.returncode == 0, plain.stderr
    assert "compiling" not in plain.stderr
    compiled = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=900)
    assert compiled.returncode == 0, compiled.stderr
    a, b = plain.stdout.split(), compiled.stdout.split()
    assert a[2] == b[2] == "periodic"
    np.testing.assert_allclose([float(x) for x in a[:2]], [float(x) for x in b[:2]], rtol=1e-10)


def test_a_value_seen_before_is_refused_as_before_when_its_items_are_of_other_types():
    """The canonical values are looked up when seen before (a continuation rebuilds a case per
    point); True == 1 and (0, True) == (0, 1) as keys must not let a boolean pass as a number."""
    import crankgen
    from crankgen.declaration.cases import Case
    from crankgen.errors import ParameterError

    Case(motion="motor", torque_curve=((0, 1), (1, 0)))
    for curve in (((0, True), (1, False)), ((0, 1), (True, 0))):
        with pytest.raises(ParameterError, match="^torque_curve"):
            Case(motion="motor", torque_curve=curve)
    Case(n_elements=2)
    with pytest.raises(ParameterError):
        Case(n_elements=True)
    assert crankgen.Mechanism(eps=0.01) == crankgen.Mechanism(eps=0.01)
