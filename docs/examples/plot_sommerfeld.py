"""
The Sommerfeld effect: a motor that cannot pass the rod's resonance
===================================================================

A weak motor (stall torque T_stall* = 0.0022 on the linear law, crank inertia J* = 0.05) starts the
default slider-crank from rest. The crank's speed is an unknown here, not prescribed
(:doc:`/howto/motor`): near the rod's resonance (Omega* about 0.93) the motor's torque goes into
the rod's vibration instead of the crank's speed. Below a no-load speed of about 8.7 the crank is
captured there, well below the no-load speed; above it the crank passes the resonance, and what it
does next depends on the rod's period-2 motions beyond it: at 9.5 it settles near a mean speed of
1.13, at 11 it has not settled after three motor time constants (the rod snaps through and
brakes the crank again and again). Four
run-ups from rest, each three motor time constants long, at 2 elements and 40 steps per no-load
revolution; each point is the crank's mean speed over one of its revolutions (2 pi over the
revolution's time).

The full example (about 12 minutes on 2 cores) continues the steady motions in the no-load speed
(the S-shaped curve and its two folds), marches a staircase up and down through the hysteresis,
and adds flywheels of growing inertia::

    .venv/bin/python examples/sommerfeld.py
"""

import warnings

import matplotlib.pyplot as plt
import numpy as np

import crankgen

STALL, J = 0.0022, 0.05
fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
for k, no_load in enumerate((6.5, 8.0, 9.5, 11.0)):
    motor = crankgen.Motor(stall_torque=STALL, no_load_speed=no_load, inertia=J)
    duration = 3 * (J + 0.005) * no_load / STALL            # three motor time constants
    with warnings.catch_warnings():                         # the rod's deflection is beyond the theory
        warnings.simplefilter("ignore")
        run = crankgen.simulate(crank=motor, revolutions=duration * no_load / (2 * np.pi),
                                n_elements=2, steps_per_rev=40)
    turns = np.arange(1, int((run.theta[-1] - run.theta[0]) / (2 * np.pi)) + 1)
    passed = np.interp(run.theta[0] + 2 * np.pi * turns, run.theta, run.t)   # time at each full turn
    mean = 2 * np.pi / np.diff(np.concatenate([[run.t[0]], passed]))
    ax.plot(passed, mean, ".-", ms=2, lw=0.8, color=f"C{k}", label=f"no-load speed {no_load}")
    print(f"no-load speed {no_load:5.1f}: mean crank speed over the last 10 revolutions {np.mean(mean[-10:]):.3f}")
ax.axhspan(0.90, 0.96, color="0.85", zorder=0, label="the rod's resonance")
ax.set_ylim(0, None)
ax.set_xlabel("time t*")
ax.set_ylabel("mean crank speed over each revolution")
ax.set_title("run-ups from rest with a weak motor: captured below, passing above")
ax.legend(loc="lower right", fontsize=8)
