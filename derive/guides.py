"""Stage 2c: the curve the rod's end travels on, the rigid closure it defines, and the end map.

The crank pin is at A = a (cos theta, sin theta) and the rod's rigid chord runs from A along
e_i = (cos phi, -sin phi) to the end point B = A + L e_i (L = 1; e_j = (sin phi, cos phi)).  A guide
is a curve C(beta) of the inertial frame that B must lie on; the closure

    A(theta) + e_i(phi) = C(beta)                                           (two equations)

fixes the rod angle phi and the guide co-ordinate beta of the rigid mechanism at every crank
angle.  Each guide gives that position analysis in closed form; the rates (phid, betad) and
accelerations (phidd, betadd) follow by differentiating the closure in time (linear equations,
solved here symbolically, with the crank's thetad and thetadd).

The end map.  The rod's end node is not rigid: its displacement (u, v) in the moving frame
(e_i, e_j) is written through one reduced co-ordinate s, the deviation of the guide co-ordinate
from the rigid one,

    (u, v) = g(s, t) = ( (C(beta + s) - C(beta)) . e_i,  (C(beta + s) - C(beta)) . e_j ),

so that the end stays on the guide exactly, whatever s.  g is rheonomic (beta and phi move), so
velocities and accelerations carry its time derivatives; the end map kernel returns g, its rates
and every derivative that the reduced equations (d'Alembert: r_s = g_s . r_end) and their Newton
tangent need (engine/elements.py, model.py).

- line: the straight guide Y = e (the slider-crank); beta is the slider's abscissa X and s its
  displacement along the guide; g = s (cos phi, sin phi) (eq. 26 holds identically).  The crank
  turns a full revolution iff a + |e| < L.
- circle: a rigid rocker of length c pivoted at D = (d, e): the four-bar linkage with a flexible
  coupler (the rocker massless unless given a mass, centre of mass and inertia: its own families); beta is the rocker angle and s its deviation.  Two closures exist; branch +1
  puts B on the counter-clockwise side of the line from A to D.  The crank turns a full
  revolution iff |L - c| < |D - A| < L + c at every crank angle; |D - A| runs from ||D| - a| to
  |D| + a, so iff ||D| - a| > |L - c| and |D| + a < L + c: a crank-rocker when |D| > a, a drag
  link (the rocker turns fully too) when the ground pivot lies inside the crank's circle.
"""

from dataclasses import dataclass

import sympy as sp
from sympy.simplify.fu import TR10i

from crankgen.declaration import records

from . import symbols as s
from .euler_lagrange import total_time_derivative

E_I = sp.Matrix([sp.cos(s.phi), -sp.sin(s.phi)])
E_J = sp.Matrix([sp.sin(s.phi), sp.cos(s.phi)])
PIN = sp.Matrix([s.a * sp.cos(s.theta), s.a * sp.sin(s.theta)])

# The end map's reduced co-ordinate and its rates.
sp_s, sp_sd, sp_sdd = sp.symbols("s sd sdd", real=True)
END_MAP_ROWS = ("q", "qd", "qdd", "g_s", "dqd_ds", "dqdd_ds", "dqdd_dsd", "g_ss")


@dataclass(frozen=True)
class Guide(records.Guide):
    """A guide (crankgen.declaration.records.Guide: name, title of its runtime record, parameters it reads
    besides a, doc, keyword aliases of its record) with its geometry: the curve C(beta) (a
    parametric curve), the step C(beta + s) - C(beta) written without cancellation for small s
    (None: the plain difference), the rigid position analysis phi(theta), beta(theta) in closed form
    or, when they are None, a `guess` of beta(theta) from which the closure |C(beta) - A(theta)| = L
    is solved by Newton at run time (closure: the residual, its derivative and phi are generated),
    the full-turn margins ((expression, text), ...: every expression > 0 iff the crank turns fully;
    a numerical closure is checked by sampling the crank angle instead) and the natural size of s
    (end_scale, in eps and the parameters: Newton's scaled increments)."""

    curve: sp.Matrix = None
    step: sp.Matrix = None
    phi: sp.Expr = None
    beta: sp.Expr = None
    margin: tuple = ()
    end_scale: sp.Expr = None
    pivot: sp.Matrix = None      # the ground pivot of a link carrying the end (a rocker), if any
    guess: sp.Expr = None        # without phi and beta: a starting value of beta(theta) for the
                                 # closure's Newton iterations at run time (a numerical closure)


def line():
    sin_phi = s.a * sp.sin(s.theta) - s.e
    phi = sp.asin(sin_phi)
    return Guide(
        "line", "Line", ("offset",), "straight guide Y = e: a slider (the end mass ms) on the line", label="slider",
        curve=sp.Matrix([s.beta, s.e]), step=sp.Matrix([sp_s, 0]), phi=phi,
        beta=s.a * sp.cos(s.theta) + sp.sqrt(1 - sin_phi**2),
        margin=((1 - s.a - sp.Abs(s.e), "a* + |offset| < 1 (the rod must reach the guide Y = offset at "
                                        "every crank angle)"),),
        end_scale=s.eps**2)


def circle():
    D = sp.Matrix([s.d, s.e])
    delta = D - PIN
    rho = sp.sqrt(delta.dot(delta))
    along = (1 - s.c**2 + rho**2) / (2 * rho)
    across = sp.sqrt(1 - along**2)
    chord = (along * delta + s.branch * across * sp.Matrix([-delta[1], delta[0]])) / rho   # B - A
    end = PIN + chord
    ground = sp.sqrt(s.d**2 + s.e**2)
    return Guide(
        "circle", "Circle", ("offset", "c", "d", "branch", "rocker_stiffness", "rocker_free_angle",
                             "rocker_mass", "rocker_centre", "rocker_inertia", "rocker_elements", "rocker_density",
                             "rocker_bending", "rocker_axial"),
        "circle of radius c about D = (d, e): a rigid rocker DB (massless unless given rocker_mass, "
        "rocker_inertia) carrying the end mass ms "
        "(a four-bar linkage with a flexible coupler)",
        aliases=(("center", ("d", "offset")), ("radius", ("c",))), label="four-bar",
        curve=D + s.c * sp.Matrix([sp.cos(s.beta), sp.sin(s.beta)]),
        step=2 * s.c * sp.sin(sp_s / 2) * sp.Matrix([-sp.sin(s.beta + sp_s / 2), sp.cos(s.beta + sp_s / 2)]),
        phi=sp.atan2(-chord[1], chord[0]), beta=sp.atan2(end[1] - s.e, end[0] - s.d),
        margin=((sp.Abs(ground - s.a) - sp.Abs(1 - s.c), "||D| - a*| > |1 - c| (the rod and the rocker "
                                                         "reach each other when the crank pin is nearest D)"),
                (1 + s.c - ground - s.a, "|D| + a* < 1 + c (they reach each other when the crank points "
                                         "away from D)")),
        end_scale=s.eps**2 / s.c, pivot=D)


# a cam track's height and wavelength (units of L)
cam_height, cam_wavelength = sp.symbols("h_cam lambda_cam", positive=True)


def cam():
    k = 2 * sp.pi / cam_wavelength
    sin_phi = s.a * sp.sin(s.theta) - s.e               # the straight guide's closure: Newton's guess
    return Guide(
        "cam", "Cam", ("offset", "cam_height", "cam_wavelength"),
        "cam track Y = e + h cos(2 pi X / lambda): a slider (the end mass ms) on a wavy guide, its "
        "closure solved by Newton at run time", label="slider on a cam track",
        curve=sp.Matrix([s.beta, s.e + cam_height * sp.cos(k * s.beta)]),
        step=sp.Matrix([sp_s, -2 * cam_height * sp.sin(k * sp_s / 2) * sp.sin(k * (s.beta + sp_s / 2))]),
        guess=s.a * sp.cos(s.theta) + sp.sqrt(1 - sin_phi**2), end_scale=s.eps**2)


# the angle of an inclined straight guide to the X axis
inclination = sp.Symbol("alpha_g", real=True)


def incline():
    direction = sp.Matrix([sp.cos(inclination), sp.sin(inclination)])
    sin_phi = s.a * sp.sin(s.theta - inclination) - s.e     # the slider-crank turned by the inclination
    return Guide(
        "incline", "Incline", ("offset", "inclination"),
        "straight guide at an angle alpha to the X axis, at a distance e from the crank's axis: a "
        "slider (the end mass ms) on an inclined line", label="slider on an incline",
        curve=s.e * sp.Matrix([-sp.sin(inclination), sp.cos(inclination)]) + s.beta * direction,
        step=sp_s * direction, phi=sp.asin(sin_phi) - inclination,
        beta=s.a * sp.cos(s.theta - inclination) + sp.sqrt(1 - sin_phi**2),
        margin=((1 - s.a - sp.Abs(s.e), "a* + |offset| < 1 (the rod must reach the guide at every "
                                        "crank angle)"),),
        end_scale=s.eps**2)


GUIDES = (line(), circle(), cam(), incline())


def closure_rates(guide):
    """(phid, betad, phidd, betadd) in theta, thetad, thetadd, phi, beta (and the parameters), from
    the time derivatives of the closure A(theta) + e_i(phi) - C(beta) = 0."""
    closure = PIN + E_I - guide.curve
    first = closure.applyfunc(lambda x: total_time_derivative(x, (), (), ()))
    sol1 = sp.solve(list(first), [s.phid, s.betad], dict=True)[0]
    second = first.applyfunc(lambda x: total_time_derivative(x, (), (), ()))
    sol2 = sp.solve(list(second), [s.phidd, s.betadd], dict=True)[0]
    phid, betad = sp.simplify(sol1[s.phid]), sp.simplify(sol1[s.betad])
    phidd = sp.simplify(sol2[s.phidd].subs({s.phid: phid, s.betad: betad}))
    betadd = sp.simplify(sol2[s.betadd].subs({s.phid: phid, s.betad: betad}))
    return phid, betad, phidd, betadd


def kinematics(guide):
    """kin = derive/symbols.KINEMATICS as expressions in (theta, thetad, thetadd) and the parameters
    (and, for a numerical closure, in the phi and beta its Newton iterations find: closure)."""
    phid, betad, phidd, betadd = closure_rates(guide)
    if guide.phi is None:
        position = {}
        phi, beta = s.phi, s.beta
    else:
        position = {s.phi: guide.phi, s.beta: guide.beta}
        phi, beta = guide.phi, guide.beta
    values = {s.a: s.a, s.theta: s.theta, s.thetad: s.thetad, s.thetadd: s.thetadd,
              s.phi: phi, s.beta: beta,
              s.phid: phid.subs(position), s.betad: betad.subs(position),
              s.phidd: phidd.subs(position), s.betadd: betadd.subs(position)}
    return sp.Matrix([values[sym] for sym in s.KINEMATICS])


def closure(guide):
    """A numerical closure, (unknown beta, its guess, the residual |C(beta) - A|^2 - L^2, its
    derivative in beta, ((phi, phi from beta),)): the rod's chord B - A = e_i = (cos phi, -sin phi)
    from the crank pin A to the guide's point C(beta) has the rod's length L = 1; None for a guide
    whose phi and beta are in closed form."""
    if guide.phi is not None:
        return None
    chord = guide.curve - PIN
    residual = sp.expand(chord.dot(chord) - 1)
    return (s.beta, guide.guess, residual, sp.diff(residual, s.beta), ((s.phi, sp.atan2(-chord[1], chord[0])),))


def end_map(guide):
    """The (8, 2) matrix of the end map (rows END_MAP_ROWS): the end node's (u, v) and rates, and
    their derivatives in the reduced co-ordinate s and its rates, in s, sd, sdd and kin."""
    exact = guide.curve.subs(s.beta, s.beta + sp_s) - guide.curve
    step = exact if guide.step is None else guide.step
    assert (step - exact).applyfunc(lambda x: sp.simplify(sp.expand_trig(x))) == sp.zeros(2, 1), guide.name
    g = sp.Matrix([step.dot(E_I), step.dot(E_J)]).applyfunc(lambda x: TR10i(sp.factor_terms(x)))
    coords, rates, accels = (sp_s,), (sp_sd,), (sp_sdd,)
    gd = g.applyfunc(lambda x: total_time_derivative(x, coords, rates, accels))
    gdd = gd.applyfunc(lambda x: total_time_derivative(x, coords, rates, accels))
    rows = (g, gd, gdd, g.diff(sp_s), gd.diff(sp_s), gdd.diff(sp_s), gdd.diff(sp_sd), g.diff(sp_s, 2))
    return sp.Matrix([list(r.applyfunc(sp.expand)) for r in rows])


# A flexible rocker's tip: its (u_r, v_r) in the rocker's frame and their rates, the reduced
# co-ordinates of the rod's end (Constraint "tip" in derive/declaration.py)
TIP = sp.symbols("u_r v_r", real=True)
TIP_RATES = sp.symbols("ud_r vd_r", real=True)
TIP_ACCELERATIONS = sp.symbols("udd_r vdd_r", real=True)
E_IR = sp.Matrix([sp.cos(s.beta), sp.sin(s.beta)])       # the rigid rocker's frame: e_i at phi_r = -beta
E_JR = sp.Matrix([-sp.sin(s.beta), sp.cos(s.beta)])


def map_rows(g, coords, rates, accels):
    """The rows of a map (u, v) = g(z, t) of m reduced co-ordinates z (the engine's layout,
    engine/elements.py): g, gd, gdd; per co-ordinate j: dg/dz_j, dgd/dz_j, dgdd/dz_j, dgdd/dzd_j; then
    d2g/dz_j dz_l (m x m rows)."""
    gd = g.applyfunc(lambda x: total_time_derivative(x, coords, rates, accels))
    gdd = gd.applyfunc(lambda x: total_time_derivative(x, coords, rates, accels))
    rows = [g, gd, gdd]
    for z, zd in zip(coords, rates):
        rows += [g.diff(z), gd.diff(z), gdd.diff(z), gdd.diff(zd)]
    rows += [g.diff(z1, z2) for z1 in coords for z2 in coords]
    return sp.Matrix([list(r.applyfunc(sp.expand)) for r in rows])


def flexible_rocker_end_map():
    """The rod's end held by a flexible rocker's tip, equal positions at B: u e_i + v e_j = u_r e_ir +
    v_r e_jr (the rigid mechanism's ends coincide, A + L e_i = D + c e_ir), so (u, v) = R (u_r, v_r)
    with R the rotation from the rocker's frame to the rod's, R = [[cos(phi + beta), -sin(phi + beta)],
    [sin(phi + beta), cos(phi + beta)]]: linear in (u_r, v_r) and rheonomic; rows map_rows
    (3 + 4 m + m^2 = 15 for m = 2)."""
    tip = TIP[0] * E_IR + TIP[1] * E_JR
    g = sp.Matrix([tip.dot(E_I), tip.dot(E_J)]).applyfunc(lambda x: TR10i(sp.factor_terms(sp.expand(x))))
    return map_rows(g, TIP, TIP_RATES, TIP_ACCELERATIONS)


def rigid_end(guide):
    """(X, Y) of the rigid mechanism's end point B = C(beta) as expressions in kin and the parameters."""
    return guide.curve
