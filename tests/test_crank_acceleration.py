"""The inertia kernels with a crank that accelerates (thetadd != 0): the generated terms against
the Euler-Lagrange equations of the generated kinetic energies, differentiated by finite
differences along a trajectory whose crank speed varies, theta = Omega t + c sin(w t).

With a constant crank speed (tests/test_kernel_derivatives.py) every thetadd term is multiplied by
zero; here they carry the inertia of the crank pin's tangential acceleration a thetadd and the rod
angle's share of it (phidd includes a thetadd cos(theta) / (L cos phi)).
"""

import numpy as np
import pytest

import reference as ref
from kernel_api import energy, lagrange
from reference import APPROACHES, assert_close
from test_kernel_derivatives import Trajectory, _euler_lagrange, random_rod

FD_RTOL = 2e-6


class AcceleratingTrajectory(Trajectory):
    """The nodal trajectory of test_kernel_derivatives.Trajectory; the crank at
    theta = Omega t + c sin(w t) (speed and acceleration vary), the slider-crank's rod angle
    sin phi = (a / L) sin theta."""

    def __init__(self, rng, shape, a, omega, c, w, L=1.0):
        super().__init__(rng, shape, a, omega, L)
        self.c_crank, self.w_crank = c, w

    def kinematics(self, t):
        """(a, theta, thetad, phi, phid, phidd, thetadd) at time t, differentiated by hand."""
        a, c, w = self.a / self.L, self.c_crank, self.w_crank
        theta = self.omega * t + c * np.sin(w * t)
        thetad = self.omega + c * w * np.cos(w * t)
        thetadd = -c * w**2 * np.sin(w * t)
        phi = np.arcsin(a * np.sin(theta))
        cp = np.cos(phi)
        phid = a * thetad * np.cos(theta) / cp
        phidd = (np.sin(phi) * phid**2 + a * (thetadd * np.cos(theta) - thetad**2 * np.sin(theta))) / cp
        return (self.a, theta, thetad, phi, phid, phidd, thetadd)


def test_the_trajectory_rates_are_derivatives():
    traj = AcceleratingTrajectory(np.random.default_rng(1), (1,), a=0.3, omega=1.7, c=0.4, w=2.2, L=0.9)
    t = np.linspace(0.1, 3.0, 7)
    k = traj.kinematics(t)
    for value, rate in ((1, 2), (2, 6), (3, 4), (4, 5)):
        fd = ref.fd_derivative(lambda s, i=value: traj.kinematics(s)[i], t, 1e-4)
        np.testing.assert_allclose(fd, k[rate], rtol=1e-7, atol=1e-9)
    assert np.max(np.abs(k[6])) > 0.5                      # the crank does accelerate


@pytest.mark.parametrize("approach", APPROACHES)
@pytest.mark.parametrize("t", [0.3, 2.1])
def test_rod_euler_lagrange_with_an_accelerating_crank(approach, t):
    rng = np.random.default_rng(52)
    n = 7
    l, x0, rhoA, rhoI, EA, EI = random_rod(rng, n)
    traj = AcceleratingTrajectory(rng, (n,), a=0.25, omega=2.3, c=1.5, w=1.9)
    U = getattr(energy, f"strain_energy_{approach}")

    def lag(q, qd, s):
        kin = traj.kinematics(s)[:5]
        return energy.rod_kinetic_energy(q, qd, l, x0, rhoA, rhoI, *kin) - U(q, l, EA, EI)

    el = _euler_lagrange(lag, traj, t)
    q, qd, qdd = traj.q(t)
    a, theta, thetad, phi, phid, phidd, thetadd = traj.kinematics(t)
    r = (lagrange.rod_inertia(q, qd, qdd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid, phidd,
                              thetadd=thetadd)[0]
         + getattr(lagrange, f"rod_elastic_{approach}")(q, l, EA, EI)[0])
    assert_close(r, el, FD_RTOL, 1, f"EL residual with thetadd, approach {approach}, t={t}")
    # the thetadd terms must stand far above the mismatch, or the check would be blind to them
    r0 = (lagrange.rod_inertia(q, qd, qdd, l, x0, rhoA, rhoI, a, theta, thetad, phi, phid, phidd)[0]
          + getattr(lagrange, f"rod_elastic_{approach}")(q, l, EA, EI)[0])
    assert np.all(np.linalg.norm(r - r0, axis=-1) > 100 * np.linalg.norm(r - el, axis=-1))


@pytest.mark.parametrize("t", [0.3, 2.1])
def test_slider_euler_lagrange_with_an_accelerating_crank(t):
    rng = np.random.default_rng(53)
    n, L = 5, 1.1
    ms = rng.uniform(0.1, 1.0, n)
    traj = AcceleratingTrajectory(rng, (n,), a=0.25, omega=2.3, c=1.5, w=1.9, L=L)
    full_q = traj.q
    traj.q = lambda s: tuple(x[..., ref.END_UV] for x in full_q(s))

    def lag(qs, qsd, s):
        return energy.slider_kinetic_energy(qs, qsd, ms, L, *traj.kinematics(s)[:5])

    el = _euler_lagrange(lag, traj, t)
    qs, qsd, qsdd = traj.q(t)
    a, theta, thetad, phi, phid, phidd, thetadd = traj.kinematics(t)
    r = lagrange.slider_inertia(qs, qsd, qsdd, ms, L, a, theta, thetad, phi, phid, phidd, thetadd=thetadd)[0]
    assert_close(r, el, FD_RTOL, 1, f"slider EL residual with thetadd, t={t}")
    r0 = lagrange.slider_inertia(qs, qsd, qsdd, ms, L, a, theta, thetad, phi, phid, phidd)[0]
    assert np.all(np.linalg.norm(r - r0, axis=-1) > 100 * np.linalg.norm(r - el, axis=-1))
