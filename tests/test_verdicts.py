"""Stability verdicts that are the mechanism's, not the step's (the consistent model's default,
generalized-alpha with rho_inf = 0.8).

1. Floquet multipliers converged in step and mesh.  The trapezoidal rule maps the rod's heavily
   damped stiff modes (Kelvin-Voigt: a mode of frequency omega decays at mu omega^2) to step
   factors near -1, so their images crowd at the unit circle, by amounts set by the step and the
   mesh (the issue: 0.998 / 0.975 / 0.905 at 100 / 400 / 800 steps, Omega* = 0.1).  Generalized-
   alpha damps them (step factor (1 - gamma) / gamma = 0.64 in the overdamped limit), leaving the
   mechanism's own: at Omega* = 0.6 the first bending mode's exp(-zeta omega T), zeta = mu/2,
   T = 2 pi / Omega* (0.073; measured 0.0757 with the parametric forcing).
2. The four-bar (a = 0.1, rocker c = 0.5 pivoted at D = (1, 0), eps = 0.01, 16 elements, 100 steps
   per revolution): period-1 and stable at Omega* = 0.97 to 1.005, found by shooting (the
   trapezoidal rule's near-unit multipliers made shooting fail and marching mistake a slowly
   decaying alternation for a sub-harmonic); marching honours max_revolutions; the continuation
   finds the period-2 branch's fold near Omega* = 0.800.
3. The consistent model's special points stay where Newmark's trapezoidal rule put them: its
   period doubling moves by less than 2e-5 (measured 6.8e-6 at 8 elements, 7e-6 at 16).
"""

import numpy as np
import pytest

import crankgen

FOUR_BAR = crankgen.Mechanism(a=0.1, eps=0.01, guide=crankgen.Circle(center=(1.0, 0.0), radius=0.5))


@pytest.mark.slow
@pytest.mark.parametrize("omega", [0.1, 0.6])
def test_the_largest_multiplier_is_converged_in_step_and_mesh(omega):
    steps = [crankgen.steady_state(omega=omega, n_elements=8, steps_per_rev=s) for s in (100, 200, 400)]
    mesh = [crankgen.steady_state(omega=omega, n_elements=n, steps_per_rev=100) for n in (8, 16, 32)]
    for runs in (steps, mesh):
        assert all(r.status == "periodic" for r in runs), [r.message for r in runs]
        mu = [r.multiplier for r in runs]
        assert max(mu) - min(mu) < 0.02, mu
    if omega == 0.6:       # the first bending mode's damping over a revolution
        expected = np.exp(-0.25 * 2 * np.pi / omega)
        assert steps[0].multiplier == pytest.approx(expected, rel=0.1)
    else:                  # over 63 time units every mode has decayed
        assert steps[0].multiplier < 1e-3


@pytest.mark.parametrize("omega", [0.97, 0.98, 0.99, 1.0, 1.005])
def test_the_four_bar_is_period_one_and_stable_found_by_shooting(omega):
    st = crankgen.steady_state(FOUR_BAR, omega=omega)
    assert (st.case.n_elements, st.case.steps_per_rev, st.case.rho_inf) == (16, 100, 0.8)
    assert st.status == "periodic" and st.message == "", st.message
    assert st.iterations >= 1 and st.periods == 3                   # shooting after the warm-up
    assert 0.4 < st.multiplier < 0.95


def test_marching_honours_max_revolutions_and_does_not_mistake_a_decaying_alternation():
    """Newmark (the trapezoidal rule) at Omega* = 1.0: shooting fails and marching settles through
    an alternation decaying by about 0.97 per two revolutions, which repeats every second
    revolution to the tolerance long before every revolution: marching goes on (to 111
    revolutions) instead of calling it a sub-harmonic; with max_revolutions = 50 it stops there,
    not-periodic, and says how many more would do."""
    st = crankgen.steady_state(FOUR_BAR, omega=1.0, rho_inf=1.0, max_revolutions=1000)
    assert st.status == "periodic" and st.periods > 101, (st.periods, st.message)
    assert "shooting did not converge (" in st.message and "marched instead" in st.message
    short = crankgen.steady_state(FOUR_BAR, omega=1.0, rho_inf=1.0, max_revolutions=50)
    assert short.status == "not-periodic" and short.periods == 50
    assert "no periodic state with the crank period within max_revolutions = 50" in short.message
    assert "more would reach tol" in short.message and "sub-harmonic" not in short.message


@pytest.mark.slow
def test_the_four_bar_period_two_branch_folds_near_0_800():
    """The period-2 branch born at the period doubling near 1.016 folds at 1.122 and turns back near
    0.8006 (0.80022 at 200 steps per revolution), where a real multiplier crosses +1 and the branch
    turns sharply (the multiplier runs from 2.9 to 0.8 over one step): found on default settings."""
    d = crankgen.continuation(FOUR_BAR, "omega", 0.75, 1.2, max_period=2, quantities=False)
    folds = sorted(s.parameter for s in d.special_points if s.kind == "fold" and s.period == 2)
    assert len(folds) == 2 and abs(folds[0] - 0.8006) < 1e-3 and abs(folds[1] - 1.1223) < 1e-3, folds
    two = next(b for b in d.branches if b.period == 2)
    assert np.min(two.parameter) == pytest.approx(folds[0], abs=1e-12)     # the fold is where it turns
    for s in d.special_points:
        target = {"fold": 1.0, "period-doubling": -1.0}[s.kind]
        assert abs(s.multiplier - target) < 1e-4


def test_the_consistent_models_period_doubling_stays_where_newmark_put_it():
    """8 elements, 100 steps per revolution: the crank-periodic branch's period doubling (1.055109
    with the trapezoidal rule) with the model's default scheme, generalized-alpha at rho_inf = 0.8,
    within 2e-5 of it, both located to their critical multiplier -1."""
    found = {}
    for rho_inf in (0.8, 1.0):
        d = crankgen.continuation(crankgen.Mechanism(eps=0.01), "omega", 1.03, 1.08, max_period=1,
                                  n_elements=8, steps_per_rev=100, rho_inf=rho_inf, quantities=False)
        assert d.info["rho_inf"] == rho_inf
        (pd,) = [s for s in d.special_points if s.kind == "period-doubling"]
        assert abs(pd.multiplier + 1.0) < 1e-4
        found[rho_inf] = pd.parameter
    assert found[1.0] == pytest.approx(1.055109, abs=2e-6)
    assert abs(found[0.8] - found[1.0]) < 2e-5, found


@pytest.mark.slow
def test_generalized_alphas_branches_follow_newmarks_where_the_accelerations_are_stiff():
    """eps = 0.03125, 8 elements (a line of the README's stability chart): the period-2 branch runs
    from its period doubling over both folds and its own period doubling to the range's end with
    either scheme, and finds the same special points (measured within 3.2e-5).  The continuation's
    metric weighs (d, v) and not generalized-alpha's algorithmic accelerations, whose stiff axial
    components, larger than the rest of the scaled state, made its step jump from Omega* 1.087 onto
    the period-1 branch (a branch 'merged' at 0.9 and no fold)."""
    found = {}
    for rho_inf in (0.8, 1.0):
        d = crankgen.continuation(crankgen.Mechanism(eps=0.03125), "omega", 0.9, 1.95, max_period=2,
                                  n_elements=8, rho_inf=rho_inf, quantities=False)
        assert [b.stop_reason for b in d.branches] == ["reached omega = 1.95"] * 2
        found[rho_inf] = [(s.kind, s.period, s.parameter) for s in d.special_points]
    assert [k[:2] for k in found[0.8]] == [k[:2] for k in found[1.0]] == [
        ("period-doubling", 1), ("fold", 2), ("fold", 2), ("period-doubling", 2)]
    assert max(abs(a[2] - b[2]) for a, b in zip(found[0.8], found[1.0])) < 5e-5, found
