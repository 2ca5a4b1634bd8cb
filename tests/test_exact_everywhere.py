"""The geometrically exact rod in every analysis (issue 26 item 4): each takes model="exact" and
gives finite numbers that agree with the consistent model where the two theories agree (small
deflections: eps = 0.01 at low speed, or a short crank), and its section forces are the exact
ones (N = EA e, M = EI kappa of the element's stretch, tests/exact_reference.py)."""

import numpy as np
import pytest

import crankgen
import exact_reference as xr
from crankgen.discrete.system import Model

MECH = crankgen.Mechanism(a=0.1, eps=0.01, ms=0.5, mu=0.5)
SMALL = dict(n_elements=4, steps_per_rev=60)


def _close(a, b, rtol):
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.all(np.isfinite(a))
    assert np.max(np.abs(a - b)) <= rtol * np.max(np.abs(b)), (a, b)


def test_steady_state_section_forces_are_the_exact_ones():
    """bending_moment and axial_force of a steady state at Omega* = 0.8 (|v|/L 0.09) against
    EI kappa and EA (lambda - 1) computed here from its nodal states."""
    st = crankgen.steady_state(MECH, model="exact", omega=0.8, **SMALL)
    model = Model(st.case)
    q = model.mesh.gather(st.states)                         # interior elements: no end map needed
    l = float(np.mean(model.mesh.length))
    k = int(np.argmax(np.abs(st.v_mid)))
    element, zeta = 1, 0.5                                   # x* = 0.375 of 4 elements
    x = (element + zeta) / 4
    kappa = xr.curvature(q[k, element], l, np.array([zeta]))[0]
    strain = xr.element_strain(q[k, element], l)
    EI, EA = model.mechanism.EI, model.mechanism.EA
    assert np.isclose(st.bending_moment(x)[k], kappa, rtol=1e-7)              # M* = M L / EI = kappa
    assert np.isclose(st.axial_force(x)[k], strain * EA / EI, rtol=1e-7)       # N* = N L^2 / EI
    assert abs(st.bending_moment(x)[k] - _consistent_v_xx(st, model, q[k], element, zeta)) > 1e-4 * abs(kappa)


def _consistent_v_xx(st, model, q, element, zeta):
    """v_xx of the same state (the paper's curvature): the exact kappa differs from it."""
    import reference as ref
    _, _, _, _, _, b_psi = ref.shape_at(np.array([zeta]), np.array([float(np.mean(model.mesh.length))]))
    return float(np.sum(b_psi * q[element], -1).ravel()[0])


@pytest.mark.parametrize("guide, motion", [("line", None), ("circle", crankgen.RunUp(start=0.2, stop=0.4, revolutions=2)),
                                           ("line", crankgen.Fluctuation(omega=0.3, amplitude=0.2, order=2))])
def test_simulate_on_every_guide_and_motion_agrees_with_consistent_at_small_deflection(guide, motion):
    mech = MECH if guide == "line" else crankgen.Mechanism(a=0.1, eps=0.01, ms=0.5, mu=0.5, guide=crankgen.Circle(center=(1.1, 0.2), radius=0.9))
    speed = dict(omega=0.3) if motion is None else dict(crank=motion)
    runs = [crankgen.simulate(mech, model=m, revolutions=2, **speed, **SMALL) for m in ("exact", "consistent")]
    _close(runs[0].v_mid, runs[1].v_mid, 5e-3)
    _close(runs[0].torque, runs[1].torque, 5e-3)


def test_sweep_continuation_poincare_and_modes_take_the_exact_model():
    table = crankgen.sweep([crankgen.Case(model="exact", omega=w, **SMALL) for w in (0.3, 0.5)])
    assert len(table.rows) == 2
    assert all(r["approach"] == "exact" and r["status"] == "periodic" and np.isfinite(r["amplitude"]) for r in table.rows)
    d = crankgen.continuation(MECH, "omega", 0.3, 0.5, model="exact", **SMALL)
    assert d.branches and all(np.all(np.isfinite(b.amplitude)) for b in d.branches)
    pc = crankgen.poincare(MECH, "omega", [0.3, 0.5], "up", transient=5, samples=2, model="exact", **SMALL)
    assert len(pc.points) > 0 and all(np.all(np.isfinite(p.amplitude)) for p in pc.points)
    m_exact = crankgen.modes(MECH, omega=0.3, theta=1.0, count=2, model="exact", n_elements=4)
    m_cons = crankgen.modes(MECH, omega=0.3, theta=1.0, count=2, n_elements=4)
    _close(m_exact.frequencies, m_cons.frequencies, 1e-3)


def test_si_and_an_initial_state_take_the_exact_model():
    steel = crankgen.SIMechanism(L=0.3, a=0.15, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10,
                                 slider_mass=0.0756, crank_speed=150.0)
    bent = crankgen.InitialState(v=lambda x: 1e-3 * np.sin(np.pi * x / 0.3))
    runs = [crankgen.simulate(steel, units="si", initial=bent, times=[0.05, 0.1], model=m, n_elements=4)
            for m in ("exact", "consistent")]
    _close(runs[0].si.at_times.slider_position, runs[1].si.at_times.slider_position, 1e-3)


def test_a_section_turning_90_degrees_from_the_chord_ends_the_run_in_words():
    """eps = 0.01, Omega* = 1.2 from rest: the rod snaps through and, at t* = 34.6, the section at
    the crank pin turns to 90 degrees from the rod's chord, where the element's slope v_x reaches
    its stretch (theta = asin(v_x / lambda)); the run stops there with a message that says so, and
    its partial result shows the rotation (|v_x| / lambda above 0.99 at a Gauss point)."""
    with pytest.raises(crankgen.ConvergenceError, match="90 degrees from the rod's chord") as info:
        crankgen.simulate(MECH, model="exact", omega=1.2, revolutions=8, n_elements=16, steps_per_rev=100)
    partial = info.value.partial
    assert 34.0 < partial.t[-1] < 34.7
    model = Model(partial.case)
    q = model.mesh.gather(partial.states[-1:])[0, :-1]           # the interior elements
    l = float(np.mean(model.mesh.length))
    z, _ = xr.rule()
    _, v_x, _ = xr._fields_at(q, l, z)
    assert np.max(np.abs(v_x) / xr.element_stretch(q, l)[:, None]) > 0.99
