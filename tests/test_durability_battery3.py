"""Durability, third battery (issue 32): no input turns into a silent wrong number, every run's
size is bounded before it starts, every input is checked once at the boundary, a branch that
stops short says why.  Each test failed on the main branch the issue was filed against (the
damaged-cache and numba-upgrade checks are in test_compile_cache.py)."""

import concurrent.futures as cf
import importlib
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import crankgen
from crankgen import Case, Circle, Fluctuation, InitialState, Mechanism, ParameterError, RunUp, SIMechanism
from crankgen.discrete import kinematics
from crankgen.cli import main
from helpers import fake_steady_states, true_angle

sweep_mod = importlib.import_module("crankgen.analyses.sweeps")
SMALL = dict(n_elements=2, steps_per_rev=20)
STEEL = dict(L=0.3, a=0.15, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10, slider_mass=0.0756, crank_speed=150.0)


def _dt(omega=0.5, steps_per_rev=20):
    return kinematics.step_period(Case(omega=omega, steps_per_rev=steps_per_rev)) / steps_per_rev


# ---- 1. no silent wrong numbers --------------------------------------------------------------

FAR = 9.9e6 + 0.123            # within records.ANGLE_LIMIT (1e7 rad): its float is 1.9e-9 rad from the next


@pytest.mark.parametrize("crank", [None, RunUp(start=0.3, stop=0.6, revolutions=1),
                                   Fluctuation(omega=0.5, amplitude=0.2, order=2)])
def test_a_far_start_angle_gives_the_run_at_its_crank_position(crank):
    """theta0 = 9.9e6 rad: the same v* as the run from the crank position of that float (main at
    issue 32: theta0 = 1e17 gave v* off by 3-13; issue 41: beyond 1e7 rad an angle is refused,
    test_durability_battery4)."""
    kw = dict(SMALL, revolutions=1, **({"omega": 0.5} if crank is None else {"crank": crank}))
    far = crankgen.simulate(Mechanism(), theta0=FAR, **kw)
    near = crankgen.simulate(Mechanism(), theta0=true_angle(FAR), **kw)
    assert far.case.theta0 == pytest.approx(true_angle(FAR), abs=1e-12)
    np.testing.assert_allclose(far.v_mid, near.v_mid, rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(far.theta - far.theta[0], near.theta - near.theta[0], rtol=1e-12, atol=1e-12)
    assert far.theta[-1] - far.theta[0] > 6.0                                         # the crank turns


def test_the_command_line_turns_the_crank_from_a_far_theta0(tmp_path):
    assert main(["simulate", "--theta0", str(FAR), "--elements", "2", "--revolutions", "1",
                 "--steps-per-rev", "20", "--out", str(tmp_path / "o"), "--quiet"]) == 0
    rows = (tmp_path / "o" / "simulation.csv").read_text().splitlines()
    header = rows[0].split(",")
    theta = [float(r.split(",")[header.index("theta_deg")]) for r in rows[1:]]
    assert theta[-1] - theta[0] == pytest.approx(360.0, rel=1e-9)


def _fluctuation_steps_needed(omega, k, j, steps_per_rev):
    """The steps per revolution the rule asks of Fluctuation(omega, k, j), from the closed form:
    thetad = omega (1 + k sin j theta), thetadd = omega^2 k j cos(j theta) (1 + k sin j theta),
    period 2 pi / (omega sqrt(1 - k^2)); at most pi/2 of turn and 1/4 of the top speed a step."""
    phi = np.linspace(0, 2 * np.pi, 200001)
    top = omega * (1 + abs(k))
    accel = omega**2 * abs(k) * j * np.max(np.abs(np.cos(phi) * (1 + k * np.sin(phi))))
    dt = 2 * np.pi / (omega * math.sqrt(1 - k * k)) / steps_per_rev
    return steps_per_rev * max(top * dt / (np.pi / 2), accel * dt / (0.25 * top))


def test_a_crank_motion_stepped_too_coarsely_is_refused_in_every_analysis():
    """Fluctuation(omega=0.5, amplitude=0.999) at 40 steps a revolution: one step turns the crank
    about 4 rad (main: simulate returned max |v*| 1.18 against 7.87 when resolved, no warning).
    Refused by simulate, steady_state, sweep, continuation and poincare alike, naming the
    steps_per_rev the rule needs (the closed form's, computed here).  At 60 steps (the periodic
    analyses refuse 40 already: a step longer than the rod's bending period)."""
    crank = Fluctuation(omega=0.5, amplitude=0.999)
    need = _fluctuation_steps_needed(0.5, 0.999, 1, 60)
    spr = dict(n_elements=2, steps_per_rev=60)
    calls = [lambda: crankgen.simulate(Mechanism(), crank=crank, **spr, revolutions=2),
             lambda: crankgen.steady_state(Mechanism(), crank=crank, **spr),
             lambda: crankgen.sweep([Case(motion="fluctuation", omega=0.5, fluctuation=0.999, **spr)]),
             lambda: crankgen.continuation(Mechanism(), "omega", 0.5, 0.6, crank=crank, **spr),
             lambda: crankgen.poincare(Mechanism(), "omega", [0.5], crank=crank, **spr)]
    for call in calls:
        with pytest.raises(ParameterError, match=r"steps_per_rev >= (\d+)") as info:
            call()
        asked = int(info.value.args[0].rsplit(">= ", 1)[1])
        assert need <= asked <= need * 1.01 + 1, (need, asked)
        assert "\n" not in str(info.value)
    resolved = Case(motion="fluctuation", omega=0.5, fluctuation=0.999, steps_per_rev=asked)
    kinematics.check_crank_steps(resolved, kinematics.period(resolved) / asked)        # accepted


def test_the_command_line_refuses_a_coarse_crank_step_before_anything(tmp_path, capsys):
    rc = main(["simulate", "--crank", "fluctuation", "--fluctuation", "0.999", "--omega", "0.5",
               "--steps-per-rev", "40", "--elements", "2", "--out", str(tmp_path / "o")])
    captured = capsys.readouterr()
    assert rc == 2 and captured.out == "" and len(captured.err.strip().splitlines()) == 1
    assert "use steps_per_rev >= " in captured.err and not (tmp_path / "o").exists()


@pytest.mark.parametrize("revolutions", [5, None])
def test_a_run_down_asked_for_more_revolutions_than_the_crank_turns_is_refused(revolutions):
    """A run-down to rest over 2 revolutions (main: OverflowError traceback; 10 by default)."""
    kw = {} if revolutions is None else {"revolutions": revolutions}
    with pytest.raises(ParameterError, match="turns only 2 revolutions"):
        crankgen.simulate(Mechanism(), crank=RunUp(start=0.5, stop=0.0, revolutions=2), **SMALL, **kw)


def test_the_command_line_refuses_a_run_down_asked_too_far_in_one_line(tmp_path, capsys):
    rc = main(["simulate", "--crank", "runup", "--omega0", "0.5", "--omega", "0", "--ramp", "2",
               "--revolutions", "5", "--elements", "2", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "at most 2 revolutions" in err[0]
    assert not (tmp_path / "o").exists()


# ---- 3. every run's size bounded before it starts --------------------------------------------

@pytest.fixture
def no_engine(monkeypatch):
    """The compiled engine refuses to start: a refusal must come before any work."""
    def refuse(*args, **kwargs):
        raise AssertionError("the run started")
    monkeypatch.setattr(crankgen.engine, "Batch", refuse)


def test_history_false_counts_its_per_step_outputs(monkeypatch, no_engine):
    """history=False still keeps 5 numbers a step: 6.4e8 steps are about 50 GB (main: not
    checked, check_run_size was given 0 steps)."""
    monkeypatch.setenv("CRANKGEN_MEMORY_LIMIT", "16G")
    with pytest.raises(ParameterError, match="time steps x 5 per-step outputs.*CRANKGEN_MEMORY_LIMIT"):
        crankgen.simulate(Mechanism(), omega=0.5, **SMALL, history=False, times=[(6.4e8 + 0.95) * _dt()])


def test_the_states_at_requested_times_count(monkeypatch, no_engine):
    """10^5 times between steps: each a stored state and a case of the batch that steps to it."""
    monkeypatch.setenv("CRANKGEN_MEMORY_LIMIT", "100M")
    with pytest.raises(ParameterError, match="times: 100000 requested times"):
        crankgen.simulate(Mechanism(), omega=0.5, **SMALL, history=False,
                          times=(np.arange(10**5) + 0.5) * _dt())


def test_a_last_time_just_past_a_step_is_reached():
    """(2e5 + 1e-5) dt: 1e-5 of a step past step 200000 (main: refused as beyond the run's end,
    ceil(N (1 - 1e-9)) fell a step short)."""
    dt = _dt()
    t = (2e5 + 1e-5) * dt
    run = crankgen.simulate(Mechanism(), omega=0.5, **SMALL, history=False, times=[t])
    assert run.at_times.t[0] == t and len(run.t) == 200002


def test_states_at_many_times_match_the_run_whatever_the_chunks(monkeypatch):
    """States at every step taken from chunks of a few steps (history=False) are the run's own."""
    sim = importlib.import_module("crankgen.analyses.marching")
    monkeypatch.setattr(sim, "CHUNK_BYTES", 3 * 8 * 6 * 7)            # 7 steps a chunk
    dt = _dt()
    full = crankgen.simulate(Mechanism(), omega=0.5, **SMALL, revolutions=2)
    times = np.arange(41) * dt
    light = crankgen.simulate(Mechanism(), omega=0.5, **SMALL, history=False, times=times)
    np.testing.assert_array_equal(light.at_times.v_mid, full.v_mid[:41])
    np.testing.assert_array_equal(light.at_times.states, full.states[:41])


@pytest.mark.parametrize("times", ["0.5", True, ["0.5", "1"], [np.True_, 1.0], np.array([True, False])])
def test_times_that_are_text_or_booleans_are_refused(times):
    with pytest.raises(ParameterError, match="^times must be a number"):
        crankgen.simulate(Mechanism(), omega=0.5, **SMALL, times=times)


# ---- 4. every input validated once, at the boundary ------------------------------------------

class _DaskFuture:
    """What a Dask client's submit returns: not a concurrent.futures.Future."""


class Client:
    """Stands in for distributed.Client: submit gives Dask futures, get_executor a
    concurrent.futures.Executor on the same cluster."""

    def __init__(self):
        self.pool = cf.ThreadPoolExecutor(2)

    def submit(self, fn, *args, **kwargs):
        return _DaskFuture()

    def get_executor(self):
        return self.pool


def test_a_dask_client_as_executor_runs_through_its_get_executor(monkeypatch):
    """Main accepted the client (it has submit) and died in as_completed with AttributeError."""
    monkeypatch.setattr(sweep_mod, "steady_states", fake_steady_states([]))
    cases = [Case(omega=w, **SMALL) for w in (0.2, 0.3, 0.4)]
    client = Client()
    try:
        table = crankgen.sweep(cases, executor=client, batch_size=1)
    finally:
        client.pool.shutdown()
    assert table.rows == crankgen.sweep(cases).rows


def test_an_object_that_only_submits_is_refused_naming_get_executor(monkeypatch):
    class Submits:
        def submit(self, fn, *args):
            return _DaskFuture()
    with pytest.raises(ParameterError, match=r"get_executor\(\)"):
        crankgen.sweep([Case(omega=0.3, **SMALL)], executor=Submits())


@pytest.mark.parametrize("make", [lambda: Case(n_elements=np.bool_(True)), lambda: Case(omega=np.True_),
                                  lambda: Mechanism(ms=np.True_), lambda: Case(branch=np.bool_(True)),
                                  lambda: SIMechanism(**dict(STEEL, slider_mass=np.True_)),
                                  lambda: SIMechanism(**dict(STEEL, crank_speed=np.True_)),
                                  lambda: Case(theta0=np.True_),
                                  lambda: crankgen.simulate(Mechanism(), omega=0.5, revolutions=np.True_)])
def test_booleans_are_refused_as_numbers_numpy_included(make):
    with pytest.raises(ParameterError):
        make()


@pytest.mark.parametrize("fields, name", [(dict(L=1e-200, a=5e-201), "L"), (dict(rho=1e-300, A=1e-300), "rho"),
                                          (dict(E=1e300, I=1e10), "E")])
def test_si_magnitudes_that_overflow_are_refused_naming_the_field(fields, name):
    """Main: OverflowError, ZeroDivisionError, and 'mu must be finite' about a damping never set."""
    with pytest.raises(ParameterError, match=f"^SIMechanism: {name} = "):
        SIMechanism(**dict(STEEL, **fields))


def test_the_command_line_refuses_si_magnitudes_in_one_line(tmp_path, capsys):
    path = tmp_path / "si.json"
    path.write_text('{"L": 1e-200, "a": 5e-201, "E": 2e11, "rho": 7870, "A": 6.4e-5, "I": 3.41e-10, '
                    '"slider_mass": 0.0756, "crank_speed": 150}')
    assert main(["simulate", "--si", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "L = 1e-200" in err[0]


@pytest.mark.parametrize("field, fn, words", [
    ("u", lambda x: np.zeros((np.size(x), 2)), "shape"),
    ("v", lambda x: "a text", "str"),
    ("u_t", lambda x: {"x": x}, "dict"),
    ("v", lambda x: np.zeros((np.size(x), 3)), "shape")])
def test_initial_state_callables_are_checked_for_shape_and_type(field, fn, words):
    """Main: 'truth value of an array is ambiguous', ValueError, TypeError, and for v a message
    that blamed the complex step."""
    with pytest.raises(ParameterError, match=f"^initial state: {field}\\(x\\) must return one real number.*{words}"):
        crankgen.simulate(Mechanism(), omega=0.5, **SMALL, revolutions=0.1, initial=InitialState(**{field: fn}))


@pytest.mark.parametrize("tol", [float("inf"), float("nan"), 0.0, -1.0])
def test_initial_state_tol_must_be_finite_and_positive(tol):
    """Main accepted tol = inf, and an off-pin u(0) = 1e-3 was dropped silently."""
    with pytest.raises(ParameterError, match="tol must be a finite number > 0"):
        InitialState(u=lambda x: 1e-3 + 0 * x, tol=tol)


def test_a_guide_parameter_given_twice_is_refused():
    """Circle(c=0.8, radius=0.7): main took 0.7 silently."""
    with pytest.raises(ParameterError, match="c is given twice"):
        Circle(c=0.8, radius=0.7)
    with pytest.raises(ParameterError, match="d is given twice"):
        Circle(center=(1.0, 0.0), d=1.0)


def test_a_mechanism_parameter_as_a_keyword_builds_the_mechanism_or_is_refused_beside_one():
    """simulate(omega=0.1, eps=0.02) raised a raw TypeError (make_case got eps twice)."""
    case = crankgen.declaration.cases.run_case(omega=0.1, eps=0.02, ms=0.3)
    assert (case.eps, case.ms) == (0.02, 0.3)
    assert case == Case(eps=0.02, ms=0.3, omega=0.1)
    with pytest.raises(ParameterError, match="eps given both in the mechanism and as a keyword"):
        crankgen.declaration.cases.run_case(Mechanism(), omega=0.1, eps=0.02)
    with pytest.raises(ParameterError, match="eps given both"):
        crankgen.steady_state(Mechanism(), omega=0.1, eps=0.02)


def test_a_linkage_exactly_at_its_locking_limit_is_refused():
    """a = 0.1, D = (1, 0), c = 1.9: ||D| - a| = |1 - c| exactly, the dead point; rounding gave a
    margin of 1e-16 and main accepted it (its first step failed).  Just inside is accepted."""
    with pytest.raises(ParameterError, match="cannot turn a full revolution"):
        Mechanism(a=0.1, guide=Circle(center=(1.0, 0.0), radius=1.9))
    Mechanism(a=0.1, guide=Circle(center=(1.0, 0.0), radius=1.9 - 1e-6))


def test_a_fifo_given_as_si_file_is_refused_without_waiting(tmp_path):
    """Main hung until killed (the timeout guards the test only)."""
    fifo = tmp_path / "si.fifo"
    os.mkfifo(fifo)
    run = subprocess.run([sys.executable, "-m", "crankgen", "simulate", "--si", str(fifo), "--out",
                          str(tmp_path / "o")], capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and "FIFO" in run.stderr and len(run.stderr.strip().splitlines()) == 1


# ---- 5. a branch that stops short says why ---------------------------------------------------

def test_the_locking_limit_inside_a_continuation_range_is_found():
    """A four-bar with a = 0.1, c = 0.8 locks for |d| < a + |1 - c| = 0.3 (closed form)."""
    from crankgen.analyses.bifurcation.api import locking_limit
    case = Case(a=0.1, guide="circle", c=0.8, d=-1.0)
    value, why = locking_limit(case, "d", -1.0, 1.0)
    assert value == pytest.approx(-0.3, abs=1e-9) and "||D| - a*| > |1 - c|" in why
    assert locking_limit(case, "d", -1.0, -0.5) is None


def test_crankgen_continue_prints_and_writes_each_branch_stop_reason(tmp_path, capsys, monkeypatch):
    """Main printed "1 branches, 39 points, 0 special points" and nothing about why."""
    from crankgen.analyses.bifurcation.diagram import BifurcationDiagram, Branch
    import crankgen.analyses.bifurcation as bif

    reason = "step below ds_min at d = -0.34 (...); d = -0.3 is the locking limit"

    def fake(**kwargs):
        n = 3
        branch = Branch(period=1, parameter_name="d", parameter=np.linspace(-1, -0.34, n),
                        amplitude=np.ones(n), stable=np.ones(n, bool), multipliers=np.full((n, 2), 0.5 + 0j),
                        states=np.zeros((n, 2)), section=np.zeros((n, 1)), stop_reason=reason)
        return BifurcationDiagram("d", [branch], [], info=dict(wall_time=0.0, eps=0.01))
    monkeypatch.setattr(bif, "continuation", fake)
    rc = main(["continue", "--parameter", "d", "--from", "-1", "--to", "1", "--guide", "circle", "--rocker",
               "0.8", "--a", "0.1", "--elements", "2", "--steps-per-rev", "40", "--out", str(tmp_path / "c"),
               "--quiet"])
    out = capsys.readouterr().out
    assert rc == 0 and f"ends: {reason}" in out
    import csv
    rows = list(csv.DictReader(open(tmp_path / "c" / "branches.csv")))
    assert {r["stop_reason"] for r in rows} == {reason}


# ---- 2 and 6. crankgen compile counts what it compiled; the sweep module split ----------------

def test_crankgen_compile_counts_only_what_it_compiled(monkeypatch, capsys):
    """Items another process compiled meanwhile are not counted as this command's."""
    from crankgen.engine import build
    monkeypatch.setattr(build, "done", lambda item: False)
    monkeypatch.setattr(build, "prepare", lambda items, quiet=False: list(items[:2]))
    assert main(["compile"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("2 item(s) compiled, 0 already there, ") and "by another crankgen process" in out


def test_sweeps_is_split_into_modules_of_one_concern():
    """Driver, checkpoint store, lock, pool workers and table each in a module under 600 lines."""
    root = Path(crankgen.__file__).parent
    for name in ("analyses/sweeps", "analyses/checkpoint", "analyses/file_lock", "analyses/pool_workers",
                 "results/sweep_table"):
        assert len((root / f"{name}.py").read_text().splitlines()) < 600, name
