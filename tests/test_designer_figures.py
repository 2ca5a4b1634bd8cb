"""The figures a designer looks at, checked as a reader would: every frame of an animation in the
same place (its first frame sat 4 px off the others, so the loop jumped), titles inside the figure
(modes.png's ran past both edges) and in SI for a mechanism given in SI."""

import numpy as np

import crankgen
from crankgen.plots.figures import layout_problems

PRESS = dict(L=0.25, E=2.1e11, rho=7850.0, A=1e-4, I=1e-8 / 12, a=0.05, slider_mass=0.5, crank_speed=314.16)


def _frames(path):
    from PIL import Image, ImageSequence
    return [np.asarray(f.convert("L"), dtype=float) for f in ImageSequence.Iterator(Image.open(path))]


def test_every_frame_of_an_animation_is_in_the_same_place(tmp_path):
    """The axes' frame (its dark spines) at the same pixels in every frame; the title in SI."""
    si = crankgen.SIMechanism(**PRESS)
    run = crankgen.simulate(si, units="si", revolutions=0.5, n_elements=2, steps_per_rev=20)
    path = run.animate(tmp_path / "run.gif", frames=5)
    frames = _frames(path)
    assert len(frames) == 5
    spines = [(np.flatnonzero((f < 60).mean(axis=0) > 0.5), np.flatnonzero((f < 60).mean(axis=1) > 0.5)) for f in frames]
    assert len(spines[0][0]) and len(spines[0][1])                # the vertical and horizontal spines
    for columns, rows in spines[1:]:
        assert np.array_equal(columns, spines[0][0]) and np.array_equal(rows, spines[0][1])
    from crankgen.plots.animation import Frames
    movie = Frames(run, None, 5)
    fig, _ = movie.figure()
    title = movie.ax.get_title().replace("\xa0", " ")
    assert "L = 0.25 m" in title and "crank speed = 314.16 rad/s" in title and "a* =" not in title


def test_the_modes_title_stays_inside_the_figure():
    """A four-bar with gravity, an offset and a rocker spring: the longest title the modes draw."""
    from crankgen.plots.modes import modes_figure
    m = crankgen.modes(crankgen.Mechanism(guide="circle", gravity=(0, -1e-3), offset=0.05, rocker_stiffness=0.01),
                       0.8, count=3, n_elements=4)
    fig = modes_figure(m)
    renderer = fig.canvas.get_renderer()
    box, width = fig._suptitle.get_window_extent(renderer), fig.get_figwidth() * fig.dpi
    assert box.x0 >= 0 and box.x1 <= width, (box, width)
    assert layout_problems(fig) == []
    si = crankgen.modes(crankgen.SIMechanism(**PRESS), units="si", count=2, n_elements=4)
    text = modes_figure(si)._suptitle.get_text().replace("\xa0", " ")
    assert "3000 rpm" in text and "slider mass = 0.5 kg" in text and "ms* =" not in text


def test_the_campbell_title_has_no_unused_speed_and_speaks_si():
    d = crankgen.campbell(crankgen.SIMechanism(**PRESS), units="si", speeds=[0.0, 300.0], angles=4, count=2,
                          n_elements=4)
    from crankgen.plots.campbell import campbell_figure
    title = campbell_figure(d).axes[0].get_title()
    title = title.replace("\xa0", " ")
    assert "Omega*" not in title and "crank speed" not in title and "a = 0.05 m" in title
