"""Branches a researcher can use: every point's physical quantities against the same quantities of
a steady state or a simulation of its orbit, the diagram's JSON and CSV files read back, and the
marched amplitudes of a sweep up and down against the branches they are drawn over."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.analyses.bifurcation import BifurcationDiagram

SMALL = dict(n_elements=4, steps_per_rev=50)
SECTION = crankgen.sections.rectangle(0.01, 0.01)


@pytest.fixture(scope="module")
def diagram():
    return crankgen.continuation(crankgen.Mechanism(eps=0.02), "omega", 0.8, 1.3, max_period=2,
                                 section=SECTION, **SMALL)


def _quantities_of(result, n):
    xs = np.arange(2 * n + 1) / (2 * n)
    torque = np.asarray(result.torque)
    fibre = math.sqrt(3)
    return dict(peak_torque=torque[np.argmax(np.abs(torque))],
                peak_pin_force_A=np.max(np.hypot(result.crank_on_rod_x, result.crank_on_rod_y)),
                peak_pin_force_B=np.max(np.hypot(result.rod_on_slider_x, result.rod_on_slider_y)),
                peak_support_force=np.max(np.hypot(result.guide_on_slider_x, result.guide_on_slider_y)),
                peak_strain=max(np.max(np.abs(result.surface_strain(xs, fiber=f))) for f in (fibre, -fibre)),
                peak_stress=crankgen.stress(result, SECTION).largest.value,
                peak_v=np.max(np.abs(result.v_mid)))


def test_every_branch_point_has_its_orbits_quantities(diagram):
    one = next(b for b in diagram.branches if b.period == 1)
    assert set(one.quantities) == {"peak_v", "peak_torque", "peak_pin_force_A", "peak_pin_force_B",
                                   "peak_support_force", "peak_axial_force", "peak_strain", "peak_stress"}
    assert one.quantity_units["peak_torque"] == "rhoA L^3 omega_b^2" and one.quantity_units["peak_stress"] == "E"
    i = int(np.argmin(np.abs(one.parameter - 0.9)))
    st = crankgen.steady_state(crankgen.Mechanism(eps=0.02), omega=float(one.parameter[i]), **SMALL)
    assert st.ok
    for name, value in _quantities_of(st, 4).items():
        assert abs(one.quantities[name][i] - value) < 1e-5 * abs(value), (name, one.quantities[name][i], value)
    assert abs(one.quantities["peak_v"][i] - one.amplitude[i]) < 0.01 * one.amplitude[i]


def test_a_period_two_point_measures_both_revolutions(diagram):
    two = next(b for b in diagram.branches if b.period == 2)
    i = len(two) // 2
    run = diagram.orbit(diagram.branches.index(two), i)           # simulate over its two revolutions
    for name, value in _quantities_of(run, 4).items():
        assert abs(two.quantities[name][i] - value) < 1e-6 * abs(value), name


def test_the_diagram_files_read_back(diagram, tmp_path):
    back = BifurcationDiagram.from_json(diagram.to_json(tmp_path / "d.json"))
    csv_back = BifurcationDiagram.read_csv(diagram.to_csv(tmp_path / "csv")[0].parent, info=diagram.info)
    for got in (back, csv_back):
        assert got.parameter_name == diagram.parameter_name and len(got.branches) == len(diagram.branches)
        for a, b in zip(got.branches, diagram.branches):
            assert a.period == b.period and a.origin == b.origin and a.stop_reason == b.stop_reason
            for name in ("parameter", "amplitude", "stable", "multipliers", "states", "section"):
                assert np.array_equal(getattr(a, name), getattr(b, name)), name
            assert set(a.quantities) == set(b.quantities)
            for q in b.quantities:
                assert np.array_equal(a.quantities[q], b.quantities[q], equal_nan=True), q
        assert len(got.special_points) == len(diagram.special_points)
        for s, t in zip(got.special_points, diagram.special_points):
            assert (s.kind, s.parameter, s.amplitude, s.period, s.branch, s.multiplier) == \
                   (t.kind, t.parameter, t.amplitude, t.period, t.branch, t.multiplier)
            assert np.array_equal(s.multipliers, t.multipliers) and np.array_equal(s.state, t.state)
            assert s.case == t.case                       # crankgen.follow takes a loaded point
    assert back.info == {k: list(v) if isinstance(v, tuple) else v for k, v in diagram.info.items()}


def test_a_sweep_up_and_down_lies_on_the_stable_branches(diagram, tmp_path):
    values = [0.85, 1.0, 1.2]
    pc = crankgen.poincare(crankgen.Mechanism(eps=0.02), "omega", values, "both", transient=150, samples=16,
                           **SMALL)
    for q in pc.points:
        assert q.amplitude is not None
        if not q.classification.startswith("period-"):
            continue
        k = int(q.classification.split("-")[1])
        near = [abs(b.amplitude[i] - q.amplitude) for b in diagram.branches if b.period == k
                for i in np.flatnonzero(b.stable) if abs(b.parameter[i] - q.parameter) < 0.01]
        assert near and min(near) < 0.02 * q.amplitude, (q.direction, q.parameter, q.amplitude)
    png = diagram.plot(tmp_path / "overlay.png", sweep=pc)
    assert png.exists()


def test_the_continue_command_writes_quantities_json_and_the_sweep(tmp_path):
    import csv
    import subprocess
    import sys
    out = tmp_path / "c"
    r = subprocess.run([sys.executable, "-m", "crankgen", "continue", "--from", "0.9", "--to", "1.1",
                        "--elements", "4", "--steps-per-rev", "50", "--max-period", "1", "--section",
                        "rectangle:0.01,0.01", "--sweep", "3", "--out", str(out), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(out / "branches.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert all(float(row["peak_stress"]) != 0 and float(row["peak_torque"]) != 0 for row in rows)
    d = BifurcationDiagram.from_json(out / "continuation.json")
    assert len(d.branches[0]) == len(rows)
    with open(out / "poincare_summary.csv", newline="") as fh:
        sweep = list(csv.DictReader(fh))
    assert len(sweep) == 6 and all(float(row["amplitude"]) > 0 for row in sweep)
