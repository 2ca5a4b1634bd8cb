"""Rigid mechanisms written out independently (test helper; imports nothing of crankgen or derive/).

Conventions as crankgen's (derive/guides.py states them; nothing is taken from its code): the crank
pivot at the origin, the crank pin A = a (cos theta, sin theta), the rod's chord e_i =
(cos phi, -sin phi) from A to its end B (rod length L = 1), e_j = (sin phi, cos phi).

* four_bar: the four-bar linkage whose end B is the tip of a rocker of length c pivoted at
  D = (d, e), B = D + c (cos beta, sin beta).  Position analysis by Freudenstein's equation in the
  rocker angle, |D + c u(beta) - A| = 1, i.e. P . u(beta) = K with P = D - A and
  K = (1 - c^2 - |P|^2) / (2 c), solved through the half-angle tangent (crankgen intersects two
  circles instead); branch +1 is the root with B on the counter-clockwise side of the line from A
  to D (cross(D - A, B - A) > 0).  Rates from the time derivatives of the loop equation
  A + e_i = D + c u(beta), solved as 2 x 2 linear systems (velocities, then accelerations).
* slider_crank: the (offset) slider-crank, sin phi = a sin theta - e, with the crank's angular
  acceleration.
* inverse_dynamics: the rigid mechanism driven at (theta, thetad, thetadd): rigid rod of mass
  rho A L = 1 and moment of inertia 1/12 + rho I about its centre (the sections' rotary inertia
  rho I per unit length), end mass ms at B, a massless crank and a massless frictionless guide
  (slider: a force normal to the line; rocker: a force along DB).  Newton-Euler for rod + end mass:
  the driving torque, the force of the crank pin on the rod and the guide's force at B.
* quasi_static: the elastic rod loaded statically by the rigid mechanism's inertia (approach C:
  EI v'''' = -rho A A_j, EA u'' = rho A A_i), pinned at A, moment-free ends, its end node moving
  on the guide's tangent, in balance along it with the end mass's inertia.
* crank motions: a run-up's speed (quintic smooth step in time) and a fluctuating crank's rate
  law, integrated numerically here (crankgen has closed forms).
"""

import math

import numpy as np
from scipy.integrate import solve_ivp


def _cross(p, q):
    return p[..., 0] * q[..., 1] - p[..., 1] * q[..., 0]


def _vec(x, y):
    return np.stack(np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float)), -1)


def rocker_angle(theta, a, c, d, e, branch=1):
    """Rigid rocker angle beta (rad, in (-pi, pi]) of the four-bar (Freudenstein's equation)."""
    theta = np.asarray(theta, float)
    A = _vec(a * np.cos(theta), a * np.sin(theta))
    P = _vec(d, e) - A
    px, py = P[..., 0], P[..., 1]
    K = (1.0 - c**2 - (px**2 + py**2)) / (2.0 * c)
    # px cos b + py sin b = K;  tan(b/2) = t:  (K + px) t^2 - 2 py t + (K - px) = 0
    disc = px**2 + py**2 - K**2
    assert np.all(disc > 0), "the linkage does not close"
    root = np.sqrt(disc)
    betas = []
    for sign in (1.0, -1.0):
        q = py + sign * root                     # stable pair of roots: t = q / (K + px) = (K - px) / q
        t = (K - px) / q
        betas.append(2.0 * np.arctan(t))
    out = np.empty_like(theta)
    for b in betas:
        B = _vec(d + c * np.cos(b), e + c * np.sin(b))
        side = np.sign(_cross(P, B - A))
        out = np.where(side == branch, b, out)
    # both roots are distinct when the linkage closes (disc > 0): exactly one has the branch's side
    return out


def four_bar(theta, thetad, thetadd, a, c, d, e, branch=1):
    """dict of phi, phid, phidd, beta, betad, betadd of the rigid four-bar."""
    theta = np.asarray(theta, float)
    beta = rocker_angle(theta, a, c, d, e, branch)
    A = _vec(a * np.cos(theta), a * np.sin(theta))
    B = _vec(d + c * np.cos(beta), e + c * np.sin(beta))
    ei = B - A
    phi = np.arctan2(-ei[..., 1], ei[..., 0])
    ej = _vec(np.sin(phi), np.cos(phi))
    et = _vec(-np.sin(theta), np.cos(theta))           # crank tangent
    er = _vec(np.cos(theta), np.sin(theta))
    ub = _vec(np.cos(beta), np.sin(beta))
    tb = _vec(-np.sin(beta), np.cos(beta))             # rocker tangent
    # velocity loop: a thetad et - phid ej = c betad tb  ->  [-ej, -c tb] (phid, betad) = -a thetad et
    thetad, thetadd = np.broadcast_arrays(np.asarray(thetad, float), np.asarray(thetadd, float))
    M = np.stack([-ej, -c * tb], -1)                   # (..., 2, 2), columns: phid, betad
    rhs = -(a * thetad)[..., None] * et
    phid, betad = np.moveaxis(np.linalg.solve(M, rhs[..., None])[..., 0], -1, 0)
    # acceleration loop: a thetadd et - a thetad^2 er - phidd ej - phid^2 ei
    #                    = c betadd tb - c betad^2 ub
    rhs = (-(a * thetadd)[..., None] * et + (a * thetad**2)[..., None] * er + (phid**2)[..., None] * ei
           - (c * betad**2)[..., None] * ub)
    phidd, betadd = np.moveaxis(np.linalg.solve(M, rhs[..., None])[..., 0], -1, 0)
    return dict(theta=theta, thetad=thetad, thetadd=thetadd, phi=phi, phid=phid, phidd=phidd,
                beta=beta, betad=betad, betadd=betadd, B=B, tangent=tb, normal=-ub)


def slider_crank(theta, thetad, thetadd, a, e=0.0):
    """dict of phi, phid, phidd and the slider's abscissa X with its rates (line Y = e)."""
    theta, thetad, thetadd = np.broadcast_arrays(*(np.asarray(x, float) for x in (theta, thetad, thetadd)))
    sphi = a * np.sin(theta) - e
    cphi = np.sqrt(1 - sphi**2)
    phid = a * thetad * np.cos(theta) / cphi
    phidd = (sphi * phid**2 + a * (thetadd * np.cos(theta) - thetad**2 * np.sin(theta))) / cphi
    X = a * np.cos(theta) + cphi
    B = _vec(X, e + 0 * X)
    ones, zeros = np.ones_like(X), np.zeros_like(X)
    return dict(theta=theta, thetad=thetad, thetadd=thetadd, phi=np.arcsin(sphi), phid=phid,
                phidd=phidd, B=B, tangent=_vec(ones, zeros), normal=_vec(zeros, ones))


def _frame(phi):
    return _vec(np.cos(phi), -np.sin(phi)), _vec(np.sin(phi), np.cos(phi))


def accelerations(k, a, x):
    """Inertial acceleration (..., 2) of the rigid rod's point x (0 <= x <= 1)."""
    th, thd, thdd = k["theta"], k["thetad"], k["thetadd"]
    ei, ej = _frame(k["phi"])
    aA = a * (thdd[..., None] * _vec(-np.sin(th), np.cos(th)) - (thd**2)[..., None] * _vec(np.cos(th), np.sin(th)))
    # d^2 e_i / dt^2 = -phidd e_j - phid^2 e_i
    return aA + x * (-(k["phidd"])[..., None] * ej - (k["phid"] ** 2)[..., None] * ei)


def inverse_dynamics(k, a, ms, rhoI, guide_normal=None):
    """Rigid mechanism's (torque, pin force (..., 2), end force (..., 2)) in the inertial frame:
    the torque the crank needs (counter-clockwise), the force of the crank pin on the rod, the
    force of the guide on rod + end mass at B (along guide_normal, default k["normal"])."""
    n = k["normal"] if guide_normal is None else guide_normal
    th = k["theta"]
    A = a * _vec(np.cos(th), np.sin(th))
    ei, _ = _frame(k["phi"])
    aG, aB = accelerations(k, a, 0.5), accelerations(k, a, 1.0)
    J = 1.0 / 12.0 + rhoI
    alpha = -k["phidd"]                                 # the rod's inertial angle is -phi
    # moments about A:  (B - A) x (lam n) = J alpha + (G - A) x aG + ms (B - A) x aB
    lam = (J * alpha + _cross(0.5 * ei, aG) + ms * _cross(ei, aB)) / _cross(ei, n)
    end = lam[..., None] * n
    pin = aG + ms * aB - end                            # rod mass rho A L = 1
    torque = _cross(A, pin)
    return torque, pin, end


def quasi_static(k, a, eps, ms, rotary_inertia=True):
    """(v*(1/2), u*(1)) of the static rod under the rigid mechanism's inertia loads (approach C;
    tests/test_linear_truths.py does the same for the slider-crank, along the guide)."""
    EI, EA = 1 / math.pi**4, 1 / (math.pi**4 * eps**2)
    rhoI = eps**2 if rotary_inertia else 0.0
    ei, ej = _frame(k["phi"])
    a0, a1 = accelerations(k, a, 0.0), accelerations(k, a, 1.0)
    alpha, beta_ = np.sum(a0 * ej, -1), np.sum((a1 - a0) * ej, -1)      # A_j = alpha + beta x
    gamma, delta = np.sum(a0 * ei, -1), np.sum((a1 - a0) * ei, -1)     # A_i = gamma + delta x
    v_mid_pinned = 5 * (-(alpha + beta_ / 2)) / (384 * EI)
    shear_end = -(alpha / 2 + beta_ / 3)
    T = k["tangent"]
    ti, tj = np.sum(T * ei, -1), np.sum(T * ej, -1)                    # guide tangent on the frame
    mass_along = ms * np.sum(a1 * T, -1)
    du_end = -((-shear_end - rhoI * k["phidd"]) * tj + mass_along) / (EA * ti)
    u_end = du_end - (gamma / 2 + delta / 3) / EA
    v_end = u_end * tj / ti
    return (v_mid_pinned + v_end / 2) / eps, u_end / eps**2


# ---- crank motions ---------------------------------------------------------------------------

def smooth_step(x):
    x = np.clip(x, 0.0, 1.0)
    return x**3 * (10 - 15 * x + 6 * x**2), 30 * x**2 * (1 - x) ** 2


class RunUp:
    """Speed rising from w0 to w1 along the quintic smooth step of t / T, theta(T) = 2 pi N."""

    def __init__(self, w0, w1, revolutions):
        self.w0, self.w1 = w0, w1
        self.T = 2 * math.pi * revolutions / (0.5 * (w0 + w1))     # the step's mean is 1/2

    def rates(self, t, theta):
        s, ds = smooth_step(t / self.T)
        inside = t < self.T
        return self.w0 + (self.w1 - self.w0) * s, np.where(inside, (self.w1 - self.w0) * ds / self.T, 0.0)


class Fluctuation:
    """thetad = w (1 + k sin(j theta))."""

    def __init__(self, w, k, j):
        self.w, self.k, self.j = w, k, j

    def rates(self, t, theta):
        thd = self.w * (1 + self.k * np.sin(self.j * theta))
        return thd, self.w * self.k * self.j * np.cos(self.j * theta) * thd

    def period(self):
        from scipy.integrate import quad
        return quad(lambda th: 1.0 / (self.w * (1 + self.k * math.sin(self.j * th))), 0, 2 * math.pi,
                    epsabs=1e-13, epsrel=1e-13, limit=400)[0]


class Constant:
    def __init__(self, w):
        self.w = w

    def rates(self, t, theta):
        return self.w + 0 * np.asarray(theta, float), 0 * np.asarray(theta, float)


def crank_history(motion, t):
    """(theta, thetad, thetadd) at the times t, theta integrated from 0 at t = 0 (DOP853)."""
    t = np.asarray(t, float)
    sol = solve_ivp(lambda s, y: [float(motion.rates(s, y[0])[0])], (0.0, float(t[-1])), [0.0],
                    method="DOP853", t_eval=t, rtol=1e-13, atol=1e-13)
    assert sol.success, sol.message
    theta = sol.y[0]
    thd, thdd = motion.rates(t, theta)
    return theta, thd, thdd
