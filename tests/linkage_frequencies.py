r"""Exact natural frequencies of the four-bar frozen with its crank locked (test helper, NumPy/SciPy
only, independent of crankgen): a coupler and a rocker, both Euler-Bernoulli beams with axial
stretch, pinned to two fixed points and to each other, by the dynamic stiffness (transcendental)
method with the Wittrick-Williams count.

The frame
---------
The crank is rigid and locked, so the crank pin A is a fixed point; the rocker's ground pivot D is
a fixed point.  The coupler is a straight beam A -> B of length L (mass per length rhoA, axial
stiffness EA, bending stiffness EI), the rocker a straight beam D -> B of length c (rhoA_r, EA_r,
EI_r).  All three joints are ideal pins (positions equal, rotations independent, no moment); a
point mass m_B may sit at B.  Small planar vibrations about the straight configuration, no gravity,
no pre-stress (the crank is locked, nothing rotates: the members carry no axial force in the
reference state).  gamma is the angle between the two members' axes at B.

Each member alone (the member's own convention)
-----------------------------------------------
Let x run from the fixed end (x = 0: A, or D) to B (x = l), e the unit vector along the member's
axis from the fixed end to B, n a unit normal.  At frequency omega, with

    alpha = omega sqrt(rhoA / EA)          (axial wave number),
    beta  = (rhoA omega^2 / EI)^(1/4)      (bending wave number),

the axial motion u(x) solves EA u'' + rhoA omega^2 u = 0 with u(0) = 0, u(l) = u_B, so
u = u_B sin(alpha x) / sin(alpha l) and the force on the member's end B, along e, is

    N_B = EA u'(l) = k_ax u_B,      k_ax(omega) = EA alpha cot(alpha l).

The transverse motion w(x) solves EI w'''' - rhoA omega^2 w = 0 with w(0) = 0, w''(0) = 0 (pin at
the fixed end, no moment), w''(l) = 0 (pin at B, no moment) and w(l) = w_B; the end rotations are
free and are eliminated exactly, which is why no rotation appears among the unknowns.  Then
w = (w_B / 2) [sin(beta x) / sin(beta l) + sinh(beta x) / sinh(beta l)], and the force on the
member's end B along n (from the virtual work, F_B = -EI w'''(l)) is

    F_B = k_tr w_B,      k_tr(omega) = (EI beta^3 / 2) [cot(beta l) - coth(beta l)].

Limits (used for small arguments, where the closed forms cancel): with y = alpha l, z = beta l,

    k_ax = (EA / l) (y cot y),   y cot y = 1 - y^2/3 - y^4/45 - 2 y^6/945 - ...,
    k_tr = -(rhoA l omega^2 / 3) (1 + 2 z^4/315 + 2 z^8/31185 + ...),

so k_ax(0) = EA / l, and k_tr(0) = 0 (the pinned-pinned member swings freely about its fixed
pin: no static transverse stiffness) with the mass rhoA l / 3 of a bar rotating about its end.  A
member with rhoA = 0 is exactly its static self (k_ax = EA / l, k_tr = 0).

Poles: k_ax is infinite where sin(alpha l) = 0 (the member's fixed-fixed axial frequencies,
alpha l = j pi) and k_tr where sin(beta l) = 0 (its pinned-pinned bending frequencies,
beta l = j pi, omega = (j pi / l)^2 sqrt(EI / rhoA)), i.e. at the frequencies of the member with B
held fixed.  Between poles both decrease monotonically with omega (d k / d(omega^2) < 0).

The frame (global)
------------------
The only joint unknowns are B's two translations d = (X, Y).  In the global frame the coupler's
axis is e_c = (1, 0) (A -> B) and the rocker's is e_r = (cos gamma, -sin gamma) (D -> B): A at
(-L, 0), B at the origin, D at c (-cos gamma, sin gamma), so that the angle between B -> A and
B -> D is gamma (radians).  A member contributes k_ax e e^T + k_tr n n^T (no e-n cross terms: a
straight, unstressed member's axial and transverse motions are uncoupled in its own frame), and
n n^T = I - e e^T.  The coupling of the coupler's bending with the rocker's stretching (and vice
versa) is all in the sum at B.  The 2 x 2 dynamic stiffness at B is

    K(omega) = sum over {coupler, rocker} of [k_ax e e^T + k_tr (I - e e^T)]  -  m_B omega^2 I,

and the natural frequencies are the omega > 0 with det K(omega) = 0, together with any member
frequency that happens to be a frame frequency (B motionless).  Only the lines of e_c and e_r
matter (e e^T is even in e): gamma and pi - gamma give the same frequencies.  gamma = 0 (or pi),
the toggle position, is a mechanism (K(0) singular: a zero-frequency mode); near it the lowest
frequency tends to 0.

No root missed: the Wittrick-Williams count
-------------------------------------------
The number of natural frequencies of the frame strictly below omega is

    N(omega) = J_0(omega) + s{K(omega)},

where s{K} is the number of negative eigenvalues of K(omega) and J_0 is the number of natural
frequencies below omega of the members with B fixed (their end rotations free, as eliminated
above):

    J_0 = sum over members of  #{j >= 1: j pi < alpha l}  +  #{j >= 1: j pi < beta l}.

(The point mass has no frequencies of its own.)  The counts are taken consistently with the
computed sines, so that a frequency evaluated within round-off of a pole is still counted on the
side the sine says.  N(0+) = 0 for a non-mechanism.

The i-th frequency (i = 0, 1, ...) is inf{omega : N(omega) > i}: it is bracketed by bisection on
N; as soon as the bracket [lo, hi] holds exactly one frequency (N(hi) - N(lo) = 1) and no pole
(J_0(lo) = J_0(hi)), det K is continuous on it and changes sign exactly once (one eigenvalue of K
crosses zero, monotonically), and scipy.optimize.brentq finishes on det K (to round-off).  A
repeated frequency (N jumping by 2 or more), or one on a pole, is left to the bisection, run to
a relative width of 1e-15.  Nothing here depends on a frequency grid: no root can be missed.

Units are whatever the caller's are; frequencies are circular (rad per unit time).
"""

import math

import numpy as np
from scipy.optimize import brentq

__all__ = ["member_stiffness", "joint_stiffness", "member_count", "count_below", "frequencies",
           "pinned_pinned_bending", "directions"]

_SMALL = 0.05     # below this argument, the series of y cot y and cot z - coth z are used


def _y_cot_y(y):
    """y cot y, by its series for small |y| (for y = 0 exactly, 1)."""
    if abs(y) < _SMALL:
        y2 = y * y
        return 1.0 - y2 / 3.0 - y2 * y2 / 45.0 - 2.0 * y2 ** 3 / 945.0
    return y * math.cos(y) / math.sin(y)


def member_stiffness(omega, l, rhoA, EA, EI):
    """(k_ax, k_tr): the exact axial and transverse dynamic stiffnesses at end B of a member of
    length l pinned at a fixed point at its other end, pinned (moment-free) at B.

    k_ax = EA alpha cot(alpha l), k_tr = (EI beta^3 / 2)(cot(beta l) - coth(beta l)); see the
    module docstring.  Positive = restoring (force on the member's end B along the displacement
    of B)."""
    omega = float(omega)
    if rhoA == 0.0 or omega == 0.0:
        return EA / l, 0.0
    y = omega * math.sqrt(rhoA / EA) * l
    k_ax = EA / l * _y_cot_y(y)
    z = (rhoA * omega * omega / EI) ** 0.25 * l
    if z < _SMALL:
        z4 = z ** 4
        k_tr = -(rhoA * l * omega * omega / 3.0) * (1.0 + 2.0 * z4 / 315.0
                                                    + 2.0 * z4 * z4 / 31185.0)
    else:
        beta = z / l
        k_tr = 0.5 * EI * beta ** 3 * (math.cos(z) / math.sin(z) - 1.0 / math.tanh(z))
    return k_ax, k_tr


def _count_multiples_of_pi(x):
    """#{j >= 1 : j pi < x} for x >= 0, consistent with the sign of the computed sin(x): within
    round-off of a multiple of pi the side is the one sin(x) (hence cot(x)) says."""
    j = int(math.floor(x / math.pi))
    s = math.sin(x)
    if s != 0.0 and (s > 0.0) != (j % 2 == 0):
        j += -1 if x / math.pi - j < 0.5 else 1
    return max(j, 0)


def member_count(omega, l, rhoA, EA, EI):
    """The member's J: its natural frequencies below omega with B held fixed (fixed-fixed axial
    j pi < alpha l, pinned-pinned bending j pi < beta l)."""
    if rhoA == 0.0 or omega <= 0.0:
        return 0
    y = omega * math.sqrt(rhoA / EA) * l
    z = (rhoA * omega * omega / EI) ** 0.25 * l
    return _count_multiples_of_pi(y) + _count_multiples_of_pi(z)


def directions(gamma):
    """(e_c, e_r): the unit axes of the coupler (A -> B) and of the rocker (D -> B) in the global
    frame: e_c = (1, 0), e_r = (cos gamma, -sin gamma)."""
    return np.array([1.0, 0.0]), np.array([np.cos(gamma), -np.sin(gamma)])


def _entries(omega, args):
    """(K_xx, K_xy, K_yy) of K(omega), in plain floats (the searches call this thousands of
    times)."""
    L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B = args
    kxx = kyy = -m_B * omega * omega
    kxy = 0.0
    members = (((1.0, 0.0), (L, rhoA, EA, EI)),
               ((math.cos(gamma), -math.sin(gamma)), (c, rhoA_r, EA_r, EI_r)))
    for (ex, ey), (l, r, ea, ei) in members:
        k_ax, k_tr = member_stiffness(omega, l, r, ea, ei)
        # k_ax e e^T + k_tr (I - e e^T)
        kxx += k_tr + (k_ax - k_tr) * ex * ex
        kyy += k_tr + (k_ax - k_tr) * ey * ey
        kxy += (k_ax - k_tr) * ex * ey
    return kxx, kxy, kyy


def joint_stiffness(omega, L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B=0.0):
    """K(omega), the 2 x 2 exact dynamic stiffness of the frame at B's translations (global):
    sum over the members of k_ax e e^T + k_tr (I - e e^T), minus m_B omega^2 I."""
    kxx, kxy, kyy = _entries(omega, (L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B))
    return np.array([[kxx, kxy], [kxy, kyy]])


def _j0(omega, args):
    L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r = args[:8]
    return member_count(omega, L, rhoA, EA, EI) + member_count(omega, c, rhoA_r, EA_r, EI_r)


def _det(omega, args):
    kxx, kxy, kyy = _entries(omega, args)
    return kxx * kyy - kxy * kxy


def count_below(omega, L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B=0.0):
    """N(omega): the Wittrick-Williams count of the frame's natural frequencies below omega
    (J_0 + the number of negative eigenvalues of K(omega))."""
    args = (L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B)
    return _count(omega, args)


def _negative_eigenvalues(kxx, kxy, kyy):
    """s{K}: the number of negative eigenvalues of the symmetric [[kxx, kxy], [kxy, kyy]], from
    the signs of its determinant and trace (so that it is consistent with the sign of the
    determinant the root finder uses, even where the determinant is lost in round-off)."""
    d = kxx * kyy - kxy * kxy
    t = kxx + kyy
    if d < 0.0:
        return 1
    if d > 0.0:
        return 2 if t < 0.0 else 0
    return int(t < 0.0)        # one eigenvalue zero, the other t


def _count(omega, args):
    return _j0(omega, args) + _negative_eigenvalues(*_entries(omega, args))


def pinned_pinned_bending(l, rhoA, EI, j=1):
    """The j-th pinned-pinned bending frequency (j pi / l)^2 sqrt(EI / rhoA)."""
    return (j * np.pi / l) ** 2 * np.sqrt(EI / rhoA)


def frequencies(L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B=0.0, n=3):
    """The n lowest circular natural frequencies (ascending, repeated ones repeated) of the
    frozen four-bar: coupler A -> B (L, rhoA, EA, EI) and rocker D -> B (c, rhoA_r, EA_r, EI_r),
    A and D fixed pins, B a pin joining them with a point mass m_B, gamma the angle between the
    members' axes at B (radians).  Exact (dynamic stiffness + Wittrick-Williams, see the module
    docstring); a mechanism's zero-frequency mode (gamma = 0) comes out as a value within about
    1e-13 of the reference scale of zero.

    The stiffnesses and the mass per length of the coupler must be positive; the rocker may
    have rhoA_r = 0 (a massless rocker)."""
    args = (float(L), float(rhoA), float(EA), float(EI), float(c), float(rhoA_r), float(EA_r),
            float(EI_r), float(gamma), float(m_B))
    if min(L, rhoA, EA, EI, c, EA_r, EI_r) <= 0.0 or rhoA_r < 0.0 or m_B < 0.0:
        raise ValueError("lengths, stiffnesses and the coupler's rhoA must be positive; "
                         "rhoA_r and m_B non-negative")
    # reference scale: the coupler's first pinned-pinned bending frequency (times an irrational
    # factor, so that the start of the search is never on a pole)
    scale = pinned_pinned_bending(L, rhoA, EI)
    hi = 0.7390851332151607 * scale
    while _count(hi, args) < n:
        hi *= 2.0
        if hi > 1e12 * scale:
            raise RuntimeError("no {} frequencies below {:g}".format(n, hi))
    out = []
    tiny = 1e-13 * scale
    for i in range(n):
        lo, top = (out[-1] if out else 0.0), hi
        # the i-th frequency is >= the previous one: start from it (bisection keeps N(lo) <= i)
        if lo > 0.0 and _count(lo, args) > i:
            out.append(lo)          # a repeated frequency already pinned by the bisection
            continue
        while True:
            if top < tiny:
                out.append(top)     # a zero-frequency (mechanism) mode
                break
            if top - lo <= 1e-15 * top:
                out.append(0.5 * (lo + top))
                break
            if lo > 0.0 and _count(top, args) - _count(lo, args) == 1 \
                    and _j0(lo, args) == _j0(top, args):
                f_lo, f_hi = _det(lo, args), _det(top, args)
                if f_lo == 0.0:
                    out.append(lo)
                elif f_hi == 0.0:
                    out.append(top)
                elif f_lo * f_hi < 0.0:
                    out.append(brentq(_det, lo, top, args=(args,), xtol=1e-15 * top,
                                      rtol=1e-15, maxiter=200))
                else:  # pragma: no cover  (cannot happen by the count's theorem)
                    raise RuntimeError("det K does not change sign on [{!r}, {!r}]".format(lo, top))
                break
            mid = 0.5 * (lo + top)
            if _count(mid, args) > i:
                top = mid
            else:
                lo = mid
    return np.array(out)
