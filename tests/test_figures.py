"""Figures: measured, not estimated.  crankgen.plots.figures.layout_problems finds what a reader would
see as broken (text or a legend beyond the image, a legend over a panel, panels overlapping, a
special-point label over data); every figure of a reproduce run and of the continue / poincare
commands has none.  The colours of distinct meanings are distinct."""

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from crankgen.plots.figures import fit_panels, layout_problems, panels, place_labels  # noqa: E402


def test_the_checker_sees_a_clipped_legend_and_a_label_on_data():
    fig, axes = panels(1, 2, width=3.0, height=2.0)
    ax = axes[0, 1]
    ax.plot([0, 1], [0, 1], label="a label far longer than the panel and the figure are wide " * 3)
    leg = ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.3))
    leg._crankgen_outside = True
    problems = layout_problems(fig)
    assert any("beyond the figure" in p for p in problems), problems
    fig2, axes2 = panels(1, 1)
    ax2 = axes2[0, 0]
    ax2.plot(np.linspace(0, 1, 50), np.linspace(0, 1, 50))
    t = ax2.annotate("PD 0.5", (0.5, 0.5), xytext=(0, 0), textcoords="offset points", ha="center")
    t._crankgen_label = True                          # placed on the line by hand
    assert any("covers" in p for p in layout_problems(fig2))


def test_fit_panels_makes_room_for_what_the_panels_need():
    fig, axes = panels(2, 2, width=3.0, height=2.0, space_below=0.0)
    for ax in axes.flat:
        ax.plot([0, 1], [0, 1], label="a long legend entry that needs width")
        ax.set_title("a title\non two lines")
        leg = ax.legend([f"entry {k}" for k in range(1)] * 6, loc="upper center", ncol=1,
                        bbox_to_anchor=(0.5, -0.2))
        leg._crankgen_outside = True
    assert layout_problems(fig)                       # the estimate leaves no room
    assert layout_problems(fit_panels(fig)) == []


def test_place_labels_avoids_curves_and_markers():
    fig, axes = panels(1, 1)
    ax = axes[0, 0]
    x = np.linspace(0, 1, 200)
    ax.plot(x, np.sin(6 * x))
    ax.scatter([0.3, 0.31, 0.7], [np.sin(1.8), 0.2, np.sin(4.2)], s=30)
    place_labels(ax, [(0.3, np.sin(1.8), "F 0.3", "k"), (0.7, np.sin(4.2), "PD 0.7", "k")])
    assert layout_problems(fit_panels(fig)) == []


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    from crankgen.experiments import ReproduceConfig, reproduce
    out = tmp_path_factory.mktemp("figures") / "r"
    reproduce(out, config=ReproduceConfig.tiny(), quiet=True)
    return out


@pytest.mark.parametrize("name", ["fig2", "fig3", "fig4", "fig5", "fig6", "fig7", "fig8", "convergence"])
def test_every_reproduce_figure_is_laid_out_cleanly(tiny, name):
    from crankgen.experiments import ReproduceConfig, plots
    from crankgen.experiments import figures as F
    from crankgen.experiments.io import read_json
    cfg = ReproduceConfig.tiny()
    conv = read_json(tiny / "data" / "convergence.json")
    if name == "convergence":
        fig = plots.plot_convergence(conv, cfg)
    else:
        data = read_json(tiny / "data" / f"{name}.json", {"TransientCurve": F.TransientCurve})
        bif = read_json(tiny / "data" / "bifurcations.json") if name == "fig6" else None
        fig = plots.plot_figure(data, cfg, conv["counts"], bifurcations=bif)
    assert layout_problems(fig) == []


def test_continue_and_poincare_figures(tmp_path, monkeypatch):
    """The command-line figures, captured before they are saved: laid out cleanly, axes named
    after what they show, a title, the legend outside the data."""
    from crankgen.analyses.bifurcation import diagram, sweeps
    from crankgen.cli import main
    seen = {}

    def capture(module):
        real = module.save_figure

        def save(fig, path, **kw):
            seen[path.name] = (layout_problems(fig), [(a.get_xlabel(), a.get_ylabel(), a.get_title())
                                                      for a in fig.axes])
            return real(fig, path, **kw)
        monkeypatch.setattr(module, "save_figure", save)
    capture(diagram)
    capture(sweeps)
    assert main(["poincare", "--from", "0.9", "--to", "1.2", "--values", "4", "--transient", "20",
                 "--samples", "8", "--with-continuation", "--max-period", "2", "--elements", "4",
                 "--steps-per-rev", "50", "--out", str(tmp_path / "p"), "--quiet"]) == 0
    problems, labels = seen["poincare.png"]
    assert problems == []
    assert labels[0][0] == "Omega*" and "v*(1/2)" in labels[0][1] and labels[0][2]
    from crankgen import Mechanism, continuation
    d = continuation(Mechanism(), "omega", 0.8, 1.2, n_elements=4, steps_per_rev=50, max_period=2,
                     formulation="lagrange", damping="kelvin-voigt", membrane="averaged")
    d.plot(tmp_path / "continuation.png")
    problems, labels = seen["continuation.png"]
    assert problems == [] and labels[0][0] == "Omega*" and "max |v*(1/2)|" in labels[0][1]
    assert "approach A" in labels[0][2] and "eps = 0.01" in labels[0][2]


def test_branch_colours_differ_from_the_approach_colours():
    from matplotlib.colors import to_rgb

    from crankgen.analyses.bifurcation.diagram import PERIOD_COLORS
    from crankgen.plots.figures import APPROACH_COLORS
    approaches = [np.array(to_rgb(c)) for c in APPROACH_COLORS.values()]
    for period, c in PERIOD_COLORS.items():
        distance = min(np.linalg.norm(np.array(to_rgb(c)) - a) for a in approaches)
        assert distance > 0.35, (period, c)
