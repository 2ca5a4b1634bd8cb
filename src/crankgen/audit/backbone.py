"""Backbone curve of the free rod: first bending frequency against vibration amplitude (audit §5).

The crank stands still (Omega* -> 0, so phi = 0 and the slider end moves along the rod axis) and
damping is off.  The rod starts at rest in its first bending mode v = A sin(pi x) (psi = v_x, no
axial displacement); the frequency is measured from the zero crossings of v*(1/2) over several
periods and corrected for the trapezoidal rule's period elongation, w = (2/dt) tan(w_h dt / 2).
In crankgen's units the small-amplitude value is omega_b = 1 (rotary inertia: 1/sqrt(1 + pi^2 eps^2)).
"""

import math
from dataclasses import dataclass

import numpy as np

from .. import engine
from ..declaration import schema
from ..declaration.cases import Case
from ..discrete.mesh import Mesh, PSI, V

STANDSTILL = 1e-9       # Omega* of a crank that does not move over the run


@dataclass(frozen=True)
class BackbonePoint:
    case: Case
    amplitude: float        # initial v*(1/2)
    frequency: float        # omega / omega_b (nan if the run failed)
    status: str


def mode_state(mesh, amplitude):
    """Reduced displacement vector of v = amplitude sin(pi x), psi = v_x (units of L)."""
    d = np.zeros(mesh.n_dofs)
    for node in range(mesh.n_elements + 1):
        x = node * mesh.length
        for comp, value in ((V, amplitude * math.sin(math.pi * x)),
                            (PSI, amplitude * math.pi * math.cos(math.pi * x))):
            i = mesh.reduced_index(node, comp)
            if i is not None:
                d[i] = value
    return d


def _frequency(t, y):
    idx = np.where(np.sign(y[:-1]) * np.sign(y[1:]) < 0)[0]
    if len(idx) < 4:
        return math.nan
    tz = t[idx] - y[idx] * (t[idx + 1] - t[idx]) / (y[idx + 1] - y[idx])
    return math.pi / float(np.mean(np.diff(tz)))


def backbone(amplitudes, eps=0.01, ms=0.5, approach="A", formulation="lagrange",
             membrane="averaged", n_elements=8, steps_per_period=200, periods=8):
    """Frequency (units of omega_b) of free vibrations of initial mid-span amplitude v* (list), with
    the trapezoidal rule (rho_inf = 1: no numerical damping, and its frequency warping, undone
    below by 2/dt tan(omega dt / 2))."""
    cases = [Case(eps=eps, ms=ms, mu=0.0, omega=STANDSTILL, approach=approach, formulation=formulation,
                  damping="kelvin-voigt", membrane=membrane, n_elements=n_elements, rho_inf=1.0)
             for _ in amplitudes]
    dt = 2 * math.pi / steps_per_period
    batch = engine.Batch(cases, dt=dt)
    mesh = Mesh(n_elements)
    D0 = np.stack([mode_state(mesh, a * eps) for a in amplitudes])
    res = engine.march(batch, steps_per_period * periods, D0=D0)
    t = dt * np.arange(steps_per_period * periods + 1)
    points = []
    for i, (case, amp) in enumerate(zip(cases, amplitudes)):
        if res.status[i] != engine.OK:
            points.append(BackbonePoint(case, amp, math.nan, engine.STATUS_TEXT[int(res.status[i])]))
            continue
        w_h = _frequency(t, res.y[i, :, schema.ENGINE_OUTPUTS.index("v_mid")])
        if not math.isfinite(w_h):
            points.append(BackbonePoint(case, amp, math.nan, "no oscillation"))
        elif w_h * dt > 2 * math.pi / 8:      # fewer than 8 steps per period: not resolved
            points.append(BackbonePoint(case, amp, math.nan, "too fast for the time step"))
        else:
            points.append(BackbonePoint(case, amp, 2 / dt * math.tan(w_h * dt / 2), "ok"))
    return points
