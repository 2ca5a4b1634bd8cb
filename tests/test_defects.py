"""Defects a new user met (issue 28, item 6), each pinned by a test that failed before its fix: a
crank at rest, commands that said something before refusing, flags silently ignored or named
unlike their siblings, a failed run whose progress claimed completion, a run-up drawn so that its
last revolutions collapse onto one line, figures whose ranges, bands and labels misled, and docs
that no longer described the program."""

import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import crankgen  # noqa: E402
from crankgen.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
TINY = ["--elements", "2", "--steps-per-rev", "20", "--quiet"]


def _one_line_error(capsys, words):
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert all(w in err for w in words), err
    return err


# ---- the command line ----------------------------------------------------------------------------

@pytest.mark.parametrize("argv", [["steady", "--omega", "0"], ["sweep", "--omega", "0,0.5"],
                                  ["continue", "--from", "0", "--to", "0.5"]],
                         ids=["steady", "sweep", "continue"])
def test_a_crank_at_rest_is_refused_in_one_line(argv, tmp_path, capsys):
    """--omega 0 documents a crank at rest; steady, sweep and continue divided by it."""
    assert main(argv + ["--out", str(tmp_path / "o"), "--quiet"]) == 2
    _one_line_error(capsys, ["0"])
    assert not (tmp_path / "o").exists()


def test_steady_refuses_a_run_up_before_it_says_anything(tmp_path, capsys):
    assert main(["steady", "--crank", "runup", "--out", str(tmp_path / "o")]) == 2
    err = _one_line_error(capsys, ["periodic", "runup"])
    assert err.startswith("crankgen steady: error:")          # no heading line before it
    assert not (tmp_path / "o").exists()


def test_continue_refuses_the_continued_parameters_own_flag(tmp_path, capsys):
    """`--parameter omega --omega 0.3` ignored --omega without a word."""
    assert main(["continue", "--parameter", "omega", "--omega", "0.3", "--from", "0.7", "--to", "0.9",
                 "--out", str(tmp_path / "o")]) == 2
    _one_line_error(capsys, ["--omega", "--from", "--to"])


def test_continue_over_a_guide_parameter_names_the_guide(tmp_path, capsys):
    """`--parameter c` on a line guide told the user to leave c 'at its default 0.8'."""
    assert main(["continue", "--parameter", "c", "--from", "0.7", "--to", "0.9",
                 "--out", str(tmp_path / "o")]) == 2
    err = _one_line_error(capsys, ["--guide circle", "line"])
    assert "default" not in err
    with pytest.raises(crankgen.ParameterError, match="circle guide") as info:
        crankgen.continuation(crankgen.Mechanism(), "c", 0.7, 0.9)
    assert "default" not in str(info.value)


def test_the_rocker_and_the_ground_pivot_are_continued_by_either_name(tmp_path):
    """--parameter c|d were named unlike the flags --rocker / --ground: both names are accepted,
    the diagram is over c, and its title names the speed and the linkage."""
    from crankgen.cli.main import build_parser
    from crankgen.cli.studies import _parameter, _title

    for flag, name in (("rocker", "c"), ("ground", "d"), ("c", "c"), ("d", "d")):
        args = build_parser().parse_args(["continue", "--guide", "circle", "--parameter", flag,
                                          "--from", "0.7", "--to", "0.8"])
        assert _parameter(args) == name
    args = build_parser().parse_args(["continue", "--guide", "circle", "--parameter", "rocker",
                                      "--omega", "0.5", "--from", "0.7", "--to", "0.8"])
    title = _title(args, "continuation")
    assert "rocker length" in title and "Omega* = 0.5" in title and "four-bar" in title
    assert "ground pivot d/L = 1" in title and "rocker c/L" not in title


def test_a_continuation_with_no_periodic_start_is_a_failed_run(tmp_path, capsys, monkeypatch):
    """`continue --from 1.6 --to 0.2` computed, then exited 2 (a usage error): it is a run that
    found nothing to start from (exit 1), and the message says a continuation can start from the
    other end."""
    from crankgen.analyses import steady

    def not_periodic(cases, **kwargs):
        return [crankgen.SteadyState(c, "not-periodic", None, None, 400, 0, None,
                                     "no periodic state with the crank period") for c in cases]
    monkeypatch.setattr(steady, "steady_states", not_periodic)
    assert main(["continue", "--from", "1.6", "--to", "0.2", "--out", str(tmp_path / "o"),
                 *TINY]) == 1
    err = capsys.readouterr().err
    assert "run failed" in err and "other end" in err and "from 0.2 to 1.6" in err


def test_a_failed_run_does_not_report_completion(tmp_path, capsys):
    """Approach B fails in step 36 at Omega* = 0.8 on 4 elements (37 with Newmark's rule); the
    progress printed 100 %."""
    seen = []
    with pytest.raises(crankgen.ConvergenceError) as info:
        crankgen.simulate(crankgen.Mechanism(), omega=0.8, approach="B", n_elements=4, revolutions=1,
                          progress=lambda done, total: seen.append(done))
    step = info.value.step
    assert 30 < step < 50 and len(info.value.partial.t) == step
    assert max(seen) < step
    assert main(["simulate", "--approach", "B", "--omega", "0.8", "--elements", "4",
                 "--out", str(tmp_path / "b")]) == 1
    err = capsys.readouterr().err
    assert "(100 %)" not in err and f"step {step}" in err


def test_a_run_up_is_drawn_against_the_revolutions_too(tmp_path, capsys):
    """Against the crank speed alone, every revolution after the ramp fell on one vertical line;
    and a run shorter than its ramp ended below the final speed without saying so."""
    from crankgen.discrete.kinematics import time_of_revolutions
    from crankgen.plots.figures import runup_figure

    res = crankgen.simulate(crankgen.Mechanism(), crank=crankgen.RunUp(start=0.2, stop=0.8, revolutions=1),
                            revolutions=2, n_elements=2, steps_per_rev=20)
    ramp_end = time_of_revolutions(res.case, 1)
    fig = runup_figure(res, ramp_end)
    speed_panel, revolution_panel = fig.axes[:2]
    x_speed = speed_panel.get_lines()[0].get_xdata()
    assert np.all(np.diff(x_speed) > 0) and x_speed[-1] == pytest.approx(0.8)   # the ramp only
    x_revs = revolution_panel.get_lines()[0].get_xdata()
    assert x_revs[0] == 0 and x_revs[-1] == pytest.approx(2.0) and len(x_revs) == len(res.t)
    short = crankgen.simulate(crankgen.Mechanism(), crank=crankgen.RunUp(start=0.2, stop=0.8, revolutions=4),
                              revolutions=1, n_elements=2, steps_per_rev=20)
    assert "before the ramp completes" in runup_figure(short, time_of_revolutions(short.case, 4)).axes[0].get_title()
    assert main(["simulate", "--crank", "runup", "--ramp", "4", "--revolutions", "1",
                 "--elements", "2", "--steps-per-rev", "20", "--out", str(tmp_path / "r")]) == 0
    assert "before the ramp of 4 revolutions completes" in capsys.readouterr().err


# ---- figures -------------------------------------------------------------------------------------

def test_convergence_figure_spans_the_counts_computed_and_used():
    """convergence.png ran x to the configured ladder's 64 where the ladder stopped at 4, with a
    dotted count no data explained."""
    from crankgen.experiments import ReproduceConfig, plots
    from crankgen.experiments.config import MODELS

    cfg = ReproduceConfig.quick()
    rows = [dict(model=m.key, approach=ap, omega=om, n_elements=n, amplitude=1.0 + 0.01 / n,
                 status="periodic", change_to_next=0.001)
            for m in MODELS for ap in "ABC" for om in cfg.conv_omegas for n in (2, 4)]
    counts = {(m.key, ap): (16 if ap == "A" else 4) for m in MODELS for ap in "ABC"}
    fig = plots.plot_convergence(dict(rows=rows, counts=counts), cfg)
    top = fig.axes[0]
    lo, hi = top.get_xlim()
    assert hi < 16 * 1.3 and 16 < hi                 # up to the count A uses, not to 64
    texts = [t.get_text() for t in top.get_legend().get_texts()]
    assert any("n = 16 (A)" in t for t in texts)


def test_poincare_figure_shades_the_range_beyond_the_theory(tmp_path):
    from crankgen.analyses.bifurcation.sweeps import PoincareDiagram, PoincarePoint
    seen = {}
    pc = PoincareDiagram("omega", [PoincarePoint("up", w, "irregular", 0, 0.1, 0.2, 30,
                                                 np.linspace(-40, 40, 30)) for w in (1.4, 1.5)],
                         info=dict(eps=0.01, approach="A"))
    from crankgen.analyses.bifurcation import sweeps
    real = sweeps.save_figure
    try:
        sweeps.save_figure = lambda fig, path, **kw: seen.setdefault("fig", fig)
        pc.plot(tmp_path / "p.png")
    finally:
        sweeps.save_figure = real
    ax = seen["fig"].axes[0]
    spans = [p for p in ax.patches if p.get_facecolor()[:3] == matplotlib.colors.to_rgb("0.88")]
    assert spans                                       # |v*| > 10 at eps = 0.01: |v|/L > 0.1
    assert any("beyond the theory" in t.get_text() for t in ax.get_legend().get_texts())


def test_a_label_away_from_its_point_has_a_leader():
    """'PD 1.322' floated 16 points above its point with no line to it."""
    from crankgen.plots.figures import panels, place_labels

    fig, axes = panels(1, 1)
    ax = axes[0, 0]
    ax.set_ylim(0, 1)
    ax.set_xlim(0, 1)
    fig.canvas.draw()
    per_pixel = 1.0 / ax.get_window_extent().height            # data units of one pixel
    x = np.linspace(0, 1, 400)
    for dy in np.arange(-26, 11, 2):                   # lines 2 pixels apart, from 26 below to 10 above:
        ax.plot(x, 0.5 + dy * per_pixel + 0 * x, color="k", lw=0.5)   # the four adjacent places taken
    place_labels(ax, [(0.5, 0.5, "PD 0.5", "k")])
    label = [t for t in ax.texts if t.get_text() == "PD 0.5"][0]
    dx, dy = label.xyann
    assert max(abs(dx), abs(dy)) > 14 and label.arrow_patch is not None


# ---- docs ----------------------------------------------------------------------------------------

def test_the_docs_describe_the_mechanisms_crankgen_runs():
    """The README's first paragraph and `crankgen --help` said: constant speed, straight guide."""
    from crankgen.cli.main import build_parser

    intro = README.split("\n\n")[1]
    help_text = build_parser().description
    for text in (intro, help_text):
        assert "four-bar" in text and "run-up" in text and "constant speed" in text


def test_examples_are_run_with_the_venvs_python():
    """After the README's set-up `python` is not the venv's: the commands say .venv/bin/python."""
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]:
        bare = re.findall(r"(?<![/\w.])python3? examples/", path.read_text(encoding="utf-8"))
        assert not bare, path


def test_the_first_compile_time_is_said_alike_by_the_program_and_the_readme():
    from crankgen.experiments.runner import COMPILE_TIME
    assert COMPILE_TIME in " ".join(README.split())


def test_the_continuation_docstring_names_every_continuable_parameter():
    from crankgen.declaration import schema
    doc = " ".join(crankgen.continuation.__doc__.split())
    for name in schema.CONTINUABLE:
        assert re.search(rf"\b{name}\b", doc), name


def test_the_si_help_names_the_damping_the_default_model_has():
    from crankgen.cli.main import build_parser
    sub = next(a for a in build_parser()._actions if hasattr(a, "choices") and a.choices
               and "simulate" in a.choices)
    text = next(a.help for a in sub.choices["simulate"]._actions if "--si" in a.option_strings)
    assert "Kelvin-Voigt" in text and "mu of eq. 24" not in text


def test_the_ivp_plot_writes_micrometres():
    source = (ROOT / "examples" / "ivp_testset_slider_crank.py").read_text(encoding="utf-8")
    assert "(um)" not in source and "(µm)" in source


def test_a_periodic_poincare_point_has_no_lyapunov_number_rather_than_nan():
    """The README says no result holds NaN; PoincarePoint.lyapunov was nan where periodic."""
    from crankgen.analyses.bifurcation import FunctionMap, sweep_map

    logistic = FunctionMap(lambda x, r: (r * x * (1 - x), r * (1 - 2 * x), x * (1 - x)), 1, "r")
    pc = sweep_map(logistic, [2.8, 3.2], np.array([0.3]), "up", 200, 16, 8, 1e-8, 0.01, None)
    assert [q.classification for q in pc.points] == ["period-1", "period-2"]
    assert all(q.lyapunov is None and q.repeat_residual is not None for q in pc.points)


def test_the_docs_say_what_crankgen_models_and_what_it_does_not():
    """The scope page lists what is modelled and what is not, and the README points to it; the
    motor is modelled (crankgen.Motor), and neither says otherwise (issue 43, item 4)."""
    page = (ROOT / "docs" / "theory" / "scope.md").read_text(encoding="utf-8").lower()
    modelled, _, not_modelled = page.partition("what it does not model:")
    for words in ("planar", "euler-bernoulli", "ideal joints", "prescribed", "crankgen.motor",
                  "point mass", "linear elastic", "moment of inertia"):
        assert words in modelled, words
    for words in ("rocker are rigid", "shear deformation", "friction"):
        assert words in not_modelled, words
    assert "the motor and the flywheel as a dynamic system" not in page
    readme = README.split("## What it models, and what it does not")[1].split("\n## ")[0].lower()
    assert "crankgen.motor" in readme and "docs/theory/scope.md" in readme
