"""The model's ingredients, declared once as data: what crankgen can combine, and how each is built.

This is the one place to read every ingredient of the flexible mechanism model:

- OPTIONS and PRESETS: the model options a case chooses (formulation, approach, membrane,
  damping, rotary_inertia) with their choices, and the named models `consistent` (the default)
  and `paper`, each a set of option values.
- PARAMETERS: every parameter of a case, typed (kind, default, range, units, help, command-line
  flag): the mechanism (a, eps, ms, mu, gravity), its guide (line or circle, with offset, c, d,
  branch), the crank's motion (constant, runup, fluctuation, with omega, omega0, ramp,
  fluctuation, order, and the start angle theta0) and the run's discretization (n_elements, steps_per_rev, integrator).
- COEFFICIENTS: the values every element kernel receives, each a formula in the parameters and
  options (rotary_inertia=False is rho*I = 0; a switched-off term group has weight 0).
- FAMILIES: the term families of the equations of motion, each a set of mutually exclusive
  variants selected by option values (`when`); a variant builds its element residual from the
  energies (derive/energies.py) or the printed form (derive/printed.py).  `part` says where it
  acts: "rod" on every element, "end" on the rod's end node (the end mass: the slider, the
  rocker's tip; rows 3-4 of the last element).  The residual convention is
  r = d/dt dT/dqd - dT/dq + dU/dq + dV/dq + dD/dqd.
- GUIDES and MOTIONS: the curve the rod's end travels on and the crank's prescribed motion
  (derive/guides.py, derive/motions.py: closures, end maps and rates derived there).
- OUTPUTS (derive/outputs.py, beside this module): the quantities a result can give, per step,
  as fields of x* or as reductions over the rod, with their units.

derive/representation.py turns this declaration into typed immutable records (the model
representation); derive/kernels.py, emit.py and schema.py read only those records, and the
runtime reads the generated schema: it never names a kernel, a family, a parameter or a guide.  To
add an ingredient, declare it here (a Family variant, an Option, a Parameter and the derivation
that uses it, a Guide, a Motion or an Output), then `make derive`.
"""

from dataclasses import dataclass
from typing import Callable

import sympy as sp

from crankgen.declaration import records
from crankgen.declaration.records import Option, Preset

from . import energies as en
from . import guides, motions
from . import printed
from . import quadrature
from . import symbols as s
from .euler_lagrange import gradient, jacobian, kinetic_residual
from .groups import ELEMENT_VARS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from .shape_functions import integrate_element


# ----------------------------------------------------------------------------------------------
# Options and presets (crankgen.declaration.records.Option, Preset)
# ----------------------------------------------------------------------------------------------

OPTIONS = (
    Option("formulation", ("lagrange", "paper"), None,
           "lagrange: the exact Euler-Lagrange equations of T_c + T_s - U_c; paper: the printed "
           "matrix form, eqs. (17)-(29) and Appendix B with its transcription problems corrected"),
    Option("approach", ("A", "B", "C", "exact"), "A",
           "strain energy: A full non-linear (eq. 2), B without the quartic v_x^4 term, C linear strain, "
           "exact the geometrically exact rod (stretch |r'| - 1, curvature of the exact section "
           "rotation, exact rotary inertia; lagrange formulation and kelvin-voigt damping only)"),
    Option("membrane", ("pointwise", "averaged"), None,
           "membrane strain of approaches A and B: pointwise (eq. 1) or its element mean (u_x + "
           "<v_x^2>/2; no membrane locking); no effect on approach C, on printed matrices or on the "
           "exact rod (whose cubic u makes its pointwise strain |r'| - 1 free of membrane locking)"),
    Option("damping", ("paper", "kelvin-voigt"), None,
           "paper: C = mu (K_lin + K_non), eq. (24) as printed; kelvin-voigt: strain-rate damping "
           "from the Rayleigh function of the approach's strain"),
    Option("rotary_inertia", (True, False), True,
           "keep the rho*I (section rotation) terms of the kinetic energy, eq. (5)", "rotary-inertia"),
)


PRESETS = (
    Preset("consistent", {"formulation": "lagrange", "damping": "kelvin-voigt", "membrane": "averaged"},
           "the exact Lagrange equations, strain-rate (Kelvin-Voigt) damping, averaged membrane strain "
           "(free of membrane locking)"),
    Preset("paper", {"formulation": "paper", "damping": "paper", "membrane": "pointwise"},
           "the printed matrix form (eqs. 17-29, Appendix B, transcription problems corrected), the "
           "printed damping of eq. (24), the element as derived from eq. (2), integrated with the "
           "paper's Newmark rule (rho_inf = 1)", {"rho_inf": 1.0}),
    Preset("exact", {"approach": "exact", "formulation": "lagrange", "damping": "kelvin-voigt",
                     "membrane": "pointwise"},
           "the geometrically exact rod: exact stretch, curvature and section rotation at any angle, "
           "the exact Lagrange equations, strain-rate (Kelvin-Voigt) damping"),
)
DEFAULT_PRESET = "consistent"


EXACT = "exact"                  # the approach of the geometrically exact rod

# Option values that have no meaning together (crankgen.declaration.records.Exclusion): a case choosing them is
# refused with the reason.
EXCLUSIONS = (
    records.Exclusion({"approach": EXACT, "formulation": "paper"},
                      "approach 'exact' has no printed matrix form: use formulation='lagrange' (or model='exact')"),
    records.Exclusion({"approach": EXACT, "damping": "paper"},
                      "approach 'exact' has no printed damping (eq. 24 is built from the matrices of eq. 2): "
                      "use damping='kelvin-voigt' (or model='exact')"),
)

# ----------------------------------------------------------------------------------------------
# Parameters of a case: the mechanism, its guide, the crank's motion, the run's discretization
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Parameter(records.Parameter):
    """A parameter of a case (crankgen.declaration.records.Parameter: kind, default, range, units, flag, ...)
    with its symbol in the derivation (a pair: a tuple of two), None for a parameter that enters
    no equation.  owner: declared "mechanism" (a Mechanism field) or "run"; a parameter that a
    guide or motion reads (Guide.parameters, Motion.parameters) is owned by those
    (derive/representation.py).  The choices of a choice parameter may be the guides or the
    motions: it then selects the case's guide or motion."""

    symbol: object = None


# the torsional spring at the rocker's ground pivot: its stiffness and the rocker angle at which it is relaxed
rocker_stiffness = sp.Symbol("k_rocker", nonnegative=True)
rocker_free_angle = sp.Symbol("beta_free", real=True)
# the rigid rocker's mass, its centre of mass (a fraction k of c along the rocker from its pivot D)
# and its moment of inertia about that centre; the coefficients they enter: the tip mass that
# carries the rocker's kinetic energy, J_D / c^2 with J_D = J_G + m (k c)^2 its moment of inertia
# about D, and the weight of the tip mass that carries its weight's moment, m k (gX, gY)
rocker_mass = sp.Symbol("m_rocker", nonnegative=True)
rocker_centre = sp.Symbol("k_rocker_G", real=True)
rocker_inertia = sp.Symbol("J_rocker_G", nonnegative=True)
rocker_tip_mass = sp.Symbol("m_rocker_tip", nonnegative=True)
rocker_tip_weight = (sp.Symbol("wX_rocker", real=True), sp.Symbol("wY_rocker", real=True))
# the rigid crank's own mass, its centre of mass (a fraction k of a along the crank from its axis O)
# and its moment of inertia about that centre: they enter no equation of the rod, only the torque
# the crank's drive supplies (derive/outputs.py: J_O thetadd and the weight's moment, J_O = J_G +
# m (k a)^2; a motor's equation reads that torque) and the force on the crank's bearing at O
crank_mass = sp.Symbol("m_crank", nonnegative=True)
# a flexible rocker's section relative to the coupler's (its rho A, E I and E A over the coupler's):
# its elements are the coupler's kernels with these coefficients (BODY_COEFFICIENTS)
rocker_density = sp.Symbol("rhoA_rocker", positive=True)
rocker_bending = sp.Symbol("EI_rocker", positive=True)
rocker_axial = sp.Symbol("EA_rocker", positive=True)
crank_centre = sp.Symbol("k_crank_G", real=True)
crank_inertia = sp.Symbol("J_crank_G", nonnegative=True)

PARAMETERS = (
    Parameter("a", "real", 0.1, "a (crank length a* = a/L)", "crank length over rod length a* = a/L",
              low=0.0, high=1.0, low_open=True, high_open=True, units="L", continuable=True, symbol=s.a,
              axis="a*"),
    Parameter("eps", "real", 0.01, "eps (slenderness r/L)",
              "slenderness eps = r/L, r the radius of gyration of the rod's section",
              low=0.0, low_open=True, continuable=True, symbol=s.eps, axis="eps"),
    Parameter("ms", "real", 0.5, "ms (end mass ms* = m_s/(rho A L))",
              "mass at the rod's end (the slider; the rocker's tip) ms* = m_s/(rho A L)",
              low=0.0, units="rhoA L", continuable=True, symbol=s.ms, axis="ms*", si="slider_mass"),
    Parameter("mu", "real", 0.5, "mu (damping mu* = omega_b mu)", "damping mu* = omega_b mu",
              low=0.0, units="1/omega_b", continuable=True, symbol=s.mu, axis="mu*", si="damping",
              si_default=0.0),
    Parameter("gravity", "pair", (0.0, 0.0), "gravity",
              "gravity (gX, gY) in the inertial frame (X along the guide, the crank pin at "
              "a* (cos theta, sin theta)), units of L omega_b^2", units="L omega_b^2", metavar="GX,GY",
              symbol=(s.gX, s.gY)),
    Parameter("guide", "choice", "line", "guide",
              "the curve the rod's end travels on: line (a slider on the line Y = offset), circle "
              "(the tip of a rigid rocker of length c pivoted at (d, offset), massless unless given a mass: a four-bar "
              "linkage with a flexible coupler), cam (a slider on a wavy track) or incline (a slider on a "
              "line at an angle inclination to the X axis)", choices=guides.GUIDES),
    Parameter("offset", "real", 0.0, "offset (guide offset e/L)",
              "guide offset e/L: the line Y = e (a cam track's mean line; an inclined line's "
              "distance from the crank's axis), or the ordinate of the rocker's pivot",
              units="L", continuable=True, symbol=s.e, axis="offset e/L"),
    Parameter("c", "real", 0.8, "c (rocker length c/L)", "rocker length c/L",
              low=0.0, low_open=True, units="L", cli="rocker", continuable=True,
              symbol=s.c, axis="rocker length c/L"),
    Parameter("d", "real", 1.0, "d (ground pivot abscissa d/L)",
              "abscissa d/L of the rocker's ground pivot D = (d, offset)",
              units="L", cli="ground", continuable=True, symbol=s.d, axis="ground pivot d/L"),
    Parameter("branch", "sign", 1, "branch",
              "closure of the four-bar: +1 puts the rocker's tip on the counter-clockwise side of the "
              "line from the crank pin to the ground pivot, -1 on the other",
              symbol=s.branch),
    Parameter("rocker_stiffness", "real", 0.0, "rocker_stiffness (rocker spring k*)",
              "stiffness k* of a torsional spring at the rocker's ground pivot (moment per radian of the "
              "rocker's turn from its free angle), units of rho A L^3 omega_b^2", low=0.0,
              units="rhoA L^3 omega_b^2", continuable=True, symbol=rocker_stiffness, axis="rocker spring k*"),
    Parameter("rocker_free_angle", "real", 0.0, "rocker_free_angle (rocker spring's free angle, rad)",
              "the rocker angle (rad, counter-clockwise from the X axis) at which the rocker's spring is "
              "relaxed", units="rad", symbol=rocker_free_angle),
    Parameter("rocker_mass", "real", 0.0, "rocker_mass (rocker's mass m_r*)",
              "mass m_r* = m_r/(rho A L) of the rigid rocker (0: a massless rocker, the tip's mass being "
              "ms)", low=0.0, units="rhoA L", continuable=True, symbol=rocker_mass, axis="rocker mass m_r*"),
    Parameter("rocker_centre", "real", 0.5, "rocker_centre (rocker's centre of mass, fraction of c)",
              "where the rigid rocker's centre of mass G lies on the line from its ground pivot D to its "
              "tip: DG = rocker_centre * c (0.5: a uniform bar; 1: at the tip; negative: behind the pivot, "
              "a counterweight)", units="1", continuable=True, symbol=rocker_centre,
              axis="rocker centre DG/c"),
    Parameter("rocker_inertia", "real", 0.0, "rocker_inertia (rocker's J_G* about its centre of mass)",
              "moment of inertia J_G* of the rigid rocker about its centre of mass (a uniform bar: "
              "m_r c^2 / 12), units of rho A L^3; about the pivot it is J_G + m_r (rocker_centre c)^2",
              low=0.0, units="rhoA L^3", continuable=True, symbol=rocker_inertia,
              axis="rocker inertia J_G*"),
    Parameter("rocker_elements", "count", 0, "rocker_elements (flexible rocker's elements)",
              "number of elements of a flexible rocker (0: the rocker is rigid); a flexible rocker is a beam "
              "of the coupler's strain model, pinned at its ground pivot and to the coupler's end, its section "
              "rocker_density, rocker_bending, rocker_axial", low=0),
    Parameter("rocker_density", "real", 1.0, "rocker_density (flexible rocker's rho A over the coupler's)",
              "mass per length of a flexible rocker over the coupler's, rho A_r / (rho A)", low=0.0,
              low_open=True, units="1", continuable=True, symbol=rocker_density, axis="rocker rho A_r/(rho A)"),
    Parameter("rocker_bending", "real", 1.0, "rocker_bending (flexible rocker's E I over the coupler's)",
              "bending stiffness of a flexible rocker over the coupler's, E I_r / (E I)", low=0.0,
              low_open=True, units="1", continuable=True, symbol=rocker_bending, axis="rocker E I_r/(E I)"),
    Parameter("rocker_axial", "real", 1.0, "rocker_axial (flexible rocker's E A over the coupler's)",
              "axial stiffness of a flexible rocker over the coupler's, E A_r / (E A)", low=0.0,
              low_open=True, units="1", continuable=True, symbol=rocker_axial, axis="rocker E A_r/(E A)"),
    Parameter("crank_mass", "real", 0.0, "crank_mass (crank's mass m_c*)",
              "mass m_c* = m_c/(rho A L) of the rigid crank (0: its mass and inertia left out, or held in a "
              "motor's `inertia`); it changes the driving torque and the crank bearing's force, not the rod's "
              "motion under a prescribed crank", low=0.0, units="rhoA L", continuable=True, symbol=crank_mass,
              axis="crank mass m_c*"),
    Parameter("crank_centre", "real", 0.5, "crank_centre (crank's centre of mass, fraction of a)",
              "where the rigid crank's centre of mass G lies on the line from its axis O to the crank pin A: "
              "OG = crank_centre * a (0.5: a uniform bar; 0: balanced; negative: a counterweight)", units="1",
              continuable=True, symbol=crank_centre, axis="crank centre OG/a"),
    Parameter("crank_inertia", "real", 0.0, "crank_inertia (crank's J_G* about its centre of mass)",
              "moment of inertia J_G* of the rigid crank about its centre of mass (a uniform bar: m_c a^2 / "
              "12), units of rho A L^3; about its axis it is J_G + m_c (crank_centre a)^2.  A motor's `inertia` "
              "then holds the rotor's and flywheel's only", low=0.0, units="rhoA L^3", continuable=True,
              symbol=crank_inertia, axis="crank inertia J_G*"),
    Parameter("cam_height", "real", 0.02, "cam_height (cam track height h/L)",
              "height h/L of a cam track's waves, Y = e + h cos(2 pi X / lambda)", low=0.0, units="L",
              continuable=True, symbol=guides.cam_height, axis="cam height h/L"),
    Parameter("cam_wavelength", "real", 0.25, "cam_wavelength (cam track wavelength lambda/L)",
              "wavelength lambda/L of a cam track's waves", low=0.0, low_open=True, units="L",
              symbol=guides.cam_wavelength),
    Parameter("inclination", "real", 0.0, "inclination (incline's angle alpha, rad)",
              "angle alpha of an inclined guide to the X axis (counter-clockwise); the line lies at the "
              "distance offset from the crank's axis", units="rad", continuable=True,
              symbol=guides.inclination, axis="inclination alpha (rad)"),
    Parameter("motion", "choice", "constant", "motion",
              "the crank's prescribed motion: constant speed, a run-up from omega0 to omega over "
              "`ramp` revolutions, or a cyclic fluctuation omega (1 + k sin(j theta)); or motor: the crank "
              "driven by a motor of limited torque (its angle a degree of freedom)", owner="run",
              cli="crank", choices=motions.MOTIONS),
    Parameter("omega", "real", 0.8, "omega (crank speed Omega*)",
              "crank speed Omega* = Omega/omega_b (constant speed; a run-up's final speed; a "
              "fluctuating crank's nominal speed; 0: a crank at rest)", owner="run", low=0.0,
              units="omega_b", continuable=True, symbol=s.omega, axis="Omega*", si="crank_speed"),
    Parameter("omega0", "real", 0.2, "omega0 (run-up start speed)", "a run-up's start speed Omega0*",
              owner="run", low=0.0, low_open=True, units="omega_b", symbol=s.omega0),
    Parameter("ramp", "real", 20.0, "ramp (run-up revolutions)",
              "crank revolutions over which a run-up's speed rises", owner="run", low=0.0,
              low_open=True, units="rev", symbol=s.ramp),
    Parameter("fluctuation", "real", 0.1, "fluctuation (speed fluctuation k)",
              "relative amplitude k of a cyclic speed fluctuation", owner="run",
              low=-1.0, high=1.0, low_open=True, high_open=True, continuable=True, symbol=s.k_fl,
              axis="speed fluctuation k"),
    Parameter("order", "count", 1, "order (speed fluctuation order j)",
              "order j of a cyclic speed fluctuation (j per revolution)",
              owner="run", low=1, symbol=s.j_fl),
    Parameter("theta0", "real", 0.0, "theta0 (crank angle at t = 0, rad)",
              "the crank angle at t = 0 (rad, counter-clockwise from the X axis); the rod starts in "
              "the rigid mechanism's position at that angle", owner="run", units="rad",
              symbol=motions.theta0),
    Parameter("stall_torque", "real", 0.05, "stall_torque (motor's stall torque T_stall*)",
              "a motor's torque at rest T_stall* (the linear law T_m = T_stall (1 - thetad / Omega_nl)), "
              "units of rho A L^3 omega_b^2", owner="run", low=0.0, low_open=True, units="rhoA L^3 omega_b^2",
              continuable=True, symbol=motions.stall_torque, axis="stall torque T_stall*"),
    Parameter("no_load_speed", "real", 1.0, "no_load_speed (motor's no-load speed Omega_nl*)",
              "a motor's no-load speed Omega_nl* (where its torque vanishes), units of omega_b", owner="run",
              low=0.0, low_open=True, units="omega_b", continuable=True, symbol=motions.no_load_speed,
              axis="no-load speed Omega_nl*"),
    Parameter("inertia", "real", 0.05, "inertia (crank, rotor and flywheel J*)",
              "the moment of inertia J* of the crank, the motor's rotor and any flywheel about the crank "
              "axis (the rod and end mass not included: they are modelled; the crank's not included either "
              "when declared as crank_mass, crank_inertia), units of rho A L^3", owner="run",
              low=0.0, low_open=True, units="rhoA L^3", continuable=True, symbol=motions.inertia,
              axis="inertia J*"),
    Parameter("load_torque", "real", 0.0, "load_torque (constant load torque T_load*)",
              "a constant torque T_load* resisting the motor-driven crank (friction, a useful load), "
              "units of rho A L^3 omega_b^2", owner="run", units="rhoA L^3 omega_b^2", continuable=True,
              symbol=motions.load_torque, axis="load torque T_load*"),
    Parameter("torque_curve", "curve", ((0.0, 1.0), (1.0, 0.0)), "torque_curve (motor's per-unit torque-speed curve)",
              "a motor's torque-speed curve in per-unit, T_m / T_stall against thetad / Omega_nl, as pairs S:F "
              "through 0:1 and 1:0 (cubic Hermite, shape-preserving, between them; linear beyond); the default "
              "0:1,1:0 is the linear law", owner="run", metavar="S:F,S:F,...", axis="torque curve s:f"),
    Parameter("rotor_inertia", "real", 0.02, "rotor_inertia (motor rotor's J_rotor*)",
              "the moment of inertia J_rotor* of a motor's rotor behind a flexible shaft (motion shaft; the "
              "crank side's is `inertia`), units of rho A L^3", owner="run", low=0.0, low_open=True,
              units="rhoA L^3", continuable=True, symbol=motions.rotor_inertia, axis="rotor inertia J_rotor*"),
    Parameter("shaft_stiffness", "real", 1.0, "shaft_stiffness (shaft's torsional stiffness k*)",
              "the torsional stiffness k* of the shaft between a motor's rotor and the crank (motion shaft), "
              "units of rho A L^3 omega_b^2 per rad", owner="run", low=0.0, low_open=True,
              units="rhoA L^3 omega_b^2", continuable=True, symbol=motions.shaft_stiffness,
              axis="shaft stiffness k*"),
    Parameter("shaft_damping", "real", 0.0, "shaft_damping (shaft's torsional damping c*)",
              "the torsional damping c* of the shaft between a motor's rotor and the crank (motion shaft), "
              "units of rho A L^3 omega_b per rad", owner="run", low=0.0, units="rhoA L^3 omega_b",
              continuable=True, symbol=motions.shaft_damping, axis="shaft damping c*"),
    Parameter("initial_speed", "real", 0.0, "initial_speed (motor-driven crank's speed at t = 0)",
              "the crank speed at t = 0 of a motor-driven crank (0: a start from rest), units of omega_b",
              owner="run", low=0.0, units="omega_b", symbol=motions.initial_speed),
    Parameter("n_elements", "count", 16, "n_elements", "number of rod elements", owner="run", low=1,
              cli="elements"),
    Parameter("steps_per_rev", "count", 100, "steps_per_rev", "time steps per crank revolution",
              owner="run", low=4),
    Parameter("integrator", "choice", "newton", "integrator",
              "newton: Newton iterations on the exact tangent, its factorization reused while they "
              "converge fast; full-newton: the tangent refreshed at every iteration; one-pass: the "
              "paper's eqs. (34)-(39)", owner="run", choices=("newton", "full-newton", "one-pass")),
    Parameter("rho_inf", "real", 0.8, "rho_inf (time scheme's spectral radius at infinite frequency)",
              "the time scheme: 1 is Newmark's trapezoidal rule (beta 1/4, gamma 1/2, the paper's: no "
              "numerical damping); below 1, generalized-alpha (Chung & Hulbert), second order, which "
              "damps what a step cannot resolve: a mode's step factor tends to -rho_inf at high "
              "frequency", owner="run", low=0.0, high=1.0, cli="rho-inf"),
)

# The crank's (nominal) speed: simulate's `omega` argument, the default continued parameter; the
# crank's angle at t = 0 (where a frozen mechanism is frozen).
CRANK_SPEED = "omega"
CRANK_ANGLE = "theta0"
# The units that are parameters: the radius of gyration r = eps L (outputs in units of r, e.g. v*).
UNIT_PARAMETERS = {"r": "eps"}

# Indicators usable in coefficient formulas: 1 when a case's option has a value, else 0
# (INDICATORS: symbol -> (option, value)), and 1 when the audit switches a term group off.
INDICATORS = {}


def indicator(option, value):
    """The symbol that is 1 when the case's option `option` has `value`, else 0."""
    symbol = sp.Symbol(f"with_{option}" if value is True else f"{option}_{value}")
    INDICATORS[symbol] = (option, value)
    return symbol


with_rotary_inertia = indicator("rotary_inertia", True)
switched_off = {g: sp.Symbol(f"off_{g}") for g in s.SWITCHABLE_GROUPS}
eps = s.eps

# crankgen's units: length L, mass rho A L, time 1/omega_b with omega_b = (pi/L)^2 sqrt(EI/(rho A)),
# so rho A = 1, E I = 1/pi^4, E A = E I / r^2 = 1/(pi^4 eps^2), rho I = rho A r^2 = eps^2.
COEFFICIENTS = {
    s.rhoA: sp.Integer(1),
    s.rhoI: with_rotary_inertia * eps**2,
    s.EA: 1 / (sp.pi**4 * eps**2),
    s.EI: 1 / sp.pi**4,
    s.mu: s.mu,
    s.ms: s.ms,
    s.gX: s.gX,
    s.gY: s.gY,
    **{w: 1 - switched_off[g] for g, w in s.WEIGHT.items()},
    rocker_stiffness: rocker_stiffness,
    rocker_free_angle: rocker_free_angle,
    s.c: s.c,
    rocker_tip_mass: (rocker_inertia + rocker_mass * (rocker_centre * s.c) ** 2) / s.c**2,
    rocker_tip_weight[0]: rocker_mass * rocker_centre * s.gX,
    rocker_tip_weight[1]: rocker_mass * rocker_centre * s.gY,
}
# The coefficients of another flexible body's elements (the same kernels as the coupler's): the
# coupler's with these replaced.  A flexible rocker: its rho A, E I and E A in the coupler's units, and
# rho I = rho A_r r_r^2 with r_r^2 = I_r / A_r = (E I_r / E A_r) eps^2 (one material).
BODY_COEFFICIENTS = {
    "rocker": {
        s.rhoA: rocker_density,
        s.rhoI: with_rotary_inertia * eps**2 * rocker_density * rocker_bending / rocker_axial,
        s.EA: rocker_axial / (sp.pi**4 * eps**2),
        s.EI: rocker_bending / sp.pi**4,
    },
}


# ----------------------------------------------------------------------------------------------
# Term families
# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Term:
    """An element residual (6-vector in q, qd, qdd of eq. 14) and, where the printed one-pass scheme
    of eq. (37) iterates with another stiffness than the exact tangent, that `printed_stiffness`
    ("exact": dr/dq; "none": no stiffness; a 6x6 Matrix: the printed secant).  `tangents`: (K, C, M)
    when the build derived them itself (at the points of a quadrature rule, derive/quadrature.py);
    None: code generation differentiates the residual."""

    residual: sp.Matrix
    printed_stiffness: object = "exact"
    tangents: tuple = None
    definitions: tuple = ()      # stages of (symbol, expression) the terms are written in (quadrature)


@dataclass(frozen=True)
class Energy:
    """An energy (or Rayleigh dissipation) function per element, built by `build()` as an
    expression in q, qd, geo, coef, kin (the end node's energies on the last element's slots): its
    kernel `name` in generated/energy.py serves the energy balance and the outputs."""

    name: str
    doc: str
    build: Callable


@dataclass(frozen=True)
class Variant(records.Variant):
    """A variant of a term family (crankgen.declaration.records.Variant: name, option values `when`, doc,
    switchable groups, energy) with `build`, () -> Term, its element residual; `energy` is the
    Energy it derives from (None: none)."""

    build: Callable = None

    def __post_init__(self):
        if not (isinstance(self.doc, str) and callable(self.build)):
            raise TypeError(f"Variant {self.name!r}: Variant(name, when, doc, groups, energy, build=...)")


@dataclass(frozen=True)
class Family(records.Family):
    """A term family (crankgen.declaration.records.Family: name, part, doc, energy_kind, variants,
    vanishes_with): part "rod" acts on every element, "end" on the end node (the end mass)."""


def _weighted(residual, variables, axial_rows, groups):
    """residual with each switchable group's part multiplied by its weight (derive/groups.py)."""
    parts = group_vector(sp.Matrix(residual), variables, axial_rows)
    total = sp.zeros(residual.shape[0], 1)
    for group, part in parts.items():
        total += (s.WEIGHT[group] if group in groups else 1) * sp.Matrix(part)
    return total.applyfunc(sp.expand)


# ----------------------------------------------------------------------------------------------
# The DOF map: the nodes' components (derive/symbols.py NODE), the constraints condensed out of the
# equations, the natural size of each component
# ----------------------------------------------------------------------------------------------

BODIES = (
    records.Body("crank", "rigid", "the crank, from its axis O to the crank pin A (length a*): turned by the "
                 "prescribed motion or a driven motion's crank co-ordinate", "crank angle"),
    records.Body("rod", "flexible", "the connecting rod (a four-bar's coupler): an Euler-Bernoulli beam of "
                 "n_elements elements, its nodes' (u, v, psi, chi) in the moving frame of the rigid linkage's "
                 "chord A-B (chi = u_x only on the exact rod, whose u is cubic)", "chord", node=s.NODE,
                 elements="n_elements", conditional=(("chi", "approach", (EXACT,)),)),
    records.Body("end", "rigid", "the end mass ms* at B on the guide: a slider on a line, a four-bar's rocker "
                 "tip on its circle", "guide"),
    records.Body("rocker", "flexible", "a four-bar's flexible rocker (rocker_elements > 0): a beam from its "
                 "ground pivot D to its tip B, its nodes' (u, v, psi, chi) in the frame of the rigid rocker "
                 "DB (origin D, axis at the rocker angle beta)", "rocker", node=s.NODE,
                 elements="rocker_elements", conditional=(("chi", "approach", (EXACT,)),), length="c"),
)
# The kinematics of a flexible body's frame, as the entries of the mechanism's kinematics vector
# (derive/symbols.py KINEMATICS) that differ: the rod's kernels read a frame whose origin is the
# crank pin a e_r and whose axis e_i = (cos phi, -sin phi); the rocker's origin is its fixed pivot
# (a = 0: the crank terms vanish, gravity's potential changes by a constant) and its axis the
# rigid rocker's (cos beta, sin beta), phi_r = -beta.
BODY_FRAMES = {"rocker": {s.a: sp.Integer(0), s.phi: -s.beta, s.phid: -s.betad, s.phidd: -s.betadd}}
CONSTRAINTS = (
    records.Constraint("pin", 0, ("u", "v"), "the crank pin holds the rod's first node: u = v = 0",
                       body="rod", joint="crank"),
    records.Constraint("end", -1, ("u", "v"), "the guide holds the rod's last node: (u, v) = g(s, t), the "
                       "end map of the case's guide (derive/guides.py), one reduced co-ordinate s",
                       reduced=("s",), map="end_map", body="rod", joint="end", excludes="rocker"),
    records.Constraint("ground", 0, ("u", "v"), "the ground pivot D holds a flexible rocker's first node: "
                       "u = v = 0", body="rocker", joint="end", requires="rocker"),
    records.Constraint("tip", -1, ("u", "v"), "a flexible rocker's tip holds the rod's last node: equal "
                       "positions at B, u e_i + v e_j = u_r e_ir + v_r e_jr, the reduced co-ordinates the "
                       "rocker's last node's (u_r, v_r) (the end map of the circle guide with a flexible "
                       "rocker, end_map_circle_flexible)", reduced=("u", "v"), map="end_map", body="rod",
                       joint="rocker", requires="rocker"),
)
END = CONSTRAINTS[1]
# natural size of each component of a node (units of L) for Newton's scaled increments: the paper's
# scaled outputs u* = u / eps^2, v* = v / eps
NATURAL_SIZES = {"u": eps**2, "v": eps, "psi": eps, "chi": eps**2}

SLIDER_ROWS = s.element_slots(1, END.eliminated)   # the end node's (u, v) in the last element's vector
_ON_LAST_ELEMENT = {**dict(zip(s.qs, [s.q[k] for k in SLIDER_ROWS])),
                    **dict(zip(s.qsd, [s.qd[k] for k in SLIDER_ROWS])),
                    **dict(zip(s.qsdd, [s.qdd[k] for k in SLIDER_ROWS])), s.L: s.x0 + s.l}


def on_last_element(vector2):
    """An end-mass vector on (u, v)_{n+1} as a vector of the last element (L = x0 + l)."""
    out = sp.zeros(s.ELEMENT_DOFS, 1)
    for k, row in enumerate(SLIDER_ROWS):
        out[row] = sp.expand(vector2[k].subs(_ON_LAST_ELEMENT))
    return out


INERTIA_GROUPS = ("gyroscopic", "phidd", "centrifugal")
ELASTIC_GROUPS = ("cubic_axial", "cubic_transverse", "quartic")


def _on_last_element(energy):
    return lambda: energy().subs(_ON_LAST_ELEMENT)


ROD_KINETIC = Energy("rod_kinetic_energy", "Element kinetic energy T_i of the rod, eqs. (4)-(5).",
                     en.rod_kinetic_energy)
SLIDER_KINETIC = Energy("slider_kinetic_energy", "Kinetic energy T_s of the end mass, eqs. (6)-(7), on "
                        "the last element.", _on_last_element(en.slider_kinetic_energy))
ROD_GRAVITY = Energy("rod_gravity_potential", "Element potential of gravity V_i.", en.rod_gravity_potential)
ROD_GRAVITY_EXACT = Energy("rod_gravity_potential_exact", "Element potential of gravity V_i on the exact rod's "
                           "cubic u.", lambda: en.rod_gravity_potential(approach=EXACT))
SLIDER_GRAVITY = Energy("slider_gravity_potential", "Potential of gravity on the end mass, on the last "
                        "element.", _on_last_element(en.slider_gravity_potential))


def rocker_angle(qs=s.qs):
    """The rocker angle gamma: the rigid one, beta, plus the turn from the rigid tip D + c (cos beta,
    sin beta) to the end node, displaced by (u, v) on (e_i, e_j) (the guide keeps it on the
    rocker's circle)."""
    dX = qs[0] * sp.cos(s.phi) + qs[1] * sp.sin(s.phi)
    dY = -qs[0] * sp.sin(s.phi) + qs[1] * sp.cos(s.phi)
    turn = sp.atan2(sp.cos(s.beta) * dY - sp.sin(s.beta) * dX, s.c + sp.cos(s.beta) * dX + sp.sin(s.beta) * dY)
    return s.beta + turn


def rocker_spring_potential(qs=s.qs):
    """V = k (gamma - gamma_free)^2 / 2 of the torsional spring at the rocker's pivot D."""
    return rocker_stiffness * (rocker_angle(qs) - rocker_free_angle) ** 2 / 2


def rocker_kinetic_energy(qs=s.qs, qsd=s.qsd):
    """T_r = J_D gamma_dot^2 / 2 of the rigid rocker turning about its ground pivot D (J_D = J_G +
    m_r (k c)^2): the tip B moves on the rocker's circle at the speed c gamma_dot (the end map keeps
    it there), so T_r is the kinetic energy of a point mass J_D / c^2 at B, eq. (7)'s velocity."""
    return en.point_mass_kinetic_energy(rocker_tip_mass, qs, qsd)


def rocker_gravity_potential(qs=s.qs):
    """V_r = -m_r g . (G - D) of the rigid rocker's weight: its centre of mass G lies at k (B - D) on
    the line from the pivot to the tip, so V_r is the potential of a point mass m_r k at B (the
    constant +m_r k g . D left out)."""
    return en.point_mass_gravity_potential(rocker_tip_weight, qs)


ROCKER_SPRING = Energy("rocker_spring_potential", "Potential of the torsional spring at the rocker's "
                       "pivot, on the last element.", _on_last_element(rocker_spring_potential))
ROCKER_KINETIC = Energy("rocker_kinetic_energy", "Kinetic energy of the rigid rocker turning about its "
                        "pivot, on the last element.", _on_last_element(rocker_kinetic_energy))
ROCKER_GRAVITY = Energy("rocker_gravity_potential", "Potential of gravity on the rigid rocker, on the "
                        "last element.", _on_last_element(rocker_gravity_potential))


def _strain_energy(ap, averaged):
    suffix = "_averaged" if averaged else ""
    build = (lambda: en.strain_energy_averaged(ap)) if averaged else (lambda: en.strain_energy(ap))
    return Energy(f"strain_energy_{ap}{suffix}",
                  f"Element strain energy U_i of approach {ap}{', element-mean membrane strain' if averaged else ''}.",
                  build)


def _dissipation(ap, averaged):
    suffix = "_averaged" if averaged else ""
    build = ((lambda: en.kelvin_voigt_dissipation_averaged(ap)) if averaged
             else (lambda: en.kelvin_voigt_dissipation(ap)))
    return Energy(f"dissipation_{ap}{suffix}",
                  f"Kelvin-Voigt Rayleigh dissipation function D of approach {ap}"
                  f"{', element-mean membrane strain rate' if averaged else ''}.", build)


STRAIN_ENERGY = {(ap, avg): _strain_energy(ap, avg) for ap in en.APPROACHES for avg in (False, True)
                 if not (ap == "C" and avg)}
DISSIPATION = {(ap, avg): _dissipation(ap, avg) for ap in en.APPROACHES for avg in (False, True)
               if not (ap == "C" and avg)}


def rod_inertia_lagrange():
    r = kinetic_residual(en.rod_kinetic_energy(), s.q, s.qd, s.qdd)
    return Term(_weighted(r, ELEMENT_VARS, ROD_AXIAL_ROWS, INERTIA_GROUPS))


def rod_inertia_paper():
    return Term(printed.rod_kinetic_residual(printed.printed_matrices(corrected=True)))


def elastic_lagrange(approach, averaged):
    U = en.strain_energy_averaged(approach) if averaged else en.strain_energy(approach)
    groups = ELASTIC_GROUPS if approach == "A" else ()
    return lambda: Term(_weighted(gradient(U, s.q), ELEMENT_VARS, ROD_AXIAL_ROWS, groups))


def elastic_paper(approach):
    def build():
        r, k_secant = printed.rod_elastic_residual(approach, printed.printed_matrices(corrected=True))
        return Term(r, k_secant)
    return build


def kelvin_voigt(approach, averaged):
    D = (en.kelvin_voigt_dissipation_averaged if averaged else en.kelvin_voigt_dissipation)(approach)
    return lambda: Term(gradient(D, s.qd), "none")


def damping_paper(approach):
    return lambda: Term(printed.rod_damping_residual(approach, printed.printed_matrices(corrected=True)),
                        "none")


def rod_gravity(approach=None):
    return lambda: Term(gradient(en.rod_gravity_potential(approach=approach), s.q))


# ---- the geometrically exact rod: element integrals by quadrature ---------------------------------
#
# The exact strain, curvature and section rotation are not polynomials in the nodal values: their
# element integrals use the rule declared here (its degree is a choice, like FFCx's
# quadrature_degree).  Degree 5, the 3-point Gauss-Legendre rule, integrates every term of the
# small-rotation limit that is quadratic in the deformation exactly (v_x^2 of the mean stretch,
# v_xx^2, psi'^2 of the rotary inertia: degree 4); the centre line's kinetic energy, a polynomial, is
# integrated in closed form.  Residuals and tangents are derived at the points (derive/quadrature.py).
EXACT_RULE = quadrature.gauss(degree=5)


def by_quadrature(kind, element_energy, rule=EXACT_RULE):
    """A build whose residual and tangents derive, at the points of `rule`, from the element energy
    element_energy(space) of kind "potential" (dE/dq), "dissipation" (dE/dqd) or "kinetic"."""
    def build():
        space = _exact_space(rule)
        r, K, C, M, definitions = space.element_terms(space.generalized_forces(kind, element_energy(space)))
        return Term(r, "exact", (K, C, M), definitions)      # never in the printed iteration (EXCLUSIONS)
    return build


def rod_inertia_exact(rule=EXACT_RULE):
    """The exact rod's inertia forces: the centre line's (the same exact terms as
    rod_inertia_lagrange's rho A part, closed form, with their switchable groups) and the exact
    section rotation's rho I (theta'' - phidd) forces by quadrature, the phidd part weighted as
    the phidd group."""
    def build():
        f = dict(en.fields(s.q, s.qd, EXACT), x=s.x0 + s.l * s.zeta)
        T = integrate_centre_line(f)
        r = _weighted(kinetic_residual(T, s.q, s.qd, s.qdd), ELEMENT_VARS, ROD_AXIAL_ROWS, INERTIA_GROUPS)
        closed = (jacobian(r, s.q), jacobian(r, s.qd), jacobian(r, s.qdd))
        space = _exact_space(rule)
        forces = space.generalized_forces("kinetic", en.element_rotary_kinetic_energy(space))
        weighted = {}
        for p, force in forces.items():
            coupling = sp.diff(force, s.phidd)
            assert not coupling.has(s.phidd)
            weighted[p] = force.subs(s.phidd, 0) + s.WEIGHT["phidd"] * s.phidd * coupling
        r_q, K, C, M, definitions = space.element_terms(weighted)
        return Term(r + r_q, "exact", tuple(a + b for a, b in zip(closed, (K, C, M))), definitions)
    return build


def integrate_centre_line(f):
    """Element kinetic energy of the centre line, closed form."""
    return integrate_element(en.centre_line_kinetic_energy_density(f))


def _exact_space(rule=EXACT_RULE):
    """The exact rod's point space: its cubic u (energies.field_columns), strain, rotation, curvature."""
    return quadrature.PointSpace(rule, en.QUANTITIES, en.ELEMENT_FIELDS, en.POINT_FIELDS, en.field_columns(EXACT))


def _exact_kinetic_energy():
    space = _exact_space()
    f = dict(en.fields(s.q, s.qd, EXACT), x=s.x0 + s.l * s.zeta)
    return integrate_centre_line(f) + space.in_nodal(en.element_rotary_kinetic_energy(space))


def _exact_energy(element_energy):
    def build():
        space = _exact_space()
        return space.in_nodal(element_energy(space, EXACT))
    return build


CLASSICAL = ("A", "B", "C")      # the approaches of the paper's strain measure (closed-form integrals)
EXACT_KINETIC = Energy("rod_kinetic_energy_exact", "Element kinetic energy of the geometrically exact rod "
                       f"(centre line and exact section rotation; the rotation by {EXACT_RULE.text} "
                       "quadrature).", _exact_kinetic_energy)
EXACT_STRAIN_ENERGY = Energy("strain_energy_exact", "Element strain energy of the exact rod, by "
                             f"{EXACT_RULE.text} quadrature.", _exact_energy(en.element_strain_energy))
EXACT_DISSIPATION = Energy("dissipation_exact", "Kelvin-Voigt Rayleigh dissipation function of the exact rod, "
                           f"by {EXACT_RULE.text} quadrature.", _exact_energy(en.element_dissipation))


def slider_inertia_lagrange():
    r = kinetic_residual(en.slider_kinetic_energy(), s.qs, s.qsd, s.qsdd)
    return Term(on_last_element(_weighted(r, SLIDER_VARS, SLIDER_AXIAL_ROWS, INERTIA_GROUPS)))


def slider_inertia_paper():
    return Term(on_last_element(printed.slider_kinetic_residual(printed.printed_matrices(corrected=True))))


def slider_damping_paper():
    return Term(on_last_element(printed.slider_damping_residual(printed.printed_matrices(corrected=True))),
                "none")


def slider_gravity():
    return Term(on_last_element(gradient(en.slider_gravity_potential(), s.qs)))


def rocker_spring():
    return Term(on_last_element(gradient(rocker_spring_potential(), s.qs)))


def rocker_inertia_lagrange():
    return Term(on_last_element(kinetic_residual(rocker_kinetic_energy(), s.qs, s.qsd, s.qsdd)))


def rocker_gravity():
    return Term(on_last_element(gradient(rocker_gravity_potential(), s.qs)))


def _elastic_variants():
    out = []
    for ap in ("A", "B"):
        for membrane, averaged in (("pointwise", False), ("averaged", True)):
            suffix = "_averaged" if averaged else ""
            out.append(Variant(f"lagrange_{ap}{suffix}",
                               {"formulation": "lagrange", "approach": ap, "membrane": membrane},
                               f"dU/dq of approach {ap}, {membrane} membrane strain",
                               ELASTIC_GROUPS if ap == "A" else (), STRAIN_ENERGY[ap, averaged],
                               build=elastic_lagrange(ap, averaged)))
    out.append(Variant("lagrange_C", {"formulation": "lagrange", "approach": "C"},
                       "dU/dq of approach C (linear strain)", energy=STRAIN_ENERGY["C", False],
                       build=elastic_lagrange("C", False)))
    out.append(Variant("lagrange_exact", {"formulation": "lagrange", "approach": EXACT},
                       f"dU/dq of the geometrically exact rod, by {EXACT_RULE.text} quadrature",
                       energy=EXACT_STRAIN_ENERGY, quadrature=EXACT_RULE,
                       build=by_quadrature("potential", lambda space: en.element_strain_energy(space, EXACT))))
    for ap in ("A", "B", "C"):
        out.append(Variant(f"paper_{ap}", {"formulation": "paper", "approach": ap},
                           f"printed (k_uu + k_psipsi + k_pvv + k_non) q of approach {ap}, P_i of "
                           "eq. (B9) taken at q; printed secant for eq. (37)",
                           energy=STRAIN_ENERGY[ap, False],       # nominal: the printed form has no potential
                           build=elastic_paper(ap)))
    return tuple(out)


def _damping_variants():
    out = []
    for ap in ("A", "B"):
        for membrane, averaged in (("pointwise", False), ("averaged", True)):
            suffix = "_averaged" if averaged else ""
            out.append(Variant(f"kelvin_voigt_{ap}{suffix}",
                               {"damping": "kelvin-voigt", "approach": ap, "membrane": membrane},
                               f"dD/dqd, strain-rate damping of approach {ap}, {membrane} membrane strain",
                               energy=DISSIPATION[ap, averaged], build=kelvin_voigt(ap, averaged)))
    out.append(Variant("kelvin_voigt_C", {"damping": "kelvin-voigt", "approach": "C"},
                       "dD/dqd, strain-rate damping of approach C", energy=DISSIPATION["C", False],
                       build=kelvin_voigt("C", False)))
    out.append(Variant("kelvin_voigt_exact", {"damping": "kelvin-voigt", "approach": EXACT},
                       "dD/dqd, strain-rate damping of the exact strain and curvature, by "
                       f"{EXACT_RULE.text} quadrature", energy=EXACT_DISSIPATION, quadrature=EXACT_RULE,
                       build=by_quadrature("dissipation", lambda space: en.element_dissipation(space, EXACT))))
    for ap in ("A", "B", "C"):
        out.append(Variant(f"paper_{ap}", {"damping": "paper", "approach": ap},
                           f"printed damping mu (K_lin + K_non) qd of approach {ap}, eq. (24)",
                           build=damping_paper(ap)))
    return tuple(out)


FAMILIES = (
    Family("inertia", "rod", "inertia forces of the rod element, from T_c of eqs. (4)-(5)", "kinetic", (
        Variant("lagrange", {"formulation": "lagrange", "approach": CLASSICAL}, "d/dt dT/dqd - dT/dq, exact",
                INERTIA_GROUPS, ROD_KINETIC, build=rod_inertia_lagrange),
        Variant("lagrange_exact", {"formulation": "lagrange", "approach": EXACT},
                "d/dt dT/dqd - dT/dq with the exact section rotation (rho I part by "
                f"{EXACT_RULE.text} quadrature)", INERTIA_GROUPS, EXACT_KINETIC, quadrature=EXACT_RULE,
                build=rod_inertia_exact()),
        Variant("paper", {"formulation": "paper"}, "printed m1 qdd - m2 q - (m4 - d/dt m3), eqs. (20)-(25)",
                energy=ROD_KINETIC, build=rod_inertia_paper),
    )),
    Family("elastic", "rod", "internal elastic force of the rod element, from U_c of eq. (2)", "potential",
           _elastic_variants()),
    Family("dissipation", "rod", "damping force of the rod element", "dissipation", _damping_variants()),
    Family("gravity", "rod", "weight of the rod element, dV/dq with V = -int rho A g.R dx", "potential", (
        Variant("uniform", {"approach": CLASSICAL}, "consistent load vector of a uniform gravity field",
                energy=ROD_GRAVITY, build=rod_gravity()),
        Variant("uniform_exact", {"approach": EXACT}, "consistent load vector of a uniform gravity field on "
                "the exact rod's cubic u", energy=ROD_GRAVITY_EXACT, build=rod_gravity(EXACT)),
    ), vanishes_with=("gX", "gY")),
    Family("slider_inertia", "end", "inertia forces of the slider on (u, v) of the last node, eqs. (6)-(7)", "kinetic", (
        Variant("lagrange", {"formulation": "lagrange"}, "d/dt dT_s/dqd - dT_s/dq, exact", INERTIA_GROUPS,
                SLIDER_KINETIC, build=slider_inertia_lagrange),
        Variant("paper", {"formulation": "paper"}, "printed m_s1, m_s2, m_s3, m_s4 terms of eqs. (27)-(29)",
                energy=SLIDER_KINETIC, build=slider_inertia_paper),
    )),
    Family("slider_dissipation", "end", "damping force of the slider", "dissipation", (
        Variant("paper", {"damping": "paper"}, "printed -mu m_s2 qd of eqs. (24), (28)",
                build=slider_damping_paper),
    )),
    Family("slider_gravity", "end", "weight of the slider, dV_s/dq with V_s = -m_s g.R_s", "potential", (
        Variant("uniform", {}, "gravity on the slider; the guide carries its normal part",
                energy=SLIDER_GRAVITY, build=slider_gravity),
    ), vanishes_with=("gX", "gY")),
    Family("rocker_spring", "end", "moment of a torsional spring at the rocker's ground pivot on the "
           "rocker's tip", "potential", (
        Variant("torsional", {}, "dV/dq, V = k (gamma - gamma_free)^2 / 2", energy=ROCKER_SPRING,
                build=rocker_spring),
    ), vanishes_with=("k_rocker",), body="rocker"),
    Family("rocker_inertia", "end", "inertia of the rigid rocker turning about its ground pivot, on the "
           "rocker's tip", "kinetic", (
        Variant("rigid", {}, "d/dt dT_r/dqd - dT_r/dq, T_r = J_D gamma_dot^2 / 2, exact (every "
                "formulation: the paper has no rocker)", energy=ROCKER_KINETIC, build=rocker_inertia_lagrange),
    ), vanishes_with=("m_rocker_tip",), body="rocker"),
    Family("rocker_gravity", "end", "weight of the rigid rocker, on the rocker's tip", "potential", (
        Variant("uniform", {}, "dV_r/dq, V_r = -m_r g . (G - D), a point mass m_r k at the tip",
                energy=ROCKER_GRAVITY, build=rocker_gravity),
    ), vanishes_with=("wX_rocker", "wY_rocker"), body="rocker"),
)
FAMILY = {f.name: f for f in FAMILIES}

# The option values under which the paper's one-pass scheme (eqs. 34-39) iterates with the printed
# matrices of eq. (37) (K_printed of the variants that declare one) instead of the exact tangent.
PRINTED_ITERATION = {"formulation": "paper"}


# ----------------------------------------------------------------------------------------------
# The end constraint (guide); the outputs are declared in derive/outputs.py
# ----------------------------------------------------------------------------------------------

# The curves the rod's end may travel on (derive/guides.py) and the crank's prescribed motions
# (derive/motions.py).
GUIDES = guides.GUIDES
MOTIONS = motions.MOTIONS
