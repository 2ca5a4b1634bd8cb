"""Every SymPy symbol of the derivation, in one place.

All quantities are dimensionless (section 5 of the paper): lengths in units of the rod length L,
mass in units of rho*A*L, time in units of 1/omega_b.  The element data and the rigid-body
kinematics are plain symbols so that they become kernel arguments.
"""

import sympy as sp

# Position inside an element, zeta = x / l (Appendix A).
zeta = sp.Symbol("zeta", real=True)

# Element data: element length l and the x co-ordinate x0 of its first node.
l = sp.Symbol("l", positive=True)
x0 = sp.Symbol("x0", real=True)

# Section and material constants (per unit length): rho*A, rho*I, E*A, E*I and the damping time mu.
rhoA, rhoI, EA, EI = sp.symbols("rhoA rhoI EA EI", positive=True)
mu = sp.Symbol("mu", nonnegative=True)

# Slider mass and rod length (the slider sits at x = L).
ms = sp.Symbol("ms", nonnegative=True)
L = sp.Symbol("L", positive=True)

# Rigid-body kinematics: crank length a, crank angle theta with its rate and angular acceleration
# (prescribed: derive/motions.py), rod (chord) angle phi with its first and second time
# derivatives, and the guide co-ordinate beta of the rigid end point (derive/guides.py: the
# slider's abscissa on a straight guide, the rocker angle on a circle) with its rates.
a = sp.Symbol("a", positive=True)
theta, thetad, phi, phid, phidd = sp.symbols("theta thetad phi phid phidd", real=True)
thetadd = sp.Symbol("thetadd", real=True)
beta, betad, betadd = sp.symbols("beta betad betadd", real=True)

# The components of a node (eq. 14): axial and transverse displacement, slope psi = v_x, and the
# axial slope chi = u_x, which only the geometrically exact rod interpolates (its u is cubic, so its
# tangent (1 + u_x, v_x) is continuous at the nodes); approaches A, B and C interpolate u linearly
# and have no chi (the DOF map leaves it out: records.Body.conditional).  An element's nodal vector
# holds its two nodes' components, the first node's first.
NODE = ("u", "v", "psi", "chi")
ELEMENT_NODES = 2
ELEMENT_DOFS = len(NODE) * ELEMENT_NODES


def element_slots(node, components):
    """The places in an element's nodal vector of components of its node 0 (first) or 1 (second)."""
    return tuple(node * len(NODE) + NODE.index(c) for c in components)


# Element nodal vector {q}_i = {u_i, v_i, psi_i, chi_i, u_i+1, v_i+1, psi_i+1, chi_i+1} (eq. 14 with
# chi) and its rates.
q = sp.Matrix(sp.symbols(f"q0:{ELEMENT_DOFS}", real=True))
qd = sp.Matrix(sp.symbols(f"qd0:{ELEMENT_DOFS}", real=True))
qdd = sp.Matrix(sp.symbols(f"qdd0:{ELEMENT_DOFS}", real=True))

# Slider node displacements (u, v) of the rod's last node and their rates.
qs = sp.Matrix(sp.symbols("qs0:2", real=True))
qsd = sp.Matrix(sp.symbols("qsd0:2", real=True))
qsdd = sp.Matrix(sp.symbols("qsdd0:2", real=True))

# The kinematics vector every kernel receives (one layout for every guide and crank motion; the
# first six entries keep the order of the constant-speed slider-crank).
KINEMATICS = (a, theta, thetad, phi, phid, phidd, thetadd, beta, betad, betadd)

# Time derivatives of the time-dependent symbols.  phidd, thetadd and betadd have no entry: no
# quantity differentiated in time by the derivation depends on them.
TIME_DERIVATIVE = {theta: thetad, thetad: thetadd, phi: phid, phid: phidd, beta: betad, betad: betadd}

# Gravity in the inertial frame (X along the guide towards the slider, Y perpendicular), in units of
# L omega_b^2, and the guides' geometry (units of L): the offset e (the line Y = e; the ordinate of
# a circle's centre), a circle's radius c (the rocker of a four-bar), the abscissa d of its centre
# (the rocker's ground pivot) and its branch (+1 or -1: which of the two closures).
gX, gY = sp.symbols("gX gY", real=True)
e = sp.Symbol("e", real=True)
c, d = sp.symbols("c d", real=True)
branch = sp.Symbol("branch", real=True)

# Time and the crank motion's parameters (derive/motions.py): the crank speed Omega* (the constant
# speed; the final speed of a run-up; the nominal speed of a fluctuating crank), the start speed
# omega0 and the revolutions of a run-up, the relative amplitude k and order j of a fluctuation.
t = sp.Symbol("t", real=True)
omega, omega0 = sp.symbols("omega omega0", positive=True)
ramp = sp.Symbol("ramp", positive=True)
# slenderness eps = r / L (r the radius of gyration): coefficients and natural sizes are formulas in it
eps = sp.Symbol("eps", positive=True)
k_fl = sp.Symbol("k", real=True)
j_fl = sp.Symbol("j", positive=True, integer=True)

# Term weights: each switchable group of terms (derive/groups.py) enters the kernels multiplied by
# its weight, 1 in every model; the audit switches a group off by setting its weight to 0.
SWITCHABLE_GROUPS = ("gyroscopic", "phidd", "centrifugal", "cubic_axial", "cubic_transverse", "quartic")
WEIGHT = {g: sp.Symbol(f"w_{g}", real=True) for g in SWITCHABLE_GROUPS}

# The element data every element kernel takes besides q, qd, qdd and the kinematics (the coefficient
# vector's layout is the declaration's COEFFICIENTS):
GEOMETRY = (l, x0)                                   # element length and first-node abscissa
