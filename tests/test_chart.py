"""crankgen.stability_chart and crankgen chart: the regions' verdicts checked by marching from rest
and from the other orbit, the exports read back, the command line."""

import csv
import json
import subprocess
import sys

import numpy as np
import pytest

import crankgen
from crankgen.analyses.bifurcation import MechanismMap, sweep_map
from crankgen.analyses.charts import StabilityChart, stability_chart

SMALL = dict(n_elements=4, steps_per_rev=50)
X, Y = ("omega", 0.8, 1.4), ("eps", 0.01, 0.04)


@pytest.fixture(scope="module")
def chart():
    return stability_chart(crankgen.Mechanism(), x=X, y=Y, lines=3, max_period=2, **SMALL)


def _march(case, omega, state=None, transient=300, samples=32):
    """The classification of a march at omega from rest (state None) or from a state (d, v), and
    the amplitude (max |v*(1/2)|) of the orbit it settled on."""
    fmap = MechanismMap(case, "omega")
    x0 = np.zeros(fmap.dim) if state is None else np.asarray(state) / fmap.s
    (point,) = sweep_map(fmap, [omega], x0, "up", transient, samples, 8).points
    return point.classification, point.amplitude


def _other_orbit(chart, region, period, exclude_amplitude):
    """A stored state of a stable orbit of `period` at the line nearest the region's label, on the
    branch that is not the one reached from rest (amplitude far from exclude_amplitude)."""
    line = min((ln for ln in chart.lines if ln.diagram is not None), key=lambda ln: abs(ln.level - region.y))
    best = None
    for br in line.diagram.branches:
        if br.period != period:
            continue
        for i in np.flatnonzero(br.stable):
            if best is None or abs(br.parameter[i] - region.x) < best[0]:
                if abs(br.amplitude[i] - exclude_amplitude) > 0.2 * exclude_amplitude:
                    best = (abs(br.parameter[i] - region.x), br.states[i])
    return None if best is None else best[1]


@pytest.mark.slow
def test_the_chart_has_the_curves_and_regions_of_the_slider_crank(chart):
    kinds = {(c.kind, c.period) for c in chart.curves}
    assert {("period-doubling", 1), ("fold", 2), ("period-doubling", 2)} <= kinds
    words = {g.words for g in chart.regions if g.key is not None and g.area > 0.02}
    assert {"stable period-1", "stable period-2", "period-1 and period-2 coexist (stable)",
            "two stable period-2 orbits coexist"} <= words
    for g in chart.regions:                 # every cell on the lines agrees with its region's verdict
        if g.key is not None:
            assert g.agreement == 1.0, (g.words, g.votes)
    pd = next(c for c in chart.curves if c.kind == "period-doubling" and c.period == 1)
    assert set(pd.stop_reasons) == {"reached eps = 0.01", "reached eps = 0.04"}
    # the special points of every line inside the box lie on the curves (the lines run beyond it)
    for ln in chart.lines:
        for s in ln.diagram.special_points:
            if not X[1] <= s.parameter <= X[2]:
                continue
            cv = [c for c in chart.curves if c.kind == s.kind and c.period == s.period]
            gap = min(np.min(np.hypot((c["omega"] - s.parameter) / 0.6, (c["eps"] - ln.level) / 0.03))
                      for c in cv)
            assert gap < 0.02, (s.kind, s.period, s.parameter, ln.level)


@pytest.mark.slow
def test_marching_inside_each_region_shows_its_verdict(chart):
    """A point in the middle of each named region, marched 300 revolutions from rest (and, where two
    orbits coexist, from the other orbit's state), settles on what the region says."""
    from dataclasses import replace
    base = chart.lines[0].diagram.special_points[0].case
    checked = set()
    for g in sorted(chart.regions, key=lambda g: -g.area):
        if g.key is None or g.area < 0.02 or g.words in checked:
            continue
        checked.add(g.words)
        case = replace(base, eps=g.y, omega=g.x)
        got, amp = _march(case, g.x)
        periods = sorted(p for p, n in g.key for _ in range(n))
        if not periods:                 # no stable orbit of period <= max_period: none is reached
            assert got not in {f"period-{p}" for p in range(1, chart.max_period + 1)}, (g.words, got)
            continue
        assert got in {f"period-{p}" for p in periods}, (g.words, g.x, g.y, got)
        if len(periods) == 2:
            other = periods[1] if got == f"period-{periods[0]}" else periods[0]
            state = _other_orbit(chart, g, other, amp)
            assert state is not None, g.words
            got2, amp2 = _march(case, g.x, state)
            assert got2 == f"period-{other}", (g.words, got2)
            assert abs(amp2 - amp) > 0.2 * amp, (g.words, amp, amp2)      # another orbit
    assert len(checked) >= 4


def test_the_chart_files_read_back(chart, tmp_path):
    back = StabilityChart.from_json(chart.to_json(tmp_path / "chart.json"))
    assert back.x == chart.x and back.y == chart.y and len(back.curves) == len(chart.curves)
    for a, b in zip(back.curves, chart.curves):
        assert np.array_equal(a["omega"], b["omega"]) and np.array_equal(a.multipliers, b.multipliers)
    assert np.array_equal(back.labels, chart.labels)
    assert [(g.words, g.x, g.y) for g in back.regions] == [(g.words, g.x, g.y) for g in chart.regions]
    assert back.region_at(0.85, 0.02).words == "stable period-1"
    d0, d1 = chart.lines[0].diagram, back.lines[0].diagram
    assert np.array_equal(d0.branches[0].multipliers, d1.branches[0].multipliers)
    paths = chart.to_csv(tmp_path / "csv")
    with open(paths[0], newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == sum(len(c) for c in chart.curves)
    with open(paths[2], newline="") as fh:
        regions = list(csv.DictReader(fh))
    assert {r["words"] for r in regions} == {g.words for g in chart.regions}
    png = chart.plot(tmp_path / "chart.png")
    assert png.exists()
    from crankgen.analyses.charts.plot import chart_figure
    from crankgen.plots.figures import layout_problems
    assert layout_problems(chart_figure(chart)) == []


def test_bad_axes_are_refused():
    with pytest.raises(crankgen.ParameterError, match="two different parameters"):
        stability_chart(x=("eps", 0.01, 0.02), y=("eps", 0.01, 0.03))
    with pytest.raises(crankgen.ParameterError, match="low < high"):
        stability_chart(x=("omega", 1.4, 0.8), y=Y)
    with pytest.raises(crankgen.ParameterError, match="parameter must be one of"):
        stability_chart(x=("theta0", 0, 1), y=Y)


@pytest.mark.slow
def test_the_chart_command(tmp_path):
    out = tmp_path / "c"
    r = subprocess.run([sys.executable, "-m", "crankgen", "chart", "--x", "omega,1.0,1.1", "--y", "eps,0.01,0.02",
                        "--lines", "1", "--max-lines", "1", "--elements", "4", "--steps-per-rev", "50",
                        "--out", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "period-doubling curve of period-1 orbits" in r.stdout
    for name in ("curves.csv", "regions.csv", "chart.json", "chart.png"):
        assert (out / name).exists()
    assert json.loads((out / "chart.json").read_text())["format"] == "crankgen-stability-chart-1"
    r = subprocess.run([sys.executable, "-m", "crankgen", "chart", "--eps", "0.02", "--out", str(tmp_path / "d")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--eps is an axis of the chart" in r.stderr


def test_the_chart_in_si(chart, tmp_path):
    """--si: an axis given in SI (a crank speed in rad/s or rpm) is Omega* = speed / omega_b in the
    computation; the figure's ticks are round SI values at their places; curves_si.csv holds the
    curves in SI."""
    import math

    from crankgen.analyses.charts import si_view
    from crankgen.plots.figures import layout_problems
    si = crankgen.SIMechanism(L=0.25, E=2.1e11, rho=7850, A=1e-4, I=1e-8 / 12, a=0.025, slider_mass=0.1,
                              crank_speed=300.0)
    wb = si.omega_b
    name, lo, hi = si_view.to_model(("omega", 3000.0, 6000.0), si.scales, rpm=True)
    assert (lo, hi) == pytest.approx((3000 * 2 * math.pi / 60 / wb, 6000 * 2 * math.pi / 60 / wb), rel=1e-14)
    assert si_view.from_model("omega", 1.0, si.scales, rpm=True) == pytest.approx(wb * 60 / (2 * math.pi), rel=1e-14)
    assert si_view.to_model(("a", 0.01, 0.02), si.scales)[1:] == pytest.approx((0.04, 0.08), rel=1e-14)
    with pytest.raises(crankgen.ParameterError, match="rod's section"):
        si_view.to_model(("eps", 0.01, 0.02), si.scales)
    fig = si_view.figure(chart, si.scales, rpm=True)
    ax = fig.axes[0]
    assert layout_problems(fig) == [] and ax.get_xlabel() == "crank speed (rpm)"
    for tick, text in zip(ax.get_xticks(), ax.get_xticklabels()):       # each label at its place
        assert float(text.get_text()) == pytest.approx(tick * wb * 60 / (2 * math.pi), rel=1e-9)
    assert "Omega*" not in ax.get_title() and "L = 0.25 m" in ax.get_title()
    rows = list(csv.DictReader(open(si_view.to_csv(chart, tmp_path / "curves_si.csv", si.scales, rpm=True))))
    first = chart.curves[0]
    assert float(rows[0]["crank_speed_rpm"]) == pytest.approx(first["omega"][0] * wb * 60 / (2 * math.pi), rel=1e-12)
    assert float(rows[0]["amplitude_m"]) == pytest.approx(first["amplitude"][0] * si.scales.base["r"], rel=1e-12)
