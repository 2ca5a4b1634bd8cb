"""Dimensionless parameters of the mechanism (section 5 of the paper) and their SI origin.

Units used inside crankgen: length L (rod length), mass rho*A*L, time 1/omega_b with
omega_b = (pi/L)^2 sqrt(EI / (rho A)) the lowest bending frequency of the pinned-pinned rod.
In these units rho*A = 1, E*I = 1/pi^4, E*A = 1/(pi^4 eps^2), rho*I = eps^2 (I = A r^2), and the
paper's scaled outputs are  v* = v / eps,  u* = u / eps^2  (v, u in units of L).
"""

import math
from dataclasses import dataclass

from .errors import ParameterError
from .validation import finite_number, in_range


@dataclass(frozen=True)
class Mechanism:
    """Dimensionless slider-crank: a* = a/L, eps = r/L, ms* = m_s/(rho A L), mu* = omega_b mu,
    gravity = (gX, gY) in units of L omega_b^2 (inertial frame: X along the guide towards the
    slider, Y so that the crank pin is at a* (cos theta, sin theta)), and the guide's offset e: the
    slider moves on the line Y = e (units of L).  The crank turns a full revolution only if
    a* + |e| < 1."""

    a: float = 0.1
    eps: float = 0.01
    ms: float = 0.5
    mu: float = 0.5
    gravity: tuple = (0.0, 0.0)
    offset: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "a", in_range("a (crank length a* = a/L)", self.a, 0, 1, True, True))
        object.__setattr__(self, "eps", in_range("eps (slenderness r/L)", self.eps, 0, None, True))
        object.__setattr__(self, "ms", in_range("ms (slider mass ms* = m_s/(rho A L))", self.ms, 0))
        object.__setattr__(self, "mu", in_range("mu (damping mu* = omega_b mu)", self.mu, 0))
        g = self.gravity
        if isinstance(g, (str, bytes)) or not hasattr(g, "__len__") or len(g) != 2:
            raise ParameterError(f"gravity must be a pair (gX, gY) of numbers, got {g!r}")
        object.__setattr__(self, "gravity", tuple(finite_number(f"gravity[{k}]", x) for k, x in enumerate(g)))
        e = finite_number("offset (guide offset e/L)", self.offset)
        if self.a + abs(e) >= 1.0:
            raise ParameterError(
                f"the crank cannot turn a full revolution: a* + |offset| must be below 1 (the rod "
                f"must reach the guide Y = offset at every crank angle), got a* = {self.a:g}, "
                f"offset = {e:g}")
        object.__setattr__(self, "offset", e)

    # Section constants in crankgen's units.
    @property
    def rhoA(self):
        return 1.0

    @property
    def rhoI(self):
        return self.eps**2

    @property
    def EA(self):
        return 1.0 / (math.pi**4 * self.eps**2)

    @property
    def EI(self):
        return 1.0 / math.pi**4

    @classmethod
    def from_si(cls, *, L, a, E, rho, A, I, slider_mass, crank_speed, damping=0.0):
        """(Mechanism, Omega*) from SI quantities.

        L, a in m; E in Pa; rho in kg/m^3; A in m^2; I in m^4; slider_mass in kg; crank_speed in
        rad/s; damping mu in s (eq. 24: C = mu K).
        """
        si = SIMechanism(L=L, a=a, E=E, rho=rho, A=A, I=I, slider_mass=slider_mass,
                         crank_speed=crank_speed, damping=damping)
        return si.mechanism, si.omega


@dataclass(frozen=True)
class SIMechanism:
    """A mechanism in SI units; `.mechanism` and `.omega` give the paper's dimensionless form."""

    L: float
    a: float
    E: float
    rho: float
    A: float
    I: float
    slider_mass: float
    crank_speed: float
    damping: float = 0.0

    def __post_init__(self):
        for name in ("L", "a", "E", "rho", "A", "I"):
            in_range(f"{name} (SI)", getattr(self, name), 0, None, True)
        in_range("slider_mass (kg)", self.slider_mass, 0)
        in_range("crank_speed (rad/s)", self.crank_speed, 0)
        in_range("damping (mu, s)", self.damping, 0)

    @property
    def omega_b(self):
        """Lowest bending natural frequency of the pinned-pinned rod, rad/s."""
        return (math.pi / self.L) ** 2 * math.sqrt(self.E * self.I / (self.rho * self.A))

    @property
    def radius_of_gyration(self):
        return math.sqrt(self.I / self.A)

    @property
    def mechanism(self):
        return Mechanism(a=self.a / self.L, eps=self.radius_of_gyration / self.L,
                         ms=self.slider_mass / (self.rho * self.A * self.L),
                         mu=self.omega_b * self.damping)

    @property
    def omega(self):
        """Omega* = crank speed / omega_b."""
        return self.crank_speed / self.omega_b
