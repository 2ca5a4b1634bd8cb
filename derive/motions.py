"""Stage 2b: the crank's prescribed motion theta(t), its rate and its angular acceleration.

Each motion is declared by closed forms in the time t and its parameters: theta(t), thetad and
thetadd (which may use theta, computed first), and, when the motion is periodic in the crank angle,
the time of one crank revolution (`period`): then theta(t + period) = theta(t) + 2 pi, the time
step of a run is period / steps_per_rev and periodic states exist.  `check()` verifies at build
time that thetad and thetadd are the time derivatives of theta (by differentiation, or numerically
where the closed form is not differentiated symbolically).

- constant: theta = Omega t (the paper's crank).
- runup: the speed rises from Omega0 to Omega over `ramp` crank revolutions along the quintic
  smooth step s(x) = 10 x^3 - 15 x^4 + 6 x^5 of x = t / T (speed and acceleration continuous),
  T = 4 pi ramp / (Omega0 + Omega) so that theta(T) = 2 pi ramp, and stays at Omega afterwards.
- fluctuation: thetad = Omega (1 + k sin(j theta)) (a flywheel's cyclic irregularity of relative
  amplitude k, |k| < 1, and order j, a positive integer).  With m = sqrt(1 - k^2) the rate law
  integrates in closed form, tan(j theta / 2) = m tan(psi) - k with psi = m j Omega t / 2 +
  atan(k / m); the revolution takes 2 pi / (m Omega).
"""

from dataclasses import dataclass

import sympy as sp

from . import symbols as s


@dataclass(frozen=True)
class Motion:
    name: str
    title: str                  # the runtime's record of this motion (crankgen.Constant, ...)
    parameters: tuple           # the parameter names it reads (derive/model.py PARAMETERS)
    theta: sp.Expr              # theta(t)
    thetad: sp.Expr             # in t and theta
    thetadd: sp.Expr            # in t, theta and thetad
    period: object              # time of one crank revolution (None: not periodic)
    step_period: sp.Expr        # the time that steps_per_rev steps divide (period, or the fastest revolution)
    doc: str
    aliases: tuple = ()         # keyword arguments of the runtime record standing for parameters


def _wrap(z):
    """z shifted by a multiple of 2 pi into [-pi, pi)."""
    return z - 2 * sp.pi * sp.floor(z / (2 * sp.pi) + sp.Rational(1, 2))


def constant():
    return Motion("constant", "Constant", ("omega",), s.omega * s.t, s.omega, sp.Integer(0),
                  2 * sp.pi / s.omega, 2 * sp.pi / s.omega,
                  "constant crank speed Omega*: theta = Omega* t")


def runup():
    T = 4 * sp.pi * s.ramp / (s.omega0 + s.omega)
    x = s.t / T
    step = 10 * x**3 - 15 * x**4 + 6 * x**5
    step_integral = sp.Rational(5, 2) * x**4 - 3 * x**5 + x**6
    dstep = sp.diff(step, s.t)
    during = s.t < T
    theta = sp.Piecewise((s.omega0 * s.t + (s.omega - s.omega0) * T * step_integral, during),
                         (2 * sp.pi * s.ramp + s.omega * (s.t - T), True))
    thetad = sp.Piecewise((s.omega0 + (s.omega - s.omega0) * step, during), (s.omega, True))
    thetadd = sp.Piecewise(((s.omega - s.omega0) * dstep, during), (0, True))
    return Motion("runup", "RunUp", ("omega0", "omega", "ramp"), theta, thetad, thetadd, None,
                  4 * sp.pi / (s.omega0 + s.omega + sp.Abs(s.omega - s.omega0)),   # 2 pi / max
                  "run-up: the crank speed rises smoothly (quintic smooth step in time) from Omega0 "
                  "to Omega* over `ramp` revolutions, then stays at Omega*",
                  (("start", ("omega0",)), ("stop", ("omega",)), ("revolutions", ("ramp",))))


def fluctuation():
    m = sp.sqrt(1 - s.k_fl**2)
    c0 = sp.atan(s.k_fl / m)
    psi = m * s.j_fl * s.omega * s.t / 2 + c0
    chi = sp.atan2(m * sp.sin(psi) - s.k_fl * sp.cos(psi), sp.cos(psi))    # j theta / 2 mod 2 pi
    half = (psi - c0) + _wrap(chi - (psi - c0))                           # unwrapped j theta / 2
    theta = 2 * half / s.j_fl
    thetad = s.omega * (1 + s.k_fl * sp.sin(s.j_fl * s.theta))
    thetadd = s.omega * s.k_fl * s.j_fl * sp.cos(s.j_fl * s.theta) * s.thetad
    period = 2 * sp.pi / (m * s.omega)
    return Motion("fluctuation", "Fluctuation", ("omega", "fluctuation", "order"), theta, thetad, thetadd, period,
                  period, "cyclic speed fluctuation: thetad = Omega* (1 + k sin(j theta)), |k| < 1, "
                          "j a positive integer", (("amplitude", ("fluctuation",)),))


MOTIONS = (constant(), runup(), fluctuation())


def rates(motion):
    """(theta, thetad, thetadd) as expressions in t and the parameters only."""
    theta = motion.theta
    thetad = motion.thetad.subs(s.theta, theta)
    thetadd = motion.thetadd.subs({s.thetad: motion.thetad}).subs(s.theta, theta)
    return theta, thetad, thetadd


def check(motion, samples=((0.3, 0.2, 1.1, 3.0, 0.4, 2), (1.7, 1.2, 0.3, 2.0, -0.6, 1),
                           (40.0, 0.5, 0.9, 5.0, 0.7, 3))):
    """Verify thetad = d theta / dt and thetadd = d thetad / dt (central differences at a few
    times and parameter values) and theta(period) = 2 pi; raises AssertionError."""
    theta, thetad, thetadd = rates(motion)
    for t0, om0, om, ramp, k, j in samples:
        values = {s.omega0: om0, s.omega: om, s.ramp: ramp, s.k_fl: k, s.j_fl: j}
        f = [sp.lambdify(s.t, e.subs(values), "mpmath") for e in (theta, thetad, thetadd)]
        h = 1e-6
        for lower, upper in ((0, 1), (1, 2)):
            fd = (f[lower](t0 + h) - f[lower](t0 - h)) / (2 * h)
            assert abs(fd - f[upper](t0)) < 1e-5 * (1 + abs(f[upper](t0))), (motion.name, t0, lower)
        if motion.period is not None:
            T = float(motion.period.subs(values))
            assert abs(float(f[0](T)) - 2 * float(sp.pi)) < 1e-9, (motion.name, "period")
    return True
