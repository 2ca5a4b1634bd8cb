"""Complete exports (issue 28 item 5): every result's to_csv writes every declared output of its
guide, each column named with its unit, in crankgen's units and in SI; sweep.csv has the model
and the range columns, leaves empty what a case's guide or crank motion does not read, and every
column is documented with its units; `crankgen sweep` draws the amplitude and the peak torque
against the swept parameter (layout measured, data from the table)."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.declaration import schema
from crankgen.cli import main
from helpers import check_csv

TINY = ["--elements", "2", "--steps-per-rev", "20", "--quiet"]


def test_a_four_bars_csv_holds_every_declared_output_of_its_guide(tmp_path):
    run = crankgen.simulate(crankgen.Mechanism(guide=crankgen.Circle()), omega=0.5, n_elements=2,
                            steps_per_rev=20, revolutions=0.5)
    run.to_csv(tmp_path / "run.csv", x=(0.25, 0.5), fiber=1.5)
    table = check_csv(tmp_path / "run.csv")
    # the four-bar's own outputs (rocker angle, transmission angle), the loads, every field at both x
    expect = {"rocker_angle_rad": run.rocker_angle, "transmission_angle_rad": run.transmission_angle,
              "torque_rhoA_L3_omega_b2": run.torque, "rocker_on_tip_x_rhoA_L2_omega_b2": run.rocker_on_tip_x,
              "v_mid_r": run.v_mid, "t_per_omega_b": run.t, "theta_deg": np.degrees(run.theta),
              "bending_moment_at_0.25_EI_per_L": run.bending_moment(0.25),
              "surface_strain_fiber_1.5_at_0.5": run.surface_strain(0.5, fiber=1.5)}
    for col, values in expect.items():
        np.testing.assert_allclose(table[col], values, rtol=1e-15, atol=0, err_msg=col)
    steps = [n for n, o in schema.OUTPUTS.items() if o.kind in ("step", "reduction") and "circle" in o.guides
             and not o.flexible]                  # (a flexible rocker's: tests/test_flexible_rocker.py)
    fields = [n for n, o in schema.OUTPUTS.items() if o.kind == "field" and "circle" in o.guides]
    pairs = [n[:-2] for n in steps if n.endswith("_x") and n[:-2] + "_y" in steps]     # the joint forces
    assert pairs == ["crank_on_rod", "rod_on_tip", "rocker_on_tip", "ground_on_rocker", "ground_on_crank"]
    for p in pairs:                          # each also as magnitude and direction (degrees)
        np.testing.assert_allclose(table[f"{p}_magnitude_rhoA_L2_omega_b2"],
                                   np.hypot(getattr(run, p + "_x"), getattr(run, p + "_y")), rtol=1e-14)
        np.testing.assert_allclose(np.radians(table[f"{p}_angle_deg"]),
                                   np.arctan2(getattr(run, p + "_y"), getattr(run, p + "_x")), rtol=1e-14)
    # t, theta, the outputs, each field at both x, the magnitude and direction of each joint force, the range
    assert len(table.columns) == 2 + len(steps) + 2 * len(fields) + 2 * len(pairs) + 3
    assert {"torque", "rocker_on_tip_y", "rocker_angle", "chord_deflection"} <= set(dir(run))
    assert "rocker_angle" not in dir(crankgen.simulate(crankgen.Mechanism(), n_elements=2, steps_per_rev=20,
                                                       revolutions=0.1))       # not a slider's


@pytest.fixture(scope="module")
def mixed_sweep(tmp_path_factory):
    """A sweep over two models, a slider and a four-bar, a constant and a fluctuating crank."""
    out = tmp_path_factory.mktemp("sweep") / "s"
    assert main(["sweep", "--omega", "0.3,0.5,0.7", "--guide", "line,circle", "--crank", "constant,fluctuation",
                 "--model", "paper,consistent", "--out", str(out), *TINY]) == 0
    return out


def test_sweep_csv_has_the_model_the_range_and_empty_inapplicable_parameters(mixed_sweep):
    table = check_csv(mixed_sweep / "sweep.csv")
    assert len(table) == 24 and set(table["model"]) == {"paper", "consistent"}
    for col in ("deflection_over_L", "axial_strain", "beyond_theory", "peak_torque", "peak_crank_on_rod_y"):
        assert col in table.columns
    periodic = table[table["status"] == "periodic"]
    np.testing.assert_allclose(periodic["deflection_over_L"], periodic["eps"] * periodic["amplitude"], rtol=1e-14)
    assert set(periodic["beyond_theory"]) <= {"yes", "no"} and (periodic["peak_torque"] > 0).all()
    line, circle = table[table["guide"] == "line"], table[table["guide"] == "circle"]
    for col in ("c", "d", "branch"):              # a slider has no rocker
        assert line[col].isna().all() and circle[col].notna().all(), col
    constant, fluctuating = table[table["motion"] == "constant"], table[table["motion"] == "fluctuation"]
    for col in ("fluctuation", "order"):
        assert constant[col].isna().all() and fluctuating[col].notna().all(), col
    for col in ("omega0", "ramp"):                # no run-up here
        assert table[col].isna().all()
    # the rows read back as their cases
    back = [crankgen.Case.from_dict(r) for r in table.astype(object).where(table.notna(), None).to_dict("records")]
    assert len(set(back)) == 24 and back[0].guide == "line"


def test_every_sweep_column_is_documented_with_its_units(mixed_sweep):
    docs = check_csv(mixed_sweep / "sweep_columns.csv")
    table = check_csv(mixed_sweep / "sweep.csv")
    assert list(docs["column"]) == list(table.columns)
    assert docs["meaning"].notna().all()
    units = dict(zip(docs["column"], docs["units"].fillna("")))
    assert units["periods"] == "rev" and units["wall_time"] == "s" and units["amplitude"] == "r"
    assert units["ms"] == "rhoA L" and units["mu"] == "1/omega_b" and units["peak_torque"] == "rhoA L^3 omega_b^2"
    assert units["gravity_x"] == "L omega_b^2" and units["status"] == "" and units["eps"] == "dimensionless"
    meaning = dict(zip(docs["column"], docs["meaning"]))
    assert "circle guide only" in meaning["c"] and "wall-clock" in meaning["wall_time"]


def test_the_sweep_figure_draws_the_table(mixed_sweep):
    """sweep.png is drawn; the figure of the same table has no layout problem (text inside, legend
    below, nothing overlapping) and plots, per series, the table's amplitudes and peak torques of
    the periodic rows against the swept parameter with the most values (omega)."""
    import matplotlib
    matplotlib.use("Agg")
    from crankgen.plots.figures import layout_problems
    from crankgen.plots.sweep import sweep_figure
    assert (mixed_sweep / "sweep.png").stat().st_size > 10000
    rows = check_csv(mixed_sweep / "sweep.csv")
    table = crankgen.SweepTable(rows.astype(object).where(rows.notna(), None).to_dict("records"))
    fig = sweep_figure(table)
    assert layout_problems(fig) == []
    top, bottom = fig.axes[0], fig.axes[1]
    assert bottom.get_xlabel() == "Omega*" and "torque" in bottom.get_ylabel()
    first = rows[(rows["guide"] == "line") & (rows["motion"] == "constant") & (rows["model"] == "paper")]
    first = first.sort_values("omega")
    line = next(ln for ln in top.get_lines() if ln.get_label() == "slider, constant crank speed, paper model")
    x, y = line.get_xydata().T
    np.testing.assert_array_equal(x, first["omega"])
    np.testing.assert_allclose(y, np.where(first["status"] == "periodic", first["amplitude"], np.nan))
    torque = bottom.get_lines()[0].get_xydata()[:, 1]
    np.testing.assert_allclose(torque, np.where(first["status"] == "periodic", first["peak_torque"], np.nan))
    labels = [t.get_text() for t in fig.legends[0].get_texts()] if fig.legends else \
        [t.get_text() for t in bottom.get_legend().get_texts()]
    assert sum(label.endswith(" model") for label in labels) == 8            # every series named


def test_the_orbit_figure_draws_the_loads_in_si():
    """orbit.png of a steady state in SI: v at mid-span in mm and the driving torque in N m
    against the crank angle, the torque being the scaled orbit's times rho A L^3 omega_b^2
    computed here from the rod; the title wraps inside the figure."""
    import matplotlib
    matplotlib.use("Agg")
    from crankgen.plots.figures import layout_problems, orbit_figure
    L, E, rho, A, I = 0.3, 2e11, 7870.0, 6.4e-5, 3.41e-10
    steel = crankgen.SIMechanism(L=L, a=0.15, E=E, rho=rho, A=A, I=I, slider_mass=0.0756, crank_speed=150.0,
                                 damping=2e-4, gravity=(0.0, -9.81), offset=0.01)
    st = crankgen.steady_state(steel, units="si", n_elements=2, steps_per_rev=40)
    omega_b = (math.pi / L) ** 2 * math.sqrt(E * I / (rho * A))
    fig = orbit_figure(st, si=st.si)
    assert layout_problems(fig) == []
    top, _, bottom = fig.axes
    x, v = top.get_lines()[0].get_xydata().T
    np.testing.assert_allclose(x, np.degrees(st.theta))
    np.testing.assert_allclose(v, st.v_mid * math.sqrt(I / A) * 1e3, rtol=1e-12)      # v* r, in mm
    torque = bottom.get_lines()[0].get_xydata()[:, 1]
    np.testing.assert_allclose(torque, st.torque * rho * A * L ** 3 * omega_b ** 2, rtol=1e-12)
    assert bottom.get_ylabel() == "driving torque (N m)" and "offset = 0.01 m" in top.get_title().replace("\xa0", " ")


def test_the_sweep_figure_spans_the_cases_without_an_orbit(mixed_sweep):
    """A case without a periodic orbit is a cross at the bottom, inside the axes: rows at the
    ends of the swept range marked not-periodic here are still within the x-limits."""
    import matplotlib
    matplotlib.use("Agg")
    from crankgen.plots.sweep import sweep_figure
    rows = check_csv(mixed_sweep / "sweep.csv")
    records = rows.astype(object).where(rows.notna(), None).to_dict("records")
    for r in records:
        if r["omega"] == 0.7:
            r.update(status="not-periodic", amplitude=None, peak_torque=None)
    fig = sweep_figure(crankgen.SweepTable(records))
    for ax in fig.axes[:2]:
        lo, hi = ax.get_xlim()
        assert lo < 0.3 and hi > 0.7
        crosses = [c for c in ax.collections if c.get_offsets().shape[0] and
                   np.allclose(c.get_offsets()[:, 0], 0.7)]
        assert len(crosses) == 8                                  # one per series


def test_steady_writes_every_declared_output_of_its_guide(tmp_path):
    """crankgen steady on a four-bar: orbit.csv has a column per declared step output of the
    circle guide (named with its unit) equal to the Python steady state's, and steady.csv the peak
    of every load (a force or a moment) over that orbit."""
    assert main(["steady", "--guide", "circle", "--omega", "0.5", "--out", str(tmp_path), *TINY]) == 0
    orbit, row = check_csv(tmp_path / "orbit.csv"), check_csv(tmp_path / "steady.csv").iloc[0]
    st = crankgen.steady_state(crankgen.Mechanism(guide=crankgen.Circle()), omega=0.5, n_elements=2,
                               steps_per_rev=20)
    steps = [n for n, o in schema.OUTPUTS.items() if o.kind == "step" and "circle" in o.guides and not o.flexible]
    assert "rocker_angle" in steps and "torque" in steps
    for name in steps:
        units = schema.OUTPUTS[name].units
        col = [c for c in orbit.columns if c == name or (c.startswith(name + "_") and units != "1"
                                                          and c[len(name) + 1:] not in ("x", "y"))]
        assert len(col) == 1, (name, col)
        np.testing.assert_allclose(orbit[col[0]], getattr(st, name), rtol=1e-9, atol=1e-12, err_msg=name)
    for name in ("torque", "crank_on_rod_x", "crank_on_rod_y", "rod_on_tip_x", "rocker_on_tip_y"):
        assert row[f"peak_{name}"] == pytest.approx(np.abs(getattr(st, name)).max(), rel=1e-9)
