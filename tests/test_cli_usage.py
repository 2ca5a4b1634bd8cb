"""Usage errors come before any computing: every option of every command with a bad value exits 2
with one line, before a progress line is printed, a folder created or an engine entry point
called; unknown options point to the command's own --help."""

import pytest

import crankgen
from crankgen.analyses import bifurcation
from crankgen.cli import main

CALLS = []


@pytest.fixture(autouse=True)
def no_computing(monkeypatch):
    """Every entry point a command computes with records the call and refuses."""
    import crankgen.audit
    import crankgen.experiments
    import crankgen.analyses.simulation
    import crankgen.analyses.steady
    import crankgen.analyses.sweeps
    CALLS.clear()

    def refuse(name):
        def f(*args, **kwargs):
            CALLS.append(name)
            raise AssertionError(f"{name} was called")
        return f
    for module, name in ((crankgen.analyses.simulation, "simulate"), (crankgen.analyses.steady, "steady_states"),
                         (crankgen.analyses.sweeps, "sweep"), (bifurcation, "continuation"),
                         (bifurcation, "poincare"), (crankgen.experiments, "reproduce"),
                         (crankgen.audit, "write_report")):
        monkeypatch.setattr(module, name, refuse(name))


BRANCH = ["--from", "0.8", "--to", "1.0"]
BAD = {
    "simulate": [["--omega", "-1"], ["--omega", "0"], ["--omega", "nan"], ["--omega", "inf"],
                 ["--omega", "abc"], ["--eps", "0"], ["--a", "1"], ["--ms", "-1"], ["--mu", "-1"],
                 ["--offset", "0.95"], ["--gravity", "nan,0"], ["--gravity", "1"],
                 ["--elements", "0"], ["--elements", "1.5"], ["--steps-per-rev", "3"],
                 ["--revolutions", "0"], ["--revolutions", "nan"], ["--tol", "0"],
                 ["--model", "rigid"], ["--model", "exact", "--damping", "paper"], ["--approach", "D"], ["--formulation", "x"],
                 ["--damping", "x"], ["--membrane", "x"], ["--rotary-inertia", "maybe"],
                 ["--integrator", "x"]],
    "steady": [["--omega", "0.005"], ["--omega", "0.05", "--steps-per-rev", "19"], ["--tol", "-1"],
               ["--max-revolutions", "0"], ["--method", "x"], ["--eps", "-0.1"]],
    "sweep": [["--omega", "0.005,0.2"], ["--omega", "0.8:0.2:0.1"], ["--eps", "0.01,-1"],
              ["--batch-size", "0"], ["--workers", "0"], ["--tol", "0"], ["--max-revolutions", "0"],
              ["--elements", "4,0"], ["--approach", "A,D"]],
    "continue": [BRANCH + ["--max-period", "0"], ["--from", "0.5", "--to", "0.5"],
                 ["--from", "nan", "--to", "1"], ["--from", "0.5", "--to", "inf"],
                 ["--from", "0.005", "--to", "0.5"], ["--from", "0.5", "--to", "0.005"],
                 ["--parameter", "eps", "--from", "0.01", "--to", "-1"],
                 ["--parameter", "a", "--from", "0.1", "--to", "1.2"],
                 ["--parameter", "offset", "--from", "0", "--to", "0.95"],
                 ["--parameter", "eps", "--from", "0.01", "--to", "0.1", "--omega", "-1"],
                 BRANCH + ["--elements", "0"], BRANCH + ["--steps-per-rev", "2"],
                 BRANCH + ["--eps", "0"], ["--parameter", "x"] + BRANCH, ["--from", "0.8"]],
    "poincare": [BRANCH + ["--max-period", "0", "--with-continuation"],
                 BRANCH + ["--values", "1"], BRANCH + ["--values", "1000000000"],
                 BRANCH + ["--transient", "-1"], BRANCH + ["--samples", "1"],
                 BRANCH + ["--direction", "sideways"], ["--from", "0.8", "--to", "nan"],
                 ["--from", "0.8", "--to", "0.8", "--with-continuation"],
                 ["--from", "0.001", "--to", "1", "--with-continuation"],
                 ["--parameter", "ms", "--from", "0.5", "--to", "-1"], BRANCH + ["--elements", "0"]],
    "reproduce": [["--figures", "1,9"], ["--figures", "x"]],
    "audit": [["--sections", "9"]],
}
CASES = [(command, argv) for command, lists in BAD.items() for argv in lists]


@pytest.mark.parametrize("command, argv", CASES, ids=[f"{c} {' '.join(a)}" for c, a in CASES])
def test_a_bad_option_exits_2_before_any_computing(tmp_path, capsys, command, argv):
    out = tmp_path / "new"
    try:
        rc = main([command, *argv, "--out", str(out)])         # not --quiet: progress would show
    except SystemExit as exc:
        rc = exc.code
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert rc == 2, captured.err
    assert len(lines) == 1 and lines[0].startswith(f"crankgen {command}: error: "), captured.err
    assert len(lines[0]) < 320, lines[0]                       # one readable line
    assert captured.out == "" and CALLS == [] and not out.exists()


def test_the_steady_command_refuses_exactly_what_steady_states_refuses(tmp_path, capsys, monkeypatch):
    """The command line's early check and the library's rule agree (Omega* * steps_per_rev >= 1)."""
    monkeypatch.undo()                                          # the real steady_states
    from crankgen import Case, ParameterError, steady_states
    for omega, spr in ((0.05, 19), (0.05, 20), (0.01, 99), (0.01, 100), (0.3, 4)):
        try:
            steady_states([Case(omega=omega, steps_per_rev=spr, n_elements=1)], max_revolutions=1)
            api = 0
        except ParameterError:
            api = 2
        monkeypatch.setattr(crankgen.analyses.steady, "steady_states", lambda *a, **k: (_ for _ in ()).throw(
            AssertionError("computing")))
        try:
            rc = main(["steady", "--omega", str(omega), "--steps-per-rev", str(spr), "--elements", "1",
                       "--out", str(tmp_path / f"{omega}-{spr}"), "--quiet"])
        except AssertionError:
            rc = 0                                              # accepted: it went on to compute
        monkeypatch.undo()
        assert rc == api, (omega, spr)
    capsys.readouterr()


@pytest.mark.parametrize("command, wrong, right", [
    ("simulate", "--omegaa", "--omega"), ("steady", "--elemnts", "--elements"),
    ("poincare", "--valuez", "--values"), ("reproduce", "--quik", "--quick")])
def test_an_unknown_option_points_to_the_commands_own_help(capsys, command, wrong, right):
    argv = [command, wrong, "1"] + (BRANCH if command == "poincare" else [])
    with pytest.raises(SystemExit) as exc:
        main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1
    assert f"(see crankgen {command} --help)" in err[0] and wrong in err[0]
    if right:
        assert f"did you mean {right}?" in err[0]
    assert CALLS == []
