"""A torsional spring at the rocker's ground pivot (stiffness and free angle: one coefficient pair and
one energy term declared in derive/): the flexible four-bar held at rest against the spring is the
rigid four-bar's static equilibrium computed here, the coupler a two-force member along its chord
and the rocker in moment balance about its pivot, the spring's moment k (beta_free - beta) taken
at the rigid rocker angle of tests/four_bar.py."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.discrete import kinematics
from crankgen.declaration import schema
from crankgen.declaration.cases import Case
from crankgen.discrete.system import Model
from crankgen.analyses.modes import FrozenModel

import four_bar as fb

FOUR_BAR = dict(guide="circle", a=0.2, c=0.8, d=1.0, offset=0.1, eps=0.005, ms=0.5, mu=0.5)


def _cross(p, q):
    return p[0] * q[1] - p[1] * q[0]


def rigid_statics(theta, k, free, a, c, d, offset, **_):
    """(rocker angle, force of the crank pin on the rod (X, Y), crank torque) of the rigid four-bar
    at rest at crank angle theta with the spring at its pivot."""
    beta = float(fb.rocker_angle(theta, a, c, d, offset))
    A = np.array([a * math.cos(theta), a * math.sin(theta)])
    D = np.array([d, offset])
    B = D + c * np.array([math.cos(beta), math.sin(beta)])
    n = (B - A) / np.linalg.norm(B - A)
    # the rod carries f n from the pin (a two-force member) and applies it to the rocker at B:
    # cross(B - D, f n) + k (free - beta) = 0 about the pivot
    f = -k * (free - beta) / _cross(B - D, n)
    F = f * n
    return beta, F, _cross(A, F), f, n, B - D


def flexible_statics(case, theta):
    """(rocker angle, pin force (X, Y), crank torque, end co-ordinate s) of the model at rest at
    crank angle theta: R(d, 0, 0) = 0 solved by Newton's method on the model's tangent."""
    frozen = FrozenModel(case)
    kin = kinematics.frozen_state(case, np.array([theta]))
    d = np.zeros((1, frozen.N))
    for _ in range(40):
        r, K, _ = frozen._assemble(kin, d)
        step = -np.linalg.solve(K, r[..., None])[..., 0]
        d += step
        if np.max(np.abs(step)) <= 1e-15 * (1 + np.max(np.abs(d))):
            break
    else:
        raise AssertionError("Newton did not converge")
    model = Model(case)
    Fi, Fj = (x[0] for x in model.reactions(0.0, d, 0 * d, 0 * d)[0].T)
    phi = float(kin.phi[0])
    F = Fi * np.array([math.cos(phi), -math.sin(phi)]) + Fj * np.array([math.sin(phi), math.cos(phi)])
    A = case.a * np.array([math.cos(theta), math.sin(theta)])
    s = float(d[0, model.mesh.reduced_coordinates()[0]])
    return float(kin.beta[0]) + s, F, _cross(A, F), s


@pytest.mark.parametrize("theta,k,free", [(0.3, 0.05, 1.2), (2.0, 0.02, 2.5), (4.0, 0.1, 0.0)])
def test_the_four_bar_at_rest_balances_the_spring_as_the_rigid_one(theta, k, free):
    """The pin's force and the crank's torque tend to the rigid linkage's as the rod stiffens
    (EA = 1 / (pi^4 eps^2): the difference is the rod's compliance, O(eps^2)), and the rocker
    turns by the rod's shortening f L / EA (Hooke) over the rate c (n . tangent) at which the
    rocker's turn lengthens the chord."""
    errors = []
    for eps in (0.005, 0.0025):
        case = Case(omega=0.0, theta0=theta, n_elements=4, rocker_stiffness=k, rocker_free_angle=free,
                    **dict(FOUR_BAR, eps=eps))
        beta, F, torque, s = flexible_statics(case, theta)
        beta0, F0, torque0, f, n, arm = rigid_statics(theta, k, free, **FOUR_BAR)
        assert abs(f) > 1e-2                                    # the spring loads the linkage
        errors.append(max(np.max(np.abs(F - F0)) / abs(f), abs(torque - torque0) / (case.a * abs(f))))
        EA = 1 / (math.pi**4 * eps**2)
        tangent = np.array([-arm[1], arm[0]])                   # c times the rocker's tangent
        hooke = -(f / EA) / float(n @ tangent)
        assert abs(s - hooke) < 1e-3 * abs(hooke)               # measured 2e-4 at most
        assert abs(beta - beta0 - s) < 1e-12                    # the frozen rigid rocker angle is beta0
    assert errors[1] < 3e-4, errors                             # measured 2e-5 to 7e-5
    assert 3.5 < errors[0] / errors[1] < 4.5, errors            # O(eps^2): 4 for eps halved


@pytest.mark.parametrize("s", [0.3, -1.0, 2.5])
def test_the_springs_energy_and_force(s):
    """Its energy kernel is k (beta + s - beta_free)^2 / 2 with the end node turned by s on the rocker's
    circle (however far), and its element kernel is the energy's gradient (central differences)."""
    from crankgen._generated import elements, energy
    k, free, theta = 0.07, 0.4, 1.1
    case = Case(omega=0.0, theta0=theta, n_elements=2, rocker_stiffness=k, rocker_free_angle=free, **FOUR_BAR)
    model = Model(case)
    kin = model.kinematics(0.0)
    d = np.zeros(model.n_dofs)
    d[model.mesh.reduced_coordinates()[0]] = s
    q = model.nodal_state(kin, d, 0 * d, 0 * d)[0][-1]
    geo, coef, z = model.geometry[-1], model.coefficients, np.zeros(schema.ELEMENT_DOFS)
    V = energy.rocker_spring_potential(q, z, geo, coef, kin.vector)
    assert V == pytest.approx(k * (float(kin.beta) + s - free) ** 2 / 2, rel=1e-13)
    force = elements.rocker_spring_torsional(q, z, z, geo, coef, kin.vector)[0]
    h = 1e-6
    for slot in range(schema.ELEMENT_DOFS):
        dq = np.zeros(schema.ELEMENT_DOFS)
        dq[slot] = h
        fd = (energy.rocker_spring_potential(q + dq, z, geo, coef, kin.vector)
              - energy.rocker_spring_potential(q - dq, z, geo, coef, kin.vector)) / (2 * h)
        assert force[slot] == pytest.approx(fd, rel=1e-7, abs=1e-10), slot


def test_the_spring_belongs_to_the_rocker():
    with pytest.raises(crankgen.ParameterError, match="rocker_stiffness"):
        Case(omega=0.8, rocker_stiffness=0.1)                   # a slider has no rocker


def test_the_engine_runs_the_spring_like_the_reference():
    """The compiled engine and the NumPy reference model agree with the spring in the equations,
    and the spring changes the run (a fast check that the engine selects its kernel)."""
    mech = crankgen.Mechanism(**dict(FOUR_BAR, eps=0.01), rocker_stiffness=0.05, rocker_free_angle=1.2)
    kw = dict(omega=0.6, n_elements=2, steps_per_rev=40, revolutions=0.5)
    compiled = crankgen.simulate(mech, engine="compiled", **kw)
    reference = crankgen.simulate(mech, engine="numpy", **kw)
    free = crankgen.simulate(crankgen.Mechanism(**dict(FOUR_BAR, eps=0.01)), **kw)
    np.testing.assert_allclose(compiled.torque, reference.torque, rtol=0, atol=1e-9 * np.max(np.abs(compiled.torque)))
    assert np.max(np.abs(compiled.torque - free.torque)) > 1e-2 * np.max(np.abs(free.torque))
