"""
The animation, as a strip of frames
===================================

``result.animate("run.gif")`` writes the deforming mechanism in the inertial frame, its elastic
deflection magnified (:doc:`/howto/animation`). Here six frames of one steady revolution at
Omega* = 0.8, drawn side by side from the same frames the animation is made of
(``crankgen.plots.animation.Frames``).

The animation itself::

    crankgen animate --steady --omega 0.8 --out movie          # movie/mechanism.gif
"""

import matplotlib.pyplot as plt
import numpy as np

import crankgen
from crankgen.plots.animation import Frames

st = crankgen.steady_state(crankgen.Mechanism(), omega=0.8, n_elements=4)
frames = Frames(st, frames=7)
fig, axes = plt.subplots(3, 2, figsize=(10, 4.2), layout="constrained", sharex=True, sharey=True)
for k, ax in enumerate(axes.flat):
    ax.plot(frames.guide_curve[:, 0], frames.guide_curve[:, 1], color="0.6", lw=1)
    ax.plot([0, frames.pin[k, 0]], [0, frames.pin[k, 1]], color="0.2", lw=3)
    ax.plot(frames.rod[k, :, 0], frames.rod[k, :, 1], color="C0", lw=2)
    ax.plot([frames.end[k, 0]], [frames.end[k, 1]], "s", color="C3", ms=8)
    ax.set_aspect("equal")
    ax.set_title(f"crank angle {np.degrees(frames.theta[k] - frames.theta[0]):.0f} deg", fontsize=9)
fig.suptitle(f"one steady revolution, Omega* = 0.8 (deflections magnified {frames.magnification:g}x; X and Y in L)")
print("frames:", len(frames), "| magnification:", frames.magnification)
