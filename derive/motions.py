"""Stage 2b: the crank's prescribed motion theta(t), its rate and its angular acceleration.

Each motion is declared by closed forms in the time t and its parameters: theta(t), thetad and
thetadd (which may use theta, computed first), and, when the motion is periodic in the crank angle,
the time of one crank revolution (`period`): then theta(t + period) = theta(t) + 2 pi, the time
step of a run is period / steps_per_rev and periodic states exist.  `check()` verifies at build
time that thetad and thetadd are the time derivatives of theta (by differentiation, or numerically
where the closed form is not differentiated symbolically) and that theta(0) = theta0.

Every motion starts at the crank angle theta0 (the parameter `theta0`, declared in
derive/declaration.py; default 0) at t = 0.  It enters only as the constant of integration of theta(t),
written so that theta0 = 0 evaluates to exactly the floating-point numbers of the motion without
it (an added 0.0 changes no sum).

- constant: theta = theta0 + Omega t (the paper's crank, theta0 = 0).
- runup: the speed rises from Omega0 to Omega over `ramp` crank revolutions along the quintic
  smooth step s(x) = 10 x^3 - 15 x^4 + 6 x^5 of x = t / T (speed and acceleration continuous),
  T = 4 pi ramp / (Omega0 + Omega) so that theta(T) = theta0 + 2 pi ramp, and stays at Omega
  afterwards (the speed is a law in time, so theta0 only shifts theta).
- fluctuation: thetad = Omega (1 + k sin(j theta)) (a flywheel's cyclic irregularity of relative
  amplitude k, |k| < 1, and order j, a positive integer).  With m = sqrt(1 - k^2) the rate law
  integrates in closed form, tan(j theta / 2) = m tan(psi) - k with psi = m j Omega t / 2 +
  atan(k / m) + D0; the revolution takes 2 pi / (m Omega).  The law is autonomous, so a start at
  theta0 is the start at 0 shifted in time: D0 is the psi-advance that brings j theta / 2 from 0
  to chi0 = j theta0 / 2.  With n = round(chi0 / pi) and c = chi0 - n pi in [-pi/2, pi/2] (where
  cos c >= 0 keeps psi in the branch of chi), the tangent of the difference of the two angles
  whose tangents are (tan c + k) / m and k / m gives
      D0 = n pi + atan2(m sin c, cos c + k sin c)            (D0 = 0 exactly at theta0 = 0).
- motor: the crank is not prescribed: its angle is one more degree of freedom, a declared
  co-ordinate of the state (`Coordinate`, crank=True) with its own equation, driven by a motor of
  characteristic T_m(thetad) = T_stall (1 - thetad / Omega_nl) (a DC motor, or an induction motor
  near synchronous speed), with the inertia J of crank, rotor and flywheel about the crank axis and
  a constant load torque T_load:
      J thetadd - T_m(thetad) + T_load + T_rod = 0,
  T_rod = a (e_r x F_pin) the torque the rod and end mass demand (the output `torque`: the
  crank's generalized residual of the same energies; `ROD_TORQUE` here, substituted by the
  representation), with the crank's own J_O thetadd and weight's moment when the crank is given a
  mass and an inertia (crank_mass, crank_inertia: then J is the rotor's and flywheel's alone).  Its theta(t) = theta0 + Omega_i t is only the crank's start (the speed at
  t = 0, Omega_i, default 0: from rest); its step period is the no-load revolution 2 pi / Omega_nl
  (the fastest the motor turns the crank in steady running).  The equation holds the linear law;
  a case's per-unit torque_curve f (crankgen.declaration.torque_curve: a table, cubic Hermite
  between its points) replaces it at run time by T_stall f(thetad / Omega_nl), added to the
  equation of the co-ordinate the motor drives (motor=True) as its departure from the linear law.

- shaft: the motor drives the crank through a torsionally flexible shaft: the motor rotor's angle
  phi_m is a second co-ordinate (its equation J_rotor phidd_m - T_m(phid_m) + T_shaft = 0), the
  crank's carries the shaft's torque T_shaft = k (phi_m - theta) + c (phid_m - thetad):
      J thetadd + T_load + T_rod - T_shaft = 0;
  J is then the crank's and any flywheel's on the crank side, the torque curve drives the rotor.
  The rotor starts with the crank (phi_m = theta0, the same speed: an untwisted shaft).

A driven motion's co-ordinates (`coordinates`) each carry their symbols (the crank's are the
kinematics' theta, thetad, thetadd), their equation's residual and their start (value and rate at
t = 0); the generated kernel `coordinates_<motion>` gives every equation and its derivatives, the
runtime steps them with the rods' nodal co-ordinates by one bordered Newton iteration.
"""

from dataclasses import dataclass

import sympy as sp

from crankgen.declaration import records

from . import symbols as s

# The crank angle at t = 0 (the parameter theta0 of derive/declaration.py).
theta0 = sp.Symbol("theta0", real=True)
# the motor's parameters (derive/declaration.py): stall torque, no-load speed, the inertia about the
# crank axis, the load torque, the crank speed at t = 0
stall_torque = sp.Symbol("T_stall", real=True)
no_load_speed = sp.Symbol("Omega_nl", positive=True)
inertia = sp.Symbol("J_crank", nonnegative=True)
load_torque = sp.Symbol("T_load", real=True)
initial_speed = sp.Symbol("Omega_i", nonnegative=True)
# a flexible shaft between the motor and the crank: the rotor's inertia, the shaft's torsional
# stiffness and damping, and the rotor's angle, speed and acceleration (a co-ordinate)
rotor_inertia = sp.Symbol("J_rotor", positive=True)
shaft_stiffness = sp.Symbol("k_shaft", positive=True)
shaft_damping = sp.Symbol("c_shaft", nonnegative=True)
rotor, rotor_rate, rotor_acceleration = sp.symbols("phi_m phid_m phidd_m", real=True)
# the torque the rod and end mass demand of the crank (the output `torque`, in the crank pin's force
# and the kinematics): the representation substitutes it into a driven crank's equation
ROD_TORQUE = sp.Symbol("T_rod", real=True)


@dataclass(frozen=True)
class Coordinate(records.Coordinate):
    """A co-ordinate of the state (crankgen.declaration.records.Coordinate: name, doc, units,
    crank, motor) with its symbols (value, rate, acceleration: the kinematics' theta, thetad,
    thetadd for the crank's), its equation's residual (in them, the other co-ordinates', ROD_TORQUE
    and the parameters) and its start (its value and rate at t = 0, in the parameters)."""

    value: sp.Symbol = None
    rate: sp.Symbol = None
    acceleration: sp.Symbol = None
    equation: sp.Expr = None
    start: tuple = None


def crank_coordinate(equation, doc, motor=False):
    """The crank angle as a co-ordinate of the state: the kinematics' symbols, the start theta0 at
    the initial speed."""
    return Coordinate("theta", doc, "rad", crank=True, motor=motor, value=s.theta, rate=s.thetad,
                      acceleration=s.thetadd, equation=equation, start=(theta0, initial_speed))


@dataclass(frozen=True)
class Motion(records.Motion):
    """A crank motion (crankgen.declaration.records.Motion: name, title of its runtime record, the parameters it
    reads, doc, keyword aliases) with theta(t), thetad (in t and theta), thetadd (in t, theta and
    thetad), the time of one crank revolution (`period`, None: not periodic) and the time that
    steps_per_rev steps divide (`step_period`: the period, or the fastest revolution)."""

    theta: sp.Expr = None
    thetad: sp.Expr = None
    thetadd: sp.Expr = None
    period: object = None
    step_period: sp.Expr = None


def _wrap(z):
    """z shifted by a multiple of 2 pi into [-pi, pi)."""
    return z - 2 * sp.pi * sp.floor(z / (2 * sp.pi) + sp.Rational(1, 2))


def constant():
    return Motion("constant", "Constant", ("omega", "theta0"), "constant crank speed Omega*: theta = theta0 + Omega* t",
                  label="constant crank speed",
                  theta=theta0 + s.omega * s.t, thetad=s.omega, thetadd=sp.Integer(0),
                  period=2 * sp.pi / s.omega, step_period=2 * sp.pi / s.omega)


def runup():
    T = 4 * sp.pi * s.ramp / (s.omega0 + s.omega)
    x = s.t / T
    step = 10 * x**3 - 15 * x**4 + 6 * x**5
    step_integral = sp.Rational(5, 2) * x**4 - 3 * x**5 + x**6
    dstep = sp.diff(step, s.t)
    during = s.t < T
    theta = theta0 + sp.Piecewise((s.omega0 * s.t + (s.omega - s.omega0) * T * step_integral, during),
                                  (2 * sp.pi * s.ramp + s.omega * (s.t - T), True))
    thetad = sp.Piecewise((s.omega0 + (s.omega - s.omega0) * step, during), (s.omega, True))
    thetadd = sp.Piecewise(((s.omega - s.omega0) * dstep, during), (0, True))
    return Motion("runup", "RunUp", ("omega0", "omega", "ramp", "theta0"),
                  "run-up: the crank speed rises smoothly (quintic smooth step in time) from Omega0 "
                  "to Omega* over `ramp` revolutions, then stays at Omega*",
                  (("start", ("omega0",)), ("stop", ("omega",)), ("revolutions", ("ramp",))), transient="ramp", label="run-up",
                  theta=theta, thetad=thetad, thetadd=thetadd, period=None,
                  step_period=4 * sp.pi / (s.omega0 + s.omega + sp.Abs(s.omega - s.omega0)))   # 2 pi / max


def fluctuation():
    m = sp.sqrt(1 - s.k_fl**2)
    c0 = sp.atan(s.k_fl / m)
    chi0 = s.j_fl * theta0 / 2
    n0 = sp.floor(chi0 / sp.pi + sp.Rational(1, 2))
    c = chi0 - n0 * sp.pi
    shift = n0 * sp.pi + sp.atan2(m * sp.sin(c), sp.cos(c) + s.k_fl * sp.sin(c))     # D0 above
    psi = m * s.j_fl * s.omega * s.t / 2 + c0 + shift
    chi = sp.atan2(m * sp.sin(psi) - s.k_fl * sp.cos(psi), sp.cos(psi))    # j theta / 2 mod 2 pi
    half = (psi - c0) + _wrap(chi - (psi - c0))                           # unwrapped j theta / 2
    theta = 2 * half / s.j_fl
    thetad = s.omega * (1 + s.k_fl * sp.sin(s.j_fl * s.theta))
    thetadd = s.omega * s.k_fl * s.j_fl * sp.cos(s.j_fl * s.theta) * s.thetad
    period = 2 * sp.pi / (m * s.omega)
    return Motion("fluctuation", "Fluctuation", ("omega", "fluctuation", "order", "theta0"),
                  "cyclic speed fluctuation: thetad = Omega* (1 + k sin(j theta)), |k| < 1, j a positive "
                  "integer", (("amplitude", ("fluctuation",)),), label="fluctuating crank speed",
                  theta=theta, thetad=thetad, thetadd=thetadd, period=period, step_period=period)


def motor():
    law = stall_torque * (1 - s.thetad / no_load_speed)
    crank = crank_coordinate(inertia * s.thetadd - law + load_torque + ROD_TORQUE,
                             "the crank angle, driven by the motor: J thetadd - T_m(thetad) + T_load + T_rod = 0",
                             motor=True)
    return Motion("motor", "Motor", ("stall_torque", "no_load_speed", "inertia", "load_torque", "initial_speed",
                                     "theta0", "torque_curve"),
                  "a motor drives the crank (its angle a degree of freedom): J thetadd = T_stall f(thetad / "
                  "Omega_nl) - T_load - (the torque the rod demands), f the per-unit torque_curve (default "
                  "f(s) = 1 - s, the linear law)", (("load", ("load_torque",)),),
                  label="motor-driven crank",
                  theta=theta0 + initial_speed * s.t, thetad=initial_speed, thetadd=sp.Integer(0), period=None,
                  step_period=2 * sp.pi / no_load_speed, coordinates=(crank,), driven=True,
                  characteristic=("torque_curve", "stall_torque", "no_load_speed", "inertia"))


def shaft():
    law = stall_torque * (1 - rotor_rate / no_load_speed)
    torque = shaft_stiffness * (rotor - s.theta) + shaft_damping * (rotor_rate - s.thetad)      # T_shaft
    crank = crank_coordinate(inertia * s.thetadd + load_torque + ROD_TORQUE - torque,
                             "the crank angle, driven through the shaft: J thetadd + T_load + T_rod - T_shaft = 0")
    rotor_angle = Coordinate("rotor", "the motor rotor's angle: J_rotor phidd_m - T_m(phid_m) + T_shaft = 0", "rad",
                             motor=True, value=rotor, rate=rotor_rate, acceleration=rotor_acceleration,
                             equation=rotor_inertia * rotor_acceleration - law + torque, start=(theta0, initial_speed))
    return Motion("shaft", "ShaftMotor", ("stall_torque", "no_load_speed", "inertia", "rotor_inertia", "shaft_stiffness",
                                          "shaft_damping", "load_torque", "initial_speed", "theta0", "torque_curve"),
                  "a motor drives the crank through a torsionally flexible shaft (the rotor's angle and the crank's "
                  "degrees of freedom): J_rotor phidd_m = T_m(phid_m) - T_shaft, J thetadd = T_shaft - T_load - (the "
                  "torque the rod demands), T_shaft = k (phi_m - theta) + c (phid_m - thetad)",
                  (("load", ("load_torque",)),), label="motor through a flexible shaft",
                  theta=theta0 + initial_speed * s.t, thetad=initial_speed, thetadd=sp.Integer(0), period=None,
                  step_period=2 * sp.pi / no_load_speed, coordinates=(crank, rotor_angle), driven=True,
                  characteristic=("torque_curve", "stall_torque", "no_load_speed", "rotor_inertia"))


MOTIONS = (constant(), runup(), fluctuation(), motor(), shaft())


def rates(motion):
    """(theta, thetad, thetadd) as expressions in t and the parameters only."""
    theta = motion.theta
    thetad = motion.thetad.subs(s.theta, theta)
    thetadd = motion.thetadd.subs({s.thetad: motion.thetad}).subs(s.theta, theta)
    return theta, thetad, thetadd


def check(motion, samples=((0.3, 0.2, 1.1, 3.0, 0.4, 2, 0.0), (1.7, 1.2, 0.3, 2.0, -0.6, 1, 0.0),
                           (40.0, 0.5, 0.9, 5.0, 0.7, 3, 0.0), (0.3, 0.2, 1.1, 3.0, 0.4, 2, 1.3),
                           (1.7, 1.2, 0.3, 2.0, -0.6, 1, -2.9), (40.0, 0.5, 0.9, 5.0, 0.7, 3, 11.0),
                           (2.1, 0.5, 0.9, 5.0, -0.9, 2, -7.5))):
    """Verify theta(0) = theta0, thetad = d theta / dt and thetadd = d thetad / dt (central
    differences at a few times and parameter values) and theta(period) = theta0 + 2 pi; raises
    AssertionError."""
    theta, thetad, thetadd = rates(motion)
    for t0, om0, om, ramp, k, j, start in samples:
        values = {sym: sp.sympify(v) for sym, v in ((s.omega0, om0), (s.omega, om), (s.ramp, ramp), (s.k_fl, k),
                                                      (s.j_fl, j), (theta0, start), (initial_speed, om0),
                                                      (no_load_speed, om))}
        f = [sp.lambdify(s.t, e.xreplace(values), "mpmath") for e in (theta, thetad, thetadd)]
        h = 1e-6
        for lower, upper in ((0, 1), (1, 2)):
            fd = (f[lower](t0 + h) - f[lower](t0 - h)) / (2 * h)
            assert abs(fd - f[upper](t0)) < 1e-5 * (1 + abs(f[upper](t0))), (motion.name, t0, lower)
        assert abs(float(f[0](0.0)) - start) < 1e-12 * (1 + abs(start)), (motion.name, "theta(0)")
        if motion.period is not None:
            T = float(motion.period.xreplace(values))
            assert abs(float(f[0](T)) - start - 2 * float(sp.pi)) < 1e-9, (motion.name, "period")
    return True
