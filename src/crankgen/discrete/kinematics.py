"""Rigid-body kinematics of a case from the generated kernels (derive/motions.py, derive/guides.py):
the crank motion gives theta, thetad, thetadd at time t; the guide's closure gives the rod angle
phi and the guide co-ordinate beta of the rigid end with their rates; the end map gives the rod
end's (u, v) from the reduced end co-ordinate s.  Straight guide: sin phi = (a* sin theta - e)/L;
circle: the four-bar's closure (derive/guides.py).
"""

import functools
from dataclasses import dataclass

import numpy as np

from ..declaration import schema
from .._generated import kinematics as _kinematics
from ..errors import ParameterError
from .mesh import rocker_of

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


def crank_angle(case, t, chunk=4096):
    """The crank angle theta(t) of a case's prescribed motion at the times t (1-d), computed a chunk
    at a time: a long run's angles cost 8 bytes a step, not its whole kinematic state."""
    t = np.asarray(t, dtype=float)
    motion = getattr(_kinematics, f"motion_{case.motion_record.name}")
    params = case.kinematic_parameters
    theta = np.empty(t.shape)
    for k in range(0, t.size, chunk):
        theta[k:k + chunk] = motion(t[k:k + chunk], params)[..., 0]
    return theta


def crank_state(case, crank):
    """CrankState of the case's guide for crank (..., 3) = (theta, thetad, thetadd) given (a driven
    crank's, from the state's crank co-ordinate)."""
    crank = np.asarray(crank, dtype=float)
    params = np.broadcast_to(case.kinematic_parameters, crank.shape[:-1] + (len(schema.KINEMATIC_PARAMETERS),))
    return _state(getattr(_kinematics, f"guide_{case.guide_record.name}")(crank, params))


def coordinates_start(case):
    """(values, rates) (m,) each of the declared co-ordinates of the case's motion at t = 0 (the
    generated start_<motion>; empty for a prescribed motion)."""
    m = len(case.motion_record.coordinates)
    if not m:
        return np.zeros(0), np.zeros(0)
    z0 = np.asarray(getattr(_kinematics, f"start_{case.motion_record.name}")(case.kinematic_parameters),
                    dtype=float).reshape(2, m)
    return z0[0].copy(), z0[1].copy()


def state_crank(case, x, v, a):
    """(..., 3) (theta, thetad, thetadd) of states (x, v, a) (..., N) of a driven motion: its crank
    co-ordinate's, the last m entries of the DOF map's state holding the co-ordinates."""
    coords = case.motion_record.coordinates
    j = next(k for k, c in enumerate(coords) if c.crank) - len(coords)
    return np.stack([np.asarray(x)[..., j], np.asarray(v)[..., j], np.asarray(a)[..., j]], axis=-1)


def frozen_state(case, theta):
    """Kinematics of a case's guide with the crank at angle(s) theta turning at the constant speed
    of the case's crank speed parameter (thetadd = 0): the mechanism frozen at those angles
    (crankgen.modes)."""
    theta = np.asarray(theta, dtype=float)
    speed = float(getattr(case, schema.CRANK_SPEED))
    crank = np.stack(np.broadcast_arrays(theta, speed, 0.0), axis=-1)
    params = np.broadcast_to(case.kinematic_parameters, theta.shape + (len(schema.KINEMATIC_PARAMETERS),))
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
    start = fn(0.0, params)[0]
    target = start + 2 * np.pi * revolutions
    hi = step_period(case) * max(revolutions, 1.0)
    for _ in range(64):
        if fn(hi, params)[0] >= target:
            break
        hi *= 2.0
    else:          # the crank comes to rest (a run-down) before it has turned that far
        turned = (fn(hi, params)[0] - start) / (2 * np.pi)
        speed = schema.PARAMETERS[schema.CRANK_SPEED]
        raise ParameterError(f"revolutions: the crank turns only {turned:.6g} revolutions in all (its "
                             f"{case.motion_record.name} motion ends at rest, {speed.name} = "
                             f"{getattr(case, speed.name):g}); ask for at most {turned:.6g} revolutions, "
                             f"or give the motion a final speed {speed.name} > 0")
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


@functools.lru_cache(maxsize=None)
def _arguments(name):
    """The argument names of the kinematics kernel `name`."""
    import inspect
    return tuple(inspect.signature(getattr(_kinematics, name)).parameters)


def call(name, case, **inputs):
    """The kinematics kernel `name` of a case: its arguments by name, the kinematic parameter vector
    for `params`, a parameter's value for an argument named after it (the end scale's eps), the
    given `inputs` for the others."""
    kernel = getattr(_kinematics, name)
    vector = case.parameter_vector
    args = []
    for arg in _arguments(name):
        if arg == "params":
            args.append(case.kinematic_parameters)
        elif arg in inputs:
            args.append(inputs[arg])
        else:
            args.append(float(vector[schema.PARAMETER_SYMBOLS.index(arg)]))
    return kernel(*args)


def end_map(case, kin, s, sd=0.0, sdd=0.0):
    """The end map (..., 8, 2) (rows schema.END_MAP_ROWS) at kin and (s, sd, sdd); with a flexible
    rocker, the map of its tip (end_map_<guide>_flexible, (..., 15, 2): constraints.map_rows(2)) at
    s, sd, sdd (..., 2), the rocker tip's (u_r, v_r) and their rates."""
    if rocker_of(case)[0]:
        s = np.asarray(s, float)
        sd, sdd = (np.broadcast_to(np.asarray(x, float), s.shape) for x in (sd, sdd))
        send = np.concatenate([s, sd, sdd], axis=-1)
        return getattr(_kinematics, f"end_map_{case.guide_record.name}_flexible")(send, kin, case.kinematic_parameters)
    send = np.stack(np.broadcast_arrays(np.asarray(s, float), sd, sdd), axis=-1)
    return getattr(_kinematics, f"end_map_{case.guide_record.name}")(send, kin, case.kinematic_parameters)


def rigid_end(case, kin):
    """(..., 2): (X, Y) of the rigid mechanism's end point."""
    return getattr(_kinematics, f"rigid_end_{case.guide_record.name}")(kin, case.kinematic_parameters)


# The one rule for the time step of a crank motion (every analysis: simulate, steady states,
# sweeps, continuation, Poincare sections): a step may turn the crank by at most a quarter turn
# (what a constant speed allows at its fewest steps per revolution, 4), and change the crank speed
# by at most a quarter of the motion's top speed.  Coarser steps sample the crank's motion, which
# drives the rod, too coarsely to be a result; they are refused, naming the steps_per_rev needed.
MAX_TURN_PER_STEP = np.pi / 2
MAX_SPEED_CHANGE_PER_STEP = 0.25         # of the motion's top speed
_SAMPLES = 1024


def crank_step_extremes(case, t_end):
    """(largest crank speed, largest |crank acceleration|) of the case's motion over [0, t_end]
    (one period for a periodic motion), sampled finely over the run and over its first 64 step
    periods (a run-up's ramp)."""
    T = period(case)
    span = T if T is not None else max(float(t_end), 0.0)
    early = min(span, 64 * step_period(case))
    t = np.concatenate([np.linspace(0.0, span, _SAMPLES + 1), np.linspace(0.0, early, _SAMPLES + 1)])
    crank = getattr(_kinematics, f"motion_{case.motion_record.name}")(t, case.kinematic_parameters)
    return float(np.max(np.abs(crank[..., 1]))), float(np.max(np.abs(crank[..., 2])))


def check_crank_steps(case, dt, t_end=None, where=""):
    """Refuse (ParameterError, naming the steps_per_rev needed) a time step dt that turns the crank
    by more than MAX_TURN_PER_STEP or changes its speed by more than MAX_SPEED_CHANGE_PER_STEP of
    its top speed, anywhere over the run (t_end; default one period or step period).  A motor-driven
    crank has no prescribed law to check: its step is the no-load revolution's (crankgen.discrete.motor)."""
    if case.motion_record.driven:
        return
    if t_end is None:
        t_end = period(case) or step_period(case)
    speed, acceleration = crank_step_extremes(case, t_end)
    turn, change = speed * dt, acceleration * dt
    excess = max(turn / MAX_TURN_PER_STEP, change / (MAX_SPEED_CHANGE_PER_STEP * speed) if speed > 0 else 0.0)
    if excess > 1.0 + 1e-12:
        need = int(np.ceil(case.steps_per_rev * excess * (1 - 1e-12)))
        what = (f"turns the crank by up to {turn:.3g} rad (at most pi/2 per step)" if
                turn / MAX_TURN_PER_STEP >= change / (MAX_SPEED_CHANGE_PER_STEP * speed) else
                f"changes the crank speed by up to {change:.3g} ({change / speed:.0%} of its top speed "
                f"{speed:.3g}; at most 25 % per step)")
        raise ParameterError(f"{where}steps_per_rev = {case.steps_per_rev} is too coarse for the "
                             f"{case.motion_record.name} crank motion: one step of dt* = {dt:.3g} {what}; use "
                             f"steps_per_rev >= {need}")
