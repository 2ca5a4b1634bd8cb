"""Rigid-body kinematics of a case from the generated kernels (derive/motions.py, derive/guides.py):
the crank motion gives theta, thetad, thetadd at time t; the guide's closure gives the rod angle
phi and the guide co-ordinate beta of the rigid end with their rates; the end map gives the rod
end's (u, v) from the reduced end co-ordinate s.  Straight guide: sin phi = (a* sin theta - e)/L;
circle: the four-bar's closure (derive/guides.py).
"""

from dataclasses import dataclass

import numpy as np

from . import schema
from ._generated import kinematics as _kinematics
from .errors import ParameterError

_K = schema.KIN


@dataclass(frozen=True)
class CrankState:
    """Rigid-body state at one or many instants (arrays broadcast like t)."""

    theta: np.ndarray
    thetad: np.ndarray
    phi: np.ndarray
    phid: np.ndarray
    phidd: np.ndarray
    vector: np.ndarray = None      # (..., len(schema.KINEMATICS)): the kernels' kin

    @property
    def thetadd(self):
        return self.vector[..., _K["thetadd"]]

    @property
    def beta(self):
        return self.vector[..., _K["beta"]]

    def as_args(self):
        """(theta, thetad, phi, phid, phidd)."""
        return self.theta, self.thetad, self.phi, self.phid, self.phidd


def _state(kin):
    return CrankState(*(kin[..., _K[n]] for n in ("theta", "thetad", "phi", "phid", "phidd")), vector=kin)


def case_state(case, t):
    """Kinematics of a case (its guide, crank motion and their parameters) at time(s) t."""
    params = case.kinematic_parameters
    crank = getattr(_kinematics, f"motion_{case.motion}")(np.asarray(t, dtype=float), params)
    return _state(getattr(_kinematics, f"guide_{case.guide}")(crank, params))


def frozen_state(case, theta):
    """Kinematics of a case's guide with the crank at angle(s) theta turning at the constant speed
    case.omega (thetadd = 0): the mechanism frozen at those angles (crankgen.modes)."""
    theta = np.asarray(theta, dtype=float)
    params = np.array(np.broadcast_to(case.kinematic_parameters,
                                      theta.shape + (len(schema.KINEMATIC_PARAMETERS),)))
    params[..., schema.KINEMATIC_PARAMETERS.index("theta0")] = theta
    crank = _kinematics.motion_constant(0.0, params)
    return _state(getattr(_kinematics, f"guide_{case.guide}")(crank, params))


def crank_state(a, omega, t, offset=0.0):
    """Kinematics of the constant-speed slider-crank (line guide) at time(s) t for crank ratio a
    (= a*), crank speed omega (= Omega*) and guide offset."""
    params = np.array([float({"a": a, "omega": omega, "offset": offset}.get(n, schema.PARAMETERS[n].default))
                       for n in schema.KINEMATIC_PARAMETERS])
    crank = _kinematics.motion_constant(np.asarray(t, dtype=float), params)
    return _state(_kinematics.guide_line(crank, params))


def _finite_time(case, value):
    if not (np.isfinite(value) and value > 0):
        raise ParameterError(f"omega (crank speed Omega*) must be > 0 for a run measured in crank "
                             f"revolutions, got {case.omega:g} (a crank at rest does not turn)")
    return value


def step_period(case):
    """The time steps_per_rev steps divide (a revolution, or a run-up's fastest one)."""
    with np.errstate(divide="ignore"):
        value = float(getattr(_kinematics, f"step_period_{case.motion}")(case.kinematic_parameters))
    return _finite_time(case, value)


def period(case):
    """Time of one crank revolution of a periodic crank motion (None for a run-up)."""
    if not schema.MOTIONS[case.motion].periodic:
        return None
    with np.errstate(divide="ignore"):
        value = float(getattr(_kinematics, f"period_{case.motion}")(case.kinematic_parameters))
    return _finite_time(case, value)


def time_of_revolutions(case, revolutions):
    """The time at which the crank has turned `revolutions` revolutions (theta = theta0 + 2 pi
    revolutions): exact for a periodic motion, by bisection on the monotone theta(t) otherwise."""
    T = period(case)
    if T is not None:
        return T * revolutions
    fn = getattr(_kinematics, f"motion_{case.motion}")
    params = case.kinematic_parameters
    target = fn(0.0, params)[0] + 2 * np.pi * revolutions
    hi = step_period(case) * max(revolutions, 1.0)
    while fn(hi, params)[0] < target:
        hi *= 2.0
    lo = 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if fn(mid, params)[0] < target:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-14 * hi:
            break
    return hi


def end_scale(case):
    """Natural size of the end map's reduced co-ordinate (eps^2 on a line)."""
    return float(getattr(_kinematics, f"end_scale_{case.guide}")(case.eps, case.kinematic_parameters))


def end_map(case, kin, s, sd=0.0, sdd=0.0):
    """The end map (..., 8, 2) (rows schema.END_MAP_ROWS) at kin and (s, sd, sdd)."""
    send = np.stack(np.broadcast_arrays(np.asarray(s, float), sd, sdd), axis=-1)
    return getattr(_kinematics, f"end_map_{case.guide}")(send, kin, case.kinematic_parameters)


def rigid_end(case, kin):
    """(..., 2): (X, Y) of the rigid mechanism's end point."""
    return getattr(_kinematics, f"rigid_end_{case.guide}")(kin, case.kinematic_parameters)


def slider_position(a, theta, offset=0.0):
    """X co-ordinate of the rigid slider, a cos theta + L cos phi (L = 1), constant-speed slider-crank."""
    theta = np.asarray(theta, dtype=float)
    kin = crank_state(a, 1.0, theta, offset).vector
    return rigid_end_line(kin, offset)[..., 0]


def rigid_end_line(kin, offset):
    params = np.array([float(offset if n == "offset" else schema.PARAMETERS[n].default)
                       for n in schema.KINEMATIC_PARAMETERS])
    return _kinematics.rigid_end_line(kin, params)
