"""Stage 2: element energies from eqs. (2)-(7), with the reduced strain energies of approaches B, C.

Kinematic convention (docs/errata.md): e_i = (cos phi, -sin phi), e_j = (sin phi, cos phi) in the inertial
frame, so de_i/dt = -phid e_j and de_j/dt = phid e_i.  The crank pin is at a e_r, e_r = (cos theta,
sin theta); e_r . e_i = cos(theta + phi), e_theta . e_i = -sin(theta + phi).
"""

import sympy as sp

from . import symbols as s
from .shape_functions import B_PSI, B_U, B_U_CUBIC, B_V, N_PSI, N_U, N_U_CUBIC, N_V, d_dx, integrate_element

APPROACHES = ("A", "B", "C")


def _dot(column, vector):
    return (column.T * vector)[0, 0]


def field_columns(approach=None):
    """The shape function columns of an element's fields (eqs. 8-13): u linear (approaches A, B, C)
    or cubic in u and chi (the exact rod), v cubic; "u_xx" vanishes for a linear u."""
    n_u, b_u = (N_U_CUBIC, B_U_CUBIC) if approach == "exact" else (N_U, B_U)
    return {"u": n_u, "v": N_V, "psi": N_PSI, "u_x": b_u, "v_x": B_V, "v_xx": B_PSI, "u_xx": d_dx(b_u)}


def fields(q, qd, approach=None):
    """Interpolated fields (eqs. 8-10) and gradients of one element (the approach's u: field_columns)."""
    cols = field_columns(approach)
    out = {"u": _dot(cols["u"], q), "v": _dot(N_V, q), "psi": _dot(N_PSI, q),
           "ud": _dot(cols["u"], qd), "vd": _dot(N_V, qd), "psid": _dot(N_PSI, qd),
           "u_x": _dot(cols["u_x"], q), "v_x": _dot(B_V, q), "v_xx": _dot(B_PSI, q),
           "ud_x": _dot(cols["u_x"], qd), "vd_x": _dot(B_V, qd), "vd_xx": _dot(B_PSI, qd)}
    if approach == "exact":
        out.update({"u_xx": _dot(cols["u_xx"], q), "ud_xx": _dot(cols["u_xx"], qd)})
    return out


def moving_frame_velocity(xi, eta, xid, etad):
    """Components along (e_i, e_j) of the velocity of the point a e_r + xi e_i + eta e_j (eqs. 4, 7)."""
    crank = s.a * s.thetad
    vel_i = -crank * sp.sin(s.theta + s.phi) + xid + eta * s.phid
    vel_j = crank * sp.cos(s.theta + s.phi) - xi * s.phid + etad
    return vel_i, vel_j


def centre_line_kinetic_energy_density(f):
    """rho A / 2 |dR/dt|^2 of the centre line R = a e_r + (x + u) e_i + v e_j (exact), from the
    field dictionary f (fields(), with "x" the abscissa)."""
    vel_i, vel_j = moving_frame_velocity(f["x"] + f["u"], f["v"], f["ud"], f["vd"])
    return s.rhoA * (vel_i**2 + vel_j**2) / 2


def small_rotation_kinetic_energy_density(f):
    """rho I / 2 |d/dt(-psi e_i + e_j)|^2: the rotary inertia of the section with the
    small-rotation director (-psi, 1) of eq. (4)."""
    rotary_i = s.phid - f["psid"]          # d/dt(-psi e_i + e_j) . e_i
    rotary_j = f["psi"] * s.phid           # d/dt(-psi e_i + e_j) . e_j
    return s.rhoI * (rotary_i**2 + rotary_j**2) / 2


def rod_kinetic_energy_density(q=s.q, qd=s.qd):
    """Kinetic energy per unit length, eq. (5) integrated over the cross-section (eq. 4).

    With int y dA = 0 and int y^2 dA = I the section integral splits into the centre-line part
    (rho A) and the rotary-inertia part (rho I) of the rotating section, R = ... + y (-psi e_i + e_j).
    """
    f = dict(fields(q, qd), x=s.x0 + s.l * s.zeta)
    return centre_line_kinetic_energy_density(f) + small_rotation_kinetic_energy_density(f)


def rod_kinetic_energy(q=s.q, qd=s.qd):
    """Element kinetic energy T_i, eq. (5) over one element."""
    return integrate_element(rod_kinetic_energy_density(q, qd))


def point_mass_kinetic_energy(mass, qs=s.qs, qsd=s.qsd):
    """Kinetic energy of a point mass at the rod's end, eqs. (6)-(7); (qs0, qs1) = (u, v) of the rod's
    last node."""
    vel_i, vel_j = moving_frame_velocity(s.L + qs[0], qs[1], qsd[0], qsd[1])
    return sp.expand(mass * (vel_i**2 + vel_j**2) / 2)


def slider_kinetic_energy(qs=s.qs, qsd=s.qsd):
    """Slider kinetic energy T_s, eqs. (6)-(7): the point mass m_s at the rod's end."""
    return point_mass_kinetic_energy(s.ms, qs, qsd)


def axial_strain(approach, q=s.q):
    """Axial strain of the neutral axis: non-linear (eq. 1) for A and B, linear for C."""
    f = fields(q, q)
    if approach == "C":
        return f["u_x"]
    return f["u_x"] + f["v_x"] ** 2 / 2


def membrane_energy_density(approach, f):
    """(u_x + v_x^2/2)^2 of eq. (2) for A, without v_x^4/4 for B, u_x^2 for C, of the fields f."""
    u_x, v_x = f["u_x"], f["v_x"]
    return {
        "A": u_x**2 + u_x * v_x**2 + v_x**4 / 4,
        "B": u_x**2 + u_x * v_x**2,
        "C": u_x**2,
    }[approach]


def strain_energy_density(approach, q=s.q):
    """Strain energy per unit length: eq. (2) for A, without 1/4 v_x^4 for B, linear strain for C."""
    f = fields(q, q)
    return (s.EA * membrane_energy_density(approach, f) + s.EI * f["v_xx"] ** 2) / 2


def strain_energy(approach, q=s.q):
    """Element strain energy U_i of the approach."""
    return integrate_element(strain_energy_density(approach, q))


def strain_rate_of(approach, f):
    """Time derivative of the approach's axial strain measure, from the fields f.

    B keeps the non-linear strain of eq. (1) (it only truncates the energy), so it shares A's
    strain rate; C uses the linear strain.  Using a full square keeps D >= 0 in every approach.
    """
    if approach == "C":
        return f["ud_x"]
    return f["ud_x"] + f["v_x"] * f["vd_x"]


def strain_rate(approach, q=s.q, qd=s.qd):
    """Time derivative of the approach's axial strain measure (strain_rate_of the element fields)."""
    return strain_rate_of(approach, fields(q, qd))


def kelvin_voigt_density_of(approach, f):
    """Rayleigh dissipation per unit length, D = mu/2 [EA edot^2 + EI (d/dt v_xx)^2], of the fields f."""
    return s.mu * (s.EA * strain_rate_of(approach, f) ** 2 + s.EI * f["vd_xx"] ** 2) / 2


def kelvin_voigt_dissipation_density(approach, q=s.q, qd=s.qd):
    """Rayleigh dissipation per unit length, D = mu/2 [EA edot^2 + EI (d/dt v_xx)^2]."""
    return kelvin_voigt_density_of(approach, fields(q, qd))


def kelvin_voigt_dissipation(approach, q=s.q, qd=s.qd):
    """Element Rayleigh dissipation function of the strain-rate (Kelvin-Voigt) damping model."""
    return integrate_element(kelvin_voigt_dissipation_density(approach, q, qd))


# ----------------------------------------------------------------------------------------------
# Element option: membrane strain averaged over the element (assumed strain, no membrane locking)
# ----------------------------------------------------------------------------------------------
#
# With linear u and cubic v, u_x is constant in an element while v_x^2 / 2 is a quartic in x, so
# the membrane strain u_x + v_x^2/2 cannot vanish for an inextensional bending shape: the element
# stores spurious membrane energy (and, with strain-rate damping, dissipates spuriously) when it
# bends, and converges slowly (membrane locking).  The cure used here replaces v_x^2 in the
# membrane strain by its element mean <v_x^2> = (1/l) int v_x^2 dx, which the linear u can match;
# bending (EI v_xx^2) is unchanged, and so is approach C (linear strain).

MEMBRANE_OPTIONS = ("pointwise", "averaged")


def mean_over_element(expr):
    """(1/l) int_0^l expr dx."""
    return sp.expand(integrate_element(expr) / s.l)


def strain_energy_averaged(approach, q=s.q):
    """Element strain energy with the element-mean membrane strain e = u_x + <v_x^2>/2."""
    f = fields(q, q)
    u_x = f["u_x"]                               # constant in the element
    m = mean_over_element(f["v_x"] ** 2)
    membrane = {
        "A": (u_x + m / 2) ** 2,
        "B": u_x**2 + u_x * m,
        "C": u_x**2,
    }[approach]
    return sp.expand(s.l * s.EA * membrane / 2 + integrate_element(s.EI * f["v_xx"] ** 2 / 2))


def kelvin_voigt_dissipation_averaged(approach, q=s.q, qd=s.qd):
    """Kelvin-Voigt dissipation with the element-mean membrane strain rate u_x' + <v_x v_x'>."""
    f = fields(q, qd)
    rate = f["ud_x"] if approach == "C" else f["ud_x"] + mean_over_element(f["v_x"] * f["vd_x"])
    return sp.expand(s.mu * (s.l * s.EA * rate**2 + integrate_element(s.EI * f["vd_xx"] ** 2)) / 2)


# ----------------------------------------------------------------------------------------------
# Gravity: potential energy of the rod and the slider in a uniform field g = (gX, gY)
# ----------------------------------------------------------------------------------------------
#
# Inertial frame: X along the guide towards the slider, Y perpendicular, crank pin at
# a (cos theta, sin theta); e_i = (cos phi, -sin phi), e_j = (sin phi, cos phi) (module docstring).

def inertial_position(xi, eta):
    """Inertial (X, Y) of the point a e_r + xi e_i + eta e_j of the moving frame (eq. 4)."""
    X = s.a * sp.cos(s.theta) + xi * sp.cos(s.phi) + eta * sp.sin(s.phi)
    Y = s.a * sp.sin(s.theta) - xi * sp.sin(s.phi) + eta * sp.cos(s.phi)
    return X, Y


def rod_gravity_potential(q=s.q, approach=None):
    """Element potential of gravity, V_i = -int rho A g . R dx (the rotary part y(-psi e_i + e_j)
    of eq. 4 integrates to zero over the section, int y dA = 0); the approach's u (field_columns)."""
    f = fields(q, q, approach)
    X, Y = inertial_position(s.x0 + s.l * s.zeta + f["u"], f["v"])
    return integrate_element(-s.rhoA * (s.gX * X + s.gY * Y))


def point_mass_gravity_potential(weight, qs=s.qs):
    """Potential -W . R of a weight W = (WX, WY) at the rod's end R (eq. 7's point at x = L)."""
    X, Y = inertial_position(s.L + qs[0], qs[1])
    return sp.expand(-(weight[0] * X + weight[1] * Y))


def slider_gravity_potential(qs=s.qs):
    """Potential of gravity on the slider, V_s = -m_s g . R_s."""
    return point_mass_gravity_potential((s.ms * s.gX, s.ms * s.gY), qs)


# ----------------------------------------------------------------------------------------------
# The geometrically exact rod (approach "exact"), and every approach's element energies over the
# points of a quadrature rule (derive/quadrature.py)
# ----------------------------------------------------------------------------------------------
#
# Planar Euler-Bernoulli rod, exact kinematics in the moving frame: the centre line
# R = a e_r + (x + u) e_i + v e_j (as in eq. 4), its tangent r' = (1 + u_x) e_i + v_x e_j = lambda
# (cos(theta) e_i + sin(theta) e_j), lambda = |r'| the stretch and e = lambda - 1 the axial strain;
# the section stays normal to the centre line (no shear), its director d = -sin(theta) e_i +
# cos(theta) e_j a unit vector turning at |dd/dt| = |theta' - phid| in the inertial frame (the
# small-rotation director (-psi, 1) of eq. (4) is longer than 1 by sqrt(1 + psi^2)); the curvature
# kappa = d theta / dx per undeformed length (Reissner's measure: the strain energy
# 1/2 int (EA e^2 + EI kappa^2) dx makes N = EA e and M = EI kappa work-conjugate to e and kappa,
# and the fibre at distance y stretches by lambda - y kappa):
#
#     kappa = (r' x r'') / |r'|^2 = ((1 + u_x) v_xx - v_x u_xx) / ((1 + u_x)^2 + v_x^2).
#
# Divided by |r'|^2, not |r'|^3 (the centre line's geometric curvature per deformed length): the
# rotation per undeformed length is what the section's moment does work on, as in Reissner's and
# Simo's rods; the two differ by a factor lambda, a strain-sized correction.
#
# The element interpolates u as it does v, cubic in the nodal values and slopes (u, chi = u_x;
# v, psi = v_x: the absolute-slope coordinates of an ANCF cable element, in the moving frame), so
# the tangent r' is continuous at the nodes and nothing limits the section's rotation: theta =
# atan2(v_x, 1 + u_x) turns through any angle (a section turned by 120 degrees has 1 + u_x < 0).
# The element never evaluates theta itself, only its rates and its x-derivative, rational in the
# slopes: no branch of atan2 is ever chosen.  The strain |r'| - 1 is integrated pointwise, at the
# three points of the rule: there the cubic u's slope (a quadratic, three values per element) can
# take the values -v_x^2 / 2 of an inextensible bend, so the element does not lock (a linear u, one
# value per element, does: the former element averaged the strain over the element instead).  The
# element mean would not do here: it leaves the axial slopes chi without stiffness (a spurious
# zero-energy mode per element), so the `membrane` option does not apply to the exact rod.

# The exact strain and the rotation are functions of a point's fields.  The derivation keeps them
# opaque (SymPy functions), so that the Euler-Lagrange terms and their tangents come out as
# polynomials in their partial derivatives (mixed partials cancel where they should:
# d/dt dT/dtheta' - dT/dtheta collapses to rho I (theta'' - phidd) grad theta); `reveal` puts the
# definitions in (quadrature.PointSpace computes each partial derivative once per point).
STRAIN = sp.Function("strain", real=True)          # e(u_x, v_x) = |r'| - 1
ROTATION = sp.Function("rotation", real=True)      # theta(u_x, v_x) = atan2(v_x, 1 + u_x)
_A, _B = sp.symbols("_a _b", real=True)
QUANTITIES = {
    # ((1 + u_x)^2 + v_x^2 - 1) / (|r'| + 1): |r'| - 1 free of cancellation at small strain
    STRAIN: sp.Lambda((_A, _B), (2 * _A + _A**2 + _B**2) / (sp.sqrt((1 + _A) ** 2 + _B**2) + 1)),
    ROTATION: sp.Lambda((_A, _B), sp.atan2(_B, 1 + _A)),
}


# fields constant in an element, built from the rule's points (quadrature.PointSpace gives each a
# symbol, with its time derivatives): none for the exact rod, whose strain is pointwise
ELEMENT_FIELDS = {}

MEMBRANES = ("pointwise", "averaged")
APPROACHES_ALL = APPROACHES + ("exact",)


def _rate_key(key):
    base, _, rest = key.partition("_")
    return f"{base}d_{rest}" if rest else f"{base}d"


def field_rate(expr, f):
    """d/dt of an expression in the fields f (symbols of a point: u_x -> ud_x -> udd_x) and the
    rigid kinematics."""
    out = [sp.diff(expr, f[k]) * f[_rate_key(k)] for k in sorted(f) if isinstance(f[k], sp.Symbol)
           and _rate_key(k) in f and expr.has(f[k])]
    out += [sp.diff(expr, sym) * rate for sym, rate in s.TIME_DERIVATIVE.items() if expr.has(sym)]
    return sp.Add(*out)


def field_x_derivative(expr, f):
    """d/dx of an expression in u_x and v_x of the fields f (u_x -> u_xx, v_x -> v_xx; the element
    fields are constant along the element)."""
    return sp.Add(*(sp.diff(expr, f[a]) * f[b] for a, b in (("u_x", "u_xx"), ("v_x", "v_xx"))
                    if isinstance(f[a], sp.Symbol)))


def reveal(expr):
    """expr with the opaque point quantities (STRAIN, ROTATION) replaced by their definitions and
    their derivatives evaluated."""
    for function, definition in QUANTITIES.items():
        expr = expr.replace(function, definition)
    return expr.doit()


_SLOPES = {k: sp.Symbol(f"_{k}", real=True) for k in ("u_x", "v_x", "u_xx", "v_xx")}


def _of_slopes(build, f):
    """build(slope symbols) at the fields f: kept opaque at the point symbols of a quadrature rule,
    revealed where the fields are expressions (outputs)."""
    expr = build(_SLOPES)
    values = {sym: f.get(k, 0) for k, sym in _SLOPES.items()}
    if all(isinstance(v, sp.Symbol) or v == 0 for v in values.values()):
        return expr.xreplace(values)
    return reveal(expr).xreplace(values)


def exact_strain(f):
    """e = |r'| - 1 at a point of the interpolated centre line, |r'| = sqrt((1 + u_x)^2 + v_x^2)."""
    return _of_slopes(lambda g: STRAIN(g["u_x"], g["v_x"]), f)


def _rotation_of(g):
    return ROTATION(g["u_x"], g["v_x"])


def _curvature_of_slopes(g):
    return field_x_derivative(_rotation_of(g), g)


def section_rotation(f):
    """theta = atan2(v_x, 1 + u_x): the angle of the tangent (and of the section's normal) from e_i
    (a point field "th" of a quadrature rule's points)."""
    return f["th"] if "th" in f else _of_slopes(_rotation_of, f)


def exact_curvature(f):
    """kappa = d theta / dx (per undeformed length), derived from section_rotation (revealed:
    ((1 + u_x) v_xx - v_x u_xx) / |r'|^2; a point field "kap" of a quadrature rule's points)."""
    return f["kap"] if "kap" in f else _of_slopes(_curvature_of_slopes, f)


# fields of a quadrature point defined from its fields (each a symbol with its time derivatives,
# quadrature.PointSpace): the section rotation and the curvature
POINT_FIELDS = {"th": _rotation_of, "kap": _curvature_of_slopes}


def exact_rotary_kinetic_energy_density(f):
    """rho I / 2 |d/dt d|^2 = rho I / 2 (theta' - phid)^2: the section's exact rotation, whose
    inertial angle is theta - phi."""
    return s.rhoI * (field_rate(section_rotation(f), f) - s.phid) ** 2 / 2


def element_kinetic_energy(space, approach):
    """Element kinetic energy by the rule of `space`: the centre line (exact in every approach) and
    the section's rotation, small-rotation (eq. 4) for A, B, C or exact."""
    rotary = exact_rotary_kinetic_energy_density if approach == "exact" else small_rotation_kinetic_energy_density
    return space.integral(lambda f: centre_line_kinetic_energy_density(f) + rotary(f))


def element_rotary_kinetic_energy(space):
    """The exact section rotation's part of the element kinetic energy, by the rule of `space`."""
    return space.integral(exact_rotary_kinetic_energy_density)


def axial_strain_of(approach, f):
    """The approach's pointwise axial strain of the fields f: u_x + v_x^2/2 (A, B), u_x (C),
    |r'| - 1 (exact)."""
    if approach == "exact":
        return exact_strain(f)
    return f["u_x"] if approach == "C" else f["u_x"] + f["v_x"] ** 2 / 2


def _curvature_of(approach, f):
    return exact_curvature(f) if approach == "exact" else f["v_xx"]


def element_strain_energy(space, approach, membrane="pointwise"):
    """Element strain energy by the rule of `space`.  pointwise: 1/2 int (EA e^2 + EI kappa^2) dx
    (eq. 2 for A, B, C; e = |r'| - 1 and the exact kappa for "exact", always pointwise: its cubic u
    matches v_x^2 / 2 at the rule's points, so it does not lock).  averaged (A, B): the membrane
    energy of one strain per element, l EA e_bar^2 / 2 (u_x + <v_x^2>/2, as
    strain_energy_averaged)."""
    bending = space.integral(lambda f: s.EI * _curvature_of(approach, f) ** 2 / 2)
    if approach == "exact":
        return space.integral(lambda f: s.EA * exact_strain(f) ** 2 / 2) + bending
    if membrane == "pointwise" or approach == "C":
        return space.integral(lambda f: s.EA * membrane_energy_density(approach, f) / 2) + bending
    u_x = space.fields(0)["u_x"]                        # constant in the element
    m = space.integral(lambda f: f["v_x"] ** 2) / s.l
    energy = {"A": (u_x + m / 2) ** 2, "B": u_x**2 + u_x * m}[approach]
    return s.l * s.EA * energy / 2 + bending


def element_dissipation(space, approach, membrane="pointwise"):
    """Element Kelvin-Voigt dissipation D = mu/2 int (EA e'^2 + EI kappa'^2) dx by the rule of
    `space` (' = d/dt); averaged (A, B): l EA e_bar'^2 for the membrane part."""
    def strain_rate_at(f):
        if approach == "exact":
            return field_rate(exact_strain(f), f)
        return strain_rate_of(approach, f)

    def curvature_rate_at(f):
        return field_rate(exact_curvature(f), f) if approach == "exact" else f["vd_xx"]

    bending = space.integral(lambda f: s.mu * s.EI * curvature_rate_at(f) ** 2 / 2)
    if membrane == "pointwise" or approach in ("C", "exact"):
        return space.integral(lambda f: s.mu * s.EA * strain_rate_at(f) ** 2 / 2) + bending
    rate = space.integral(strain_rate_at) / s.l
    return s.mu * s.l * s.EA * rate**2 / 2 + bending
