"""crankgen.sweep: tidy table, executors (process pool, real Dask cluster), failures, checkpoints."""

import os
import concurrent.futures as cf
import csv
import importlib
import json
import math

import numpy as np
import pytest

import crankgen
from crankgen import Case, ParameterError, SteadyState, SweepTable, sweep

# `crankgen.sweep` is the function; the module is reached through sys.modules.
sweep_mod = importlib.import_module("crankgen.analyses.sweeps")

SMALL = dict(formulation="paper", n_elements=2, mu=0.5)
# Mixed approaches in an order the structural grouping of chunks changes, so the tests also check
# that the table comes back in input order.
CASES = [
    Case(omega=0.3, eps=0.1, approach="C", steps_per_rev=24, **SMALL),
    Case(omega=0.5, eps=0.1, approach="A", steps_per_rev=24, **SMALL),
    Case(omega=0.5, eps=0.05, approach="C", steps_per_rev=24, **SMALL),
    Case(omega=0.8, eps=0.1, approach="A", steps_per_rev=24, **SMALL),
    Case(omega=0.8, eps=0.1, approach="C", steps_per_rev=32, **SMALL),
    Case(omega=0.3, eps=0.05, approach="C", steps_per_rev=40, **SMALL),
]
# Diverges: Newton fails within the first revolution.
DIVERGING = Case(formulation="lagrange", approach="B", omega=0.8, n_elements=4)


def _same(a, b):
    """Rows equal, as the checkpoint's JSON writes them."""
    return json.dumps(list(a)) == json.dumps(list(b))


def _without_wall_time(rows):
    return [{k: v for k, v in row.items() if k != "wall_time"} for row in rows]


@pytest.fixture(scope="module")
def reference():
    """Uninterrupted local sweep of CASES (several chunks)."""
    calls = []
    table = sweep(CASES, batch_size=4, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(4, 6), (6, 6)]
    return table


def _fake_states(calls, raise_for=()):
    """Stand-in for steady_states: instant synthetic results; raises for cases with omega in
    raise_for; records every case it is given."""
    def fake(cases, tol=1e-8, max_revolutions=400, progress=None, parallel=None):
        cases = list(cases)
        calls.extend(cases)
        if any(c.omega in raise_for for c in cases):
            raise RuntimeError("boom")
        return [SteadyState(c, "periodic", 2 * c.omega, c.omega, 3, 0, 1e-9, "", 0.01) for c in cases]
    return fake


def _counting(calls):
    """Real steady_states, recording every case it is given."""
    real = crankgen.steady_states

    def counted(cases, **kwargs):
        cases = list(cases)
        calls.extend(cases)
        return real(cases, **kwargs)
    return counted


# --- local sweeps ---------------------------------------------------------------------------

def test_local_sweep_rows_in_input_order_match_steady_state(reference):
    assert isinstance(reference, SweepTable) and len(reference) == len(CASES)
    assert reference.cases == CASES
    assert [Case.from_dict(row) for row in reference] == CASES
    for row, case in zip(reference, CASES):
        direct = crankgen.steady_state(case=case)
        assert row["status"] == "periodic" == direct.status
        assert row["amplitude"] == direct.amplitude
        assert row["half_peak_to_peak"] == direct.half_peak_to_peak
        assert row["periods"] == direct.periods and row["wall_time"] > 0
    amp = reference.column("amplitude")
    assert amp.dtype == float and amp.shape == (len(CASES),) and np.all(amp > 0)
    assert list(reference.column("approach")) == [c.approach for c in CASES]
    assert reference.failed == []
    for name in ("omega", "eps", "status", "amplitude", "periods", "wall_time", "message"):
        assert name in reference.columns
    with pytest.raises(KeyError):
        reference.column("nope")


def test_diverging_case_is_reported_and_does_not_sink_the_others(reference):
    cases = CASES[:2] + [DIVERGING] + CASES[2:3]
    table = sweep(cases, batch_size=64)                       # all in one chunk
    assert [row["status"] for row in table] == ["periodic", "periodic", "failed", "periodic"]
    bad = table[2]
    assert "Newton did not converge" in bad["message"] and bad["amplitude"] is None
    assert table.failed == [bad]
    assert _without_wall_time(table.rows[:2] + table.rows[3:]) == _without_wall_time(
        reference.rows[:3])


def test_a_raising_chunk_is_rerun_case_by_case(monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls, raise_for={0.5}))
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.5, 0.8)]
    table = sweep(cases, batch_size=3)
    assert [row["status"] for row in table] == ["periodic", "failed", "periodic"]
    assert table[1]["message"] == "RuntimeError: boom"
    assert table[0]["amplitude"] == 0.6 and table[2]["amplitude"] == 1.6


class FlakyExecutor(cf.Executor):
    """Runs tasks at once in this process; the task of any chunk holding omega=0.5 'dies'
    (its future raises, as when a worker is lost)."""

    def submit(self, fn, *args, **kwargs):
        future = cf.Future()
        if any(case.omega == 0.5 for case in args[0]):
            future.set_exception(OSError("worker died"))
        else:
            future.set_result(fn(*args, **kwargs))
        return future


def test_a_failed_future_is_not_a_result_its_chunk_is_rerun_here(monkeypatch, tmp_path):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.4, 0.5, 0.6, 0.7)]
    ckpt = tmp_path / "sweep.jsonl"
    with pytest.warns(RuntimeWarning, match=r"2 case\(s\) were not finished.*OSError: worker died"):
        table = sweep(cases, executor=FlakyExecutor(), batch_size=2,   # chunks (.3 .4) (.5 .6) (.7)
                      checkpoint=ckpt)
    assert [row["status"] for row in table] == ["periodic"] * 5 and table.failed == []
    assert [row["amplitude"] for row in table] == [2 * c.omega for c in cases]
    assert calls[-2:] == cases[2:4]                     # the lost chunk, run again in this process
    rows = [json.loads(line)["row"] for line in ckpt.read_text().splitlines()[1:]]
    assert len(rows) == 5 and all(r["status"] == "periodic" for r in rows)


def test_bad_case_raises_before_any_work(monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    good = CASES[0].as_dict()
    for bad, name in (({"omega": -1.0}, "omega"), ({"approach": "D"}, "approach"),
                      ({"n_elements": 0}, "n_elements"), ({"eps": "thin"}, "")):
        with pytest.raises(ParameterError) as exc:
            sweep([good, dict(good, **bad)])
        assert str(exc.value).startswith(f"cases[1]: {name}")
    with pytest.raises(TypeError):
        sweep([good, 42])
    with pytest.raises(TypeError):
        sweep(CASES[0])
    with pytest.raises(ParameterError):
        sweep([good], batch_size=0)
    assert calls == []


def test_dicts_duplicates_and_empty_input(monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    a, b = Case(omega=0.3, **SMALL), Case(omega=0.4, **SMALL)
    table = sweep([a.as_dict(), b, a])
    assert table.cases == [a, b, a] and calls == [a, b]            # the duplicate ran once
    empty = sweep([])
    assert len(empty) == 0 and "amplitude" in empty.columns and empty.column("amplitude").size == 0


# --- executors --------------------------------------------------------------------------------

def test_process_pool_gives_the_local_table(reference):
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        table = sweep(CASES, executor=pool, batch_size=2)
    assert _without_wall_time(table.rows) == _without_wall_time(reference.rows)


def test_real_local_dask_cluster_gives_the_local_amplitudes(reference, tmp_path):
    distributed = pytest.importorskip(
        "distributed", reason="dask.distributed is not installed (pip install 'dask[distributed]')")
    import dask
    # dask's own deadlines (30 s to connect) are hang guards, not part of the test: on a loaded
    # machine a worker can take longer to start, so they are made long enough never to decide it;
    # the scheduler's and the workers' scratch space is the test's own folder
    slow_ok = {"distributed.comm.timeouts.connect": "900s", "distributed.comm.timeouts.tcp": "900s",
               "distributed.deploy.lost-worker-timeout": "900s", "temporary-directory": str(tmp_path)}
    with dask.config.set(slow_ok), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=None, local_directory=str(tmp_path),
                                     death_timeout=900) as cluster, \
            distributed.Client(cluster, timeout=900) as client:
        with distributed.get_task_stream(client) as stream:
            table = sweep(CASES, executor=client.get_executor(), batch_size=2)
        pids = client.run(lambda: __import__("os").getpid())
    ran = [t for t in stream.data if "_run_chunk" in t["key"]]
    assert len(ran) == 3 and {t["worker"] for t in ran} <= set(pids)   # on the cluster's workers
    np.testing.assert_array_equal(table.column("amplitude"), reference.column("amplitude"))
    assert _without_wall_time(table.rows) == _without_wall_time(reference.rows)


# --- checkpoints ------------------------------------------------------------------------------

class Interrupt(KeyboardInterrupt):
    pass


def test_interrupted_sweep_resumes_without_recomputing(tmp_path, monkeypatch, reference):
    ckpt = tmp_path / "sweep.jsonl"

    def stop_after_first_chunk(done, total):
        raise Interrupt

    with pytest.raises(Interrupt):
        sweep(CASES, checkpoint=ckpt, batch_size=2, progress=stop_after_first_chunk)
    lines = ckpt.read_text().splitlines()
    assert len(lines) == 1 + 2                                 # header + the first chunk
    first = {json.loads(line)["key"]: json.loads(line)["row"] for line in lines[1:]}
    # A crash while the next chunk was being written leaves a torn line behind.
    with open(ckpt, "a") as fh:
        fh.write(lines[1][: len(lines[1]) // 2])

    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _counting(calls))
    progress = []
    with pytest.warns(RuntimeWarning, match="torn last line"):
        table = sweep(CASES, checkpoint=ckpt, batch_size=2,
                      progress=lambda done, total: progress.append(done))
    assert len(calls) == len(CASES) - 2                        # the finished two were not rerun
    assert {c.key() for c in calls}.isdisjoint(first)
    assert progress[0] == 2 and progress[-1] == len(CASES)
    for case, row in zip(CASES, table):
        if case.key() in first:
            assert row == first[case.key()]                    # wall_time and all: from the file
    assert _without_wall_time(table.rows) == _without_wall_time(reference.rows)
    records = [json.loads(line) for line in ckpt.read_text().splitlines()]   # tail repaired
    assert len(records) == 1 + len(CASES)

    calls.clear()
    again = sweep(CASES, checkpoint=ckpt, batch_size=2)
    assert calls == [] and again.rows == table.rows            # everything from the checkpoint


def test_failed_cases_are_checkpointed_and_retried_only_on_request(tmp_path, monkeypatch):
    ckpt = tmp_path / "sweep.jsonl"
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.5, 0.8)]
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls, raise_for={0.5}))
    first = sweep(cases, checkpoint=ckpt)
    assert [r["status"] for r in first] == ["periodic", "failed", "periodic"]

    calls.clear()
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    assert _same(sweep(cases, checkpoint=ckpt), first) and calls == []
    retried = sweep(cases, checkpoint=ckpt, retry_failed=True)
    assert calls == [cases[1]] and retried.failed == []
    calls.clear()
    with pytest.warns(RuntimeWarning, match="other settings"):
        sweep(cases, checkpoint=ckpt, tol=1e-6)                # another tol: nothing reused
    assert calls == cases


def test_a_foreign_file_is_not_taken_for_a_checkpoint(tmp_path):
    path = tmp_path / "results.csv"
    path.write_text("omega,amplitude\n0.8,1.2\n")
    with pytest.raises(ValueError, match="not a crankgen sweep checkpoint"):
        sweep(CASES[:1], checkpoint=path)
    assert path.read_text() == "omega,amplitude\n0.8,1.2\n"


# --- CSV --------------------------------------------------------------------------------------

def test_to_csv_round_trips(tmp_path, reference):
    path = tmp_path / "sweep.csv"
    reference.to_csv(path)
    with open(path, newline="") as fh:
        back = list(csv.DictReader(fh))
    assert list(back[0]) == reference.columns and len(back) == len(reference)
    for row, original in zip(back, reference):
        assert Case.from_dict(row) == Case.from_dict(original)
        for name in ("amplitude", "half_peak_to_peak", "residual", "wall_time"):
            assert float(row[name]) == original[name]          # full precision
        assert int(row["periods"]) == original["periods"] and row["status"] == original["status"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sweep.csv"]   # no temp file left


def test_to_csv_is_atomic(tmp_path, monkeypatch, reference):
    path = tmp_path / "sweep.csv"
    path.write_text("previous table\n")

    def crash(fd):
        raise OSError("disk full")

    monkeypatch.setattr(os, "fsync", crash)          # fails after the rows are written
    with pytest.raises(OSError, match="disk full"):
        reference.to_csv(path)
    assert path.read_text() == "previous table\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sweep.csv"]
