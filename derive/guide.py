"""Stage 2b: rigid kinematics of the crank, the rod's chord and the slider on its guide.

The guide is the line Y = e of the inertial frame (e = 0: through the crank centre, the paper's
mechanism).  The crank pin is at a (cos theta, sin theta), theta = Omega t, and the rod's chord runs
from the pin to the slider along e_i = (cos phi, -sin phi), so the slider's ordinate
a sin theta - L sin phi = e fixes phi:

    sin phi = (a sin theta - e) / L,

and phid, phidd follow by differentiating that constraint in time (constant crank speed).  The
slider is at X = a cos theta + L cos phi.  A crank that turns a full revolution needs
|a sin theta - e| < L for every theta, i.e. a + |e| < L.
"""

import sympy as sp

from . import symbols as s

t = sp.Symbol("t", real=True)
omega = sp.Symbol("omega", positive=True)


def kinematics():
    """(theta, thetad, phi, phid, phidd, X_slider) at time t, in a, e, omega (L = 1)."""
    theta = omega * t
    phi_t = sp.Function("phi")(t)
    constraint = s.a * sp.sin(theta) - sp.sin(phi_t) - s.e              # = 0 along the motion
    d1 = sp.diff(constraint, t)
    phid_expr = sp.solve(d1, sp.Derivative(phi_t, t))[0]
    d2 = sp.diff(constraint, t, 2)
    phidd_expr = sp.solve(d2, sp.Derivative(phi_t, (t, 2)))[0].subs(sp.Derivative(phi_t, t), phid_expr)
    sin_phi = s.a * sp.sin(theta) - s.e
    cos_phi = sp.sqrt(1 - sin_phi**2)
    phi = sp.asin(sin_phi)
    phid_val = sp.simplify(phid_expr.subs(phi_t, phi))
    phidd_val = sp.simplify(phidd_expr.subs(phi_t, phi))
    return theta, omega, sp.asin(sin_phi), phid_val, phidd_val, s.a * sp.cos(theta) + cos_phi


def full_turn_margin():
    """L - (a + |e|): positive when the crank can turn a full revolution."""
    return 1 - (s.a + sp.Abs(s.e))
