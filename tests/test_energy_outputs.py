"""The rod's kinetic energy as an output (a reduction over the rod: each element's energy, summed):
against the energy computed here by Gauss quadrature of the fields (energy_balance.py)."""

import numpy as np
import pytest

import crankgen
from crankgen import schema
from crankgen.model import Model

import energy_balance as eb


def _run(**kw):
    case = crankgen.Case(omega=0.8, mu=0.0, n_elements=4, steps_per_rev=400, **kw)
    return case, crankgen.simulate(case=case, revolutions=1.5)


@pytest.mark.parametrize("approach,membrane", [("A", "averaged"), ("C", "pointwise")])
def test_the_kinetic_energy_is_the_rods(approach, membrane):
    case, run = _run(approach=approach, membrane=membrane)
    assert schema.OUTPUTS["kinetic_energy"].kind == "reduction"
    T = run.kinetic_energy
    model = Model(case)
    kin = model.kinematics(run.t)
    q, qd, _ = eb.nodal_states(model, kin, run.states, run.rates, run.accelerations)
    slider = 0.5 * case.ms * run.slider_velocity ** 2            # the slider moves along its line
    np.testing.assert_allclose(T + slider, eb.kinetic_energy(model, kin, q, qd), rtol=1e-11, atol=1e-16)


def test_the_kinetic_energy_reaches_every_result_and_its_si_view(tmp_path):
    st = crankgen.steady_state(crankgen.Mechanism(), omega=0.8, n_elements=4, steps_per_rev=40)
    assert st.kinetic_energy.shape == st.t.shape and np.all(st.kinetic_energy > 0)
    si = crankgen.SIMechanism(L=0.3, a=0.045, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10, slider_mass=0.1,
                              crank_speed=150.0)
    run = crankgen.simulate(si, units="si", revolutions=0.2, n_elements=2, steps_per_rev=40)
    assert run.si.units("kinetic_energy") == "N m"
    np.testing.assert_allclose(run.si.kinetic_energy, run.kinetic_energy * run.si.scales.factor(
        schema.OUTPUTS["kinetic_energy"].units))
    from crankgen.cli import main
    assert main(["simulate", "--elements", "2", "--steps-per-rev", "20", "--revolutions", "0.5",
                 "--out", str(tmp_path), "--quiet"]) == 0
    header = (tmp_path / "simulation.csv").read_text().splitlines()[0].split(",")
    assert "kinetic_energy" in header
