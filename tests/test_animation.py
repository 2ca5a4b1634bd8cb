"""Watching the mechanism move (crankgen.plots.animation): the frames' count in the written file, the
first frame of a run from rest at the rigid mechanism's position (read from the figure's artists),
the inertial node positions against the declared outputs of the rod's end, a four-bar's rocker,
a continuation point's orbit, and the command."""

import math

import numpy as np
import pytest
from PIL import Image

import crankgen
from crankgen.discrete import kinematics
from crankgen.plots.animation import Frames, inertial_nodes
from crankgen.analyses.bifurcation.mechanism import orbit_peak

TINY = dict(n_elements=2, steps_per_rev=20)


def _on_segment(points, a, b):
    """Largest distance of points from the segment a-b (and whether they stay between its ends)."""
    d = b - a
    s = (points - a) @ d / (d @ d)
    foot = a + np.clip(s, 0, 1)[:, None] * d
    return float(np.max(np.linalg.norm(points - foot, axis=1))), bool(np.all((s > -1e-12) & (s < 1 + 1e-12)))


def test_the_first_frame_is_the_rigid_mechanism_and_the_file_has_every_frame(tmp_path):
    theta0 = 0.7
    run = crankgen.simulate(crankgen.Mechanism(offset=0.05), omega=0.8, revolutions=1, theta0=theta0, **TINY)
    path = run.animate(tmp_path / "run.gif", frames=6)
    assert Image.open(path).n_frames == 6
    movie = Frames(run, frames=6)
    _, art = movie.figure()                                  # drawn at frame 0
    A = 0.1 * np.array([math.cos(theta0), math.sin(theta0)])
    kin = kinematics.case_state(run.case, 0.0)
    B = kinematics.rigid_end(run.case, kin.vector)
    rod = art["rod"].get_xydata()
    off, between = _on_segment(rod, A, B)
    assert off < 1e-12 and between                            # the straight rigid rod from A to B
    np.testing.assert_allclose(rod[0], A, atol=1e-15)
    np.testing.assert_allclose(rod[-1], B, atol=1e-12)
    assert B[1] == pytest.approx(0.05) and np.hypot(*(B - A)) == pytest.approx(1.0)
    np.testing.assert_allclose(art["crank"].get_xydata(), [[0, 0], A], atol=1e-15)
    np.testing.assert_allclose(art["end"].get_xydata(), [B], atol=1e-12)
    assert "magnified" in movie.ax.get_title() and f"{movie.magnification:g}x" in movie.ax.get_title()
    movie.draw(5)                                             # the last frame: the last step
    np.testing.assert_allclose(art["rod"].get_xydata()[-1], movie.end[5])
    assert movie.steps[-1] == len(run.t) - 1


def test_the_nodes_in_the_inertial_frame_carry_the_rods_end(tmp_path):
    run = crankgen.simulate(crankgen.Mechanism(eps=0.05), omega=0.9, revolutions=1, **TINY)
    nodes = inertial_nodes(run)
    np.testing.assert_allclose(nodes[:, -1, 0], run.slider_position, rtol=1e-12)
    np.testing.assert_allclose(nodes[:, -1, 1], run.end_height, atol=1e-14)
    np.testing.assert_allclose(nodes[:, 0, 0], 0.1 * np.cos(run.theta), atol=1e-15)      # the crank pin
    magnified = inertial_nodes(run, magnification=10.0)
    rigid = inertial_nodes(run, magnification=0.0)
    np.testing.assert_allclose(magnified - rigid, 10 * (nodes - rigid), atol=1e-12)


def test_a_steady_orbit_and_a_four_bar(tmp_path):
    st = crankgen.steady_state(crankgen.Mechanism(), omega=0.8, **TINY)
    assert len(Frames(st)) == 21                                       # 24 per revolution, 21 steps
    path = st.animate(tmp_path / "orbit.gif", frames=3)
    assert Image.open(path).n_frames == 3
    four = crankgen.Mechanism(guide=crankgen.Circle(center=(1.0, 0.1), radius=0.8))
    run = crankgen.simulate(four, omega=0.5, revolutions=0.5, **TINY)
    movie = Frames(run, magnification=1.0)
    _, art = movie.figure()
    for k in range(len(movie)):
        movie.draw(k)
        D, tip = art["rocker"].get_xydata()
        np.testing.assert_allclose(D, [1.0, 0.1])
        assert np.hypot(*(tip - D)) == pytest.approx(0.8, rel=1e-9)   # the rocker is rigid


def test_a_continuation_points_orbit():
    d = crankgen.continuation(crankgen.Mechanism(), "omega", 0.5, 0.55, max_period=1, n_elements=2,
                              steps_per_rev=30)
    run = d.orbit(0, 3)
    br = d.branches[0]
    assert run.case.omega == pytest.approx(br.parameter[3])
    assert orbit_peak(run.v_mid) == pytest.approx(br.amplitude[3], rel=1e-6)      # the same orbit
    assert run.v_mid[0] == pytest.approx(br.section[3, 0], rel=1e-9)               # its start
    assert run.v_mid[-1] == pytest.approx(run.v_mid[0], abs=1e-6)                   # periodic
    with pytest.raises(crankgen.ParameterError, match="point must be below"):
        d.orbit(0, len(br))


def test_formats_and_the_command(tmp_path, capsys):
    from matplotlib import animation as mpl

    from crankgen.cli import main
    run = crankgen.simulate(crankgen.Mechanism(), omega=0.8, revolutions=0.2, **TINY)
    with pytest.raises(crankgen.ParameterError, match=".gif or .mp4"):
        run.animate(tmp_path / "x.avi")
    if not mpl.writers.is_available("ffmpeg"):
        with pytest.raises(crankgen.ParameterError, match="ffmpeg"):
            run.animate(tmp_path / "x.mp4")
    assert main(["animate", "--revolutions", "0.5", "--frames", "4", "--elements", "2", "--steps-per-rev", "20",
                 "--out", str(tmp_path / "a"), "--quiet"]) == 0
    assert Image.open(tmp_path / "a" / "mechanism.gif").n_frames == 4
    assert "4 frames" in capsys.readouterr().out
    assert main(["animate", "--magnify", "-1", "--out", str(tmp_path / "b")]) == 2
    assert not (tmp_path / "b").exists()
