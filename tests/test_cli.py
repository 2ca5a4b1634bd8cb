"""The command line: exit codes, one-line errors before anything is computed or created, outputs
kept unless --force, a failed run's history, and the steady / sweep commands end to end."""

import csv
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import crankgen
from crankgen import cli
from crankgen.cli import main

TINY = ["--elements", "2", "--steps-per-rev", "20", "--quiet"]


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def one_line_error(capsys, *words):
    err = capsys.readouterr().err
    # a cold compile cache adds its progress lines ("crankgen: compiling ..."): not errors
    lines = [x for x in err.strip().splitlines() if not x.startswith(("crankgen: compiling", "crankgen: recompiling"))]
    assert len(lines) == 1, err
    assert "Traceback" not in err and ("error" in lines[0] or "failed" in lines[0])
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


def run(argv):
    """main(argv) -> exit code, whether main returns it or argparse exits with it."""
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


# ---- usage errors: exit 2, one line, nothing created -----------------------------------------
@pytest.mark.parametrize("argv, words", [
    (["simulate", "--omega", "abc"], ["--omega", "abc"]),
    (["simulate", "--omega", "-1"], ["omega"]),
    (["simulate", "--omega", "nan"], ["omega"]),
    (["simulate", "--elements", "0"], ["n_elements"]),
    (["simulate", "--steps-per-rev", "2"], ["steps_per_rev"]),
    (["simulate", "--revolutions", "0"], ["revolutions"]),
    (["simulate", "--tol", "-1"], ["tol"]),
    (["simulate", "--model", "rigid"], ["model"]),
    (["simulate", "--model", "exact", "--formulation", "paper"], ["exact", "formulation"]),
    (["steady", "--a", "1.5"], ["a (crank"]),
    (["steady", "--max-revolutions", "0"], ["max_revolutions"]),
    (["sweep", "--omega", "0.8:0.2:0.1"], ["range"]),
    (["sweep", "--omega", "0.2:1:x"], ["number"]),
    (["sweep", "--approach", "A,D"], ["approach"]),
    (["sweep", "--eps", "0.01,-1"], ["eps"]),
    (["sweep", "--elements", "4,0"], ["elements"]),
])
def test_invalid_argument_exits_2_with_one_line_and_creates_nothing(tmp_path, capsys, argv, words):
    out = tmp_path / "new" / "folder"
    assert run(argv + ["--out", str(out), "--quiet"]) == 2
    one_line_error(capsys, *words)
    assert not (tmp_path / "new").exists()


@pytest.mark.parametrize("command", ["simulate", "steady", "sweep", "audit", "reproduce"])
def test_out_that_is_a_file_or_under_a_file_is_refused(tmp_path, capsys, command):
    f = tmp_path / "file"
    f.write_text("keep me")
    for out, word in ((f, "is a file"), (f / "sub", "is a file")):
        assert run([command, "--out", str(out), "--quiet"]) == 2
        one_line_error(capsys, str(f), word)
    assert f.read_text() == "keep me"


def test_out_that_cannot_be_created_or_written_is_refused(tmp_path, capsys, monkeypatch):
    """Inside the test's own folder: a name longer than any file system allows cannot be
    created; a folder whose write probe fails (root ignores mode bits, so the probe is made to
    fail) cannot be written."""
    assert run(["simulate", "--out", str(tmp_path / ("x" * 300) / "y"), "--quiet"]) == 2
    one_line_error(capsys, "cannot", "File name too long")
    assert list(tmp_path.iterdir()) == []
    from crankgen.results import io as cio

    def no_write(path):
        raise PermissionError(13, "Permission denied", str(path))
    monkeypatch.setattr(cio, "_temporary", no_write)
    ro = tmp_path / "ro"
    ro.mkdir()
    assert run(["steady", "--out", str(ro), "--quiet"]) == 2
    one_line_error(capsys, "cannot write", str(ro))
    assert list(ro.iterdir()) == []


@pytest.mark.parametrize("argv", [["simulate", "--out", "FILE"], ["simulate", "--omega", "x"]])
def test_usage_errors_in_a_subprocess(tmp_path, argv):
    f = tmp_path / "f"
    f.write_text("")
    argv = [str(f) if a == "FILE" else a for a in argv]
    proc = subprocess.run([sys.executable, "-m", "crankgen.cli"] + argv, capture_output=True, text=True,
                          cwd=tmp_path)
    assert proc.returncode == 2
    assert len(proc.stderr.strip().splitlines()) == 1 and "Traceback" not in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f"]


def test_version(capsys):
    assert run(["--version"]) == 0
    assert capsys.readouterr().out.startswith(f"crankgen {crankgen.__version__} ")


def test_interrupt_leaves_no_empty_folder(tmp_path, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr(crankgen.analyses.simulation, "simulate", interrupted)
    out = tmp_path / "a" / "b"
    assert run(["simulate", "--out", str(out)] + TINY) == 130
    assert not (tmp_path / "a").exists()
    assert "interrupted" in capsys.readouterr().err


# ---- the model shorthand ---------------------------------------------------------------------
@pytest.mark.parametrize("argv, expected", [
    ([], ("lagrange", "kelvin-voigt", "averaged")),                      # default: consistent
    (["--model", "paper"], ("paper", "paper", "pointwise")),
    (["--model", "consistent"], ("lagrange", "kelvin-voigt", "averaged")),
    (["--model", "paper", "--membrane", "averaged"], ("paper", "paper", "averaged")),
    (["--damping", "paper"], ("lagrange", "paper", "averaged")),
])
def test_model_shorthand_and_explicit_options(argv, expected):
    for command in ("simulate", "steady"):
        case = cli._case(cli.build_parser().parse_args([command] + argv))
        assert (case.formulation, case.damping, case.membrane) == expected


# ---- simulate --------------------------------------------------------------------------------
def test_simulate_writes_0644_files_and_keeps_them_unless_force(tmp_path, capsys):
    out = tmp_path / "run"
    argv = ["simulate", "--revolutions", "1", "--out", str(out)] + TINY
    assert run(argv) == 0
    rows = read_csv(out / "simulation.csv")
    assert len(rows) == 21 and {r["status"] for r in rows} == {"ok"}
    umask = os.umask(0)
    os.umask(umask)
    for name in ("simulation.csv", "v_mid.png"):
        assert (out / name).stat().st_mode & 0o777 == 0o666 & ~umask
    assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]
    before = (out / "simulation.csv").read_bytes()
    capsys.readouterr()
    assert run(argv + ["--approach", "C"]) == 2                         # kept ...
    one_line_error(capsys, "simulation.csv", "--force")
    assert (out / "simulation.csv").read_bytes() == before
    assert run(argv + ["--approach", "C", "--force"]) == 0              # ... unless --force
    assert (out / "simulation.csv").read_bytes() != before


def test_failed_simulate_writes_history_up_to_the_failure_and_exits_1(tmp_path, capsys):
    """Approach B of the exact equations (energy unbounded below) diverges at Omega* = 0.8."""
    out = tmp_path / "run"
    model = ["--approach", "B", "--formulation", "lagrange", "--damping", "paper",
             "--membrane", "pointwise", "--elements", "4"]
    assert run(["simulate", "--revolutions", "3", "--out", str(out), "--quiet"] + model) == 1
    line = one_line_error(capsys, "run failed", "simulation.csv")
    rows = read_csv(out / "simulation.csv")
    *good, last = rows
    assert {r["status"] for r in good} == {"ok"} and last["status"].startswith("failed: ")
    assert last["v_mid_r"] == "" and float(last["t_per_omega_b"]) > float(good[-1]["t_per_omega_b"])
    assert (out / "v_mid.png").stat().st_size > 1000
    assert "Traceback" not in line
    # the rows are the run's real history: a run stopped just before the failure gives them again
    n = len(good) - 1
    ref = crankgen.simulate(crankgen.Mechanism(), omega=0.8, approach="B", formulation="lagrange",
                            damping="paper", n_elements=4, revolutions=n / 100)
    assert len(ref.t) == len(good)
    np.testing.assert_allclose([float(r["v_mid_r"]) for r in good], ref.v_mid, rtol=1e-9, atol=1e-12)


# ---- steady ----------------------------------------------------------------------------------
def test_steady_end_to_end(tmp_path, capsys):
    out = tmp_path / "st"
    assert run(["steady", "--out", str(out), "--model", "paper"] + TINY) == 0
    summary = read_csv(out / "steady.csv")
    assert len(summary) == 1
    s = summary[0]
    assert s["status"] == "periodic" and s["formulation"] == "paper" and s["n_elements"] == "2"
    assert 0 < float(s["multiplier"]) < 1
    orbit = read_csv(out / "orbit.csv")
    theta = np.array([float(r["theta_deg"]) for r in orbit])
    v = np.array([float(r["v_mid_r"]) for r in orbit])
    assert len(orbit) == 21 and theta[0] == 0 and theta[-1] == pytest.approx(360.0)
    assert v[-1] == pytest.approx(v[0], rel=1e-5, abs=1e-8)              # one period: it closes
    assert float(s["amplitude"]) == pytest.approx(np.max(np.abs(v)))
    assert (out / "orbit.png").stat().st_size > 1000
    assert "status periodic" in capsys.readouterr().out


def test_failed_steady_exits_1_and_failed_sweep_case_is_a_row_without_nan(tmp_path, capsys):
    """Approach B of the exact equations (strain energy unbounded below: ill-posed) diverges from
    rest at Omega* = 0.8: no steady state is found, and the message says why."""
    diverging = ["--approach", "B", "--omega", "0.8"] + TINY
    assert run(["steady", "--out", str(tmp_path / "st")] + diverging) == 1
    one_line_error(capsys, "run failed")
    row = read_csv(tmp_path / "st" / "steady.csv")[0]
    assert row["status"] == "failed" and row["amplitude"] == "" and row["message"]
    assert "unbounded below" in row["message"] and row["strain_energy_bound"] == "unbounded below (ill-posed)"
    assert not (tmp_path / "st" / "orbit.csv").exists()
    assert run(["sweep", "--out", str(tmp_path / "sw")] + diverging) == 0
    text = (tmp_path / "sw" / "sweep.csv").read_text()
    assert "nan" not in text.lower() and read_csv(tmp_path / "sw" / "sweep.csv")[0]["status"] == "failed"


# ---- sweep -----------------------------------------------------------------------------------
SWEEP = ["sweep", "--omega", "0.2:0.6:0.2", "--eps", "0.01", "--batch-size", "1"] + TINY


def _without_wall_time(rows):
    return [{k: v for k, v in r.items() if k != "wall_time"} for r in rows]


def test_sweep_grid_and_resume_after_an_interruption(tmp_path, capsys, monkeypatch):
    sweep_module = sys.modules["crankgen.analyses.sweeps"]        # (crankgen.sweep is the function)
    whole = tmp_path / "whole"
    assert run(SWEEP + ["--out", str(whole)]) == 0
    rows = read_csv(whole / "sweep.csv")
    assert [r["omega"] for r in rows] == ["0.2", "0.4", "0.6"]        # the range, stop included
    assert all(r["status"] == "periodic" for r in rows)
    assert "3 cases, 3 periodic" in capsys.readouterr().out

    real, calls = sweep_module._run_chunk, []

    def interrupted_on_second(cases, *args):
        calls.append(cases[0].omega)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(cases, *args)
    monkeypatch.setattr(sweep_module, "_run_chunk", interrupted_on_second)
    part = tmp_path / "part"
    assert run(SWEEP + ["--out", str(part)]) == 130
    assert not (part / "sweep.csv").exists() and (part / "sweep.jsonl").exists()
    assert "the same command resumes" in capsys.readouterr().err

    def counted(cases, *args):
        calls.append(cases[0].omega)
        return real(cases, *args)
    monkeypatch.setattr(sweep_module, "_run_chunk", counted)
    calls.clear()
    assert run(SWEEP + ["--out", str(part)]) == 0                     # same command: resumes
    assert len(calls) == 2                                            # one case came from the checkpoint
    assert _without_wall_time(read_csv(part / "sweep.csv")) == _without_wall_time(rows)
    calls.clear()
    assert run(SWEEP + ["--out", str(part)]) == 2                     # finished: kept
    assert run(SWEEP + ["--out", str(part), "--force"]) == 0          # --force: sweep.csv replaced,
    assert calls == []                                                # the records reused
    assert run(SWEEP + ["--out", str(part), "--force", "--fresh"]) == 0   # --fresh: recomputed
    assert len(calls) == 3


def test_sweep_refuses_a_foreign_checkpoint(tmp_path, capsys):
    foreign = tmp_path / "notes.txt"
    foreign.write_text("my notes\n")
    assert run(SWEEP + ["--out", str(tmp_path / "o"), "--checkpoint", str(foreign)]) == 2
    one_line_error(capsys, "not a crankgen sweep checkpoint")
    assert foreign.read_text() == "my notes\n" and not (tmp_path / "o").exists()


# ---- numbers given as text are refused by the Python API too ---------------------------------
@pytest.mark.parametrize("call", [
    lambda: crankgen.Mechanism(a="0.1"),
    lambda: crankgen.Case(omega="0.8"),
    lambda: crankgen.simulate(crankgen.Mechanism(), omega="0.8", n_elements=2, steps_per_rev=20),
    lambda: crankgen.simulate(crankgen.Mechanism(), revolutions="1", n_elements=2, steps_per_rev=20),
    lambda: crankgen.steady_state(crankgen.Mechanism(), omega="0.8", n_elements=2, steps_per_rev=20),
    lambda: crankgen.steady_state(crankgen.Mechanism(), tol="1e-8", n_elements=2, steps_per_rev=20),
])
def test_numbers_given_as_strings_are_refused(call):
    with pytest.raises(crankgen.ParameterError, match="must be a number"):
        call()


def test_case_from_csv_text_still_converts():
    """Case.from_dict reads CSV rows: there text is the format, and it is converted explicitly."""
    assert crankgen.Case.from_dict({"omega": "0.4", "n_elements": "4"}).omega == 0.4


# ---- atomic writes ---------------------------------------------------------------------------
def test_atomic_write_leaves_nothing_on_failure_and_old_file_intact(tmp_path):
    from crankgen.results.io import atomic_write, atomic_write_text
    path = atomic_write_text(tmp_path / "x.csv", "old\n")

    def broken(fh):
        fh.write("half")
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        atomic_write(path, broken)
    assert path.read_text() == "old\n" and [p.name for p in tmp_path.iterdir()] == ["x.csv"]


def test_leftover_temporaries_of_a_killed_run_are_removed(tmp_path):
    """A run killed while writing leaves `.NAME.PID.X.tmp`; the next run removes it when PID is gone."""
    with open("/proc/sys/kernel/pid_max") as fh:   # a process id the kernel never gives out
        dead = int(fh.read()) + 1
    stale = tmp_path / f".simulation.csv.{dead}.0badc0de.tmp"
    alive = tmp_path / f".simulation.csv.{os.getppid()}.0badc0de.tmp"
    other = tmp_path / f".notes.txt.{dead}.0badc0de.tmp"
    for p in (stale, alive, other):
        p.write_text("half")
    from crankgen.results.io import prepare_folder
    prepare_folder(tmp_path, ["simulation.csv", "v_mid.png"])
    assert not stale.exists() and alive.exists() and other.exists()


def test_documents_cite_no_file_outside_the_repository(capsys):
    """README, docs/ and every --help text state things in the project's own words."""
    from pathlib import Path
    root = Path(__file__).resolve().parent.parent
    texts = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    for command in ("simulate", "steady", "sweep", "reproduce", "audit"):
        assert run([command, "--help"]) == 0
    helps = capsys.readouterr().out
    for text in [p.read_text(encoding="utf-8") for p in texts] + [helps]:
        assert "ERRATA" not in text and "shared/" not in text
    assert "docs/errata.md" in (root / "README.md").read_text(encoding="utf-8")


def test_every_model_ingredient_on_the_command_line_reaches_the_run(tmp_path):
    """--gravity, --offset and --rotary-inertia change what simulate computes, exactly as the
    Python API does with the same options."""
    out = tmp_path / "run"
    args = ["simulate", "--elements", "2", "--steps-per-rev", "20", "--revolutions", "1",
            "--gravity", "0.2,-0.3", "--offset", "0.1", "--rotary-inertia", "off", "--quiet"]
    assert cli.main(args + ["--out", str(out)]) == 0
    with open(out / "simulation.csv") as fh:
        v_cli = [float(row["v_mid_r"]) for row in csv.DictReader(fh)]
    ref = crankgen.simulate(crankgen.Mechanism(gravity=(0.2, -0.3), offset=0.1), n_elements=2,
                            steps_per_rev=20, revolutions=1, formulation="lagrange",
                            damping="kelvin-voigt", membrane="averaged", rotary_inertia=False)
    plain = crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20, revolutions=1,
                              formulation="lagrange", damping="kelvin-voigt", membrane="averaged")
    assert v_cli == [float(x) for x in ref.v_mid]
    assert max(abs(a - b) for a, b in zip(v_cli, plain.v_mid)) > 1e-3


def test_the_command_line_starts_without_the_engine():
    """`crankgen --version` and the parser of every command import neither numba nor matplotlib
    (nor SciPy): the engine and the figures load when a command runs, so `--help` answers at once."""
    code = ("import sys; from crankgen.cli import build_parser, main; build_parser()\n"
            "try:\n    main(['--version'])\nexcept SystemExit:\n    pass\n"
            "heavy = [m for m in ('numba', 'matplotlib', 'scipy') if m in sys.modules]\n"
            "print(heavy); sys.exit(1 if heavy else 0)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
