"""A four-bar's rigid rocker with a mass, a centre of mass and a moment of inertia (its kinetic
energy J_D gamma_dot^2 / 2 and its weight, declared in derive/ as families carried by the rocker).

Independent truths:
- a rigid body turning about a fixed pivot has the kinetic energy of a point mass J_D / c^2 at the
  tip's radius c, and the weight of a mass m whose centre lies at k c the moment of a point mass
  m k at the tip: a rocker with J_D / c^2 = m k (J_G = m k (1 - k) c^2) is exactly a tip mass
  m k more, under gravity too (in the exact Lagrange equations: the printed form's slider terms
  are not those of eqs. (6)-(7) exactly);
- the natural frequencies of the linkage frozen at rest (crank locked): the coupler an Euler-Bernoulli
  beam pinned at the crank pin, its end pinned to the rocker's tip, which moves along the circle's
  tangent only, with the tip mass and J_D / c^2 along it (a transcendental frequency equation);
- the rocker's moment balance about its pivot, J_D gamma_dd = M_tip + M_weight + M_spring, with
  gamma_dd by central differences of the rocker angle along the run and M_tip the moment of the
  force the tip applies to the rocker (minus the output rocker_on_tip).
"""

import functools
import math

import numpy as np
import pytest

from scipy.optimize import brentq

import crankgen
import four_bar as fb

FOUR_BAR = dict(guide="circle", a=0.2, c=0.8, d=1.0, offset=0.1, eps=0.01, ms=0.5, mu=0.5)
RUN = dict(omega=0.8, n_elements=2, steps_per_rev=40, revolutions=1)


def _close(x, y, rel):
    x, y = np.asarray(x), np.asarray(y)
    assert np.max(np.abs(x - y)) <= rel * np.max(np.abs(y)), np.max(np.abs(x - y)) / np.max(np.abs(y))


@pytest.mark.parametrize("model", ["consistent", "exact"])
def test_a_rocker_turning_about_its_pivot_is_a_tip_mass(model):
    """The uniform-bar-like rocker (m, centre 0.5, J_G = m c^2 / 4: J_D / c^2 = m / 2) under gravity
    runs as the massless rocker with the tip mass ms + m / 2: the same states, pin forces and crank
    torque (round-off apart), and the rocker changes the run (it is not left out)."""
    m, c, g = 0.6, FOUR_BAR["c"], (0.02, -0.08)
    rocker = crankgen.Mechanism(**FOUR_BAR, gravity=g, rocker_mass=m, rocker_centre=0.5,
                                rocker_inertia=m * c**2 / 4)
    tip = crankgen.Mechanism(**dict(FOUR_BAR, ms=FOUR_BAR["ms"] + m / 2), gravity=g)
    plain = crankgen.Mechanism(**FOUR_BAR, gravity=g)
    weightless = crankgen.Mechanism(**FOUR_BAR, rocker_mass=m, rocker_centre=0.5, rocker_inertia=m * c**2 / 4)
    runs = [crankgen.simulate(mech, model=model, **RUN) for mech in (rocker, tip, plain, weightless)]
    for name in ("v_mid", "u_end", "torque", "crank_on_rod_x", "crank_on_rod_y", "rocker_angle"):
        _close(runs[0].quantity(name), runs[1].quantity(name), 1e-9)
    assert np.max(np.abs(runs[0].v_mid - runs[2].v_mid)) > 1e-2 * np.max(np.abs(runs[2].v_mid))
    assert np.max(np.abs(runs[0].v_mid - runs[3].v_mid)) > 1e-4 * np.max(np.abs(runs[3].v_mid))   # its weight


def test_a_rocker_inertia_alone_is_a_tip_mass_J_over_c_squared():
    J, c = 0.05, FOUR_BAR["c"]
    rocker = crankgen.simulate(crankgen.Mechanism(**FOUR_BAR, rocker_inertia=J, rocker_centre=0.0), **RUN)
    tip = crankgen.simulate(crankgen.Mechanism(**dict(FOUR_BAR, ms=FOUR_BAR["ms"] + J / c**2)), **RUN)
    _close(rocker.v_mid, tip.v_mid, 1e-9)
    _close(rocker.torque, tip.torque, 1e-9)


# a rocker with a mass off its tip, an inertia and a spring, under gravity: one run per model, shared
HEAVY = dict(m=0.4, k=0.3, J_G=0.02, spring=0.03, free=1.0, g=(0.02, -0.09))
PIVOT = np.array([FOUR_BAR["d"], FOUR_BAR["offset"]])


@functools.lru_cache(maxsize=None)
def heavy_run(model):
    """(run, unwrapped rocker angle, its step) of the heavy rocker over one revolution of 400 steps."""
    h = HEAVY
    mech = crankgen.Mechanism(**FOUR_BAR, gravity=h["g"], rocker_mass=h["m"], rocker_centre=h["k"],
                              rocker_inertia=h["J_G"], rocker_stiffness=h["spring"], rocker_free_angle=h["free"])
    run = crankgen.simulate(mech, model=model, omega=0.8, n_elements=2, steps_per_rev=400, revolutions=1)
    return run, np.unwrap(run.quantity("rocker_angle")), run.t[1] - run.t[0]


def _pair(run, name):
    return np.stack([run.quantity(name + "_x"), run.quantity(name + "_y")], axis=-1)


@pytest.mark.parametrize("model", ["consistent", "paper"])
def test_the_rocker_turns_under_the_moments_on_it(model):
    """J_D gamma_dd = (B - D) x F_tip_on_rocker + m k c (cos gamma gY - sin gamma gX) - k_s (gamma -
    gamma_free) along a run, F_tip_on_rocker = -rocker_on_tip (the force the rocker applies to its
    tip mass): the joint force leaves the rocker's own spring, weight and inertia out."""
    m, k, J_G, spring, free, g = (HEAVY[n] for n in ("m", "k", "J_G", "spring", "free", "g"))
    c = FOUR_BAR["c"]
    run, gamma, dt = heavy_run(model)
    gamma_dd = (gamma[2:] - 2 * gamma[1:-1] + gamma[:-2]) / dt**2
    B = np.stack([run.quantity("slider_position"), run.quantity("end_height")], axis=-1)[1:-1]
    F = -_pair(run, "rocker_on_tip")[1:-1]
    arm = B - PIVOT
    assert np.allclose(np.hypot(*arm.T), c, atol=1e-12)             # the tip stays on the rocker's circle
    g1 = gamma[1:-1]
    moments = (arm[:, 0] * F[:, 1] - arm[:, 1] * F[:, 0]
               + m * k * c * (np.cos(g1) * g[1] - np.sin(g1) * g[0]) - spring * (g1 - free))
    J_D = J_G + m * (k * c) ** 2
    half = len(g1) // 2                           # past the start from rest (central differences of its
    _close(moments[half:], J_D * gamma_dd[half:], 2e-3)     # fast transient are rough): measured 4e-4
                                                            # (generalized-alpha), 7e-5 (Newmark)
    # the tip's force is not along the rocker (it is with a massless rocker without a spring)
    along = np.abs(arm[:, 0] * F[:, 1] - arm[:, 1] * F[:, 0])
    assert np.max(along) > 0.1 * np.max(np.abs(J_D * gamma_dd))


def test_the_massless_rockers_tip_force_is_along_it():
    run = crankgen.simulate(crankgen.Mechanism(**FOUR_BAR), **RUN)
    arm = np.stack([run.quantity("slider_position") - FOUR_BAR["d"],
                    run.quantity("end_height") - FOUR_BAR["offset"]], axis=-1)
    F = np.stack([run.quantity("rocker_on_tip_x"), run.quantity("rocker_on_tip_y")], axis=-1)
    cross = arm[:, 0] * F[:, 1] - arm[:, 1] * F[:, 0]
    assert np.max(np.abs(cross)) < 1e-9 * np.max(np.hypot(*F.T))


@pytest.mark.parametrize("name", ["rocker_mass", "rocker_inertia", "rocker_centre"])
def test_a_slider_has_no_rocker(name):
    with pytest.raises(crankgen.ParameterError, match=name):
        crankgen.Mechanism(**{name: 0.1})


def test_the_rockers_energies():
    """Along a run, the kinetic energy kernel is J_D gamma_dot^2 / 2 with gamma_dot by central
    differences of the rocker angle (past the start), and the potential kernel -m_r g . (G - D) with
    G - D = k c (cos gamma, sin gamma), less the constant m_r k g . D the kernel leaves out."""
    from crankgen._generated import energy
    from crankgen.discrete import kinematics
    from crankgen.discrete.system import Model
    m, k, J_G, g = (HEAVY[n] for n in ("m", "k", "J_G", "g"))
    c, D = FOUR_BAR["c"], PIVOT
    run, gamma, dt = heavy_run("consistent")
    model = Model(run.case)
    kin = kinematics.case_state(run.case, run.t)
    q, qd, _, _ = model.nodal_state(kin, run.states, run.rates, run.accelerations)
    geo, coef = model.geometry[-1], model.coefficients
    T = energy.rocker_kinetic_energy(q[:, -1], qd[:, -1], geo, coef, kin.vector)
    V = energy.rocker_gravity_potential(q[:, -1], qd[:, -1], geo, coef, kin.vector)
    rate = (gamma[2:] - gamma[:-2]) / (2 * dt)
    J_D = J_G + m * (k * c) ** 2
    half = len(rate) // 2
    _close(T[1:-1][half:], J_D * rate[half:] ** 2 / 2, 1e-3)
    weight = -m * k * c * (g[0] * np.cos(gamma) + g[1] * np.sin(gamma))
    _close(V + m * k * (g[0] * D[0] + g[1] * D[1]), weight, 1e-12)


@pytest.mark.parametrize("model", ["consistent", "paper"])
def test_the_pivot_bears_the_rockers_momentum_balance(model):
    """ground_on_rocker = m a_G - m g - F_tip_on_rocker with a_G by central differences of the centre
    of mass G = D + k c (cos gamma, sin gamma) along the run (past the start), F_tip_on_rocker =
    -rocker_on_tip; with a massless rocker it is the force at the tip."""
    m, k, g = (HEAVY[n] for n in ("m", "k", "g"))
    run, gamma, dt = heavy_run(model)
    G = PIVOT + k * FOUR_BAR["c"] * np.stack([np.cos(gamma), np.sin(gamma)], axis=-1)
    a_G = (G[2:] - 2 * G[1:-1] + G[:-2]) / dt**2
    tip = _pair(run, "rocker_on_tip")[1:-1]
    pivot = _pair(run, "ground_on_rocker")[1:-1]
    half = len(a_G) // 2
    _close(pivot[half:], (m * a_G - m * np.array(g) + tip)[half:], 2e-3)
    assert np.max(np.abs(pivot - tip)) > 0.05 * np.max(np.abs(tip))       # the rocker's own share

    massless = crankgen.simulate(crankgen.Mechanism(**FOUR_BAR, gravity=g), model=model, **RUN)
    np.testing.assert_array_equal(massless.quantity("ground_on_rocker_x"), massless.quantity("rocker_on_tip_x"))
    np.testing.assert_array_equal(massless.quantity("ground_on_rocker_y"), massless.quantity("rocker_on_tip_y"))


def frozen_frequencies(theta, M, count, a, c, d, offset, eps, **_):
    """The lowest natural frequencies (units of omega_b) of the four-bar at rest at crank angle theta:
    the coupler (rho A = 1, L = 1, EI = 1/pi^4, EA = EI/eps^2, no rotary inertia) with u = v = v'' = 0
    at the crank pin; at B, v'' = 0 and the displacement delta t along the circle's tangent t, the
    mass M on it: M omega^2 delta = EA u_x(1) (e_i . t) - EI v_xxx(1) (e_j . t).  u = A1 sin(k x),
    v = B1 sin(b x) + B2 sinh(b x) (k = omega / sqrt(EA), b^4 = omega^2 / EI); the roots of the 4 x 4
    determinant in (A1, B1, B2, delta)."""
    beta = float(fb.rocker_angle(theta, a, c, d, offset))
    A = np.array([a * math.cos(theta), a * math.sin(theta)])
    ei = np.array([d, offset]) + c * np.array([math.cos(beta), math.sin(beta)]) - A
    ei /= np.linalg.norm(ei)
    ej = np.array([-ei[1], ei[0]])
    tangent = np.array([-math.sin(beta), math.cos(beta)])
    ct, st = ei @ tangent, ej @ tangent
    EI, EA = 1 / math.pi**4, 1 / (math.pi**4 * eps**2)

    def det(w):
        k, b = w / math.sqrt(EA), (w**2 / EI) ** 0.25
        m = np.array([[0.0, -math.sin(b), math.sinh(b), 0.0],
                      [math.sin(k), 0.0, 0.0, -ct],
                      [0.0, math.sin(b), math.sinh(b), -st],
                      [-EA * k * math.cos(k) * ct, -EI * b**3 * math.cos(b) * st, EI * b**3 * math.cosh(b) * st,
                       M * w**2]])
        return np.linalg.det(m / np.abs(m).max(axis=1, keepdims=True)) / math.cosh(b)

    grid = np.linspace(0.05, 40.0, 8000)
    values = [det(w) for w in grid]
    roots = [brentq(det, w0, w1, xtol=1e-13) for w0, w1, f0, f1 in zip(grid[:-1], grid[1:], values[:-1], values[1:])
             if f0 * f1 < 0]
    return np.array(roots[:count])


def test_the_frozen_linkages_frequencies():
    """The first three natural frequencies at rest against the frequency equation, with and without
    a rocker of mass m (J_D = J_G + m (c/2)^2 on the tip as J_D / c^2), within 1.5e-3 at 8 elements and
    converging (16 elements); the rocker lowers the third by more than 1 %."""
    geometry = dict(FOUR_BAR, mu=0.0)
    m = 0.6
    rocker = dict(rocker_mass=m, rocker_centre=0.5, rocker_inertia=m * geometry["c"] ** 2 / 12)
    J_D = rocker["rocker_inertia"] + m * (geometry["c"] / 2) ** 2
    found = {}
    for extra, M in ((dict(), geometry["ms"]), (rocker, geometry["ms"] + J_D / geometry["c"] ** 2)):
        exact = frozen_frequencies(0.7, M, 3, **geometry)
        errors = []
        for n in (8, 16):
            computed = crankgen.modes(crankgen.Mechanism(**geometry, **extra), omega=0.0, theta=0.7, count=3,
                                      n_elements=n, rotary_inertia=False).frequencies
            errors.append(np.abs(computed / exact - 1))
        assert np.all(errors[0] < 1.5e-3), errors            # measured 2e-5, 3e-4, 1e-3 (8 elements)
        assert np.all(errors[1] < errors[0] / 8), errors     # 16 times smaller (h^4) for the first two,
                                                             # 10-14 for the third (the axial field's h^2)
        found[bool(extra)] = exact
    assert found[True][2] < 0.99 * found[False][2], found  # measured 8.29 against 8.76
