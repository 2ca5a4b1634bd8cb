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
from crankgen import Case, ParameterError, sweep
from crankgen.cli import main
from helpers import fake_steady_states as _fake_states

sweep_mod = importlib.import_module("crankgen.analyses.sweeps")
TINY = ["--elements", "2", "--steps-per-rev", "20"]
SMALL = dict(model="paper", n_elements=2, eps=0.1, steps_per_rev=24)
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


# --- item 1: a checkpoint that is a device, a FIFO, CRLF, another version ------------------------

def test_a_device_or_fifo_checkpoint_is_refused_and_left_alone(tmp_path, capsys):
    device = _device(tmp_path / "null", 1, 3)                       # a copy of /dev/null
    assert run(["sweep", "--omega", "0.4", "--out", str(tmp_path / "o"), "--force",
                "--checkpoint", str(device), "--quiet"] + TINY) == 2
    one_line_error(capsys, str(device), "character device")
    assert stat.S_ISCHR(os.lstat(device).st_mode)                   # not deleted, not replaced
    assert not (tmp_path / "o").exists()
    with pytest.raises(ParameterError, match="checkpoint .*character device"):
        sweep([Case(**SMALL)], checkpoint=device)
    assert stat.S_ISCHR(os.lstat(device).st_mode)

    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    argv = ["sweep", "--omega", "0.4", "--out", str(tmp_path / "o"), "--checkpoint", str(fifo),
            "--quiet"] + TINY
    child = subprocess.run([sys.executable, "-m", "crankgen", *argv], capture_output=True,
                           text=True, timeout=CHILD_TIMEOUT, env=_env())   # hung before
    assert child.returncode == 2 and "FIFO" in child.stderr and "Traceback" not in child.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_crlf_checkpoint_is_read_and_another_version_refused_in_one_line(tmp_path, capsys,
                                                                             monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.4)]
    ckpt = tmp_path / "sweep.jsonl"
    sweep(cases, checkpoint=ckpt)
    crlf = tmp_path / "crlf.jsonl"
    crlf.write_bytes(ckpt.read_bytes().replace(b"\n", b"\r\n"))      # as an editor on Windows saves it
    calls.clear()
    table = sweep(cases + [Case(omega=0.5, **SMALL)], checkpoint=crlf)
    assert calls == [Case(omega=0.5, **SMALL)] and len(table) == 3  # the CRLF records are reused

    other = tmp_path / "v2.jsonl"
    other.write_text('{"format": "crankgen-sweep-checkpoint", "version": 2}\n')
    assert run(["sweep", "--omega", "0.4", "--out", str(tmp_path / "o"), "--checkpoint",
                str(other), "--quiet"] + TINY) == 2
    one_line_error(capsys, str(other), "version 2", "reads version 1")
    with pytest.raises(sweep_mod.CheckpointError, match="version 2"):
        sweep(cases, checkpoint=other)
    assert other.read_text() == '{"format": "crankgen-sweep-checkpoint", "version": 2}\n'


def test_a_checkpoint_link_is_used_inside_its_folder_and_refused_out_of_it(tmp_path, capsys,
                                                                          monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    outside = tmp_path / "outside.jsonl"
    sweep([Case(omega=0.4, eps=0.1, n_elements=2, steps_per_rev=20, damping="kelvin-voigt",
                membrane="averaged")], checkpoint=outside)
    folder = tmp_path / "f"
    folder.mkdir()
    (folder / "real.jsonl").write_bytes(outside.read_bytes())
    (folder / "link.jsonl").symlink_to("real.jsonl")
    (folder / "out.jsonl").symlink_to(outside)
    before = outside.read_bytes()
    calls.clear()
    argv = ["sweep", "--omega", "0.4,0.5", "--eps", "0.1", "--quiet"] + TINY
    assert run(argv + ["--out", str(tmp_path / "a"), "--checkpoint", str(folder / "link.jsonl")]) == 0
    assert [c.omega for c in calls] == [0.5] and (folder / "link.jsonl").is_symlink()
    assert len((folder / "real.jsonl").read_text().splitlines()) == 3        # written through
    assert run(argv + ["--out", str(tmp_path / "b"), "--checkpoint", str(folder / "out.jsonl")]) == 2
    one_line_error(capsys, str(folder / "out.jsonl"), "symbolic link", "outside")
    assert outside.read_bytes() == before


# --- item 3: a checkpoint removed while its sweep runs -------------------------------------------

def test_a_checkpoint_removed_during_the_sweep_is_recreated_with_its_header(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.4, 0.5, 0.6)]
    ckpt = tmp_path / "sweep.jsonl"

    def remove_after_the_first(done, total):
        if done == 1:
            ckpt.unlink()
    with pytest.warns(RuntimeWarning, match="removed during the sweep"):
        sweep(cases, checkpoint=ckpt, batch_size=1, progress=remove_after_the_first)
    lines = ckpt.read_text().splitlines()
    assert json.loads(lines[0]) == {"format": "crankgen-sweep-checkpoint", "version": 1}
    assert sorted(json.loads(line)["key"] for line in lines[1:]) == sorted(c.key() for c in cases)
    calls.clear()
    assert run(["sweep", "--omega", "0.3,0.4,0.5,0.6", "--eps", "0.1", "--model", "paper",
                "--steps-per-rev", "24", "--elements", "2", "--out", str(tmp_path / "o"),
                "--checkpoint", str(ckpt), "--quiet", "--approach", "A"]) == 0   # refused before
    assert calls == []                                              # everything from the file


# --- item 4: a lock on the checkpoint -----------------------------------------------------------

READER = """
import sys, crankgen
from crankgen import Case
for cases in ([], [Case(omega=0.9, model="paper", n_elements=2, eps=0.1, steps_per_rev=24)]):
    try:
        crankgen.sweep(cases, checkpoint=sys.argv[1])
        print("opened")
    except crankgen.analyses.sweeps.CheckpointError as exc:
        print("refused:", exc)
"""


def test_another_process_cannot_repair_or_share_a_checkpoint_being_written(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    ckpt = tmp_path / "sweep.jsonl"
    seen = {}

    def meanwhile(done, total):
        if done != 1:
            return
        size = ckpt.stat().st_size
        with open(ckpt, "ab") as fh:                   # a record still being written ...
            fh.write(b'{"key": "half a rec')
        child = subprocess.run([sys.executable, "-c", READER, str(ckpt)], capture_output=True,
                               text=True, timeout=CHILD_TIMEOUT, env=_env())
        seen["out"], seen["grown"] = child.stdout, ckpt.stat().st_size - size
        os.truncate(ckpt, size)                        # ... (this test finishes it off)
    sweep([Case(omega=w, **SMALL) for w in (0.3, 0.4)], checkpoint=ckpt, batch_size=1,
          progress=meanwhile)
    lines = seen["out"].splitlines()
    assert len(lines) == 2, seen["out"]
    for line in lines:                                 # the reader and the second sweep: refused
        assert line.startswith("refused:") and f"process {os.getpid()}" in line, line
    assert seen["grown"] == len('{"key": "half a rec')              # nothing truncated
    assert not (tmp_path / "sweep.jsonl.lock").exists()
    assert len(ckpt.read_text().splitlines()) == 3                  # header + both records


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


# --- item 9: pool workers die with their parent ---------------------------------------------------

POOL = """
import os, signal, sys
from crankgen.analyses import pool_workers, sweeps
from crankgen.cli import main
if sys.argv[2] == "watchdog":                       # the portable fallback alone
    pool_workers._set_parent_death_signal = lambda signum: False
parent = os.getpid()

def hold(cases, *args):                             # a worker: say who it is, then keep working
    if os.getpid() != parent:
        os.write(1, f"worker {os.getpid()}\\n".encode())
        while True:
            signal.pause()
    raise AssertionError("no chunk runs in the parent")
sweeps._run_chunk = hold
sys.exit(main(["sweep", "--omega", "0.2,0.3,0.4,0.5", "--batch-size", "1", "--workers", "2",
               "--elements", "2", "--steps-per-rev", "20", "--out", sys.argv[1], "--quiet"]))
"""


@pytest.mark.parametrize("signum, death", [(signal.SIGKILL, "prctl"), (signal.SIGKILL, "watchdog"),
                                           (signal.SIGTERM, "prctl")])
def test_pool_workers_die_with_the_sweep(tmp_path, signum, death):
    proc = subprocess.Popen([sys.executable, "-c", POOL, str(tmp_path / "o"), death],
                            stdout=subprocess.PIPE, stderr=open(tmp_path / "stderr", "wb"),
                            start_new_session=True, env=_env())
    workers = set()
    try:
        while len(workers) < 2:
            line = proc.stdout.readline()
            assert line.startswith(b"worker "), (line, (tmp_path / "stderr").read_text())
            workers.add(int(line.split()[1]))
        os.kill(proc.pid, signum)
        proc.wait(timeout=CHILD_TIMEOUT)
        # Every worker holds the pipe's write end: EOF means all of them have exited.
        reader = threading.Thread(target=proc.stdout.read, daemon=True)
        reader.start()
        reader.join(CHILD_TIMEOUT)
        assert not reader.is_alive(), f"orphaned workers {workers} still alive"
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)       # this test's process group only
        proc.stdout.close()
    assert proc.returncode == (143 if signum == signal.SIGTERM else -signal.SIGKILL)
    if signum == signal.SIGTERM:
        assert "terminated" in (tmp_path / "stderr").read_text()


# --- item 10: bounded work and memory, checked before computing ---------------------------------

def test_runs_too_large_for_the_machine_are_refused_before_computing(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("CRANKGEN_MEMORY_LIMIT", "64G")
    out = tmp_path / "o"
    assert run(["simulate", "--revolutions", "1e12", "--out", str(out)]) == 2
    one_line_error(capsys, "--revolutions", "PiB", "64 GiB")
    assert run(["simulate", "--elements", "1000000000", "--out", str(out)]) == 2
    one_line_error(capsys, "--elements", "3000000000 degrees of freedom", "iB")
    assert run(["sweep", "--omega", "0.001:100:0.001", "--eps", "0.001:1:0.001",
                "--out", str(out)]) == 2                     # 10^8 cases: the grid is never built
    one_line_error(capsys, "100000000 cases", "--omega (100000)", "--eps (1000)", "GiB")
    assert not out.exists()

    from crankgen.analyses.limits import check_run_size
    with pytest.raises(ParameterError, match=r"^revolutions x n_elements: .* (TiB|PiB)"):
        check_run_size(16, 10**12, names={"n_steps": "revolutions"})
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    with pytest.raises(ParameterError, match=r"^n_elements .*: 20000 elements .*GiB"):
        sweep([Case(n_elements=20000)])
    assert calls == []


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


# --- item 14: misuse of the Python API ----------------------------------------------------------

def test_api_misuse_gets_a_parameter_error_or_the_documented_fallback(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.4)]
    pool = cf.ProcessPoolExecutor(1)
    pool.shutdown()
    with pytest.warns(RuntimeWarning, match=r"2 case\(s\) were not finished.*after shutdown"):
        assert len(sweep(cases, executor=pool, batch_size=1)) == 2
    assert calls == cases
    distributed = pytest.importorskip("distributed")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        client = distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                                    dashboard_address=None)
        executor = client.get_executor()
        client.close()
    with pytest.warns(RuntimeWarning, match="not finished by the executor.*ClosedClientError"):
        assert len(sweep(cases, executor=executor)) == 2
    with pytest.raises(ParameterError, match="^executor must be"):
        sweep(cases, executor="dask")
    with pytest.raises(ParameterError, match="^checkpoint .*is a folder"):
        sweep(cases, checkpoint=tmp_path)
    with pytest.raises(ParameterError, match="^values must be a sequence"):
        crankgen.poincare(values=0.8)
    with pytest.raises(ParameterError, match="^case must be None or a crankgen.Case"):
        crankgen.continuation(case="x")


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


# --- issue 18, item 13: checkpoint per small batch; a true interrupt message; extending ----------

def test_an_interrupted_sweep_keeps_every_finished_batch_and_says_so(tmp_path, capsys, monkeypatch):
    calls = []
    fake = _fake_states(calls)
    monkeypatch.setattr(sweep_mod, "steady_states", fake)
    grid = ["sweep", "--omega", "0.2:1.1:0.1", "--eps", "0.1", "--out", str(tmp_path / "o"),
            "--quiet"] + TINY                                          # 10 cases, default batch

    def interrupted(cases, **kwargs):
        if calls:                                                      # the second batch
            raise KeyboardInterrupt
        return fake(cases, **kwargs)
    monkeypatch.setattr(sweep_mod, "steady_states", interrupted)
    assert run(grid) == 130
    err = capsys.readouterr().err
    assert "8 of 10 cases are recorded" in err and "sweep.jsonl" in err
    assert len((tmp_path / "o" / "sweep.jsonl").read_text().splitlines()) == 1 + 8

    calls.clear()
    monkeypatch.setattr(sweep_mod, "steady_states", lambda cases, **kw: (_ for _ in ()).throw(
        KeyboardInterrupt))
    assert run(["sweep", "--omega", "0.2:1.1:0.1", "--eps", "0.1", "--out", str(tmp_path / "p"),
                "--quiet"] + TINY) == 130
    assert "nothing new was recorded" in capsys.readouterr().err

    monkeypatch.setattr(sweep_mod, "steady_states", fake)
    assert run(grid) == 0 and len(calls) == 2                        # resumed: the last two
    calls.clear()
    more = ["sweep", "--omega", "0.2:1.3:0.1", "--eps", "0.1", "--out", str(tmp_path / "o"),
            "--quiet", "--force"] + TINY
    assert run(more) == 0 and sorted(c.omega for c in calls) == [1.2, 1.3]   # extended, reused


# --- issue 18, item 12 (part): an empty --out ---------------------------------------------------

def test_an_empty_out_is_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert run(["simulate", "--out", "", "--quiet"]) == 2
    one_line_error(capsys, "empty")
    assert run(["sweep", "--out", " ", "--quiet"]) == 2
    one_line_error(capsys, "empty")
    assert list(tmp_path.iterdir()) == []
