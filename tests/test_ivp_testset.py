"""The slider crank of the Test Set for IVP Solvers (release 2.3, problem 'crank'): crankgen's
linear-strain model, started from the published initial state, against the published values at
t = 0.1 s, at the finest settings the suite affords (the example runs the fine ladder).

The published data and the mapping of the initial state live in examples/ivp_testset_slider_crank.py
(the example is the one place that holds them); the checks here are those the example shows at
finer settings: the positions within 1e-6 relative of the published ones, the midpoint deflection
within 1 %, the step convergence on 4 elements and the mesh convergence of the deflection at
51200 steps per revolution monotone."""

import importlib.util
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
_spec = importlib.util.spec_from_file_location("ivp_testset_example",
                                               ROOT / "examples" / "ivp_testset_slider_crank.py")
example = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(example)

STEPS = (51200, 102400, 204800)          # steps per revolution on 4 elements
MESHES = (8, 16, 32)                     # elements at 51200 steps per revolution


@pytest.fixture(scope="module")
def runs():
    jobs = [(4, spr) for spr in STEPS] + [(n, STEPS[0]) for n in MESHES]
    with ThreadPoolExecutor(2) as pool:
        return dict(zip(jobs, pool.map(lambda job: example.at_end(*job), jobs)))


def test_the_published_initial_state_is_consistent_and_lands_on_the_mesh():
    example.check_published_state()
    import crankgen
    from crankgen.discrete.initial import reduced_state
    from crankgen.declaration.si import scales_of
    si = example.mechanism()
    case = crankgen.Case(**si.mechanism.values(), omega=si.omega, n_elements=4, **example.MODEL)
    d0, v0 = reduced_state(case, example.published_initial_state(), scales_of(si))
    L = example.ROD
    # the slider's guide co-ordinate is q4 (in L) and its rate q4' (in L omega_b)
    assert d0[-2] * L == pytest.approx(example.Q[3], rel=1e-12)
    assert v0[-2] * L * si.omega_b == pytest.approx(example.QD[3], rel=1e-9)


def test_positions_and_deflection_at_0_1_s_against_the_published_values(runs):
    published = example.PUBLISHED
    for (n, spr), r in runs.items():
        for name in ("slider_position", "chord_angle"):
            assert abs(r[name] / published[name] - 1) < 1e-6, (n, spr, name, r[name])
        assert abs(r["midpoint_deflection"] / published["midpoint_deflection"] - 1) < 0.01, (n, spr)
        # the rates carry the rod's axial vibration: within 1e-3 relative
        for name in ("chord_rate", "slider_velocity"):
            assert abs(r[name] / published[name] - 1) < 1e-3, (n, spr, name, r[name])


def _monotone(values):
    d = np.diff(values)
    return bool(np.all(d > 0) or np.all(d < 0)) and all(abs(d[k + 1]) < abs(d[k]) for k in range(len(d) - 1))


def test_step_convergence_on_four_elements_is_monotone(runs):
    for name in example.PRIMARY:
        values = [runs[(4, spr)][name] for spr in STEPS]
        assert _monotone(values), (name, values)


def test_mesh_convergence_of_the_deflection_is_monotone(runs):
    values = [runs[(n, STEPS[0])]["midpoint_deflection"] for n in MESHES]
    assert _monotone(values), values


def test_no_damping_whichever_damping_model():
    """damping = 0 s in the SIMechanism is mu* = 0: the Kelvin-Voigt and the printed damping then add
    nothing, so the two runs are the same to the last bit."""
    import crankgen
    si = example.mechanism()
    assert si.mechanism.mu == 0.0
    runs = [crankgen.simulate(si, units="si", times=[0.01], initial=example.published_initial_state(),
                              n_elements=4, steps_per_rev=3200, damping=damping, **example.MODEL)
            for damping in ("kelvin-voigt", "paper")]
    assert np.array_equal(runs[0].states, runs[1].states)
    assert np.array_equal(runs[0].at_times.states, runs[1].at_times.states)


def test_the_example_table_parses_into_numbers(tmp_path):
    """crank.csv holds numbers pandas reads as numbers (NumPy 2's repr of its scalars,
    "np.float64(...)", once made every column text), a source column of words, and the published
    row with empty run settings."""
    from helpers import check_csv

    row = example.at_end(2, 400)                 # a short, coarse run: the values are NumPy scalars
    assert any(isinstance(v, np.floating) for v in row.values())
    path = tmp_path / "crank.csv"
    example.write_table(path, [row])
    table = check_csv(path)
    assert list(table["source"]) == ["crankgen", "published"]
    for column in table.columns[1:]:
        assert np.issubdtype(table[column].dtype, np.number), column
    assert table["slider_position_m"].iloc[1] == example.PUBLISHED["slider_position"]
    assert table["n"].iloc[0] == 2 and np.isnan(table["n"].iloc[1])
