"""Derivative identities of the generated kernels, checked with finite differences.

* every tangent output (K, C, M) is the derivative of the kernel's own residual r;
* exact elastic and Kelvin-Voigt forces are gradients of the generated energy kernels;
* the Lagrange inertia + elastic forces equal d/dt dLag/dqd - dLag/dq of the discrete Lagrangian
  built from the generated energy kernels, evaluated with nested finite differences along a
  smooth trajectory of a real slider-crank motion;
* the printed forcing uses the time derivatives of m3 and m_s4 (errata), checked in time.

Finite differences use the 5-point central stencil, which is exact for the polynomial (degree
<= 4) dependence on q, qd, qdd, so only rounding limits the accuracy.
"""

import numpy as np
import pytest

from kernel_api import damping, energy, lagrange, paper

import reference as ref
from reference import APPROACHES, assert_close, pick

FD_RTOL = 1e-6
FORMULATIONS = {"lagrange": lagrange, "paper": paper}


@pytest.fixture(params=(0, 1), ids=lambda s: f"seed{s}")
def elems(request):
    return ref.random_elements(np.random.default_rng(2000 + request.param), n=7)


def _replace(args, names, **new):
    return [new.get(n, a) for n, a in zip(names, args)]


def _check_tangent(kernel, args, names, wrt, out_index, what, h=1e-3):
    """Output `out_index` of kernel against the FD Jacobian of its r w.r.t. argument `wrt`."""
    outputs = kernel(*args)
    x = args[names.index(wrt)]
    fd = ref.fd_jacobian(lambda y: kernel(*_replace(args, names, **{wrt: y}))[0], x, h)
    # rounding of the stencil ~ eps |r| / h; matters only where the tangent vanishes
    atol = 1e-12 * np.max(np.abs(outputs[0])) / h
    assert_close(outputs[out_index], fd, FD_RTOL, 2, what, atol=atol)


# --------------------------------------------------------------------------------------------
# tangents of every residual kernel
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("formulation", FORMULATIONS)
@pytest.mark.parametrize("part", ["rod", "slider"])
def test_inertia_tangents(formulation, part, elems):
    module = FORMULATIONS[formulation]
    kernel = getattr(module, f"{part}_inertia")
    names = ref.ROD_INERTIA_ARGS if part == "rod" else ref.SLIDER_INERTIA_ARGS
    args = pick(elems, *names)
    for wrt, k in zip(names[:3], (1, 2, 3)):
        _check_tangent(kernel, args, names, wrt, k,
                       f"{formulation}.{part}_inertia.{'KCM'[k - 1]}")


@pytest.mark.parametrize("formulation", FORMULATIONS)
@pytest.mark.parametrize("approach", APPROACHES)
def test_elastic_tangent(formulation, approach, elems):
    kernel = getattr(FORMULATIONS[formulation], f"rod_elastic_{approach}")
    names = ("q", "l", "EA", "EI")
    _check_tangent(kernel, pick(elems, *names), names, "q", 1,
                   f"{formulation}.rod_elastic_{approach}.K")


@pytest.mark.parametrize("formulation", FORMULATIONS)
@pytest.mark.parametrize("approach", APPROACHES)
def test_elastic_tangent_large_slopes(formulation, approach):
    """Slopes of order one, where the cubic terms of A dominate the tangent."""
    rng = np.random.default_rng(5)
    q = rng.uniform(-1, 1, (6, ref.NDOF)) * [0.05, 0.3, 1.0, 0.05, 0.05, 0.3, 1.0, 0.05]
    args = [q, rng.uniform(0.1, 0.5, 6), rng.uniform(10, 100, 6), rng.uniform(0.01, 0.1, 6)]
    kernel = getattr(FORMULATIONS[formulation], f"rod_elastic_{approach}")
    _check_tangent(kernel, args, ("q", "l", "EA", "EI"), "q", 1,
                   f"{formulation}.rod_elastic_{approach}.K (large slopes)")


@pytest.mark.parametrize("model", [f"kelvin_voigt_{ap}" for ap in APPROACHES]
                         + [f"paper_{ap}" for ap in APPROACHES] + ["paper_slider"])
def test_damping_tangents(model, elems):
    kernel = getattr(damping, model)
    if model.startswith("kelvin_voigt"):
        names = ("q", "qd", "l", "EA", "EI", "mu")
    elif model == "paper_slider":
        names = ("qsd", "ms", "phid", "mu")
    else:
        names = ("q", "qd", "l", "EA", "EI", "rhoA", "rhoI", "phid", "mu")
    args = pick(elems, *names)
    if model == "paper_slider":
        _check_tangent(kernel, args, names, "qsd", 2, f"damping.{model}.C")
        return
    _check_tangent(kernel, args, names, "q", 1, f"damping.{model}.K")
    _check_tangent(kernel, args, names, "qd", 2, f"damping.{model}.C")


# --------------------------------------------------------------------------------------------
# forces as gradients of the generated energies
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("approach", APPROACHES)
def test_elastic_force_is_gradient_of_strain_energy(approach, elems):
    q, l, EA, EI = pick(elems, "q", "l", "EA", "EI")
    U = getattr(energy, f"strain_energy_{approach}")
    r, K = getattr(lagrange, f"rod_elastic_{approach}")(q, l, EA, EI)
    grad = ref.fd_jacobian(lambda y: U(y, l, EA, EI), q, 1e-3)
    assert_close(r, grad, FD_RTOL, 1, f"rod_elastic_{approach}.r vs dU/dq")
    hess = ref.fd_jacobian(lambda y: ref.fd_jacobian(lambda z: U(z, l, EA, EI), y, 1e-2), q, 1e-2)
    assert_close(K, hess, 1e-5, 2, f"rod_elastic_{approach}.K vs d2U/dq2")


@pytest.mark.parametrize("approach", APPROACHES)
def test_kelvin_voigt_force_is_gradient_of_dissipation(approach, elems):
    q, qd, l, EA, EI, mu = pick(elems, "q", "qd", "l", "EA", "EI", "mu")
    D = getattr(energy, f"dissipation_{approach}")
    r = getattr(damping, f"kelvin_voigt_{approach}")(q, qd, l, EA, EI, mu)[0]
    grad = ref.fd_jacobian(lambda y: D(q, y, l, EA, EI, mu), qd, 1e-2)
    assert_close(r, grad, FD_RTOL, 1, f"kelvin_voigt_{approach}.r vs dD/dqd")
    # Rayleigh function of a quadratic form in qd: qd . dD/dqd = 2 D
    np.testing.assert_allclose(np.sum(qd * r, axis=-1), 2 * D(q, qd, l, EA, EI, mu), rtol=1e-10)


def test_strain_energies_are_nonnegative_and_consistent(elems):
    """U_A = U_B + EA/8 int v_x^4 dx and U_B = U_C + EA/2 int u_x v_x^2 dx (generated kernels)."""
    q, l, EA, EI = pick(elems, "q", "l", "EA", "EI")
    f = ref.element_fields(q, q, l)
    v4 = ref.integrate(f["v_x"] ** 4, l)
    uv2 = ref.integrate(f["u_x"] * f["v_x"] ** 2, l)
    UA, UB, UC = (getattr(energy, f"strain_energy_{ap}")(q, l, EA, EI) for ap in APPROACHES)
    np.testing.assert_allclose(UA - UB, EA / 8 * v4, rtol=1e-8)
    np.testing.assert_allclose(UB - UC, EA / 2 * uv2, rtol=1e-8)
    assert np.all(UA >= 0) and np.all(UC >= 0)


# --------------------------------------------------------------------------------------------
# Euler-Lagrange equations of the discrete Lagrangian, by nested finite differences
# --------------------------------------------------------------------------------------------

class Trajectory:
    """q(t) = c0 + c1 sin(w1 t) + c2 cos(w2 t) per element; slider-crank kinematics theta = Omega t."""

    def __init__(self, rng, shape, a, omega, L=1.0):
        self.c = [ref.random_nodal(rng, shape) for _ in range(3)]
        self.w = rng.uniform(0.5, 3.0, (2,) + shape + (1,))
        self.a, self.omega, self.L = a, omega, L

    def q(self, t):
        c0, c1, c2 = self.c
        w1, w2 = self.w
        return (c0 + c1 * np.sin(w1 * t) + c2 * np.cos(w2 * t),
                c1 * w1 * np.cos(w1 * t) - c2 * w2 * np.sin(w2 * t),
                -c1 * w1**2 * np.sin(w1 * t) - c2 * w2**2 * np.cos(w2 * t))

    def kinematics(self, t):
        """(a, theta, thetad, phi, phid, phidd) at time t."""
        return (self.a,) + ref.slider_crank_angles(t, self.a, self.omega, self.L)


def test_slider_crank_kinematics_rates():
    """Sanity of the reference kinematics used below: phid, phidd are the time derivatives of phi."""
    a, omega, L = 0.3, 1.7, 0.9
    t = np.linspace(0, 4, 9)
    _, _, phi, phid, phidd = ref.slider_crank_angles(t, a, omega, L)
    np.testing.assert_allclose(np.sin(phi), a / L * np.sin(omega * t), atol=1e-15)
    np.testing.assert_allclose(
        ref.fd_derivative(lambda s: ref.slider_crank_angles(s, a, omega, L)[2], t, 1e-3), phid,
        rtol=1e-9, atol=1e-11)
    np.testing.assert_allclose(
        ref.fd_derivative(lambda s: ref.slider_crank_angles(s, a, omega, L)[3], t, 1e-3), phidd,
        rtol=1e-9, atol=1e-11)


def _euler_lagrange(lag, traj, t, h_q=1e-3, h_qd=1e-2, tau=1e-3):
    """d/dt dLag/dqd - dLag/dq along traj at time t, all derivatives by finite differences."""
    def momentum(s):
        q, qd, _ = traj.q(s)
        return ref.fd_jacobian(lambda y: lag(q, y, s), qd, h_qd)

    q, qd, _ = traj.q(t)
    dmomentum = ref.fd_derivative(momentum, t, tau)
    force = ref.fd_jacobian(lambda y: lag(y, qd, t), q, h_q)
    return dmomentum - force


def random_rod(rng, n):
    """Element lengths, positions, rhoA, rhoI, EA and EI of n random elements."""
    l, x0 = rng.uniform(0.05, 0.5, n), rng.uniform(0.0, 0.9, n)
    rhoA, rhoI = rng.uniform(0.5, 2.0, n), rng.uniform(0.01, 0.1, n)
    EA, EI = rng.uniform(10.0, 1000.0, n), rng.uniform(0.005, 0.05, n)
    return l, x0, rhoA, rhoI, EA, EI


@pytest.mark.parametrize("approach", APPROACHES)
@pytest.mark.parametrize("t", [0.3, 2.1])
def test_rod_euler_lagrange(approach, t):
    """lagrange.rod_inertia + lagrange.rod_elastic_X = EL(rod_kinetic_energy - strain_energy_X)."""
    rng = np.random.default_rng(42)
    n = 7
    l, x0, rhoA, rhoI, EA, EI = random_rod(rng, n)
    traj = Trajectory(rng, (n,), a=0.25, omega=2.3)
    U = getattr(energy, f"strain_energy_{approach}")

    def lag(q, qd, s):
        kin = traj.kinematics(s)[:-1]
        return energy.rod_kinetic_energy(q, qd, l, x0, rhoA, rhoI, *kin) - U(q, l, EA, EI)

    el = _euler_lagrange(lag, traj, t)
    q, qd, qdd = traj.q(t)
    kin = traj.kinematics(t)
    r = (lagrange.rod_inertia(q, qd, qdd, l, x0, rhoA, rhoI, *kin)[0]
         + getattr(lagrange, f"rod_elastic_{approach}")(q, l, EA, EI)[0])
    assert_close(r, el, FD_RTOL, 1, f"EL residual, approach {approach}, t={t}")
    # the elastic part must matter at this tolerance, or the check would be blind to it
    r_el = getattr(lagrange, f"rod_elastic_{approach}")(q, l, EA, EI)[0]
    assert np.all(np.linalg.norm(r_el, axis=-1) > 1e3 * FD_RTOL * np.linalg.norm(el, axis=-1))


@pytest.mark.parametrize("t", [0.3, 2.1])
def test_slider_euler_lagrange(t):
    rng = np.random.default_rng(43)
    n = 5
    ms, L = rng.uniform(0.1, 1.0, n), 1.1
    traj = Trajectory(rng, (n,), a=0.25, omega=2.3, L=L)
    full_q = traj.q

    def slider_q(s):
        return tuple(x[..., ref.END_UV] for x in full_q(s))

    traj.q = slider_q

    def lag(qs, qsd, s):
        kin = traj.kinematics(s)[:-1]
        return energy.slider_kinetic_energy(qs, qsd, ms, L, *kin)

    el = _euler_lagrange(lag, traj, t)
    qs, qsd, qsdd = traj.q(t)
    r = lagrange.slider_inertia(qs, qsd, qsdd, ms, L, *traj.kinematics(t))[0]
    assert_close(r, el, FD_RTOL, 1, f"slider EL residual, t={t}")


# --------------------------------------------------------------------------------------------
# printed forcing: time derivatives of m3 and m_s4 along the motion (errata of B3 and eq. 29)
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("t", [0.4, 1.9])
def test_paper_rod_forcing_uses_time_derivative_of_m3(t):
    rng = np.random.default_rng(44)
    n = 7
    l, x0 = rng.uniform(0.05, 0.5, n), rng.uniform(0.0, 0.9, n)
    rhoA, rhoI = rng.uniform(0.5, 2.0, n), rng.uniform(0.01, 0.1, n)
    traj = Trajectory(rng, (n,), a=0.25, omega=2.3)
    zero = np.zeros(n)

    def mats(s):
        return ref.printed_matrices(zero[:, None] + np.zeros(ref.NDOF), l, x0, rhoA, rhoI, 1.0, 1.0,
                                    *traj.kinematics(s))

    m = mats(t)
    m3dot = ref.fd_derivative(lambda s: mats(s)["m3"], t, 1e-3)
    q, qd, qdd = traj.q(t)
    expected = ref.matvec(m["m1"], qdd) - ref.matvec(m["m2"], q) - (m["m4"] - m3dot)
    r = paper.rod_inertia(q, qd, qdd, l, x0, rhoA, rhoI, *traj.kinematics(t))[0]
    assert_close(r, expected, FD_RTOL, 1, "paper.rod_inertia with FD d/dt m3")


@pytest.mark.parametrize("t", [0.4, 1.9])
def test_paper_slider_forcing_uses_time_derivative_of_ms4(t):
    rng = np.random.default_rng(45)
    n, L = 5, 1.1
    ms = rng.uniform(0.1, 1.0, n)
    traj = Trajectory(rng, (n,), a=0.25, omega=2.3, L=L)

    def ms34(s):
        a, theta, thetad, phi, phid, _ = traj.kinematics(s)
        crank, tp = a * thetad, theta + phi
        ms3 = np.stack([ms * (-crank * phid * np.cos(tp) + phid**2 * L),
                        ms * (-crank * phid * np.sin(tp))], -1)
        ms4 = np.stack([ms * (-crank * np.sin(tp)), ms * (crank * np.cos(tp) - phid * L)], -1)
        return ms3, ms4

    ms3 = ms34(t)[0]
    ms4dot = ref.fd_derivative(lambda s: ms34(s)[1], t, 1e-3)
    qs, qsd, qsdd = (x[..., ref.END_UV] for x in traj.q(t))
    phid = traj.kinematics(t)[4]
    expected = ms[:, None] * qsdd - ms[:, None] * phid**2 * qs - (ms3 - ms4dot)
    r = paper.slider_inertia(qs, qsd, qsdd, ms, L, *traj.kinematics(t))[0]
    assert_close(r, expected, FD_RTOL, 1, "paper.slider_inertia with FD d/dt m_s4")
