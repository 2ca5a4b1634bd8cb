"""The outputs, declared as data: the quantities a result can give (per step, as fields of x*, or
as reductions over the rod), each with its units and its expression in the inputs it names.

One more part of the declaration (derive/declaration.py holds the options, parameters, energies
and term families these expressions read); derive/representation.py turns OUTPUTS and the engine's
PRIMITIVES into records and kernels.  To add an output, declare it in OUTPUTS, then `make derive`.
"""

from dataclasses import dataclass
from typing import Callable

import sympy as sp

from crankgen.declaration import records

from . import declaration
from . import energies as en
from . import symbols as s
from .declaration import EXACT, GUIDES, EXACT_KINETIC, EXACT_STRAIN_ENERGY, STRAIN_ENERGY, eps
from .euler_lagrange import total_time_derivative

# the guides whose end mass is a slider on the guide's curve (the joint forces at B are the
# rod-on-slider and guide-on-slider pairs), and those whose end is the tip of a rocker, a link from
# a ground pivot (a four-bar's: the rocker angle, the transmission angle, the rod-on-tip and
# rocker-on-tip pairs)
SLIDER_GUIDES = tuple(g.name for g in GUIDES if g.pivot is None)
TIP_GUIDES = tuple(g.name for g in GUIDES if g.pivot is not None)


@dataclass(frozen=True)
class Output(records.Output):
    """A quantity a result can give (crankgen.declaration.records.Output: name, kind, doc, units, arguments,
    guides, options, engine) with `build(options)`, its expression in the inputs it names.  kind:
    "step" (one value per stored step), "field" (per stored step at any x* in [0, 1]) or
    "reduction" (per stored step, the sum over the rod's elements of the element expression the
    build gives: an integral over the rod).  Inputs a build may use: q, qd (the nodal vector of the
    element holding x*, or of each element for a reduction, and its rate), zeta (x / l in it), geo,
    coef, kin, the parameters' symbols, q_end ((u, v) of the rod's end node in the moving frame),
    qd_end, qdd_end (their first and second time derivatives), s (the end map's reduced co-ordinate), pin ((F_i, F_j): the
    force the crank pin applies to the rod, in the moving frame), end ((F_i, F_j): the force the
    guide's body applies to the end mass: the slider's guide, a four-bar's rocker), rod_end ((F_i, F_j):
    the force the end mass applies to the rod at B, the rod's own terms at its end node), fiber,
    and the engine's
    primitives (at_point, over_rod).  options: the model options the expression depends on (its
    kernels by their values).  engine: the engine computes it at every step (its build may use
    q_end, the parameters and the primitives only).  guides None: every guide."""

    build: Callable = None


@dataclass(frozen=True)
class Primitive(records.Primitive):
    """A quantity of the nodal state the engine accumulates at every step for its outputs
    (crankgen.declaration.records.Primitive: name, kind, field, at) with its symbol in the outputs' builds and,
    for an integral, its integrand (quadratic in the element's nodal vector q)."""

    symbol: sp.Symbol = None
    integrand: sp.Expr = None


PRIMITIVES = {}


def at_point(field, x):
    """The interpolated field u, v or psi (eqs. 8-10) at x* (in the element holding it)."""
    name = f"{field}_at_{str(sp.nsimplify(x)).replace('/', '_')}"
    if name not in PRIMITIVES:
        PRIMITIVES[name] = Primitive(name, "point", field=field, at=float(x), symbol=sp.Symbol(name, real=True))
    return PRIMITIVES[name].symbol


def over_rod(name, integrand):
    """int_0^1 integrand dx over the rod, the integrand quadratic in the element's nodal vector q."""
    if name not in PRIMITIVES:
        PRIMITIVES[name] = Primitive(name, "integral", kernel=f"gram_{name}", symbol=sp.Symbol(name, real=True),
                                     integrand=integrand)
    return PRIMITIVES[name].symbol


V_AT_MIDSPAN = at_point("v", sp.Rational(1, 2))
SLOPE_SQUARED = over_rod("slope_squared", en.fields(s.q, s.q)["v_x"] ** 2)


fiber = sp.Symbol("fiber", real=True)
q_end = sp.Matrix(sp.symbols("qe0:2", real=True))
qd_end = sp.Matrix(sp.symbols("qde0:2", real=True))
qdd_end = sp.Matrix(sp.symbols("qdde0:2", real=True))
pin = sp.Matrix(sp.symbols("pin0:2", real=True))
end_force = sp.Matrix(sp.symbols("end0:2", real=True))
# the force the ground pivot D applies to a flexible rocker, on the rocker's frame (e_ir, e_jr): the
# reaction of the constraint "ground" (derive/declaration.py)
ground_force = sp.Matrix(sp.symbols("ground0:2", real=True))
rod_end = sp.Matrix(sp.symbols("rodend0:2", real=True))
s_end = sp.Symbol("s", real=True)


def membrane_strain(options, q=s.q):
    """The membrane strain of the approach in use: u_x + v_x^2/2 for A and B (pointwise or element
    mean), u_x for C, |r'| - 1 for exact."""
    f = en.fields(q, q, options["approach"])
    if options["approach"] == "C":
        return f["u_x"]
    if options["approach"] == EXACT:
        return en.exact_strain(f)
    if options["membrane"] == "averaged":
        return f["u_x"] + en.mean_over_element(f["v_x"] ** 2) / 2
    return f["u_x"] + f["v_x"] ** 2 / 2


def _curvature(options, q=s.q):
    """v_xx (A, B, C); the exact section rotation's d theta / dx (exact)."""
    f = en.fields(q, q, options["approach"])
    if options["approach"] != EXACT:
        return f["v_xx"]
    return en.exact_curvature(f)


def _strain_energy_of(options):
    """The Energy of the approach and membrane strain in use."""
    if options["approach"] == EXACT:
        return EXACT_STRAIN_ENERGY
    averaged = options["approach"] != "C" and options["membrane"] == "averaged"
    return STRAIN_ENERGY[options["approach"], averaged]


def _inertial(vector):
    """Inertial (X, Y) of a vector given by its moving-frame components (e_i, e_j)."""
    return sp.Matrix([vector[0] * sp.cos(s.phi) + vector[1] * sp.sin(s.phi),
                      -vector[0] * sp.sin(s.phi) + vector[1] * sp.cos(s.phi)])


def _rocker_inertial(vector):
    """Inertial (X, Y) of a vector given by its components on a flexible rocker's frame (e_ir, e_jr),
    e_ir = (cos beta, sin beta) along the rigid rocker from its pivot."""
    return sp.Matrix([vector[0] * sp.cos(s.beta) - vector[1] * sp.sin(s.beta),
                      vector[0] * sp.sin(s.beta) + vector[1] * sp.cos(s.beta)])


def end_position():
    """Inertial position of the rod's end B = A + (L + u) e_i + v e_j (L = 1)."""
    return sp.Matrix([s.a * sp.cos(s.theta), s.a * sp.sin(s.theta)]) + _inertial(
        sp.Matrix([1 + q_end[0], q_end[1]]))


def _rate(expr):
    """d/dt of an expression in the end node's (u, v) and the rigid kinematics (theta, phi)."""
    return total_time_derivative(expr, tuple(q_end), tuple(qd_end), ())


def end_acceleration():
    """Inertial acceleration of the rod's end B: d/dt of its velocity (_rate of end_position),
    with the end node's accelerations qdd_end."""
    return sp.Matrix([total_time_derivative(_rate(x), tuple(q_end), tuple(qd_end), tuple(qdd_end))
                      for x in end_position()])


def ground_on_rocker():
    """The force the ground applies to the rigid rocker at its pivot D: the rocker's momentum balance
    m a_G = F_D + F_tip + m g, with its centre of mass G - D = k (B - D) (so a_G = k a_B, the tip on
    the rocker's circle) and F_tip = -end the force its tip mass applies to it (the rocker's own
    spring, weight and inertia left out of `end`)."""
    m_k = declaration.rocker_mass * declaration.rocker_centre
    gravity = sp.Matrix([s.gX, s.gY])
    return m_k * end_acceleration() - declaration.rocker_mass * gravity + _inertial(end_force)


def chord_angle():
    """Inertial angle of the chord from the pin A to the rod's end B, counter-clockwise from X: the
    chord's angle in the moving frame, atan2(v, L + u) at the end (e_j is counter-clockwise of
    e_i), less phi (the moving frame's e_i is at -phi)."""
    return sp.atan2(q_end[1], 1 + q_end[0]) - s.phi


def chord_elongation():
    """|B - A| - L (L = 1) without the cancellation of sqrt(...) - 1 for a short end displacement."""
    stretch = 2 * q_end[0] + q_end[0] ** 2 + q_end[1] ** 2
    return stretch / (sp.sqrt((1 + q_end[0]) ** 2 + q_end[1] ** 2) + 1)


def chord_deflection(approach=None):
    """Signed distance of the rod's point at x (element zeta) from its chord, the line from the pin to
    the end node, positive on the counter-clockwise side (towards e_j for a straight rod)."""
    f = en.fields(s.q, s.q, approach)
    x = s.x0 + s.l * s.zeta
    length = sp.sqrt((1 + q_end[0]) ** 2 + q_end[1] ** 2)
    return ((1 + q_end[0]) * f["v"] - q_end[1] * (x + f["u"])) / length


def pin_torque():
    """a (e_r x F_pin): the torque the rod and end mass demand of the crank through the crank pin."""
    return s.a * (sp.cos(s.theta) * _inertial(pin)[1] - sp.sin(s.theta) * _inertial(pin)[0])


def crank_own_torque():
    """The torque that turns the rigid crank itself and holds its weight's moment about its axis O:
    J_O thetadd + m k a (gX sin theta - gY cos theta), J_O = J_G + m (k a)^2 (G = k a e_r, the
    crank's centre of mass; zero without crank_mass and crank_inertia)."""
    m, k = declaration.crank_mass, declaration.crank_centre
    moment_of_inertia = declaration.crank_inertia + m * (k * s.a) ** 2
    return moment_of_inertia * s.thetadd + m * k * s.a * (s.gX * sp.sin(s.theta) - s.gY * sp.cos(s.theta))


def ground_on_crank():
    """The force the ground applies to the rigid crank at its axis O (its main bearing): the crank's
    momentum balance m a_G = F_O - F_pin + m g, with a_G the acceleration of G = k a e_r and -F_pin
    the force the rod applies to the crank at A."""
    m, k = declaration.crank_mass, declaration.crank_centre
    e_r = sp.Matrix([sp.cos(s.theta), sp.sin(s.theta)])
    e_t = sp.Matrix([-sp.sin(s.theta), sp.cos(s.theta)])
    a_G = k * s.a * (s.thetadd * e_t - s.thetad ** 2 * e_r)
    return m * a_G - m * sp.Matrix([s.gX, s.gY]) + _inertial(pin)


# the options the membrane strain depends on
MEMBRANE_OPTIONS = ("approach", "membrane")
# N* = N L^2/EI = EA e / EI = e / eps^2 = e EA/EI;  M* = M L / EI = v_xx (L = 1).  Forces in rho A L^2
# omega_b^2 and torques in rho A L^3 omega_b^2 are crankgen's units (rho A = L = omega_b = 1).
FORCE, TORQUE = "rhoA L^2 omega_b^2", "rhoA L^3 omega_b^2"
OUTPUTS = (
    Output("v_mid", "step", "v* = v/r at x* = 1/2 (shape-function interpolation)", "r", engine=True,
           build=lambda o: V_AT_MIDSPAN / eps),
    Output("u_end", "step", "u*(1) = L u(L) / r^2", "r^2/L", engine=True, build=lambda o: q_end[0] / eps**2),
    Output("extension", "step", "delta* = u(L)/L + (1/2) int (dv/dx)^2 dx / L, eq. (40)", "1", engine=True,
           build=lambda o: q_end[0] + SLOPE_SQUARED / 2),
    Output("crank_speed", "step", "crank speed theta' (units of omega_b)", "omega_b", build=lambda o: s.thetad),
    Output("slider_position", "step", "X/L of the rod's end (the slider; the rocker's tip)", "L",
           build=lambda o: end_position()[0]),
    Output("end_height", "step", "Y/L of the rod's end", "L", build=lambda o: end_position()[1]),
    Output("rocker_angle", "step", "the rocker's angle (rad, counter-clockwise from the X axis)", "rad",
           build=lambda o: s.beta + s_end, guides=TIP_GUIDES),
    Output("transmission_angle", "step",
           "the four-bar's transmission angle: the angle at the rocker's tip between the coupler's "
           "chord and the rocker, in [0, pi] (pi/2 transmits the crank's force best)", "rad",
           build=lambda o: sp.acos(sp.cos(sp.atan2(q_end[1], 1 + q_end[0]) - s.phi - s.beta - s_end)),
           guides=TIP_GUIDES),
    Output("chord_angle", "step",
           "inertial angle of the rod's chord, the line from the crank pin to the rod's end (rad, "
           "counter-clockwise from the X axis)", "rad", build=lambda o: chord_angle()),
    Output("chord_rate", "step", "angular velocity of the rod's chord (d/dt chord_angle, counter-clockwise)",
           "omega_b", build=lambda o: _rate(chord_angle())),
    Output("chord_elongation", "step",
           "change of the chord's length: the distance from the crank pin to the rod's end, less L",
           "L", build=lambda o: chord_elongation()),
    Output("slider_velocity", "step", "X velocity of the rod's end (the slider; the rocker's tip)",
           "L omega_b", build=lambda o: _rate(end_position()[0])),
    Output("torque", "step",
           "driving torque the crank needs to hold its prescribed motion (counter-clockwise): the rod's "
           "a (e_r x F_pin) and, with a crank_mass or crank_inertia, the crank's own J_O thetadd and its "
           "weight's moment (a motor supplies it: its equation reads this torque), units of rho A L^3 "
           "omega_b^2", TORQUE, build=lambda o: pin_torque() + crank_own_torque()),
    # the joint forces, named "<body>_on_<body>": who acts on whom (inertial X, Y components)
    Output("crank_on_rod_x", "step",
           "X component of the force the crank applies to the rod at the crank pin A (sizes the pin "
           "and bearing at A)", FORCE, build=lambda o: _inertial(pin)[0]),
    Output("crank_on_rod_y", "step", "Y component of the force the crank applies to the rod at A", FORCE,
           build=lambda o: _inertial(pin)[1]),
    Output("rod_on_slider_x", "step",
           "X component of the force the rod applies to the slider at B, through the pin at B (sizes "
           "that pin)", FORCE, build=lambda o: -_inertial(rod_end)[0], guides=SLIDER_GUIDES),
    Output("rod_on_slider_y", "step", "Y component of the force the rod applies to the slider at B", FORCE,
           build=lambda o: -_inertial(rod_end)[1], guides=SLIDER_GUIDES),
    Output("guide_on_slider_x", "step",
           "X component of the force the guide applies to the slider (normal to the guide, no "
           "friction: zero on the horizontal line Y = e)", FORCE, build=lambda o: _inertial(end_force)[0],
           guides=SLIDER_GUIDES),
    Output("guide_on_slider_y", "step",
           "Y component of the force the guide applies to the slider: the guide's normal force (sizes "
           "the guide)", FORCE, build=lambda o: _inertial(end_force)[1], guides=SLIDER_GUIDES),
    Output("rod_on_tip_x", "step",
           "X component of the force the coupler (the rod) applies to the rocker's tip at B, through "
           "the pin at B (sizes that pin)", FORCE, build=lambda o: -_inertial(rod_end)[0], guides=TIP_GUIDES),
    Output("rod_on_tip_y", "step", "Y component of the force the rod applies to the rocker's tip at B", FORCE,
           build=lambda o: -_inertial(rod_end)[1], guides=TIP_GUIDES),
    Output("rocker_on_tip_x", "step",
           "X component of the force the rocker applies to its tip mass at B (along the rocker when "
           "it is a massless two-force member without a spring: then the force at its pivot D too)", FORCE,
           build=lambda o: _inertial(end_force)[0], guides=TIP_GUIDES),
    Output("rocker_on_tip_y", "step", "Y component of the force the rocker applies to its tip mass at B",
           FORCE, build=lambda o: _inertial(end_force)[1], guides=TIP_GUIDES),
    Output("ground_on_rocker_x", "step",
           "X component of the force the ground applies to the rocker at its pivot D (sizes the pivot's "
           "bearing): the force at the tip with a massless rocker, plus the rocker's mass times its "
           "centre's acceleration less its weight", FORCE, build=lambda o: ground_on_rocker()[0],
           guides=TIP_GUIDES, rigid=("rocker",)),
    Output("ground_on_rocker_y", "step", "Y component of the force the ground applies to the rocker at D",
           FORCE, build=lambda o: ground_on_rocker()[1], guides=TIP_GUIDES, rigid=("rocker",)),
    Output("ground_on_flexible_rocker_x", "step",
           "X component of the force the ground applies to a flexible rocker at its pivot D (sizes the pivot's "
           "bearing): the reaction of the pivot's pin, which holds the rocker's first node", FORCE,
           build=lambda o: _rocker_inertial(ground_force)[0], guides=TIP_GUIDES, flexible=("rocker",)),
    Output("ground_on_flexible_rocker_y", "step",
           "Y component of the force the ground applies to a flexible rocker at its pivot D", FORCE,
           build=lambda o: _rocker_inertial(ground_force)[1], guides=TIP_GUIDES, flexible=("rocker",)),
    Output("ground_on_crank_x", "step",
           "X component of the force the ground applies to the crank at its axis O (sizes the main "
           "bearing): the rod's force at the crank pin, plus the crank's mass times its centre's "
           "acceleration less its weight (crank_mass)", FORCE, build=lambda o: ground_on_crank()[0]),
    Output("ground_on_crank_y", "step", "Y component of the force the ground applies to the crank at O",
           FORCE, build=lambda o: ground_on_crank()[1]),
    Output("kinetic_energy", "reduction",
           "the rod's kinetic energy T = sum of the elements' T_i, eqs. (4)-(5) (the end mass's not "
           "included; the exact rod's with its unit director), units of rho A L^3 omega_b^2", TORQUE,
           options=("approach",),
           build=lambda o: EXACT_KINETIC.build() if o["approach"] == EXACT else en.rod_kinetic_energy()),
    Output("strain_energy", "reduction",
           "the rod's strain energy U = sum of the elements' U_i of the approach in use (eq. 2 for A; "
           "B without the quartic term; C linear; the exact rod's), units of rho A L^3 omega_b^2", TORQUE,
           options=MEMBRANE_OPTIONS, build=lambda o: _strain_energy_of(o).build()),
    Output("axial_force", "field", "N* = N L^2 / EI, N = EA times the approach's membrane strain", "EI/L^2",
           options=MEMBRANE_OPTIONS, build=lambda o: membrane_strain(o) * s.EA / s.EI),
    Output("bending_moment", "field", "M* = M L / EI = v_xx (M = EI v_xx; exact: EI kappa, kappa the exact "
           "curvature)", "EI/L", options=MEMBRANE_OPTIONS, build=lambda o: _curvature(o)),
    Output("surface_strain", "field",
           "axial strain of the fibre at distance fiber*r from the neutral axis (towards e_j), "
           "e_m - fiber r v_xx (eq. 1 with y = fiber r; exact: e - fiber r kappa)", "1", arguments=("fiber",),
           options=MEMBRANE_OPTIONS,
           build=lambda o: membrane_strain(o) - fiber * sp.sqrt(s.EI / s.EA) * _curvature(o)),
    Output("chord_deflection", "field",
           "signed distance of the rod's point at x* from its chord (the line from the crank pin to "
           "the rod's end), positive counter-clockwise", "L", options=MEMBRANE_OPTIONS,
           build=lambda o: chord_deflection(o["approach"])),
)


# ----------------------------------------------------------------------------------------------
# Reductions over time (records.Reduction): a peak, RMS, mean or range of an output along a steady
# revolution, a continuation point's orbit or a run's last revolution.  Each is a column of the
# steady and sweep tables and a quantity of every branch point, with its output's units
# (crankgen.results.reductions computes them).
# ----------------------------------------------------------------------------------------------

REDUCTIONS = (
    records.Reduction("rms_bending_moment_mid", "bending_moment", "rms",
                      "the RMS over the revolution of the bending moment at mid-span (what a fatigue "
                      "check of the rod's bending starts from, beside its peak)", at=0.5),
)
