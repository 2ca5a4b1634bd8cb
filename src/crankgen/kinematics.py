"""Exact rigid-body kinematics of the slider-crank (constant crank speed).

theta = Omega t, and the rod angle phi follows from the slider staying on the X axis:
sin phi = a* sin theta (ERRATA.md conventions), so with c = cos phi = sqrt(1 - a*^2 sin^2 theta)
    phid  = a* Omega cos theta / c,
    phidd = -a* Omega^2 sin theta / c + phid^2 tan phi.
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class CrankState:
    """Rigid-body state at one or many instants (arrays broadcast like t)."""

    theta: np.ndarray
    thetad: np.ndarray
    phi: np.ndarray
    phid: np.ndarray
    phidd: np.ndarray

    def as_args(self):
        """(theta, thetad, phi, phid, phidd), the order of the generated kernels' arguments."""
        return self.theta, self.thetad, self.phi, self.phid, self.phidd


def crank_state(a, omega, t):
    """Kinematics at time(s) t for crank ratio a (= a*) and crank speed omega (= Omega*)."""
    t = np.asarray(t, dtype=float)
    omega = np.asarray(omega, dtype=float)
    theta = omega * t
    sin_phi = a * np.sin(theta)
    cos_phi = np.sqrt(1.0 - sin_phi**2)
    phi = np.arcsin(sin_phi)
    phid = a * omega * np.cos(theta) / cos_phi
    phidd = -a * omega**2 * np.sin(theta) / cos_phi + phid**2 * sin_phi / cos_phi
    thetad = np.broadcast_to(omega, theta.shape).astype(float)
    return CrankState(theta, thetad, phi, phid, phidd)


def slider_position(a, theta):
    """X co-ordinate of the rigid slider, a cos theta + L cos phi (L = 1)."""
    return a * np.cos(theta) + np.sqrt(1.0 - (a * np.sin(theta)) ** 2)
