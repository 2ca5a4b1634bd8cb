"""What sizes a motor: its torque T_m(thetad) along a run, and the peak, RMS and mean power of a
run's motor torque (the duty a motor is rated by), in crankgen's units."""

import math

import numpy as np

from ..declaration import schema, torque_curve


def motor_torque(case, thetad):
    """T_m(thetad) of a motor-driven case at crank speeds thetad: T_stall f(thetad / Omega_nl) on its
    curve (`torque_curve.of`)."""
    curve, stall, no_load, _ = torque_curve.of(case)
    return stall * torque_curve.evaluate(curve, np.asarray(thetad, dtype=float) / no_load)[0]


def _time_mean(t, values):
    """The time mean of values at the times t by the trapezoidal rule."""
    return float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(t)) / (t[-1] - t[0]))


def duty_units():
    """{quantity of `duty`: its units}: the output torque's, and a torque times a crank speed."""
    torque = schema.OUTPUTS["torque"].units
    return {"peak_motor_torque": torque, "rms_motor_torque": torque, "mean_motor_power": "rhoA L^3 omega_b^3"}


def duty(case, t, thetad):
    """What sizes a motor over a run of a motor-driven case, its crank speeds thetad at the times t:
    {peak_motor_torque: T_m of largest magnitude, signed; rms_motor_torque: sqrt(<T_m^2>), what a
    thermal rating is sized by; mean_motor_power: <T_m thetad>}, <.> the time mean by the
    trapezoidal rule on the steps."""
    t = np.asarray(t, dtype=float)
    speed = np.asarray(thetad, dtype=float)
    torque = motor_torque(case, speed)
    k = int(np.argmax(np.abs(torque)))
    return {"peak_motor_torque": float(torque[k]), "rms_motor_torque": math.sqrt(_time_mean(t, torque ** 2)),
            "mean_motor_power": _time_mean(t, torque * speed)}
