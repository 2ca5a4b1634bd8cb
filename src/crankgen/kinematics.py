"""Exact rigid-body kinematics of the slider-crank (constant crank speed), from the generated guide
kernel (derive/guide.py): theta = Omega t, and the rod angle phi follows from the slider staying on
its guide Y = e:  sin phi = (a* sin theta - e) / L, so with c = cos phi
    phid  = a* Omega cos theta / c,
    phidd = -a* Omega^2 sin theta / c + phid^2 tan phi.
"""

from dataclasses import dataclass

import numpy as np

from ._generated import guide as _guide


@dataclass(frozen=True)
class CrankState:
    """Rigid-body state at one or many instants (arrays broadcast like t)."""

    theta: np.ndarray
    thetad: np.ndarray
    phi: np.ndarray
    phid: np.ndarray
    phidd: np.ndarray
    vector: np.ndarray = None      # (..., 6): (a, theta, thetad, phi, phid, phidd), the kernels' kin

    def as_args(self):
        """(theta, thetad, phi, phid, phidd)."""
        return self.theta, self.thetad, self.phi, self.phid, self.phidd


def crank_state(a, omega, t, offset=0.0):
    """Kinematics at time(s) t for crank ratio a (= a*), crank speed omega (= Omega*), guide offset."""
    t = np.asarray(t, dtype=float)
    kin = _guide.crank_kinematics(t, float(omega), float(a), float(offset))
    return CrankState(*(kin[..., k] for k in range(1, 6)), vector=kin)


def slider_position(a, theta, offset=0.0):
    """X co-ordinate of the rigid slider, a cos theta + L cos phi (L = 1)."""
    theta = np.asarray(theta, dtype=float)
    return _guide.slider_rigid_position(theta, 1.0, float(a), float(offset))
