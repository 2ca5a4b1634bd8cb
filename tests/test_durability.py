"""Durability under faults (issue 12): a killed pool worker, missing values, tiny crank speeds,
canonical case keys and versioned checkpoint records."""

import concurrent.futures as cf
import csv
import importlib
import json
import math
import multiprocessing
import os
import signal
import warnings

import numpy as np
import pytest

import crankgen
from crankgen import Case, ParameterError, engine, sweep
from crankgen.results.provenance import code_version
from helpers import fake_steady_states as _fake_states

sweep_mod = importlib.import_module("crankgen.analyses.sweeps")

SMALL = dict(formulation="paper", n_elements=2, eps=0.1, steps_per_rev=24)
CASES = [Case(omega=w, approach=ap, **SMALL) for w in (0.3, 0.5, 0.8) for ap in ("A", "C")]
# Newton fails within the first revolution (as in test_sweep).
DIVERGING = Case(formulation="lagrange", approach="B", omega=0.8, n_elements=4)


def _without_wall_time(rows):
    return [{k: v for k, v in row.items() if k != "wall_time"} for row in rows]


def _strict(line):
    """json.loads that rejects NaN and Infinity, as strict JSON readers do."""
    def refuse(name):
        raise ValueError(f"non-standard JSON constant {name}")
    return json.loads(line, parse_constant=refuse)


# --- D1: a killed pool worker is not a failed case ---------------------------------------------

def _killing_states(real, marker, parent):
    """steady_states that SIGKILLs the pool worker running omega = 0.5 (once: the first worker
    that creates `marker`); never kills the parent process."""
    def states(cases, **kwargs):
        cases = list(cases)
        if os.getpid() != parent and any(c.omega == 0.5 for c in cases):
            try:
                os.close(os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
            except FileExistsError:
                pass
            else:
                os.kill(os.getpid(), signal.SIGKILL)
        return real(cases, **kwargs)
    return states


def test_a_killed_pool_worker_is_rerun_and_never_recorded(tmp_path, monkeypatch):
    reference = sweep(CASES)                                       # uninterrupted, in this process
    assert [r["status"] for r in reference] == ["periodic"] * len(CASES)

    marker, ckpt = tmp_path / "killed", tmp_path / "sweep.jsonl"
    monkeypatch.setattr(sweep_mod, "steady_states",
                        _killing_states(crankgen.steady_states, str(marker), os.getpid()))
    # fork: the workers inherit the patched module (the kill happens inside a real worker)
    with cf.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("fork")) as pool, \
            warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = sweep(CASES, executor=pool, batch_size=1, checkpoint=ckpt)
    assert marker.exists()                                         # a worker really died
    assert _without_wall_time(table.rows) == _without_wall_time(reference.rows)
    assert any(issubclass(w.category, RuntimeWarning) and "BrokenProcessPool" in str(w.message)
               and "not finished by the executor" in str(w.message) for w in caught)

    records = [_strict(line) for line in ckpt.read_text().splitlines()[1:]]
    assert sorted(r["key"] for r in records) == sorted(c.key() for c in CASES)   # each once
    assert all(r["row"]["status"] == "periodic" and "Broken" not in r["row"]["message"]
               for r in records)

    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    again = sweep(CASES, checkpoint=ckpt)                          # resume: all from the file
    assert calls == [] and _without_wall_time(again.rows) == _without_wall_time(reference.rows)


def test_an_executor_broken_before_the_sweep_runs_everything_here(monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))

    class Broken(cf.Executor):
        def submit(self, fn, *args, **kwargs):
            raise cf.BrokenExecutor("pool is broken")

    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.4, 0.5)]
    with pytest.warns(RuntimeWarning, match=r"3 case\(s\) were not finished"):
        table = sweep(cases, executor=Broken(), batch_size=1)
    assert table.failed == [] and calls == cases


# --- D3: no NaN or inf anywhere; a missing number is None / an empty field / null --------------

def test_a_failed_steady_state_holds_none_not_nan():
    s = crankgen.steady_state(case=DIVERGING)
    assert s.status == "failed" and "Newton did not converge" in s.message
    assert s.amplitude is None and s.half_peak_to_peak is None
    assert s.residual is None and s.multiplier is None
    assert all(v is None or not isinstance(v, float) or math.isfinite(v) for v in s.row().values())


def test_failed_rows_are_empty_in_csv_and_null_in_a_strict_json_checkpoint(tmp_path):
    ckpt, path = tmp_path / "sweep.jsonl", tmp_path / "sweep.csv"
    table = sweep([CASES[0], DIVERGING], checkpoint=ckpt)
    assert [r["status"] for r in table] == ["periodic", "failed"]
    bad = table[1]
    for name in ("amplitude", "half_peak_to_peak", "residual", "multiplier"):
        assert bad[name] is None
    amp = table.column("amplitude")
    assert np.ma.is_masked(amp) and list(amp.mask) == [False, True]
    assert np.all(np.isfinite(amp.data)) and amp[0] == table[0]["amplitude"]

    records = [_strict(line) for line in ckpt.read_text().splitlines()]   # strict JSON throughout
    failed = {r["key"]: r["row"] for r in records[1:]}[DIVERGING.key()]
    assert failed["amplitude"] is None and failed["status"] == "failed"

    table.to_csv(path)
    with open(path, newline="") as fh:
        fields = [x.strip().lower() for row in csv.reader(fh) for x in row]
    assert not {"nan", "inf", "-inf", "+inf", "infinity"} & set(fields)
    with open(path, newline="") as fh:
        back = list(csv.DictReader(fh))
    assert back[1]["amplitude"] == back[1]["multiplier"] == "" and back[1]["status"] == "failed"
    assert float(back[0]["amplitude"]) == table[0]["amplitude"]


def test_nan_in_an_old_checkpoint_is_read_as_missing(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    case = Case(omega=0.3, **SMALL)
    row = dict(case.as_dict(), status="failed", amplitude=math.nan, half_peak_to_peak=math.nan,
               periods=0, iterations=0, residual=math.nan, multiplier=math.nan, wall_time=0.0,
               message="RuntimeError: old")
    ckpt = tmp_path / "old.jsonl"            # as written before: bare NaN, no "code"
    ckpt.write_text('{"format": "crankgen-sweep-checkpoint", "version": 1}\n' + json.dumps(
        {"key": case.key(), "settings": {"tol": 1e-8, "max_revolutions": 400}, "row": row}) + "\n")
    assert "NaN" in ckpt.read_text()
    table = sweep([case], checkpoint=ckpt, keep_other_versions=True)
    assert calls == [] and table[0]["status"] == "failed" and table[0]["amplitude"] is None
    assert table[0]["multiplier"] is None


def _decay_rate(state, case, revolutions=8):
    """Observed per-revolution contraction of a small perturbation of a periodic state: march the
    state and a perturbed copy side by side, geometric mean of the ratio over revolutions 3-8."""
    batch = engine.Batch([case, case])
    size = batch.state_size                      # (d, v), or (d, v, a) for generalized-alpha
    S = np.concatenate([batch.scales[0]] * (size // batch.N))
    Y = np.stack([state, state + 1e-6 * S * np.random.default_rng(1).standard_normal(size)])
    dev = []
    for _ in range(revolutions):
        r = engine.march_state(batch, batch.steps_per_rev, Y)
        assert np.all(r.status == engine.OK)
        Y = engine.join_state(r, size == 3 * batch.N)
        dev.append(np.max(np.abs(Y[1] - Y[0]) / S))
    return (dev[-1] / dev[2]) ** (1 / (revolutions - 3))


@pytest.mark.parametrize("integrator, method", [("newton", "march"), ("full-newton", "shooting")])
def test_a_marched_periodic_state_reports_its_floquet_multiplier(integrator, method):
    # full-newton is not shot: its steady state is found by marching either way.  Newmark: its
    # dominant multiplier here is real (0.87), so the marched decay measures it (generalized-alpha's
    # are complex pairs of the rod's damped vibration, whose max-norm decay rotates)
    case = Case(omega=0.3, approach="A", integrator=integrator, rho_inf=1.0, **SMALL)
    s = crankgen.steady_states([case], method=method)[0]
    assert s.status == "periodic" and s.iterations == 0          # found by marching
    assert isinstance(s.multiplier, float) and 0 < s.multiplier < 1
    assert s.multiplier == pytest.approx(_decay_rate(s.state, case), rel=1e-3)


def test_one_pass_multiplier_is_none_with_the_reason():
    s = crankgen.steady_state(case=Case(omega=0.3, approach="A", integrator="one-pass", **SMALL))
    assert s.status == "periodic" and s.amplitude > 0
    assert s.multiplier is None and "multiplier not computed" in s.message


# --- D8: a time step longer than the rod's first bending period is refused ---------------------

def test_tiny_crank_speed_is_refused_with_the_limit():
    kw = dict(n_elements=4, damping="kelvin-voigt", membrane="averaged")
    with pytest.raises(ParameterError, match=r"steps_per_rev must be at least 1/Omega\* = 1000000"):
        crankgen.steady_state(crankgen.Mechanism(), omega=1e-6, **kw)
    with pytest.raises(ParameterError, match=r"^cases\[1\]: steps_per_rev .* bending"):
        sweep([Case(omega=0.8, **kw), Case(omega=1e-3, steps_per_rev=999, **kw)])
    s = crankgen.steady_state(crankgen.Mechanism(), omega=1e-3, steps_per_rev=1000, **kw)
    assert s.status == "periodic"                                  # at the limit: accepted


def test_stability_verdict_does_not_depend_on_the_step_at_the_limit():
    kw = dict(n_elements=4, damping="kelvin-voigt", membrane="averaged", omega=0.05)
    states = [crankgen.steady_state(steps_per_rev=n, **kw) for n in (20, 40, 80)]   # Omega* n >= 1
    assert [s.status for s in states] == ["periodic"] * 3
    assert all(s.multiplier < 1 for s in states)
    amps = [s.amplitude for s in states]
    assert max(amps) / min(amps) < 1.01                            # the same physical orbit


# --- D9: canonical case keys, versioned records ------------------------------------------------

def test_numpy_and_python_numbers_make_the_same_case():
    a = Case(ms=np.float64(0.5), omega=np.float32(0.25), n_elements=np.int64(4),
             approach=np.str_("B"))
    b = Case(ms=0.5, omega=0.25, n_elements=4, approach="B")
    assert a == b and a.key() == b.key() and hash(a) == hash(b)
    assert type(a.ms) is float and type(a.n_elements) is int and type(a.approach) is str
    assert Case(n_elements=16.0).key() == Case(n_elements=16).key()
    assert Case.from_dict({"ms": "0.5", "n_elements": "4"}) == Case(ms=0.5, n_elements=4)
    for bad, name in (({"n_elements": "16.5"}, "n_elements"), ({"approach": "D"}, "approach"),
                      ({"ms": "heavy"}, "ms"), ({"damping": 3}, "damping")):
        with pytest.raises(ParameterError, match=name):
            Case.from_dict(bad)


def test_equal_cases_typed_differently_are_computed_once_and_reused(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    ckpt = tmp_path / "sweep.jsonl"
    table = sweep([Case(ms=np.float64(0.5), **SMALL), Case(ms=0.5, **SMALL)], checkpoint=ckpt)
    assert len(calls) == 1 and table[0] == table[1]
    calls.clear()
    sweep([{"ms": np.float64(0.5), **SMALL}], checkpoint=ckpt)
    assert calls == []


def test_records_of_other_code_are_recomputed_unless_kept(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_mod, "steady_states", _fake_states(calls))
    ckpt = tmp_path / "sweep.jsonl"
    cases = [Case(omega=w, **SMALL) for w in (0.3, 0.4)]
    sweep(cases, checkpoint=ckpt)
    records = [_strict(line) for line in ckpt.read_text().splitlines()[1:]]
    assert [r["code"] for r in records] == [code_version()] * 2

    calls.clear()
    monkeypatch.setattr(sweep_mod, "code_version", lambda: {"crankgen": "9.9", "kernels": "x"})
    kept = sweep(cases, checkpoint=ckpt, keep_other_versions=True)
    assert calls == [] and len(kept) == 2
    with pytest.warns(RuntimeWarning, match=r"2 record\(s\) made by other code"):
        sweep(cases, checkpoint=ckpt)
    assert calls == cases                                          # recomputed, then recorded
    calls.clear()
    sweep(cases, checkpoint=ckpt)                                  # now current: reused
    assert calls == []


# --------------------------------------------------------------------------------------------
# D2: the default integrator does not give up where full Newton goes on
# --------------------------------------------------------------------------------------------

def _run_until_failure(mech, integrator, **kw):
    """(completed steps, result or None): the run, or how far it got before a ConvergenceError."""
    try:
        r = crankgen.simulate(mech, integrator=integrator, **kw)
        return len(r.t) - 1, r
    except crankgen.ConvergenceError as exc:
        return exc.step - 1, None


def test_newton_succeeds_where_full_newton_does_at_tiny_slenderness():
    """eps = 1e-4: a reused factorization diverged (a first scaled increment of about 800 grew to
    1e6) and the step never recovered; now its update is rejected and the step continues as full
    Newton.  Both reach 30 revolutions and agree far within the tolerance."""
    kw = dict(omega=0.8, n_elements=4, revolutions=30, damping="kelvin-voigt", membrane="averaged")
    mech = crankgen.Mechanism(eps=1e-4)
    n_full, full = _run_until_failure(mech, "full-newton", **kw)
    n_newton, newton = _run_until_failure(mech, "newton", **kw)
    assert full is not None and newton is not None, (n_full, n_newton)
    scale = np.max(np.abs(full.v_mid))
    assert np.max(np.abs(newton.v_mid - full.v_mid)) < 1e-6 * scale


def test_newton_gets_as_far_as_full_newton_without_damping():
    """mu = 0: the consistent model's response grows until Newton fails in both schemes; the
    default scheme must not stop earlier than full Newton."""
    kw = dict(omega=0.8, n_elements=4, revolutions=30, damping="kelvin-voigt", membrane="averaged")
    mech = crankgen.Mechanism(mu=0.0)
    n_full, _ = _run_until_failure(mech, "full-newton", **kw)
    n_newton, _ = _run_until_failure(mech, "newton", **kw)
    assert n_newton >= n_full
