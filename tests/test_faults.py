"""Durability, second battery (issue 20; and issue 18's sweep batches and empty --out): each test
reproduces one fault as the operator met it.  Everything happens in the test's own temporary
folder: devices and FIFOs are made there (mknod, mkfifo), never the real /dev/null; a full disk is
a device made there (/dev/full's numbers) or a file-size limit (RLIMIT_FSIZE) of this process."""

import concurrent.futures as cf
import contextlib
import errno
import importlib
import json
import os
import resource
import signal
import stat
import subprocess
import sys
import threading
import warnings

import pytest

import crankgen
from crankgen import Case, ParameterError, SteadyState, sweep
from crankgen.cli import main

sweep_mod = importlib.import_module("crankgen.sweeps")
TINY = ["--elements", "2", "--steps-per-rev", "20"]
SMALL = dict(formulation="paper", n_elements=2, eps=0.1, steps_per_rev=24)
CHILD_TIMEOUT = 300          # seconds: a safety net for a child that hangs, never a wait for it


def run(argv):
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


def one_line_error(capsys, *words):
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    for w in words:
        assert w in lines[0], lines[0]
    assert ".tmp" not in lines[0], lines[0]
    return lines[0]


def _fake_states(calls):
    def fake(cases, tol=1e-8, max_revolutions=400, progress=None, parallel=None):
        cases = list(cases)
        calls.extend(cases)
        return [SteadyState(c, "periodic", 2 * c.omega, c.omega, 3, 0, 1e-9, "", 0.01) for c in cases]
    return fake


def _device(path, major, minor):
    """A character device node at path (as /dev/null is 1,3 and /dev/full 1,7), or skip."""
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(major, minor))
    except (PermissionError, OSError) as exc:
        pytest.skip(f"cannot make a device node here: {exc}")
    return path


@contextlib.contextmanager
def file_size_limit(limit):
    """Writes beyond `limit` bytes fail with EFBIG in this process, as on a full disk."""
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    previous = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (limit, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (soft, hard))
        signal.signal(signal.SIGXFSZ, previous)


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    return env


# --- item 5: SimulationResult.to_csv on a full disk ----------------------------------------------

def test_simulation_to_csv_on_a_full_disk_keeps_the_old_file(tmp_path):
    import numpy as np
    n = 2000
    t = np.linspace(0.0, 10.0, n)
    res = crankgen.SimulationResult(t=t, theta=t, v_mid=np.sin(t), u_end=np.cos(t), extension=t,
                                    iterations=np.ones(n - 1, dtype=np.int32), settings={})
    path = tmp_path / "run.csv"
    path.write_text("t,theta,v_mid,u_end,extension\n0.0,0.0,0.0,0.0,0.0\n")
    old = path.read_text()
    with file_size_limit(8192), pytest.raises(OSError) as exc:
        res.to_csv(path)
    assert path.read_text() == old                                  # not a truncated CSV
    assert str(path) in str(exc.value) and ".tmp" not in str(exc.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv"]
    res.to_csv(path)
    assert len(path.read_text().splitlines()) == n + 1


# --- item 10: bounded work and memory, checked before computing ---------------------------------

def test_runs_too_large_for_the_machine_are_refused_before_computing(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("CRANKGEN_MEMORY_LIMIT", "64G")
    out = tmp_path / "o"
    assert run(["simulate", "--revolutions", "1e12", "--out", str(out)]) == 2
    one_line_error(capsys, "--revolutions", "PiB", "64 GiB")
    assert run(["simulate", "--elements", "1000000000", "--out", str(out)]) == 2
    one_line_error(capsys, "--elements", "3000000000 degrees of freedom", "TiB")
    assert run(["sweep", "--omega", "0.001:100:0.001", "--eps", "0.001:1:0.001",
                "--out", str(out)]) == 2                     # 10^8 cases: the grid is never built
    one_line_error(capsys, "100000000 cases", "--omega (100000)", "--eps (1000)", "GiB")
    assert not out.exists()

    from crankgen.limits import check_run_size
    with pytest.raises(ParameterError, match=r"^revolutions x n_elements: .* TiB"):
        check_run_size(16, 10**12, names={"n_steps": "revolutions"})


# --- item 11: progress output is best effort ---------------------------------------------------

class FullDisk:
    """A text stream on a full disk: every write fails with ENOSPC."""

    def write(self, text):
        raise OSError(errno.ENOSPC, "No space left on device")

    def flush(self):
        pass

    def isatty(self):
        return False


def test_a_full_disk_behind_stdout_and_stderr_never_stops_a_run(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "stdout", FullDisk())
    monkeypatch.setattr(sys, "stderr", FullDisk())
    assert run(["simulate", "--revolutions", "1", "--out", str(tmp_path / "s")] + TINY) == 0
    assert (tmp_path / "s" / "simulation.csv").exists() and (tmp_path / "s" / "v_mid.png").exists()
    assert run(["sweep", "--omega", "0.3,0.4", "--out", str(tmp_path / "w")] + TINY) == 0
    assert (tmp_path / "w" / "sweep.csv").exists()
    monkeypatch.undo()

    full = _device(tmp_path / "full", 1, 7)                         # a copy of /dev/full
    with open(full, "wb") as sink:
        child = subprocess.run([sys.executable, "-m", "crankgen", "simulate", "--revolutions", "1",
                                "--out", str(tmp_path / "c")] + TINY, stdout=sink, stderr=sink,
                               timeout=CHILD_TIMEOUT, env=_env())
    assert child.returncode == 0 and (tmp_path / "c" / "simulation.csv").exists()


# --- item 13: negative values on the command line -----------------------------------------------

def test_negative_numbers_lists_and_ranges_are_option_values():
    parser = crankgen.cli.build_parser()
    args = parser.parse_args(["simulate", "--gravity", "-1e-3,0", "--offset", "-5e-2"])
    assert args.gravity == (-1e-3, 0.0) and args.offset == -5e-2
    args = parser.parse_args(["sweep", "--offset", "-0.05,0.05", "--omega", "0.5"])
    assert args.offset == [-0.05, 0.05]
    assert parser.parse_args(["sweep", "--offset", "-0.1:0:0.05"]).offset == [-0.1, -0.05, 0.0]
    assert parser.parse_args(["simulate", "--offset", "-.05", "--quiet"]).quiet
    with pytest.raises(SystemExit):                  # a real option name is still an option
        parser.parse_args(["simulate", "--offset", "--quiet"])


# --- item 15: every message names the user's file, checked before computing ----------------------

def test_messages_name_the_users_file_never_a_temporary_one(tmp_path, capsys):
    out = tmp_path / "r"
    (out / "manifest.json").mkdir(parents=True)
    assert run(["reproduce", "--quick", "--quiet", "--force", "--out", str(out)]) == 2   # before computing
    one_line_error(capsys, str(out / "manifest.json"), "is a folder")
    (out / "manifest.json").rmdir()
    (out / "data").write_text("a file where the data folder goes")
    assert run(["reproduce", "--quick", "--quiet", "--out", str(out)]) == 2
    one_line_error(capsys, str(out / "data"), "is a file")

    elsewhere = tmp_path / "elsewhere.csv"
    elsewhere.write_text("keep me")
    s = tmp_path / "s"
    s.mkdir()
    (s / "simulation.csv").symlink_to(elsewhere)
    assert run(["simulate", "--revolutions", "1", "--out", str(s), "--force", "--quiet"] + TINY) == 2
    one_line_error(capsys, str(s / "simulation.csv"), "symbolic link", "outside")
    assert elsewhere.read_text() == "keep me"

    with file_size_limit(20000):                     # the PNG does not fit: a full disk, mid-run
        code = run(["simulate", "--revolutions", "1", "--out", str(tmp_path / "f"), "--quiet"] + TINY)
    assert code == 1
    one_line_error(capsys, str(tmp_path / "f" / "v_mid.png"), "File too large")


# --- issue 18, item 12 (part): an empty --out ---------------------------------------------------

def test_an_empty_out_is_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert run(["simulate", "--out", "", "--quiet"]) == 2
    one_line_error(capsys, "empty")
    assert run(["sweep", "--out", " ", "--quiet"]) == 2
    one_line_error(capsys, "empty")
    assert list(tmp_path.iterdir()) == []
