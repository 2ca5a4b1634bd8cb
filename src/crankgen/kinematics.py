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
    crank = getattr(_kinematics, f"motion_{case.motion_record.name}")(np.asarray(t, dtype=float), params)
    return _state(getattr(_kinematics, f"guide_{case.guide_record.name}")(crank, params))


def _finite_time(case, value):
    if not (np.isfinite(value) and value > 0):
        speed = schema.PARAMETERS[schema.CRANK_SPEED]
        raise ParameterError(f"{speed.label} must be > 0 for a run measured in crank revolutions, got "
                             f"{getattr(case, speed.name):g} (a crank at rest does not turn)")
    return value


def step_period(case):
    """The time steps_per_rev steps divide (a revolution, or a run-up's fastest one)."""
    with np.errstate(divide="ignore"):
        value = float(getattr(_kinematics, f"step_period_{case.motion_record.name}")(case.kinematic_parameters))
    return _finite_time(case, value)


def period(case):
    """Time of one crank revolution of a periodic crank motion (None for a run-up)."""
    if not case.periodic:
        return None
    with np.errstate(divide="ignore"):
        value = float(getattr(_kinematics, f"period_{case.motion_record.name}")(case.kinematic_parameters))
    return _finite_time(case, value)


def time_of_revolutions(case, revolutions):
    """The time at which the crank has turned `revolutions` revolutions (theta = theta0 + 2 pi
    revolutions): exact for a periodic motion, by bisection on the monotone theta(t) otherwise."""
    T = period(case)
    if T is not None:
        return T * revolutions
    fn = getattr(_kinematics, f"motion_{case.motion_record.name}")
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
    return float(call(f"end_scale_{case.guide_record.name}", case))


def call(name, case, **inputs):
    """The kinematics kernel `name` of a case: its arguments by name, the kinematic parameter vector
    for `params`, a parameter's value for an argument named after it (the end scale's eps), the
    given `inputs` for the others."""
    import inspect
    kernel = getattr(_kinematics, name)
    vector = case.parameter_vector
    args = []
    for arg in inspect.signature(kernel).parameters:
        if arg == "params":
            args.append(case.kinematic_parameters)
        elif arg in inputs:
            args.append(inputs[arg])
        else:
            args.append(float(vector[schema.PARAMETER_SYMBOLS.index(arg)]))
    return kernel(*args)


def end_map(case, kin, s, sd=0.0, sdd=0.0):
    """The end map (..., 8, 2) (rows schema.END_MAP_ROWS) at kin and (s, sd, sdd)."""
    send = np.stack(np.broadcast_arrays(np.asarray(s, float), sd, sdd), axis=-1)
    return getattr(_kinematics, f"end_map_{case.guide_record.name}")(send, kin, case.kinematic_parameters)


def rigid_end(case, kin):
    """(..., 2): (X, Y) of the rigid mechanism's end point."""
    return getattr(_kinematics, f"rigid_end_{case.guide_record.name}")(kin, case.kinematic_parameters)
