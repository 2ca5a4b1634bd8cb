"""`crankgen reproduce`: the findings functions on synthetic data with known answers, atomic output,
the overwrite policy, and a seconds-long 'tiny' configuration through the command line."""

import csv
import io
import json
import math
import os
import signal
import stat
import subprocess
import sys

import numpy as np
import pytest

import crankgen
from crankgen.cli import main as cli_main
from crankgen.experiments import ReproduceConfig, output_names, reproduce
from crankgen.experiments import findings as fd
from crankgen.experiments.io import OutputExistsError, atomic_write, write_csv


# ----------------------------------------------------------------------------- findings functions

def test_ratio_and_relative_difference_treat_missing_values_as_missing():
    r = fd.ratio([2.0, 1.0, math.nan, 3.0], [1.0, 0.0, 1.0, 2.0])
    assert r[0] == 2.0 and math.isnan(r[1]) and math.isnan(r[2]) and r[3] == 1.5
    d = fd.relative_difference([1.1, 0.8], [1.0, 1.0])
    assert d == pytest.approx([0.1, 0.2])


def test_first_exceedance_interpolates_linearly_between_sweep_points():
    x = [0.1, 0.2, 0.3, 0.4]
    assert fd.first_exceedance(x, [0.0, 0.05, 0.15, 0.3], 0.1) == pytest.approx(0.25)
    # NaN points (no periodic state) are skipped: interpolation between 0.1 and 0.3
    assert fd.first_exceedance([0.1, 0.2, 0.3], [0.0, math.nan, 0.2], 0.1) == pytest.approx(0.2)
    assert fd.first_exceedance(x, [0.0, 0.01, 0.02, 0.05], 0.1) is None
    assert fd.first_exceedance(x, [0.5, 0.6, 0.7, 0.8], 0.1) == pytest.approx(0.1)
    # only the first crossing counts even if the curve comes back below
    assert fd.first_exceedance(x, [0.0, 0.2, 0.0, 0.2], 0.1) == pytest.approx(0.15)


def test_first_where():
    assert fd.first_where([0.3, 0.1, 0.2], [True, False, True]) == 0.2
    assert fd.first_where([0.1, 0.2], [False, False]) is None


def test_loglog_slope_recovers_a_power_law_and_skips_missing_points():
    eps = np.array([0.005, 0.01, 0.02, 0.05, 0.1])
    y = 3.0 * eps ** -1.5
    f = fd.loglog_slope(eps, y)
    assert f["slope"] == pytest.approx(-1.5, abs=1e-12)
    assert math.exp(f["intercept"]) == pytest.approx(3.0)
    assert f["max_residual"] < 1e-12 and f["points"] == 5
    y2 = y.copy()
    y2[1], y2[3] = math.nan, -1.0
    f2 = fd.loglog_slope(eps, y2)
    assert f2["points"] == 3 and f2["slope"] == pytest.approx(-1.5)
    assert fd.loglog_slope([0.01], [1.0]) is None
    noisy = y * np.array([1.0, 1.1, 1.0, 0.9, 1.0])
    assert fd.loglog_slope(eps, noisy)["max_residual"] > 0.05


def test_converged_count_is_the_first_count_within_tolerance_of_the_next():
    ns = [2, 4, 8, 16, 32]
    amps = [1.0, 1.5, 1.6, 1.605, 1.606]         # changes 33 %, 6.3 %, 0.31 %, 0.06 %
    assert fd.converged_count(ns, amps, 0.01) == 8
    assert fd.converged_count(ns, amps, 0.1) == 4
    assert fd.converged_count(ns, amps, 1e-5) is None
    assert fd.converged_count(ns, [math.nan, math.nan, 1.0, 1.001, 1.0], 0.01) == 8
    assert list(fd.successive_changes([1.0, 2.0])) == [0.5]


def _periodic_curves(ms_values, zero_deg=(130.0, 310.0), points=101):
    theta = np.linspace(0.0, 360.0, points)
    base = 1e-3 * np.sin(np.radians(theta)) + 2e-4
    g = np.cos(np.radians(theta - (zero_deg[0] - 90.0)))      # zeros at zero_deg
    return theta, np.stack([base + m * 1e-3 * g for m in ms_values])


def test_extension_crossings_finds_where_all_curves_meet():
    theta, curves = _periodic_curves([0.0, 0.5, 1.0, 2.0])
    xs = fd.extension_crossings(theta, curves, rel_tol=0.05)
    assert [round(x["angle"], 1) for x in xs] == [130.0, 310.0]
    assert all(x["relative_spread"] < 1e-3 for x in xs)


def test_extension_crossings_off_grid_and_across_360():
    theta, curves = _periodic_curves([0.0, 1.0, 2.0], zero_deg=(1.7, 181.7), points=73)
    xs = fd.extension_crossings(theta, curves)
    assert len(xs) == 2
    assert xs[0]["angle"] == pytest.approx(1.7, abs=0.02)
    assert xs[1]["angle"] == pytest.approx(181.7, abs=0.02)


def test_extension_crossings_none_when_curves_never_meet():
    theta = np.linspace(0.0, 360.0, 101)
    curves = np.stack([np.sin(np.radians(theta)) + c for c in (0.0, 0.3, 0.6)])
    assert fd.extension_crossings(theta, curves) == []
    # a near-miss (spread 20 % of its maximum) is not a crossing at 5 %
    s = np.cos(np.radians(theta))
    near = np.stack([np.zeros_like(theta), np.abs(s) * 0.8 + 0.2])
    assert fd.extension_crossings(theta, near, rel_tol=0.05) == []
    assert len(fd.extension_crossings(theta, near, rel_tol=0.25)) == 2


def test_slider_acceleration_zeros_match_finite_differences():
    for a in (1e-6, 0.1, 0.3):
        zs = fd.slider_acceleration_zeros(a)
        assert len(zs) == 2
        th = np.radians(np.array(zs))
        h = 1e-4
        x = lambda t: a * np.cos(t) + np.sqrt(1 - (a * np.sin(t)) ** 2)
        acc = (x(th + h) - 2 * x(th) + x(th - h)) / h ** 2
        assert np.all(np.abs(acc) < 1e-5)
    assert fd.slider_acceleration_zeros(1e-6) == pytest.approx([90.0, 270.0], abs=1e-3)


def test_max_relative_difference_and_ranges_text():
    d = fd.max_relative_difference([1, 2, 3], [1.0, 2.4, math.nan], [1.0, 2.0, 3.0])
    assert d["value"] == pytest.approx(0.2) and d["at"] == 2 and d["points"] == 2
    assert fd.max_relative_difference([1], [math.nan], [1.0]) is None
    assert fd.ranges_text([0.3, 0.1, 0.2]) == "0.1, 0.2, 0.3"
    assert fd.ranges_text([0.1, 0.2, 0.3, 0.4]) == "0.1-0.4 (4 values)"


# ----------------------------------------------------------------------------- atomic output

def test_atomic_write_leaves_the_old_file_intact_when_interrupted(tmp_path):
    target = tmp_path / "fig5.csv"
    target.write_text("old complete table\n")

    def half_then_interrupt(fh):
        fh.write("omega,amplitude\n0.1,")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write(target, half_then_interrupt)
    assert target.read_text() == "old complete table\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig5.csv"]      # no temporary left


def test_atomic_write_of_a_new_file_leaves_nothing_on_failure(tmp_path):
    with pytest.raises(RuntimeError):
        atomic_write(tmp_path / "x.csv", lambda fh: (fh.write("a"), (_ for _ in ()).throw(RuntimeError("boom"))))
    assert list(tmp_path.iterdir()) == []


def test_write_csv_full_precision_and_empty_cells_for_missing(tmp_path):
    p = write_csv(tmp_path / "t.csv", ["a", "b", "c"], [dict(a=0.1 + 0.2, b=math.nan, c="failed")])
    rows = list(csv.reader(open(p)))
    assert rows == [["a", "b", "c"], [repr(0.1 + 0.2), "", "failed"]]
    with pytest.raises(OutputExistsError):
        write_csv(p, ["a"], [], overwrite=False)


# ----------------------------------------------------------------------------- command line

def test_refuses_to_overwrite_without_force(tmp_path, capsys):
    out = tmp_path / "res"
    out.mkdir()
    (out / "fig6.csv").write_text("earlier run\n")
    rc = cli_main(["reproduce", "--out", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert rc != 0
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "--force" in lines[0] and "fig6.csv" in lines[0]
    assert "Traceback" not in err
    assert (out / "fig6.csv").read_text() == "earlier run\n"
    assert sorted(p.name for p in out.iterdir()) == ["fig6.csv"]      # nothing computed or written


def test_bad_figure_list_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exc:
        cli_main(["reproduce", "--figures", "1,9"])
    assert exc.value.code != 0
    assert "between 2 and 8" in capsys.readouterr().err


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    """`crankgen reproduce --quick` with the quick preset replaced by the tiny one (same code path)."""
    out = tmp_path_factory.mktemp("tiny") / "results"
    out.mkdir()
    (out / "notes.txt").write_text("keep me\n")
    mp = pytest.MonkeyPatch()
    mp.setattr(ReproduceConfig, "quick", classmethod(lambda cls: ReproduceConfig.tiny()))
    try:
        rc = cli_main(["reproduce", "--quick", "--out", str(out), "--quiet"])
    finally:
        mp.undo()
    return rc, out


def test_tiny_run_writes_every_file(tiny_run):
    rc, out = tiny_run
    assert rc == 0
    names = set(p.name for p in out.iterdir())
    assert set(output_names()) <= names
    assert "notes.txt" in names and (out / "notes.txt").read_text() == "keep me\n"
    assert not [n for n in names if n.endswith(".tmp")]
    for f in range(2, 9):
        assert (out / f"fig{f}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        rows = list(csv.DictReader(open(out / f"fig{f}.csv")))
        assert rows and "status" in rows[0] and "model" in rows[0]
        # the exact rod beside the two models in the amplitude sweeps (Figures 5 and 6) only
        assert {r["model"] for r in rows} == {"paper", "consistent"} | ({"exact"} if f in (5, 6) else set())


def test_every_table_parses_into_numbers_words_and_empty_fields(tiny_run):
    from helpers import check_csv
    _, out = tiny_run
    tables = sorted(out.glob("*.csv"))
    assert len(tables) == 14
    for path in tables:
        check_csv(path)


def test_tiny_run_reports_failed_cases_in_table_and_findings(tiny_run):
    _, out = tiny_run
    rows = list(csv.DictReader(open(out / "fig6.csv")))
    failed = [r for r in rows if r["status"] not in ("periodic", "unstable", "not-periodic")]
    # the consistent model's approach B has no quartic term (its strain energy is unbounded below:
    # ill-posed) and diverges from rest at high speed: status "diverged", never "failed" or a
    # stability result, no amplitude, and the CSV says why in words
    assert failed and all(r["model"] == "consistent" and r["approach"] == "B" for r in failed)
    assert {r["status"] for r in failed} == {"diverged"}
    assert all(r["message"] and r["amplitude"] == "" and r["orbit_amplitude"] == "" for r in failed)
    assert all(r["strain_energy_bound"] == "unbounded below (ill-posed)" for r in failed)
    assert {r["strain_energy_bound"] for r in rows if r["approach"] != "B"} == {"bounded below"}
    text = (out / "findings.md").read_text()
    assert "## Cases without a stable periodic steady state" in text
    assert "| 6 | consistent | B |" in text
    assert "Newton did not converge" in text or "diverged" in text
    assert "## Approach B is ill-posed (its strain energy is unbounded below)" in text
    assert "| 6 | consistent | B | 0.01 | 0.5 | diverged (ill-posed) |" in text
    assert "no stable periodic state (while A does)" not in text


def test_tiny_findings_numbers_come_from_the_runs(tiny_run):
    _, out = tiny_run
    text = (out / "findings.md").read_text()
    for heading in ("## Element counts", "## Ratios of the B and C amplitudes to A",
                    "## Lowest speed at which B or C differs from A", "## Slope of log v* against log eps",
                    "## Crank angles where the extension does not depend on the slider mass",
                    "## Where the paper model and the consistent model disagree"):
        assert heading in text
    assert "nan" not in text.lower().replace("nano", "")
    # the ratio table agrees with fig5.csv
    rows = list(csv.DictReader(open(out / "fig5.csv")))
    amp = {(r["model"], r["approach"], float(r["omega"])): r["amplitude"] for r in rows
           if float(r["eps"]) == 0.01}
    ratio = float(amp[("paper", "C", 0.8)]) / float(amp[("paper", "A", 0.8)])
    assert f"| paper | 0.8 |" in text and f"{ratio:.5g}" in text


def test_rerun_keeps_everything_and_force_recomputes(tiny_run, capsys):
    _, out = tiny_run
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()}
    stream = io.StringIO()
    res = reproduce(out, config=ReproduceConfig.tiny(), figures=[8], stream=stream)
    assert res["computed"] == [] and res["files"] == []
    log = stream.getvalue()
    assert "figure 8: kept (complete and current)" in log
    assert "figure 5: not selected; its recorded result is used" in log
    assert "bifurcations: not selected; its recorded result is used" in log
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before
    res = reproduce(out, config=ReproduceConfig.tiny(), force=True, quiet=True, figures=[8])
    assert "figure 8" in res["computed"] and "fig8.csv" in res["files"]
    assert "figure 5" not in res["computed"]
    assert (out / "fig8.csv").read_bytes() == before["fig8.csv"]      # same runs, same numbers
    assert (out / "notes.txt").read_text() == "keep me\n"


def test_plain_progress_logs_when_not_a_terminal(tmp_path):
    stream = io.StringIO()
    reproduce(tmp_path / "r", config=ReproduceConfig.tiny(), figures=[7], stream=stream)
    text = stream.getvalue()
    assert "reproduce: convergence n = 1" in text and "(100 %)" in text
    assert "\r" not in text                                   # no terminal bar codes


def test_interrupt_keeps_finished_figures_and_leaves_no_partial_file(tmp_path, monkeypatch):
    from crankgen.experiments import figures as F

    def interrupted(ctx, counts):
        raise KeyboardInterrupt

    monkeypatch.setattr(F, "figure8", interrupted)
    out = tmp_path / "r"
    with pytest.raises(KeyboardInterrupt):
        reproduce(out, config=ReproduceConfig.tiny(), quiet=True, figures=[7, 8])
    names = sorted(os.listdir(out))
    assert names == ["data", "fig7.csv", "fig7.png", "manifest.json"]
    assert sorted(os.listdir(out / "data")) == ["convergence.json", "fig7.json"]
    manifest = json.loads((out / "manifest.json").read_text())["steps"]
    assert manifest["figure 7"]["state"] == "complete"
    assert manifest["figure 8"]["state"] == "incomplete"


# ----------------------------------------------------------------------------- resumable runs

_TINY_CLI = ("import sys; from crankgen.experiments import ReproduceConfig as R; "
             "R.quick = classmethod(lambda cls: R.tiny()); from crankgen.cli import main; "
             "sys.exit(main(sys.argv[1:]))")

# A child `crankgen reproduce --quick` (tiny preset) that stops at a defined point and waits there
# for the test: it prints PAUSED on stderr, then reads the pipe whose read end it inherited (file
# descriptor argv[2]).  The test signals it while it waits; a SIGINT raises KeyboardInterrupt out of
# the read, or, if it is handled only after the read returned, at the next step of the loops that
# follow (the signal is already pending then); a child that was never interrupted says so and
# exits 3 instead of hanging.  No clock is involved anywhere.
#   argv[1] "figure 4": after the first progress report of Figure 4's transients (in the middle
#           of the step, inside simulate_many);
#   argv[1] "fig7.png": when Figure 7's data and CSV are written but its PNG is not.
PAUSED = "crankgen-test: paused"
_PAUSING_CLI = f"""
import os, signal, sys
# Ctrl-C's default: a process started from a background job of a shell script inherits SIGINT
# ignored, and this child is about being interrupted by it
signal.signal(signal.SIGINT, signal.default_int_handler)
from crankgen.experiments import ReproduceConfig as R, figures as F, runner
R.quick = classmethod(lambda cls: R.tiny())
where, fd = sys.argv[1], int(sys.argv[2])

def pause():
    print({PAUSED!r}, file=sys.stderr, flush=True)
    while os.read(fd, 1):       # until the test has written its byte and closed the pipe
        pass
    for _ in range(10 ** 7):    # the test's signal was sent before that byte: it is pending
        pass
    print("crankgen-test: no interruption arrived", file=sys.stderr, flush=True)
    os._exit(3)

if where == "figure 4":
    real_figure4, real_simulate_many, state = F.figure4, runner.simulate_many, {{}}

    def figure4(ctx, counts):
        state["figure 4"] = True
        return real_figure4(ctx, counts)

    def simulate_many(cases, revolutions, progress=None, **kw):
        def report(done, total):
            if progress is not None:
                progress(done, total)
            if state.get("figure 4") and done > 0:
                pause()
        return real_simulate_many(cases, revolutions, progress=report, **kw)
    F.figure4, runner.simulate_many = figure4, simulate_many
elif where == "fig7.png":
    real_save = runner.save_figure

    def save_figure(fig, path, **kw):
        if os.path.basename(str(path)) == "fig7.png":
            pause()
        return real_save(fig, path, **kw)
    runner.save_figure = save_figure
from crankgen.cli import main
sys.exit(main(sys.argv[3:]))
"""


def _paused_child(where, argv):
    """Start the pausing child and return (process, write end of its pipe, stderr lines read) once
    it has reached the pause point (read from its stderr: a blocking read, no clock)."""
    r, w = os.pipe()
    proc = subprocess.Popen([sys.executable, "-c", _PAUSING_CLI, where, str(r), *argv],
                            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True,
                            pass_fds=(r,))
    os.close(r)
    seen = []
    for line in proc.stderr:
        seen.append(line)
        if line.strip() == PAUSED:
            return proc, w, seen
    os.close(w)
    raise AssertionError(f"the child ended (exit {proc.wait()}) before its pause point:\n" + "".join(seen))


def _findings_body(path):
    """findings.md without its last section (Run: date and wall times)."""
    text = path.read_text()
    return text[: text.index("## Run")]


def _tables(out):
    return {p.name: p.read_bytes() for p in sorted(out.glob("*.csv"))}


def test_sigint_then_rerun_gives_the_uninterrupted_result(tiny_run, tmp_path):
    _, ref = tiny_run
    out = tmp_path / "r"
    proc, w, seen = _paused_child("figure 4", ["reproduce", "--quick", "--out", str(out)])
    proc.send_signal(signal.SIGINT)              # in the middle of Figure 4: the child waits there
    os.write(w, b"x")                            # then let it go on (it is interrupted at once)
    os.close(w)
    seen += proc.stderr.readlines()
    assert proc.wait() == 130, "".join(seen)
    assert "figure 4: computing" in "".join(seen) and "interrupted" in seen[-1]
    assert json.loads((out / "manifest.json").read_text())["steps"]["figure 4"]["state"] == "incomplete"
    assert not (out / "findings.md").exists() and not (out / "fig5.csv").exists()
    (out / ".fig5.csv.x1y2z3.tmp").write_text("left by a killed run")     # as after a kill -9
    stream = io.StringIO()
    mp = pytest.MonkeyPatch()
    mp.setattr(ReproduceConfig, "quick", classmethod(lambda cls: ReproduceConfig.tiny()))
    try:
        from crankgen.experiments import runner
        mp.setattr(runner.sys, "stderr", stream)
        assert cli_main(["reproduce", "--quick", "--out", str(out)]) == 0
    finally:
        mp.undo()
    log = stream.getvalue()
    assert "figure 2: kept (complete and current)" in log
    assert "figure 4: computing (incomplete" in log or "figure 4: computing (missing" in log
    assert "figure 5: computing (missing" in log and "removed 1 temporary file" in log
    assert not list(out.glob(".*.tmp"))
    assert _tables(out) == _tables(ref) and len(_tables(out)) == 14
    for name in output_names():                  # the figures too, byte for byte
        if name != "findings.md":
            assert (out / name).read_bytes() == (ref / name).read_bytes(), name
    assert _findings_body(out / "findings.md") == _findings_body(ref / "findings.md")
    for p in (ref / "data").iterdir():
        assert (out / "data" / p.name).read_bytes() == p.read_bytes()


def test_output_files_have_the_mode_open_gives(tiny_run):
    _, out = tiny_run
    mask = os.umask(0)
    os.umask(mask)
    files = [p for p in list(out.iterdir()) + list((out / "data").iterdir())
             if p.is_file() and p.name != "notes.txt"]
    assert len(files) > 20
    assert {stat.S_IMODE(p.stat().st_mode) for p in files} == {0o666 & ~mask}


def test_second_command_line_run_recomputes_nothing(tiny_run, capsys, monkeypatch):
    """Nothing is computed: every engine entry point the steps use refuses to run."""
    from crankgen.experiments import runner
    from crankgen.analyses import bifurcation

    def refuse(*args, **kwargs):
        raise AssertionError("a kept step was recomputed")
    _, out = tiny_run
    monkeypatch.setattr(ReproduceConfig, "quick", classmethod(lambda cls: ReproduceConfig.tiny()))
    monkeypatch.setattr(runner._steady, "steady_states", refuse)
    monkeypatch.setattr(runner, "simulate_many", refuse)
    monkeypatch.setattr(bifurcation, "continuation", refuse)
    monkeypatch.setattr(bifurcation, "poincare", refuse)
    assert cli_main(["reproduce", "--quick", "--out", str(out)]) == 0
    captured = capsys.readouterr()
    err = captured.err
    assert "0 step(s) computed, 13 kept" in captured.out and "computing" not in err
    assert "step(s) computed" not in err                   # the summary once, on stdout
    assert "bifurcations: kept (complete and current)" in err and "starting the compiled engine" not in err


def test_figures_subset_in_a_fresh_folder_says_what_is_missing(tmp_path):
    out = tmp_path / "r"
    reproduce(out, config=ReproduceConfig.tiny(), quiet=True, figures=[8])
    text = (out / "findings.md").read_text()
    assert "Figures in this report: 8." in text
    assert text.startswith("# Findings: Figure 8 recomputed (Figures 2, 3, 4, 5, 6 and 7 are not in "
                           "this report)\n")
    run = text[text.index("## Run"):]
    assert "| engine start-up in this run: " in run and "| total of the steps |" in run
    assert "**Not in this report:** Figure 2 (not computed in this folder" in text
    rows = {line.split("|")[1].strip(): line for line in text.splitlines() if line.startswith("| C")}
    assert "| not computable |" in rows["C5b"] and "Figure 5 not computed" in rows["C5b"]
    assert "not computable" not in rows["C8b"].split("|")[7]


def test_claims_table_is_complete(tiny_run):
    from crankgen.experiments import claims
    _, out = tiny_run
    text = (out / "findings.md").read_text()
    head = text[: text.index("## Summary")]
    assert text.index("## The paper's claims beside both models") < text.index("## Summary")
    rows = [line.split(" | ") for line in head.splitlines() if line.startswith(("| C", "| K"))]
    ids = [r[0].strip("| ") for r in rows]
    assert ids == list(claims.IDS) and len(ids) == 26
    assert ids[0] == "C2a" and ids[-1] == "K4"
    for r in rows:
        assert r[6] in claims.VERDICTS, r
        assert r[7].strip(" |")                  # a reason, always


def test_failed_transient_keeps_its_rows_up_to_the_failure(tiny_run):
    _, out = tiny_run
    rows = list(csv.DictReader(open(out / "fig4.csv")))
    failed = [r for r in rows if r["status"] == "diverged"]
    assert failed                                # the consistent model's B diverges at Omega* = 0.8
    assert not [r for r in rows if r["status"] == "failed"]      # A and C never fail here
    key = lambda r: (r["model"], r["approach"], r["ms"])
    for k in {key(r) for r in failed}:
        rr = [r for r in failed if key(r) == k]
        t = [float(r["t"]) for r in rr]
        assert len(rr) > 5 and all(b > a for a, b in zip(t, t[1:]))
        assert all(r["v_mid"] != "" for r in rr[:-1]) and rr[-1]["v_mid"] == ""   # last: the failure
        fail_t = float(rr[-1]["t"])
        assert f"t* = {fail_t:.6g}" in rr[-1]["message"]
        assert all(r["beyond_theory"] in ("yes", "no") for r in rr[:-1])
        flagged = [r for r in rr[:-1] if abs(0.01 * float(r["v_mid"])) > 0.1]
        assert all(r["beyond_theory"] == "yes" for r in flagged)


def test_kill_then_rerun_finishes_the_job(tiny_run, tmp_path):
    """SIGKILL (no clean-up at all) in the middle of Figure 7 (its data and CSV written, its PNG
    not), then the same command."""
    _, ref = tiny_run
    out = tmp_path / "k"
    argv = ["reproduce", "--quick", "--figures", "7", "--out", str(out)]
    proc, w, _ = _paused_child("fig7.png", argv)
    proc.kill()
    proc.wait()
    os.close(w)
    proc.stderr.close()
    assert (out / "fig7.csv").exists() and not (out / "fig7.png").exists()
    steps = json.loads((out / "manifest.json").read_text())["steps"]
    assert steps["figure 7"]["state"] == "incomplete"
    done = subprocess.run([sys.executable, "-c", _TINY_CLI, *argv], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "figure 7: computing (incomplete" in done.stderr
    assert "convergence check: kept" in done.stderr
    assert (out / "fig7.csv").read_bytes() == (ref / "fig7.csv").read_bytes()
    assert not list(out.glob(".*.tmp")) and not list((out / "data").glob(".*.tmp"))
    text = (out / "findings.md").read_text()
    assert "**Not in this report:** Figure 2 (not computed in this folder" in text


def test_output_folder_that_cannot_be_made_is_refused_before_computing(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder\n")
    rc = cli_main(["reproduce", "--out", str(blocker / "sub"), "--quiet"])
    err = capsys.readouterr().err
    assert rc != 0 and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1 and str(blocker) in err
    assert "cannot write to" in err or "cannot create" in err


def test_theory_flag_matches_the_deflection_and_the_strain(tiny_run):
    """beyond_theory: |v|/L of the row's response (the orbit when periodic or unstable, the
    settled transient otherwise) above 0.1, or its axial strain above 0.01."""
    _, out = tiny_run
    rows = [r for r in csv.DictReader(open(out / "fig6.csv")) if r["model"] != "exact"]  # its own limits:
    key = {"periodic": "amplitude", "unstable": "orbit_amplitude"}   # test_the_exact_rods_rows_...
    for r in rows:
        v = r[key.get(r["status"], "envelope")]
        strain = float(r["axial_strain"]) if r["axial_strain"] else math.nan
        if v == "" and not math.isfinite(strain):
            assert r["beyond_theory"] == "" and r["deflection_over_L"] == ""
            continue
        x = float(r["eps"]) * float(v) if v else math.nan
        if v:
            assert float(r["deflection_over_L"]) == pytest.approx(x)
        expect = (x > 0.1) or (strain > 0.01)
        assert r["beyond_theory"] == ("yes" if expect else "no"), r
    assert any(r["beyond_theory"] == "yes" and float(r["deflection_over_L"]) <= 0.1 for r in rows), \
        "no case flagged for its strain alone"
    text = (out / "findings.md").read_text()
    assert "## Results beyond the range of the theory" in text
    flagged = {(r["model"], r["approach"]) for r in rows if r["beyond_theory"] == "yes"}
    section = text[text.index("## Results beyond"):text.index("## Settings")]
    for m, ap in flagged:
        assert f"| 6 | {m} | {ap} |" in section
    assert "axial strain of the neutral axis > 0.01" in section


def _section(text):
    return text[text.index("## Bifurcations of approach A"):text.index("## Slope of log v*")]


def test_bifurcation_findings_list_every_special_point(tiny_run):
    """Every special point of bifurcations.csv is in findings.md with its kind, Omega* and period;
    its critical multiplier is +1 (fold), -1 (period doubling) or on the unit circle."""
    _, out = tiny_run
    section = _section((out / "findings.md").read_text())
    rows = list(csv.DictReader(open(out / "bifurcations.csv")))
    cfg = ReproduceConfig.tiny()
    assert {(r["model"], float(r["eps"])) for r in rows} == {(m, e) for m in ("paper", "consistent")
                                                           for e in cfg.fig6_eps}
    points = [r for r in rows if r["kind"] in ("fold", "period-doubling", "neimark-sacker")]
    assert points
    table = [[c.strip() for c in line.split("|")[1:-1]] for line in section.splitlines()
             if line.startswith("| paper |") or line.startswith("| consistent |")]
    for r in points:
        cells = [r["model"], f"{float(r['eps']):g}", r["kind"], f"{float(r['omega']):.7g}", r["period"]]
        assert any(row[:5] == cells for row in table), cells
        mu = complex(float(r["multiplier_re"]), float(r["multiplier_im"]))
        target = {"fold": 1.0, "period-doubling": -1.0}.get(r["kind"])
        assert (abs(mu - target) if target is not None else abs(abs(mu) - 1.0)) < 1e-6, r
    for m in ("paper", "consistent"):
        assert f"- {m} model, eps = 0.01 (n = {cfg.bif_elements}, {cfg.bif_steps_per_rev} steps/rev)" in section
    assert "Beyond:" in section
    summary = (out / "findings.md").read_text().split("## Summary")[1].split("##")[0]
    assert "Bifurcations of approach A for 0.9 <= Omega* <= 1.3" in summary


def test_continuation_loses_stability_where_the_sweep_does(tiny_run):
    """Independent of the continuation: Figure 6's steady states (shooting) of the consistent
    model's A say stable or unstable at each swept speed; the continuation's crank-period branch
    says the same there, and between a stable start and an unstable swept speed it has a special
    point."""
    _, out = tiny_run
    lo, hi = ReproduceConfig.tiny().bif_range
    sweep = {float(r["omega"]): r["status"] for r in csv.DictReader(open(out / "fig6.csv"))
             if r["model"] == "consistent" and r["approach"] == "A" and float(r["eps"]) == 0.01}
    branch = [r for r in csv.DictReader(open(out / "bifurcation_branches.csv"))
              if r["model"] == "consistent" and r["branch"] == "0" and float(r["eps"]) == 0.01]
    om = np.array([float(r["omega"]) for r in branch])
    stable = [r["stable"] == "1" for r in branch]
    inside = {w: s for w, s in sweep.items() if lo <= w <= hi and s in ("periodic", "unstable")}
    assert "unstable" in inside.values()          # the tiny sweep: unstable at 1.2
    for w, s in inside.items():
        assert stable[int(np.argmin(np.abs(om - w)))] == (s == "periodic"), w
    pts = [float(r["omega"]) for r in csv.DictReader(open(out / "bifurcations.csv"))
           if r["model"] == "consistent" and r["branch"] == "0" and float(r["eps"]) == 0.01]
    first_unstable = min(w for w, s in inside.items() if s == "unstable")
    assert stable[0] and any(lo < p < first_unstable for p in pts), pts


def test_findings_rebuilt_from_the_recorded_bifurcations(tiny_run, tmp_path):
    """findings.md deleted: a rerun computes only the findings step, from the recorded data, and
    the bifurcation section is the same."""
    import shutil
    _, ref = tiny_run
    out = tmp_path / "copy"
    shutil.copytree(ref, out)
    before = _findings_body(out / "findings.md")
    (out / "findings.md").unlink()
    res = reproduce(out, config=ReproduceConfig.tiny(), quiet=True)
    assert res["computed"] == ["findings"]
    assert _findings_body(out / "findings.md") == before


def test_a_transient_is_still_growing_when_its_last_revolution_exceeds_the_one_before_by_5_percent():
    """TransientCurve.still_growing, the note of the findings (report.py, report_figures.py): the
    maxima of |v*| over the last two whole revolutions, given only when the last exceeds the one
    before by more than 5 %, and never for less than two revolutions of history."""
    from crankgen.experiments.figures import TransientCurve, TransientSpec

    spec = TransientSpec("consistent", "A", 4, 0.8, 3, steps_per_rev=10)
    theta = np.linspace(0.0, 6 * np.pi, 31)[:-1]          # three revolutions of 10 steps
    envelope = np.repeat([1.0, 2.0, 2.0 * 1.06], 10)       # the maxima grow by 6 % at the end

    def curve(v):
        return TransientCurve(spec, t=np.arange(len(v), dtype=float), v_mid=v)
    wave = -np.abs(np.sin(theta / 2 + 0.1)) - 0.5          # |v*| in [0.5, 1.5] each revolution
    before, last = curve(envelope * wave).still_growing
    assert before == pytest.approx(2.0 * np.max(np.abs(wave[10:20])))
    assert last == pytest.approx(2.0 * 1.06 * np.max(np.abs(wave[20:])))
    flat = np.repeat([1.0, 2.0, 2.0 * 1.04], 10) * wave    # 4 %: not growing
    assert curve(flat).still_growing is None
    assert curve((envelope * wave)[:20]).still_growing is None     # two revolutions: not enough history


def test_the_exact_rods_rows_sit_beside_unchanged_rows_of_the_two_models(tiny_run, tmp_path):
    """Figure 5 without the exact rod (exact_rows=False) has every row and column of the two models
    the tiny run has; the exact rod's rows use the consistent model's element count for A and are
    flagged by the exact rod's own limits (crankgen.analyses.theory), from their own measures."""
    from crankgen.analyses import theory
    _, out = tiny_run
    alone = tmp_path / "alone"
    reproduce(alone, config=ReproduceConfig.tiny().with_(exact_rows=False), quiet=True, figures=[5])
    with_exact = list(csv.DictReader(open(out / "fig5.csv")))
    without = list(csv.DictReader(open(alone / "fig5.csv")))
    two = [r for r in with_exact if r["model"] != "exact"]
    assert len(two) == len(without) and len(with_exact) == len(two) + len({(r["omega"], r["eps"]) for r in two})
    for a, b in zip(two, without):
        assert {k: a[k] for k in b} == b
    counts = {r["approach"]: r["n_elements"] for r in with_exact if r["model"] == "consistent"}
    for r in (r for f in (5, 6) for r in csv.DictReader(open(out / f"fig{f}.csv")) if r["model"] == "exact"):
        assert r["approach"] == "exact" and r["n_elements"] == counts["A"]    # tiny: exact_row_elements None
        if r["status"] in ("periodic", "unstable"):
            flag = theory.exact_range_flag(float(r["eps"]), float(r["fibre_strain"]),
                                           float(r["section_rotation_deg"]))
            assert r["beyond_theory"] == flag.label and 0 < float(r["section_rotation_deg"]) < 90


def test_the_exact_rods_special_points_are_its_own_stability_changes(tiny_run):
    """exact_rod_points.csv: each consistent special point has its fate; the exact rod's period
    doubling found by the continuation is where steady_state's own shooting (another path) finds
    the exact rod's crank-periodic orbit losing stability, with a multiplier through -1."""
    _, out = tiny_run
    rows = list(csv.DictReader(open(out / "exact_rod_points.csv")))
    assert {r["model"] for r in rows} == {"consistent", "exact"}
    cons = [r for r in rows if r["model"] == "consistent"]
    assert cons and all(r["fate"] in ("survives", "moves", "vanishes") for r in cons)
    moved = [r for r in cons if r["fate"] != "vanishes"]
    assert all(float(r["shift"]) == pytest.approx(float(r["exact_omega"]) - float(r["omega"]), abs=1e-12)
               for r in moved)
    pd = next(r for r in rows if r["model"] == "exact" and r["kind"] == "period-doubling" and r["period"] == "1")
    omega = float(pd["omega"])
    mech = crankgen.Mechanism(eps=float(pd["eps"]))
    kw = dict(model="exact", n_elements=int(pd["n_elements"]), steps_per_rev=int(pd["steps_per_rev"]))
    below = crankgen.steady_state(mech, omega=omega - 0.01, **kw)
    above = crankgen.steady_state(mech, omega=omega + 0.01, **kw)
    assert below.multiplier < 1 < above.multiplier
    text = (out / "findings.md").read_text()
    assert "## The geometrically exact rod beside the two models" in text
    assert f"period doubling {float(next(r for r in cons if r['kind'] == 'period-doubling')['omega']):.5g} -> " \
           f"{omega:.5g}" in text
    assert (out / "exact_rod.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_exact_rods_character_rows_are_the_response_an_independent_march_finds(tiny_run):
    """exact_rod_character.csv: the exact rod's Poincare samples at exact_character_omegas are the
    mid-span deflections that crankgen.simulate (another path through the engine) finds from rest
    once per revolution after the transient; a row classified period-k repeats with period k, a
    non-periodic one carries its Lyapunov exponent, and findings.md states each row."""
    _, out = tiny_run
    cfg = ReproduceConfig.tiny()
    rows = list(csv.DictReader(open(out / "exact_rod_character.csv")))
    assert [(r["mechanism"], float(r["omega"])) for r in rows] == \
        [(m, w) for m in cfg.exact_mechanisms for w in cfg.exact_character_omegas]
    text = (out / "findings.md").read_text()
    for r in rows:
        assert r["model"] == "exact" and r["classification"] != "failed", r
        n, spr = int(r["n_elements"]), int(r["steps_per_rev"])
        transient, samples = int(r["transient"]), int(r["samples"])
        assert (n, spr, transient, samples) == (cfg.exact_elements, cfg.exact_character_steps or cfg.exact_steps,
                                                cfg.exact_character_transient, cfg.exact_character_samples)
        mech = crankgen.Mechanism(a=cfg.a, eps=float(r["eps"]), ms=cfg.ms, mu=cfg.mu)
        run = crankgen.simulate(mech, omega=float(r["omega"]), model="exact", n_elements=n, steps_per_rev=spr,
                                revolutions=transient + samples, history=True)
        v = np.asarray(run.v_mid)[::spr][transient + 1:transient + samples + 1]
        assert len(v) == samples
        assert float(r["sample_min"]) == pytest.approx(v.min(), rel=1e-6, abs=1e-9)
        assert float(r["sample_max"]) == pytest.approx(v.max(), rel=1e-6, abs=1e-9)
        if r["classification"].startswith("period-"):
            k = int(r["period"])
            assert r["classification"] == f"period-{k}" and r["lyapunov"] == ""
            assert np.abs(v[k:] - v[:-k]).max() <= 1e-6 * np.abs(v).max()
        else:
            assert math.isfinite(float(r["lyapunov"]))
        assert f"- {r['mechanism']}, Omega* = {float(r['omega']):g}: {r['classification']}" in text
