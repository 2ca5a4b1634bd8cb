"""Durability, fourth battery (issue 41): one test per fault class, through the API and the command
line, with Python scalars, NumPy scalars and generators where a number or a sequence is taken;
the leftovers of batteries 2 and 3 named after their findings (F28, G11, G13, G18).

Classes: angles (a float used modulo 2 pi), callables handed to crankgen, output paths, counts,
memory with history off, numbers and sequences.  docs/howto/input-checks.md states the rules."""

import gc
import os
import signal
import subprocess
import sys
import tracemalloc

import numpy as np
import pytest

import crankgen
import crankgen.engine
from crankgen import Case, InitialState, Mechanism, ParameterError, SIMechanism
from crankgen.cli import main
from crankgen.plots import figures, modes as modes_plot
from helpers import true_angle

SMALL = dict(n_elements=2, steps_per_rev=40)
STEEL = dict(L=0.3, a=0.15, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10, slider_mass=0.0756, crank_speed=150.0)


def run_cli(argv):
    """main(argv)'s exit code, argparse's own exit (a malformed flag) included."""
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


def one_line_refusal(capsys, rc, *words):
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1, err
    for w in words:
        assert w in err[0], err[0]
    return err[0]


@pytest.fixture
def no_engine(monkeypatch):
    """The compiled engine refuses to start: a refusal must come before any work."""
    def refuse(*args, **kwargs):
        raise AssertionError("the run started")
    monkeypatch.setattr(crankgen.engine, "Batch", refuse)


# ---- angles: one rule wherever an angle enters ------------------------------------------------

LOST = [1e17, np.float64(1e300), np.array(-1e17), np.float32(3e7)]


@pytest.mark.parametrize("value", LOST, ids=["1e17", "np1e300", "0d-1e17", "f32-3e7"])
def test_an_angle_that_has_lost_its_digits_is_refused_wherever_it_enters(value, no_engine):
    """1e17 rad: floats there are 16 rad apart, more than a turn (main: modes(theta=1e17) gave
    0.68739 where the crank position gives 0.67721; theta0 = 1e17 accepted by simulate)."""
    calls = [lambda: crankgen.simulate(Mechanism(), omega=0.5, theta0=value, **SMALL),
             lambda: crankgen.steady_state(Mechanism(), omega=0.5, theta0=value, **SMALL),
             lambda: crankgen.modes(Mechanism(), theta=value, n_elements=2),
             lambda: crankgen.campbell(Mechanism(inclination=value, guide="incline"), [0, 1], n_elements=2),
             lambda: crankgen.stability_chart(theta0=value, lines=1, **SMALL),
             lambda: SIMechanism(**STEEL, theta0=value),
             lambda: Case(motion="motor", theta0=value)]
    for call in calls:
        with pytest.raises(ParameterError, match="rad is too far from 0 to name an angle.*modulo 2 pi"):
            call()


FAR = 9.9e6 + 0.123      # within the bound: floats there are 1.9e-9 rad apart


@pytest.mark.parametrize("kind", [float, np.float64, np.array])
def test_modes_at_a_far_angle_are_the_modes_at_its_crank_position(kind):
    far = crankgen.modes(Mechanism(), theta=kind(FAR), n_elements=4)
    near = crankgen.modes(Mechanism(), theta=true_angle(FAR), n_elements=4)
    assert far.theta == pytest.approx(true_angle(FAR), abs=1e-12)
    np.testing.assert_allclose(far.frequencies, near.frequencies, rtol=1e-12)


@pytest.mark.parametrize("argv", [["simulate", "--theta0", "1e300"], ["steady", "--theta0", "-1e17"],
                                  ["modes", "--theta0", "1e17"], ["simulate", "--guide", "incline",
                                                                   "--inclination", "1e20"]])
def test_the_command_line_refuses_a_lost_angle_in_one_line_before_anything(argv, tmp_path, capsys):
    rc = run_cli(argv + ["--elements", "2", "--out", str(tmp_path / "o")])
    one_line_refusal(capsys, rc, "too far from 0 to name an angle")
    assert not (tmp_path / "o").exists()


def test_an_si_file_with_a_lost_angle_is_refused(tmp_path, capsys):
    si = tmp_path / "si.json"
    si.write_text('{"L": 0.3, "a": 0.15, "E": 2e11, "rho": 7870, "A": 6.4e-5, "I": 3.41e-10, '
                  '"slider_mass": 0.0756, "crank_speed": 150, "theta0": 1e300}')
    rc = run_cli(["simulate", "--si", str(si), "--out", str(tmp_path / "o")])
    one_line_refusal(capsys, rc, "theta0", "too far from 0")


# ---- callables: sampled, checked for what the method needs -----------------------------------

def test_a_torque_curve_with_a_jump_is_refused_where_it_jumps():
    """Main tabulated lambda s: 1 if s < 0.4 else 1 - s as a jump between two points 5.6e-17
    apart, and the step-size advice assumed a slope of 2.25."""
    with pytest.raises(ParameterError, match=r"^torque_curve.*F\(S\) is not continuous.*near S = 0\.4000") as info:
        Case(motion="motor", torque_curve=lambda s: 1.0 if s < 0.4 else 1 - s)
    assert "\n" not in str(info.value)
    with pytest.raises(ParameterError, match="not continuous"):
        crankgen.simulate(Mechanism(), crank=crankgen.Motor(torque_curve=lambda s: float(s < 0.7) * (1 - s)),
                          **SMALL, revolutions=0.1)


@pytest.mark.parametrize("kind", [float, np.float64, np.float32, np.array])
def test_a_continuous_torque_curve_with_a_kink_is_tabulated_within_its_tolerance(kind):
    """A kink (slopes -0.5 and -4/3 at S = 0.4) is continuous with a bounded slope: accepted, and the
    table's interpolant matches the function within 1e-5 of the stall torque everywhere."""
    def f(s):
        return kind(1 - 0.5 * s if s < 0.4 else 0.8 * (1 - s) / 0.6)
    curve = Case(motion="motor", torque_curve=f).torque_curve
    s = np.linspace(0.0, 1.2, 4001)
    table = crankgen.torque_curve.evaluate(curve, s)[0]
    assert np.max(np.abs(table - [float(f(x)) for x in s])) < 1e-5


@pytest.mark.parametrize("returns, words", [(lambda s: True, "bool"), (lambda s: "1", "str"),
                                            (lambda s: np.array([1.0 - s]), "shape"),
                                            (lambda s: None, "NoneType"), (lambda s: complex(1, 1), "complex")])
def test_what_a_callable_returns_is_checked_by_one_rule(returns, words):
    """The torque curve and an initial state's fields: one real finite number per point."""
    with pytest.raises(ParameterError, match=f"^torque_curve.*F\\(S\\) must return one real number.*{words}"):
        Case(motion="motor", torque_curve=returns)
    with pytest.raises(ParameterError, match=f"^initial state: u\\(x\\) must return one real number.*{words}"):
        crankgen.simulate(Mechanism(), omega=0.5, **SMALL, revolutions=0.05,
                          initial=InitialState(u=lambda x: returns(0.0)))


# ---- output paths: one check for every writer, before any work --------------------------------

@pytest.fixture(scope="module")
def run():
    return crankgen.simulate(Mechanism(), omega=0.8, revolutions=0.3, **SMALL)


def _bad_paths(tmp_path, suffix):
    afile = tmp_path / "afile.txt"
    afile.write_text("a file")
    fifo = tmp_path / f"pipe{suffix}"
    if not fifo.exists():
        os.mkfifo(fifo)
    return [(None, "None"), ("", "''"), (tmp_path, "is a folder"), (afile / f"x{suffix}", "afile.txt"),
            (fifo, "FIFO")]


@pytest.mark.parametrize("writer, suffix", [
    (lambda r, p: r.to_csv(p), ".csv"),
    (lambda r, p: r.animate(p), ".gif"),
    (lambda r, p: figures.plot_deflection(r, p), ".png"),
    (lambda r, p: modes_plot.plot_modes(crankgen.modes(Mechanism(), n_elements=2), p), ".png")])
def test_every_writer_names_a_bad_path_before_any_work(writer, suffix, run, tmp_path, monkeypatch):
    """Main: result.animate raised NotADirectoryError naming a hidden temporary file, the imaging
    library's FileNotFoundError, TypeError for None."""
    import crankgen.plots.animation as anim

    def no_frames(*args, **kwargs):
        raise AssertionError("the frames were drawn before the path was checked")
    monkeypatch.setattr(anim, "Frames", no_frames)
    for path, words in _bad_paths(tmp_path, suffix):
        with pytest.raises(crankgen.CrankgenError, match=f".*{words}") as info:
            writer(run, path)
        assert isinstance(info.value, ParameterError) and "\n" not in str(info.value)
        assert ".tmp" not in str(info.value)


def test_a_folder_writer_checks_its_folder_and_every_file_first(tmp_path):
    diagram = crankgen.poincare(Mechanism(), "omega", [0.5], transient=1, samples=2, **SMALL)
    afile = tmp_path / "afile"
    afile.write_text("x")
    (tmp_path / "out" / "poincare_samples.csv").mkdir(parents=True)      # the second name is a folder
    for folder, words in [(None, "None"), (afile, "not a folder"), (tmp_path / "out", "poincare_samples.csv")]:
        with pytest.raises(ParameterError, match=words):
            diagram.to_csv(folder)
    assert not (tmp_path / "out" / "poincare_summary.csv").exists()          # nothing written first


def test_animate_a_result_without_states_is_a_crankgen_error(tmp_path):
    """Main: IndexError in animation.py for a result simulated with history=False."""
    light = crankgen.simulate(Mechanism(), omega=0.8, revolutions=0.3, history=False, **SMALL)
    with pytest.raises(ParameterError, match="history=False"):
        light.animate(tmp_path / "a.gif")
    assert not list(tmp_path.iterdir())


def test_a_missing_folder_is_created_and_the_animation_written(run, tmp_path):
    path = run.animate(tmp_path / "new" / "deeper" / "a.gif", frames=3)
    assert path.read_bytes()[:6] in (b"GIF87a", b"GIF89a")
    assert sorted(p.name for p in path.parent.iterdir()) == ["a.gif"]


KILLED = """
import os, signal, sys
import crankgen
run = crankgen.simulate(crankgen.Mechanism(), omega=0.8, revolutions=0.3, n_elements=2, steps_per_rev=40)
def progress(done, total):
    if done == 2:                           # killed mid-write, as kill -9 would
        os.kill(os.getpid(), signal.SIGKILL)
run.{writer}
"""


@pytest.mark.parametrize("writer, name", [("animate(sys.argv[1], frames=4, progress=progress)", "a.gif")])
def test_a_killed_export_leaves_no_temporary_file_after_the_next_one(writer, name, tmp_path, run):
    """Main: the hidden .tmp of a killed export stayed for ever."""
    target = tmp_path / name
    child = subprocess.run([sys.executable, "-c", KILLED.format(writer=writer), str(target)],
                           capture_output=True, timeout=600)
    assert child.returncode == -signal.SIGKILL, child.stderr.decode()[-2000:]
    left = [p.name for p in tmp_path.iterdir()]
    assert not target.exists() and len(left) == 1 and left[0].startswith(f".{name}.") and ".tmp" in left[0]
    alive = tmp_path / f".{name}.{os.getpid()}.0badc0de.tmp.gif"       # this process's: not touched
    alive.write_text("being written")
    run.animate(target, frames=3)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([name, alive.name])
    csv_tmp = tmp_path / f".r.csv.{left[0].split('.')[3]}.0badc0de.tmp"   # the dead process's, for a CSV
    csv_tmp.write_text("half a table")
    run.to_csv(tmp_path / "r.csv")
    assert not csv_tmp.exists()


# ---- counts: bounded, the bound and the way past it in the message ---------------------------

@pytest.mark.parametrize("lines", [10**6, np.int64(10**6), 1e6])
def test_a_chart_of_a_million_lines_is_refused_before_any_line(lines, no_engine):
    """Main: max_lines = max(max_lines, lines) had no bound; a million continuations started."""
    with pytest.raises(ParameterError, match=r"^lines must be at most 100, got 1000000 .*set "
                                             r"CRANKGEN_MAX_LINES=1000000$"):
        crankgen.stability_chart(lines=lines, **SMALL)


def test_the_bound_is_lifted_on_purpose(monkeypatch):
    """CRANKGEN_MAX_LINES past the bound: the chart goes on to its first line."""
    import crankgen.analyses.charts.compute as compute

    class Started(Exception):
        pass

    def first_line(*args, **kwargs):
        raise Started
    monkeypatch.setattr(compute, "continuation", first_line)
    monkeypatch.setenv("CRANKGEN_MAX_LINES", "1000")
    with pytest.raises(Started):
        crankgen.stability_chart(lines=500, max_lines=150, **SMALL)
    monkeypatch.setenv("CRANKGEN_MAX_LINES", "many")
    with pytest.raises(ParameterError, match="CRANKGEN_MAX_LINES must be a whole number"):
        crankgen.stability_chart(lines=500, **SMALL)


@pytest.mark.parametrize("call, words", [
    (lambda: crankgen.poincare(Mechanism(), "omega", (0.5 for _ in range(100001)), **SMALL), "values .*100000"),
    (lambda: crankgen.poincare(Mechanism(), "omega", [0.5], transient=np.int64(10**7), **SMALL), "transient"),
    (lambda: crankgen.campbell(Mechanism(), np.linspace(0, 1, 10001), n_elements=2), "speeds .*10000"),
    (lambda: crankgen.campbell(Mechanism(), [0, 1], angles=10**5, n_elements=2), "angles"),
    (lambda: crankgen.campbell(Mechanism(), [0, 1], orders=range(1, 10**4), n_elements=2), "orders"),
    (lambda: crankgen.continuation(Mechanism(), max_points=10**7, **SMALL), "max_points"),
    (lambda: crankgen.steady_state(Mechanism(), max_revolutions=10**9, **SMALL), "max_revolutions")])
def test_every_count_is_bounded_in_the_api(call, words, no_engine):
    with pytest.raises(ParameterError, match=f"{words}.*to go past it on purpose, set CRANKGEN_MAX_"):
        call()


@pytest.mark.parametrize("argv", [["chart", "--lines", "1000000"], ["poincare", "--from", "0.4", "--to", "0.5", "--values", "1000000"],
                                  ["campbell", "--speeds", "100000"], ["animate", "--frames", "100000"],
                                  ["sweep", "--omega", "0.5", "--workers", "100000"]])
def test_every_count_is_bounded_on_the_command_line(argv, tmp_path, capsys):
    rc = run_cli(argv + ["--elements", "2", "--out", str(tmp_path / "o")])
    one_line_refusal(capsys, rc, "must be at most", "to go past it on purpose, set CRANKGEN_MAX_")
    assert not (tmp_path / "o").exists()


# ---- memory: what the caller keeps, on every path --------------------------------------------

def _peak(call):
    gc.collect()
    tracemalloc.start()
    try:
        result = call()
        return tracemalloc.get_traced_memory()[1], result
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("crank", [dict(omega=0.5), dict(crank=crankgen.Motor()), dict(omega=0.5, model="exact")],
                         ids=["prescribed", "motor", "exact"])
def test_history_off_grows_by_what_the_result_keeps(crank):
    """Peak traced allocations at 200 and 1000 revolutions (8000 and 40000 steps) with
    history=False: under 100 bytes a step more (the result keeps t, theta, v_mid, u_end,
    extension and the iterations, 44 bytes a step; a motor's crank speed and acceleration too).
    Main: the motor grew by 694 bytes a step, the prescribed crank by 276."""
    def run(revolutions):
        return crankgen.simulate(Mechanism(), **crank, **SMALL, revolutions=revolutions, history=False)
    run(1)                                                        # compiled and loaded
    short, r1 = _peak(lambda: run(200))
    del r1
    long, r2 = _peak(lambda: run(1000))
    growth = (long - short) / (len(r2.t) - 8001)
    assert growth < 100, f"{growth:.0f} bytes a step"


def test_a_motor_run_without_history_gives_the_run_with_it_bit_for_bit():
    """The march in chunks of a motor-driven run with history=False (several chunks: 12000 steps)
    gives the same numbers as the run that keeps its history, at the requested times too."""
    kw = dict(crank=crankgen.Motor(), **SMALL, revolutions=300)
    full = crankgen.simulate(Mechanism(), **kw, times=[0.0, 3.3, 700.123])
    light = crankgen.simulate(Mechanism(), **kw, times=[0.0, 3.3, 700.123], history=False)
    assert light.states is None and len(light.t) == 12001
    for name in ("t", "theta", "v_mid", "u_end", "extension", "crank", "iterations"):
        np.testing.assert_array_equal(getattr(light, name), getattr(full, name), err_msg=name)
    np.testing.assert_array_equal(light.at_times.states, full.at_times.states)


def test_a_failed_motor_step_names_the_motor_time_constant_and_the_steps_that_resolve_it():
    """A driven crank's failed step says when the step is longer than the motor's time constant
    tau = J Omega_nl / (T_stall max|f'|) (the linear law: max|f'| = 1; here 0.005 against the step
    2 pi / (Omega_nl steps_per_rev) = 0.157), with a steps_per_rev whose step is no longer than
    tau (main's one path for every crank had dropped the sentence); a prescribed crank's does not."""
    from crankgen.analyses import simulation
    motor = crankgen.Motor(stall_torque=2.0, no_load_speed=1.0, inertia=0.01)
    with pytest.raises(crankgen.ConvergenceError) as err:
        crankgen.simulate(Mechanism(), crank=motor, **SMALL, revolutions=1)
    text = str(err.value)
    assert "time constant J Omega_nl / (T_stall max|f'|) = 0.005 is shorter than the step 0.157" in text
    n = int(text.rsplit("raise steps_per_rev above ", 1)[1])
    step = lambda spr: 2 * np.pi / spr                                               # Omega_nl = 1
    assert step(n) <= 0.005 * (1 + 1e-12) and step(n - 1) > 0.005
    prescribed = crankgen.simulate(Mechanism(), omega=0.5, **SMALL, revolutions=0.05)
    assert "time constant" not in str(simulation._failure(crankgen.engine.NOT_CONVERGED, 1, 1.0, 1.0, prescribed))


# ---- numbers and sequences: Python, NumPy, generators -----------------------------------------

@pytest.mark.parametrize("values", [(w for w in [0.4, 0.5]), (np.float64(w) for w in [0.4, 0.5]),
                                    np.array([0.4, 0.5]), [np.float32(0.4), 0.5]],
                         ids=["generator", "numpy-generator", "array", "mixed"])
def test_F28_poincare_takes_its_values_as_a_generator(values):
    """Battery 2's F28 (poincare(values=0.8): "object of type 'float' has no len()"), in the form
    of issue 41: a generator of values."""
    d = crankgen.poincare(Mechanism(), "omega", values, transient=1, samples=2, **SMALL)
    assert [p.parameter for p in d.points] == pytest.approx([0.4, 0.5], rel=1e-7)


@pytest.mark.parametrize("values", [0.8, np.float64(0.8), np.array(0.8), {0.4, 0.5}, {0.4: 1}, "0.4,0.5"])
def test_F28_poincare_refuses_what_is_not_a_sequence_by_name(values, no_engine):
    with pytest.raises(ParameterError, match="^values must be a sequence of omega values"):
        crankgen.poincare(Mechanism(), "omega", values, **SMALL)


def test_numbers_and_sequences_take_numpy_values_and_generators():
    assert Mechanism(gravity=(g for g in (0.0, np.float32(0.5)))).gravity == (0.0, 0.5)
    assert crankgen.simulate(Mechanism(), omega=np.array(0.5), **SMALL, revolutions=0.1).case.omega == 0.5
    r = crankgen.simulate(Mechanism(), omega=0.5, **SMALL, times=(np.float64(t) for t in (0.1, 0.2)))
    np.testing.assert_array_equal(r.at_times.t, [0.1, 0.2])
    c = crankgen.campbell(Mechanism(), (np.float64(s) for s in (0.0, 1.0)), angles=np.int64(4),
                          orders=(k for k in (1, 2)), n_elements=2)
    assert c.orders == (1, 2) and list(c.speeds) == [0.0, 1.0]
    stall, no_load, curve = crankgen.torque_curve.per_unit((w for w in (0.0, 50.0, 100.0)), iter([2.0, 1.5, 0.0]))
    assert (stall, no_load, curve) == (2.0, 100.0, ((0.0, 1.0), (0.5, 0.75), (1.0, 0.0)))
    for bad in (np.array([0.5]), [0.5], True, "0.5"):
        with pytest.raises(ParameterError, match="must be a number"):
            crankgen.modes(Mechanism(), omega=bad, n_elements=2)


def test_damping_none_is_the_models_damping_everywhere():
    """damping=None leaves the option to the model as every other field's None does."""
    kw = dict(n_elements=2, damping=None)
    assert crankgen.simulate(Mechanism(), omega=0.5, revolutions=0.05, steps_per_rev=40, **kw).case.damping \
        == "kelvin-voigt"
    assert crankgen.simulate(Mechanism(), omega=0.5, revolutions=0.05, steps_per_rev=40, model="paper",
                             **kw).case.damping == "paper"
    assert crankgen.modes(Mechanism(), model="paper", **kw).case.damping == "paper"
    assert Case(model="paper", damping=None).damping == "paper"
    assert SIMechanism(**STEEL, damping=None).mechanism.mu == 0.0
    with pytest.raises(ParameterError, match="the SI value goes in the SIMechanism's field damping"):
        crankgen.simulate(SIMechanism(**STEEL), units="si", damping=1e-4, n_elements=2, revolutions=0.05)


# ---- battery 3's leftovers on the newer flags -------------------------------------------------

@pytest.mark.parametrize("curve", [((0, True), (1, False)), (("0", "1"), ("1", "0")),
                                   ((0, 1), (np.bool_(True), 0)), ((0, 1), (0.5, 1e300), (1, 0))])
def test_G11_a_torque_curve_takes_numbers_only(curve):
    """Battery 3's G11 (text and booleans accepted as numbers; magnitudes beyond what floating
    point carries), on the motor's torque curve: True was taken as 1, '0.5' as 0.5, a per-unit
    torque of 1e300 ran to a non-finite state."""
    with pytest.raises(ParameterError, match="^torque_curve"):
        Case(motion="motor", torque_curve=curve)


@pytest.mark.parametrize("field", ['"torque_curve": [[0, true], [1, false]]', '"torque_curve": [["0", "1"], [1, 0]]'])
def test_G11_an_si_file_torque_curve_takes_numbers_only(field, tmp_path, capsys):
    si = tmp_path / "si.json"
    si.write_text('{"L": 0.3, "a": 0.15, "E": 2e11, "rho": 7870, "A": 6.4e-5, "I": 3.41e-10, "slider_mass": 0.0756, '
                  '"motion": "motor", "stall_torque": 10, "no_load_speed": 150, "inertia": 1e-3, ' + field + '}')
    rc = run_cli(["simulate", "--si", str(si), "--out", str(tmp_path / "o")])
    one_line_refusal(capsys, rc, "is not a number")


def test_G11_the_command_line_refuses_an_absurd_per_unit_torque(tmp_path, capsys):
    rc = run_cli(["simulate", "--crank", "motor", "--torque-curve", "0:1,0.5:1e300,1:0", "--out", str(tmp_path / "o")])
    one_line_refusal(capsys, rc, "beyond 1e50")


def test_G13_a_field_given_twice_in_an_si_file_is_refused(tmp_path, capsys):
    """Battery 3's G13 (a value given twice taken silently, the last one), in the SI file of the
    motor's fields: JSON's loader keeps the last of two "stall_torque"."""
    si = tmp_path / "si.json"
    si.write_text('{"L": 0.3, "a": 0.15, "E": 2e11, "rho": 7870, "A": 6.4e-5, "I": 3.41e-10, "slider_mass": 0.0756, '
                  '"motion": "motor", "stall_torque": 10, "no_load_speed": 150, "inertia": 1e-3, "stall_torque": 20}')
    rc = run_cli(["simulate", "--si", str(si), "--out", str(tmp_path / "o")])
    one_line_refusal(capsys, rc, "'stall_torque' is given twice")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("motion", ["motor", "shaft"])
@pytest.mark.parametrize("curve, peak", [(None, 1.0), (((0, 1), (0.5, 2), (1, 0)), 2.0)])
def test_G18_the_stall_limit_of_a_motor_is_where_its_peak_torque_meets_the_load(curve, peak, motion):
    """The motor turns the crank while T_stall max F(S) exceeds the load torque (closed form: the
    peak of the per-unit curve, at a knot of a shape-preserving interpolant), directly or through
    a flexible shaft (whose torque, untwisted, carries the motor's to the crank)."""
    from crankgen.analyses.bifurcation.api import stall_limit
    extra = {} if curve is None else {"torque_curve": curve}
    case = Case(motion=motion, stall_torque=0.05, **extra, **SMALL)
    value, why = stall_limit(case, "load_torque", 0.0, 0.2)
    assert value == pytest.approx(0.05 * peak, abs=1e-9) and "load torque" in why
    loaded = Case(motion=motion, stall_torque=0.05, load_torque=0.02, **extra, **SMALL)
    assert stall_limit(loaded, "stall_torque", 0.05, 0.001)[0] == pytest.approx(0.02 / peak, abs=1e-9)
    assert stall_limit(case, "load_torque", 0.0, 0.04 * peak) is None
    assert stall_limit(Case(**SMALL), "omega", 0.2, 0.5) is None                       # a prescribed crank


def test_G18_a_motor_branch_that_stops_short_names_the_stall_limit(tmp_path, capsys, monkeypatch):
    """Battery 3's G18 (a continuation that stops short without naming the limit), on the motor's
    flags: `continue --crank motor --parameter load_torque --from 0 --to 0.1` ended at 0.0487 with
    "Newton did not converge" and nothing about the stall torque 0.05.  The continuation itself is
    replaced by a branch that stops at 0.0487 (the real one takes a minute)."""
    import crankgen.analyses.bifurcation.api as api
    from crankgen.analyses.bifurcation.diagram import BifurcationDiagram, Branch

    class Short:
        evaluations, values = 0, 0

        def __init__(self, fmap, start, stop, settings, log=None):
            pass

        def diagram(self, state, start, direction):
            n = 3
            branch = Branch(period=1, parameter_name="load_torque", parameter=np.linspace(start, 0.0487, n),
                            amplitude=np.ones(n), stable=np.ones(n, bool), multipliers=np.full((n, 2), 0.5 + 0j),
                            states=np.tile(state, (n, 1)), section=np.zeros((n, 1)),
                            stop_reason="step below ds_min at load_torque = 0.0487 (Newton did not converge)")
            return BifurcationDiagram("load_torque", [branch], [], info={})
    monkeypatch.setattr(api, "Continuer", Short)
    rc = run_cli(["continue", "--crank", "motor", "--parameter", "load_torque", "--from", "0.04", "--to", "0.1",
               "--elements", "2", "--steps-per-rev", "40", "--out", str(tmp_path / "c"), "--quiet"])
    out = capsys.readouterr().out
    assert rc == 0 and "load_torque = 0.05 is the stall limit" in out
    assert "is the stall limit" in (tmp_path / "c" / "branches.csv").read_text()
