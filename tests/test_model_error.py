"""The model verdict (crankgen.analyses.model_error) against the measured difference between the models: the
consistent model's steady orbit and the geometrically exact rod's, each found by the engine by
shooting, compared node by node over the revolution (the largest |v| difference over the largest
|v|).  The estimate is computed from the consistent model's orbit alone."""

import numpy as np
import pytest

import crankgen
from crankgen.analyses import model_error

N_EL = 8


def measured(eps, omega):
    m = crankgen.Mechanism(eps=eps)
    model = crankgen.steady_state(m, omega=omega, n_elements=N_EL)
    exact = crankgen.steady_state(m, omega=omega, n_elements=N_EL, model="exact")
    assert model.status == exact.status == "periodic"
    v, vx = model_error.transverse(model.case, model.states), model_error.transverse(exact.case, exact.states)
    return model, float(np.max(np.abs(v - vx)) / np.max(np.abs(vx)))


@pytest.mark.parametrize("omega, low, high", [(0.6, 0.005, 0.007), (0.8, 0.085, 0.10), (0.95, 0.042, 0.05)])
def test_the_estimate_against_the_exact_rod_at_eps_001(omega, low, high):
    """At eps = 0.01 the orbits differ by 0.61 %, 9.2 % and 4.6 % (the amplitude by 0.43 %, 5.8 % and
    0.0 %: at 0.95 the resonance peaks of the two models cross, the orbits do not): the estimate
    within 5 % of that near 1 % and never below it, at most a third above where it is large."""
    model, diff = measured(0.01, omega)
    assert low < diff < high                                # the measurement itself, as recorded
    verdict = model.verdict
    ratio = verdict.error / diff
    assert (0.98 < ratio < 1.05) if diff < 0.01 else (1.0 < ratio < 1.34), (verdict.error, diff)
    # the slender paper rod's outer fibres pass 0.5 % from Omega* = 0.57 on: beyond both, however
    # close the models are; the text gives the estimate beside it
    assert verdict.words == "beyond both" and verdict.limits.tripped[0].name == "fibre_strain"
    assert f"{verdict.error:.2%}" in str(verdict)
    row = model.row()
    assert row["verdict"] == "beyond both" and row["model_error"] == pytest.approx(verdict.error, rel=1e-12)


@pytest.mark.parametrize("eps, omega, words", [(0.005, 0.6, "trust this model here"),
                                               (0.002, 0.7, "use the exact rod")])
def test_each_verdict_where_its_measure_says(eps, omega, words):
    """A rod twice as slender at 0.6 (orbits 0.60 % apart, fibres at 0.29 %): trust; five times at 0.7
    (2.0 % apart, fibres at 0.17 %): use the exact rod."""
    model, diff = measured(eps, omega)
    verdict = model.verdict
    assert verdict.words == words and (diff < 0.01) == (words == "trust this model here")
    assert 1.0 <= verdict.error / diff < 1.1


def test_the_exact_rod_is_its_own_reference_and_a_motor_has_no_estimate():
    exact = crankgen.steady_state(crankgen.Mechanism(eps=0.002), omega=0.7, n_elements=4, model="exact")
    assert exact.verdict.words == "trust this model here" and exact.verdict.error == 0.0
    run = crankgen.simulate(crankgen.Mechanism(eps=0.002), crank=crankgen.Motor(), revolutions=0.5, n_elements=2)
    assert run.verdict.error is None


def test_a_transient_gets_an_estimate_too():
    """From rest the correction starts at zero; the run's estimate is of the same size as its steady
    state's (the response of a few revolutions at 0.6 is the steady one's, plus the transient)."""
    run = crankgen.simulate(crankgen.Mechanism(eps=0.005), omega=0.6, revolutions=4, n_elements=N_EL)
    steady = crankgen.steady_state(crankgen.Mechanism(eps=0.005), omega=0.6, n_elements=N_EL)
    assert 0.5 < run.verdict.error / steady.verdict.error < 2.0
