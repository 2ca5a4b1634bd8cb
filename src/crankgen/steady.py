"""Periodic steady state over one crank revolution.

Status values: "periodic" (converged to a response with the crank period), "not-periodic" (no
periodic state with the crank period was reached: sub-harmonic, quasi-periodic or still drifting),
"unstable" (a periodic orbit exists but its monodromy has a multiplier outside the unit circle, so
the physical response does not settle on it), "failed" (the integration failed: see message).
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .cases import Case
from .errors import CrankgenError
from .model import Model
from .newmark import NewmarkSettings, integrate
from .outputs import element_history, end_axial, extension, mid_deflection

STATUSES = ("periodic", "not-periodic", "unstable", "failed")


@dataclass(frozen=True)
class SteadyState:
    """One steady revolution of a case (arrays over steps_per_rev + 1 points, theta from 0 to 2 pi)."""

    case: Case
    status: str
    amplitude: float             # max |v*(1/2)| over the revolution
    half_peak_to_peak: float     # (max v* - min v*) / 2
    periods: int                 # revolutions marched
    iterations: int              # shooting Newton iterations (0 if marching alone converged)
    residual: float              # scaled |x(2 pi) - x(0)| of the returned state
    message: str = ""
    wall_time: float = 0.0
    theta: np.ndarray = field(default=None, repr=False)
    t: np.ndarray = field(default=None, repr=False)
    v_mid: np.ndarray = field(default=None, repr=False)
    u_end: np.ndarray = field(default=None, repr=False)
    extension: np.ndarray = field(default=None, repr=False)

    @property
    def ok(self):
        return self.status == "periodic"

    def row(self):
        """Flat record for tables: the case's parameters and the scalar results."""
        out = self.case.as_dict()
        out.update(status=self.status, amplitude=self.amplitude,
                   half_peak_to_peak=self.half_peak_to_peak, periods=self.periods,
                   iterations=self.iterations, residual=self.residual, wall_time=self.wall_time,
                   message=self.message)
        return out


def _scaled_change(x0, x1, scales):
    return float(np.max(np.abs(x1 - x0) / scales) / (1.0 + np.max(np.abs(x1) / scales)))


def steady_state(mech=None, omega=0.8, approach="A", formulation="lagrange", damping="paper",
                 n_elements=16, steps_per_rev=100, integrator="newton", tol=1e-8,
                 max_revolutions=400, case=None):
    """Periodic response of a case by marching revolution by revolution from zero initial
    conditions until the state at theta = 0 repeats to tol (scaled units)."""
    if case is None:
        from .parameters import Mechanism
        mech = mech if mech is not None else Mechanism()
        case = Case(a=mech.a, eps=mech.eps, ms=mech.ms, mu=mech.mu, omega=omega, approach=approach,
                    formulation=formulation, damping=damping, n_elements=n_elements,
                    steps_per_rev=steps_per_rev, integrator=integrator)
    start = time.perf_counter()
    model = Model.build(case.mechanism, case.omega, case.n_elements, case.formulation,
                        case.approach, case.damping)
    settings = NewmarkSettings(scheme=case.integrator)
    dt = 2 * math.pi / case.omega / case.steps_per_rev
    scales = np.concatenate([model.mesh.dof_scales(case.eps)] * 2)
    d, v = np.zeros(model.n_dofs), np.zeros(model.n_dofs)
    change = math.inf
    hist = None
    try:
        for rev in range(1, max_revolutions + 1):
            hist = integrate(model, d, v, (rev - 1) * case.steps_per_rev * dt, dt,
                             case.steps_per_rev, settings)
            x0, x1 = np.concatenate([d, v]), np.concatenate([hist.d[-1], hist.v[-1]])
            change = _scaled_change(x0, x1, scales)
            d, v = hist.d[-1], hist.v[-1]
            if change < tol:
                break
    except CrankgenError as exc:
        return SteadyState(case, "failed", math.nan, math.nan, rev, 0, math.nan, str(exc),
                           time.perf_counter() - start)
    status = "periodic" if change < tol else "not-periodic"
    kin = model.kinematics(hist.t)
    q = element_history(model, hist.d, kin.phi)
    v_mid = mid_deflection(model, q)
    return SteadyState(
        case, status, float(np.max(np.abs(v_mid))), float((v_mid.max() - v_mid.min()) / 2), rev, 0,
        change, "" if status == "periodic" else f"state still changing by {change:.2e} after {rev} revolutions",
        time.perf_counter() - start, theta=kin.theta - kin.theta[0], t=hist.t,
        v_mid=v_mid, u_end=end_axial(model, q), extension=extension(model, q))


def steady_states(cases, tol=1e-8, max_revolutions=400, progress=None):
    """Steady states of many cases (list in, list out, same order); a failing case is returned with
    status "failed" and its message, it does not stop the others.  progress(done, total) per case."""
    cases = list(cases)
    out = []
    for i, case in enumerate(cases):
        out.append(steady_state(case=case, tol=tol, max_revolutions=max_revolutions))
        if progress is not None:
            progress(i + 1, len(cases))
    return out
