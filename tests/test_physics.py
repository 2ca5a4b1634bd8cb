"""Physics of the runtime against independent truths: analytic frequency, energy balance,
convergence order, the guide constraint at velocity and acceleration level, the mass matrix,
long-run periodicity, low-speed agreement of A, B, C."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.discrete.system import Model
from crankgen.discrete.newmark import NewmarkSettings, integrate
from crankgen.results.outputs import StateHistory, mid_deflection

import energy_balance as eb
from helpers import bending_mode_state, observed_order, zero_crossing_frequency


def test_small_free_vibration_at_omega_b_converges_with_elements():
    """Stationary crank, no damping: the pinned / sliding rod vibrates in its first bending mode at
    omega_b (= 1 in crankgen's units; rotary inertia gives 1/sqrt(1 + pi^2 eps^2), Rayleigh beam).
    Newmark's period elongation is removed exactly (w_fe = (2/dt) tan(w dt / 2))."""
    mech = crankgen.Mechanism(eps=0.01, mu=0.0)
    exact = 1.0 / math.sqrt(1.0 + (math.pi * mech.eps) ** 2)
    steps_per_period, periods = 200, 4
    dt = 2 * math.pi / steps_per_period
    errors = []
    for n in (2, 4, 8):
        model = Model.build(mech, 0.0, n, "lagrange", "A", "kelvin-voigt")
        d0 = bending_mode_state(model.mesh, 1e-7)
        hist = integrate(model, d0, np.zeros_like(d0), 0.0, dt, steps_per_period * periods)
        q = StateHistory(model.case, hist.t, hist.d).element_vectors()
        w = zero_crossing_frequency(hist.t, mid_deflection(model.mesh, q, mech.eps))
        w_fe = 2 / dt * math.tan(w * dt / 2)
        errors.append(abs(w_fe - exact) / exact)
    assert errors[-1] < 2e-4
    assert errors[0] > errors[1] > errors[2]
    assert observed_order([2, 1], errors[:2]) > 3.5     # cubic Hermite bending: O(h^4) frequencies


def _energy_history(model, hist):
    return np.array([sum(model.energies(t, d, v)) for t, d, v in zip(hist.t, hist.d, hist.v)])


@pytest.mark.parametrize("approach", ["A", "C"])
def test_energy_conserved_without_crank_motion_or_damping(approach):
    """Omega = 0, mu = 0: the Lagrangian is autonomous, so T + U is constant; the average
    acceleration rule keeps the drift at O(dt^2) for the non-linear model."""
    mech = crankgen.Mechanism(eps=0.05, ms=0.5, mu=0.0)
    drifts = []
    for steps in (40, 80, 160):
        model = Model.build(mech, 0.0, 4, "lagrange", approach, "kelvin-voigt")
        d0 = bending_mode_state(model.mesh, 0.05)   # large enough for the non-linear terms to act
        hist = integrate(model, d0, np.zeros_like(d0), 0.0, 2 * math.pi / steps, 2 * steps)
        E = _energy_history(model, hist)
        drifts.append(np.max(np.abs(E - E[0])) / E[0])
    assert drifts[-1] < 1e-3
    if approach == "C":   # linear: the trapezoidal rule conserves the quadratic energy exactly
        assert max(drifts) < 1e-10
    else:
        assert observed_order([4, 2, 1], drifts) > 1.8


def test_second_order_convergence_in_time_step():
    """v* after one revolution at Omega* = 0.8 converges at order 2 in dt (Newmark, beta=1/4)."""
    mech = crankgen.Mechanism()
    ref = crankgen.simulate(mech, omega=0.8, n_elements=4, steps_per_rev=1600, revolutions=1)
    errs, hs = [], []
    for spr in (50, 100, 200):
        r = crankgen.simulate(mech, omega=0.8, n_elements=4, steps_per_rev=spr, revolutions=1)
        errs.append(abs(r.v_mid[-1] - ref.v_mid[-1]))
        hs.append(1 / spr)
    assert 1.8 < observed_order(hs, errs) < 2.3


@pytest.mark.parametrize("formulation", ["lagrange", "paper"])
def test_slider_velocity_and_acceleration_stay_on_the_guide(formulation):
    """The slider's inertial velocity and acceleration, from the nodal rates the model builds out of
    (s, sd, sdd) (rheonomic map, constraints.expand), have no Y component: the guide constraint
    Y = a sin(theta) - (1 + u) sin(phi) + v cos(phi) = 0 holds to second order in time, not only
    in position.  The inertial kinematics is written out in energy_balance.py."""
    mech = crankgen.Mechanism(a=0.3)
    model = Model.build(mech, 0.8, 4, formulation, "A", "paper")
    hist = integrate(model, np.zeros(model.n_dofs), np.zeros(model.n_dofs), 0.0,
                     2 * math.pi / 0.8 / 100, 100)
    Ys = []
    for t, d, v, a in zip(hist.t, hist.d, hist.v, hist.a):
        kin = model.kinematics(t)
        q, qd, qdd, _ = model.nodal_state(kin, d, v, a)
        one = model.kinematics(np.array([t]))
        (Vi, Vj), (Ai, Aj) = eb.point_kinematics(1.0, q[-1, eb.U1], qd[-1, eb.U1], qdd[-1, eb.U1],
                                                 q[-1, eb.V1], qd[-1, eb.V1], qdd[-1, eb.V1], one, mech.a)
        # e_Y = -sin(phi) e_i + cos(phi) e_j
        Ys.append([-np.sin(kin.phi) * Vi[0] + np.cos(kin.phi) * Vj[0],
                   -np.sin(kin.phi) * Ai[0] + np.cos(kin.phi) * Aj[0],
                   np.hypot(Vi[0], Vj[0]), np.hypot(Ai[0], Aj[0])])
    Ys = np.array(Ys)
    assert np.max(np.abs(Ys[:, 0])) < 1e-14 * np.max(Ys[:, 2])
    assert np.max(np.abs(Ys[:, 1])) < 1e-13 * np.max(Ys[:, 3])


@pytest.mark.slow
def test_response_stays_bounded_and_periodic_over_60_revolutions():
    """No parasitic growth from the rheonomic constraint: with light damping (mu* = 0.05, so a
    slowly growing mode would show), after 60 revolutions the response repeats with the crank
    period and its amplitude is not drifting."""
    spr, revs = 100, 60
    r = crankgen.simulate(crankgen.Mechanism(mu=0.05), omega=0.8, n_elements=4, steps_per_rev=spr,
                          revolutions=revs, integrator="newton", damping="paper", membrane="pointwise")
    per_rev = np.abs(r.v_mid[1:].reshape(revs, spr)).max(axis=1)
    assert np.all(np.isfinite(r.v_mid))
    assert abs(per_rev[-1] - per_rev[-21]) < 1e-8 * per_rev[-1]
    last, previous = r.v_mid[-spr:], r.v_mid[-2 * spr:-spr]
    assert np.max(np.abs(last - previous)) < 1e-8 * np.max(np.abs(last))


@pytest.mark.parametrize("formulation", ["lagrange", "paper"])
def test_approaches_agree_at_low_speed(formulation):
    """At Omega* = 0.1 the rod deflects little and A, B, C give nearly the same response."""
    mech = crankgen.Mechanism()
    runs = {ap: crankgen.simulate(mech, omega=0.1, approach=ap, formulation=formulation,
                                  n_elements=4, revolutions=1.5).v_mid for ap in "ABC"}
    scale = np.max(np.abs(runs["A"]))
    for ap in "BC":
        assert np.max(np.abs(runs[ap] - runs["A"])) < 0.02 * scale


def test_mass_matrix_equals_an_independent_assembly():
    """The reduced mass matrix (rod, rotary inertia, slider through the guide map) equals the one
    assembled here from the hand-typed shape functions: int rho A (N_u N_u + N_v N_v)
    + rho I N_v' N_v', with the slider mass on s (its end moves by s (cos phi, sin phi)) and
    the pinned rows dropped.  It does not depend on the crank angle."""
    mech = crankgen.Mechanism(a=0.4, ms=2.0, eps=0.05)
    n = 5
    l = 1.0 / n
    live = [k for k in range(2 * 4) if k % 4 != 3]             # (u, v, psi) of each node: no chi in A
    Nu, _, Nv, Nvx, _ = (N[:, live] for N in eb.shapes(eb.ZETA, l))
    w = eb.WEIGHTS * l
    me = (np.einsum("g,gi,gj->ij", w, Nu, Nu) + np.einsum("g,gi,gj->ij", w, Nv, Nv)
          + mech.rhoI * np.einsum("g,gi,gj->ij", w, Nvx, Nvx))
    full = np.zeros((3 * (n + 1), 3 * (n + 1)))
    for e in range(n):
        full[3 * e:3 * e + 6, 3 * e:3 * e + 6] += me
    full[3 * n, 3 * n] += mech.ms
    full[3 * n + 1, 3 * n + 1] += mech.ms
    for formulation in ("lagrange", "paper"):
        model = Model.build(mech, 0.8, n, formulation, "A", "paper")
        rng = np.random.default_rng(1)
        d, v = 1e-3 * rng.standard_normal((2, model.n_dofs))
        for t in (0.0, 1.3, 4.0):
            kin = model.kinematics(t)
            # reduced -> full: psi_0, interior nodes as they are, slider end (cos, sin) s, psi_n
            Tm = np.zeros((3 * (n + 1), model.n_dofs))
            Tm[2, 0] = 1.0
            Tm[3:3 * n, 1:3 * n - 2] = np.eye(3 * n - 3)
            Tm[3 * n, 3 * n - 2], Tm[3 * n + 1, 3 * n - 2] = np.cos(kin.phi), np.sin(kin.phi)
            Tm[3 * n + 2, 3 * n - 1] = 1.0
            terms = model.element_terms(kin, d, v, np.zeros_like(d))
            M = model.assembler.dense(terms.M)
            np.testing.assert_allclose(M, Tm.T @ full @ Tm, rtol=0, atol=1e-13 * np.abs(M).max())


def test_one_pass_and_newton_agree_when_steps_are_small():
    mech = crankgen.Mechanism()
    a = crankgen.simulate(mech, omega=0.8, n_elements=4, steps_per_rev=400, revolutions=1,
                          integrator="newton", formulation="paper")
    b = crankgen.simulate(mech, omega=0.8, n_elements=4, steps_per_rev=400, revolutions=1,
                          integrator="one-pass", formulation="paper")
    assert np.max(np.abs(a.v_mid - b.v_mid)) < 1e-3 * np.max(np.abs(a.v_mid))
