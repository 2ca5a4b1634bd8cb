"""The time-integration scheme: Newmark's trapezoidal rule and the generalized-alpha method.

Generalized-alpha (Chung & Hulbert, J. Appl. Mech. 60, 1993) in the form of Arnold & Bruls
(Multibody Syst. Dyn. 18, 2007): the equations of motion hold exactly at every step,
R(t_{n+1}, d_{n+1}, v_{n+1}, qdd_{n+1}) = 0, and an algorithmic acceleration a, a second state
beside the true acceleration qdd, carries the scheme's memory:

    (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) qdd_{n+1} + alpha_f qdd_n
    d_{n+1} = d_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
    v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}

with Chung & Hulbert's parameters from the spectral radius at infinite frequency rho_inf in [0, 1]:

    alpha_m = (2 rho_inf - 1) / (rho_inf + 1),   alpha_f = rho_inf / (rho_inf + 1),
    gamma = 1/2 + alpha_f - alpha_m,   beta = (gamma + 1/2)^2 / 4.

Eliminating a_{n+1}, the step's unknown is qdd_{n+1}: d_{n+1} = dp + cd qdd_{n+1} and
v_{n+1} = vp + cv qdd_{n+1} with cd = beta' h^2, cv = gamma' h, beta' = beta r, gamma' = gamma r,
r = (1 - alpha_f) / (1 - alpha_m), so Newton iterates on qdd_{n+1} with the iteration matrix
M + cv C + cd K of eq. (37), as Newmark's does.  On a linear problem this is Chung & Hulbert's
method exactly (the two forms give the same d, v; a of Arnold & Bruls is Chung & Hulbert's
acceleration); on a non-linear one the forces are evaluated where the equations hold, at t_{n+1},
so the reactions and every output are consistent with the state (Chung & Hulbert's original
form balances forces at the intermediate times t_{n+1-alpha_f}, t_{n+1-alpha_m}, where a
non-linear residual has no unique meaning).

rho_inf = 1 is the trapezoidal rule (Newmark beta = 1/4, gamma = 1/2; alpha_m = alpha_f = 1/2
gives a = qdd at every step from a consistent start, the same d, v): crankgen runs it as Newmark
(alpha_m = alpha_f = 0), whose state needs no algorithmic acceleration, bit for bit the former
scheme.  rho_inf < 1 damps what a step cannot resolve: every mode's step factor tends to -rho_inf
as omega h -> infinity (and to -(1 - gamma)/gamma for a mode whose damping dominates), while
second-order accuracy and a low-frequency dissipation of order (omega h)^3 are kept.  The price of
rho_inf < 1 in shooting: the revolution map acts on (d, v, a), 3N numbers, and has N algorithmic
roots besides the mechanism's 2N (per step -alpha_m / (1 - alpha_m) at low frequency, at most
rho_inf in modulus): a continuation's branches report the 2N largest.
"""

import math
from dataclasses import dataclass

import numpy as np

from .. import notices
from ..notices import StepWarning  # noqa: F401  (re-exported)
from ..declaration.validation import in_range

NEWMARK_BETA, NEWMARK_GAMMA = 0.25, 0.5


@dataclass(frozen=True)
class Coefficients:
    """The scheme's parameters: alpha_m, alpha_f, beta, gamma (Newmark: alpha_m = alpha_f = 0)."""

    alpha_m: float = 0.0
    alpha_f: float = 0.0
    beta: float = NEWMARK_BETA
    gamma: float = NEWMARK_GAMMA

    @property
    def generalized(self):
        """True when the scheme carries an algorithmic acceleration (alpha_m or alpha_f non-zero)."""
        return self.alpha_m != 0.0 or self.alpha_f != 0.0

    @property
    def ratio(self):
        """r = (1 - alpha_f) / (1 - alpha_m): d a_{n+1} / d qdd_{n+1}."""
        return (1.0 - self.alpha_f) / (1.0 - self.alpha_m)

    def as_array(self):
        """(beta, gamma, alpha_m, alpha_f): the row the compiled engine reads."""
        return np.array([self.beta, self.gamma, self.alpha_m, self.alpha_f])


# The first step of a generalized-alpha run from a state without algorithmic accelerations (a start:
# from rest or from an initial state): Newmark's beta = 1/2, gamma = 1, which damps every mode it
# cannot resolve at once (step factor 0 at omega h -> infinity) and whose O(h^2) error, taken once,
# keeps the run second order; a = qdd after it.
STARTER = Coefficients(0.0, 0.0, 0.5, 1.0)


def coefficients(rho_inf):
    """The scheme of spectral radius rho_inf in [0, 1]: Chung & Hulbert's parameters, or Newmark's
    trapezoidal rule for rho_inf = 1."""
    rho = in_range("rho_inf", rho_inf, 0.0, 1.0)
    if rho == 1.0:
        return Coefficients()
    return chung_hulbert(rho)


def chung_hulbert(rho):
    """Chung & Hulbert's parameters for spectral radius rho (rho = 1 included: alpha_m = alpha_f = 1/2)."""
    alpha_m = (2.0 * rho - 1.0) / (rho + 1.0)
    alpha_f = rho / (rho + 1.0)
    gamma = 0.5 + alpha_f - alpha_m
    beta = 0.25 * (gamma + 0.5) ** 2
    return Coefficients(alpha_m, alpha_f, beta, gamma)


def amplification(coef, omega_h, zeta=0.0):
    """The step's amplification matrix of a linear mode qdd + 2 zeta omega qd + omega^2 q = 0 with
    step h (omega_h = omega h), acting on (q, h qd, h^2 a) (a: the algorithmic acceleration; for
    Newmark the state's third entry is qdd, determined by the other two)."""
    am, af, b, g = coef.alpha_m, coef.alpha_f, coef.beta, coef.gamma
    w2, c = omega_h ** 2, 2.0 * zeta * omega_h
    # unknowns of a step: (q1, v1, x1, a1) with x = h^2 qdd, a = h^2 a, v = h qd; knowns (q0, v0, x0, a0)
    # x1 + c v1 + w2 q1 = 0 and x0 = -(c v0 + w2 q0): qdd at the step before from the equations
    A = np.array([[1.0, 0.0, 0.0, -b], [0.0, 1.0, 0.0, -g], [w2, c, 1.0, 0.0],
                  [0.0, 0.0, -(1.0 - af), 1.0 - am]])
    # right-hand side per known (q0, v0, a0), with x0 = -(c v0 + w2 q0)
    B = np.array([[1.0, 1.0, 0.5 - b], [0.0, 1.0, 1.0 - g], [0.0, 0.0, 0.0],
                  [-af * w2, -af * c, -am]])
    step = np.linalg.solve(A, B)
    return step[[0, 1, 3], :]


def spectral_radius(coef, omega_h, zeta=0.0):
    """Largest modulus of the step's amplification of a linear mode (amplification)."""
    return float(np.max(np.abs(np.linalg.eigvals(amplification(coef, omega_h, zeta)))))


def label(rho_inf):
    """The scheme in a few words, for the command line's lines."""
    return ("Newmark's trapezoidal rule" if float(rho_inf) == 1.0
            else f"generalized-alpha (rho_inf = {float(rho_inf):g})")


def first_axial_frequency(eps, ms):
    """The rod's first axial natural frequency in units of omega_b: a uniform rod pinned at A and
    carrying the end mass ms* at B, lambda tan(lambda) = 1/ms*, omega = lambda sqrt(EA/rhoA)/L
    = lambda / (pi^2 eps) (the guide's angle to the rod is not counted; without an end mass,
    lambda = pi/2)."""
    if ms <= 0.0:
        lam = 0.5 * math.pi
    else:
        lo, hi = 0.0, 0.5 * math.pi
        for _ in range(100):                     # lambda tan(lambda) increases on (0, pi/2)
            mid = 0.5 * (lo + hi)
            if mid * math.tan(mid) < 1.0 / ms:
                lo = mid
            else:
                hi = mid
        lam = 0.5 * (lo + hi)
    return lam / (math.pi ** 2 * eps)


# a step-to-step oscillation that keeps more than this fraction of itself over a crank revolution
# counts as undamped (the forces then alternate from step to step)
SURVIVING = 0.01


def unresolved_modes(rho_inf, dt, steps_per_rev, eps, ms, mu):
    """[(name, omega, omega dt, kept)] of the rod's first bending and first axial modes that the step
    leaves unresolved and undamped: the scheme's step factor for that mode (a linear mode with the
    damping ratio mu omega / 2 of both damping models' linear part) has a root with a negative real
    part, a step-to-step oscillation, that keeps more than SURVIVING of itself over steps_per_rev
    steps (kept: that fraction).  Frequencies in units of omega_b (the first bending mode is 1)."""
    coef = coefficients(rho_inf)
    out = []
    for name, omega in (("bending", 1.0), ("axial", first_axial_frequency(eps, ms))):
        zeta = 0.5 * mu * omega
        mu_step = np.linalg.eigvals(amplification(coef, omega * dt, zeta))
        alternating = mu_step[mu_step.real < 0.0]
        if alternating.size:
            kept = float(np.max(np.abs(alternating))) ** steps_per_rev
            if kept > SURVIVING:
                out.append((name, omega, omega * dt, kept))
    return out


def step_warning(case, omega_b=None):
    """The one-line warning of a case whose step leaves the rod's first bending or axial mode
    unresolved and undamped (unresolved_modes), or None.  omega_b: the unit of frequency in rad/s
    (an SI run's), to state the modes' frequencies in rad/s too."""
    from . import kinematics
    from ..errors import ParameterError
    try:
        dt = kinematics.step_period(case) / case.steps_per_rev
    except ParameterError:                      # a crank at rest: the run says why
        return None
    modes = unresolved_modes(case.rho_inf, dt, case.steps_per_rev, case.eps, case.ms, case.mu)
    if not modes:
        return None
    names = " and ".join(m[0] for m in modes)
    si = (lambda w: f" = {w * omega_b:.3g} rad/s") if omega_b else (lambda w: "")
    shown = "; ".join(f"{m[0]}: omega = {m[1]:.3g} omega_b{si(m[1])}, omega dt = {m[2]:.3g}, "
                      f"{100 * min(m[3], 1.0):.0f} % kept over a revolution" for m in modes)
    scheme = "Newmark's trapezoidal rule" if case.rho_inf == 1.0 else f"rho_inf = {case.rho_inf:g}"
    advice = ("rho_inf = 0.8 (the consistent model's default) or less" if case.rho_inf > 0.8
              else f"a rho_inf below {case.rho_inf:g}")
    return (f"the step leaves the rod's first {names} mode{'s' if len(modes) > 1 else ''} unresolved and "
            f"{scheme} does not damp the step-to-step oscillation ({shown}): accelerations and forces "
            f"alternate from step to step; use {advice}, more steps per revolution, or damping")


def warn_steps(cases, stacklevel=3, omega_b=None):
    """Warn once (StepWarning) when the step of any of the cases leaves a mode unresolved and
    undamped (step_warning): the first such case, and how many more.  Silent inside
    crankgen.notices.quiet()."""
    texts = [t for t in (step_warning(c, omega_b) for c in cases) if t is not None]
    if texts:
        more = f" (and {len(texts) - 1} more case(s))" if len(texts) > 1 else ""
        notices.warn(StepWarning, texts[0] + more, stacklevel=stacklevel)
