"""Reductions over time declared as data (schema.REDUCTIONS, derive/outputs.py): the RMS bending
moment at mid-span over a steady revolution against a trapezoidal RMS of simulate's bending moment
over the same, settled, revolution; the kinds against their definitions on known signals; the
column in the steady row with its units."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.declaration import schema
from crankgen.results import reductions
from crankgen.results.steady_row import describe, row

CASE = dict(omega=0.8, n_elements=4, steps_per_rev=60)


def test_the_kinds_on_known_signals():
    t = np.linspace(0.0, 2 * np.pi, 2001)
    v = 3.0 + 2.0 * np.sin(t)
    assert reductions.reduce("mean", t, v) == pytest.approx(3.0, abs=1e-12)
    assert reductions.reduce("rms", t, v) == pytest.approx(math.sqrt(9.0 + 2.0), rel=1e-6)   # mean^2 + amp^2 / 2
    assert reductions.reduce("range", t, v) == pytest.approx(4.0, abs=1e-5)
    assert reductions.reduce("peak", t, -v) == pytest.approx(-5.0, abs=1e-5)                  # signed
    assert reductions.reduce("max", t, v) == pytest.approx(5.0, abs=1e-5)
    with pytest.raises(ValueError):
        reductions.reduce("median", t, v)


@pytest.fixture(scope="module")
def steady():
    st = crankgen.steady_state(crankgen.Mechanism(), **CASE)
    assert st.status == "periodic"
    return st


def test_the_rms_bending_moment_is_simulate_s_over_the_settled_revolution(steady):
    names = {r.name for r in schema.REDUCTIONS}
    assert "rms_bending_moment_mid" in names
    N = 3 * CASE["n_elements"]
    parts = np.split(steady.state, len(steady.state) // N)          # (d, v) or (d, v, a) at theta = 0
    run = crankgen.simulate(crankgen.Mechanism(), initial=parts, revolutions=1, **CASE)
    m = run.bending_moment(0.5)
    t = run.t
    rms = math.sqrt(sum(0.5 * (m[k] ** 2 + m[k + 1] ** 2) * (t[k + 1] - t[k]) for k in range(len(t) - 1))
                    / (t[-1] - t[0]))
    assert rms > 0
    assert steady.reductions["rms_bending_moment_mid"] == pytest.approx(rms, rel=1e-7)
    assert run.last_revolution()["rms_bending_moment_mid"] == pytest.approx(rms, rel=1e-7)
    # the column of the steady row, with the output's units
    assert row(steady)["rms_bending_moment_mid"] == steady.reductions["rms_bending_moment_mid"]
    described = {d["column"]: d for d in describe(["rms_bending_moment_mid"])}
    assert described["rms_bending_moment_mid"]["units"] == schema.OUTPUTS["bending_moment"].units
