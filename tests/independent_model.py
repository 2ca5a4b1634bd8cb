"""A second, independent model of the flexible slider-crank and four-bar (test helper; imports
nothing of crankgen or derive/).

Same physics as crankgen's lagrange formulation, other coordinates and another derivation:

* the rod is described in the frame that the RIGID mechanism's chord defines (origin at the crank
  pin, e_i towards the rigid end point), with ALL nodal co-ordinates (u, v, psi) of the n + 1
  nodes free: nothing is eliminated;
* the crank pin (u = v = 0 at x = 0) and the guide are enforced by Lagrange multipliers, the
  index-1 form with Baumgarte stabilisation: a slider on the line Y = e (-sin(phi) u_n +
  cos(phi) v_n = 0), or a four-bar's rocker, the end on the circle of radius c about D = (d, e),
  |A + (1 + u_n) e_i + v_n e_j - D|^2 = c^2 (a constraint non-linear in the co-ordinates; its
  velocity and acceleration forms written out here);
* the equations of motion come from d'Alembert's principle: the inertial acceleration of every
  centre-line point and of every cross-section (rotary inertia, switchable), written out here from
  R = a e_r + (x + u - y v_x) e_i + (y + v) e_j, projected on the virtual displacements; elastic and
  Kelvin-Voigt forces are the hand-differentiated gradients of the strain energy (eq. 2 for A, the
  linear strain for C) and of the Rayleigh function; Gauss quadrature;
* the crank's motion is a rate law thetad(t, theta) (constant, run-up, fluctuation: tests/four_bar.py)
  integrated with the rod (theta is a state), the crank pin's acceleration a thetadd e_theta -
  a thetad^2 e_r; the rigid mechanism's rod angle and rates from tests/four_bar.py (the slider-crank's
  closed form, the four-bar by Freudenstein's equation);
* it is integrated with scipy's explicit DOP853 at tight tolerances (no Newmark);
* the multipliers are the reactions: the pin's two are the force of the crank pin on the rod (on
  e_i, e_j), the guide's, times its constraint gradient, the force of the guide on the end node.

Units as crankgen's: L = 1, rho A = 1, time 1/omega_b: EI = 1/pi^4, EA = 1/(pi^4 eps^2),
rho I = eps^2.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

import four_bar

_XG, _WG = np.polynomial.legendre.leggauss(6)
ZETA, W = (_XG + 1) / 2, _WG / 2


def hermite(z, l):
    """Shape functions on an element of length l at zeta = z: rows for the six element DOFs
    (u1, v1, psi1, u2, v2, psi2); returns N_u, N_u', N_v, N_v', N_v''."""
    z = np.asarray(z, float)
    zero, one = 0 * z, 1 + 0 * z
    Nu = np.stack([1 - z, zero, zero, z, zero, zero], -1)
    Nux = np.stack([-one, zero, zero, one, zero, zero], -1) / l
    h1, h2, h3, h4 = 1 - 3 * z**2 + 2 * z**3, l * (z - 2 * z**2 + z**3), 3 * z**2 - 2 * z**3, l * (z**3 - z**2)
    d1, d2, d3, d4 = (6 * z**2 - 6 * z) / l, 1 - 4 * z + 3 * z**2, (6 * z - 6 * z**2) / l, 3 * z**2 - 2 * z
    s1, s2, s3, s4 = (12 * z - 6) / l**2, (6 * z - 4) / l, (6 - 12 * z) / l**2, (6 * z - 2) / l
    Nv = np.stack([zero, h1, h2, zero, h3, h4], -1)
    Nvx = np.stack([zero, d1, d2, zero, d3, d4], -1)
    Nvxx = np.stack([zero, s1, s2, zero, s3, s4], -1)
    return Nu, Nux, Nv, Nvx, Nvxx


class SliderCrank:
    """n equal elements; approach "A" (eq. 2) or "C" (linear strain); Kelvin-Voigt damping mu.
    guide: ("line", e) (default: the line Y = 0) or ("circle", c, d, e, branch); motion: a crank
    motion of tests/four_bar.py (rates(t, theta) -> thetad, thetadd; default constant omega)."""

    def __init__(self, a, eps, ms, mu, omega, n, approach="A", rotary_inertia=True, baumgarte=20.0,
                 guide=("line", 0.0), motion=None):
        assert approach in ("A", "C")
        assert guide[0] in ("line", "circle")
        self.a, self.eps, self.ms, self.mu, self.omega, self.n = a, eps, ms, mu, omega, n
        self.approach, self.alpha = approach, baumgarte
        self.guide = guide
        self.motion = four_bar.Constant(omega) if motion is None else motion
        self.EI, self.EA = 1 / math.pi**4, 1 / (math.pi**4 * eps**2)
        self.rhoI = eps**2 if rotary_inertia else 0.0
        self.l = l = 1.0 / n
        self.ndof = 3 * (n + 1)
        self.Nu, self.Nux, self.Nv, self.Nvx, self.Nvxx = hermite(ZETA, l)
        self.x = (np.arange(n)[:, None] + ZETA[None, :]) * l                 # (n, g)
        self.wl = W * l
        self.dofs = np.array([[3 * e + k for k in range(6)] for e in range(n)])
        # constant mass matrix: rho A (N_u N_u + N_v N_v) + rho I N_v' N_v', end mass at node n
        me = (np.einsum("g,gi,gj->ij", self.wl, self.Nu, self.Nu)
              + np.einsum("g,gi,gj->ij", self.wl, self.Nv, self.Nv)
              + self.rhoI * np.einsum("g,gi,gj->ij", self.wl, self.Nvx, self.Nvx))
        M = np.zeros((self.ndof, self.ndof))
        for e in range(n):
            M[np.ix_(self.dofs[e], self.dofs[e])] += me
        M[3 * n, 3 * n] += ms
        M[3 * n + 1, 3 * n + 1] += ms
        self.M = M
        self.Minv = np.linalg.inv(M)

    def crank(self, t, theta):
        """theta, thetad, thetadd, phi, phid, phidd of the rigid mechanism at the crank angle theta."""
        thd, thdd = (float(x) for x in self.motion.rates(t, theta))
        if self.guide[0] == "line":
            k = four_bar.slider_crank(theta, thd, thdd, self.a, self.guide[1])
        else:
            _, c, d, e, branch = self.guide
            k = four_bar.four_bar(theta, thd, thdd, self.a, c, d, e, branch)
        return theta, thd, thdd, float(k["phi"]), float(k["phid"]), float(k["phidd"])

    def _elements(self, vec):
        return vec[self.dofs]                                                 # (n, 6)

    def forces(self, t, q, qd, kin):
        """Generalized forces f(t, q, qd) with M qdd = f + G^T lambda (kin: self.crank(t, theta))."""
        th, thd, thdd, ph, phd, phdd = kin
        qe, qde = self._elements(q), self._elements(qd)
        u, ud = qe @ self.Nu.T, qde @ self.Nu.T
        v, vd = qe @ self.Nv.T, qde @ self.Nv.T
        psi = qe @ self.Nvx.T
        ux, uxd = qe @ self.Nux.T, qde @ self.Nux.T
        psid = qde @ self.Nvx.T
        vxx, vxxd = qe @ self.Nvxx.T, qde @ self.Nvxx.T
        x = self.x
        # absolute acceleration of a centre-line point without its qdd part, on (e_i, e_j):
        # crank pin a thdd e_theta - a thd^2 e_r, with e_r . e_i = cos(theta + phi), e_r . e_j =
        # sin(theta + phi), e_theta . e_i = -sin(theta + phi), e_theta . e_j = cos(theta + phi);
        # frame rates d e_i/dt = -phid e_j, d e_j/dt = phid e_i
        ai_p = -self.a * thd**2 * math.cos(th + ph) - self.a * thdd * math.sin(th + ph)
        aj_p = -self.a * thd**2 * math.sin(th + ph) + self.a * thdd * math.cos(th + ph)

        def accel(x, u, ud, v, vd):
            wi, wj = ud + v * phd, vd - (x + u) * phd
            return (ai_p + vd * phd + v * phdd + wj * phd, aj_p - ud * phd - (x + u) * phdd - wi * phd)

        Ai, Aj = accel(x, u, ud, v, vd)
        rot = phdd + psi * phd**2             # section: -(rotation accel. along e_i) without psidd
        # elastic and Kelvin-Voigt stresses
        if self.approach == "A":
            strain, rate = ux + 0.5 * psi**2, uxd + psi * psid
        else:
            strain, rate = ux, uxd
        N = self.EA * (strain + self.mu * rate)           # axial force incl. strain-rate damping
        Mb = self.EI * (vxx + self.mu * vxxd)             # bending moment incl. damping
        dstrain_v = psi if self.approach == "A" else 0.0 * psi
        wl = self.wl
        fe = -((Ai * wl) @ self.Nu + (Aj * wl) @ self.Nv - self.rhoI * (rot * wl) @ self.Nvx
               + (N * wl) @ self.Nux + (N * dstrain_v * wl) @ self.Nvx + (Mb * wl) @ self.Nvxx)
        f = np.zeros(self.ndof)
        np.add.at(f, self.dofs, fe)
        n = self.n
        Si, Sj = accel(1.0, q[3 * n], qd[3 * n], q[3 * n + 1], qd[3 * n + 1])
        f[3 * n] -= self.ms * Si
        f[3 * n + 1] -= self.ms * Sj
        return f

    def constraints(self, t, q, qd, kin):
        """(G, g, gd, gamma) of the three constraints (pin u_0 = v_0 = 0, the guide): G = dg/dq,
        g and its time derivative, and gamma with d^2 g / dt^2 = G qdd + gamma."""
        th, thd, thdd, ph, phd, phdd = kin
        G = np.zeros((3, self.ndof))
        G[0, 0] = G[1, 1] = 1.0
        g, gd, gamma = np.zeros(3), np.zeros(3), np.zeros(3)
        g[:2], gd[:2] = q[:2], qd[:2]
        j = 3 * self.n
        u, v, ud, vd = q[j], q[j + 1], qd[j], qd[j + 1]
        s, c = math.sin(ph), math.cos(ph)
        if self.guide[0] == "line":
            # -sin(phi) u + cos(phi) v = 0, differentiated twice by hand
            G[2, j], G[2, j + 1] = -s, c
            g[2] = -s * u + c * v
            gd[2] = -s * ud + c * vd - phd * (c * u + s * v)
            gamma[2] = (-2 * phd * (c * ud + s * vd) - phdd * (c * u + s * v) + phd**2 * (s * u - c * v))
            return G, g, gd, gamma
        _, rc, d, e, _ = self.guide
        ei, ej = np.array([c, -s]), np.array([s, c])
        er, et = np.array([math.cos(th), math.sin(th)]), np.array([-math.sin(th), math.cos(th)])
        A = self.a * er
        Ad = self.a * thd * et
        Add = self.a * (thdd * et - thd**2 * er)
        P = A + (1 + u) * ei + v * ej - np.array([d, e])
        Pd = Ad + ud * ei + vd * ej - (1 + u) * phd * ej + v * phd * ei
        Pdd_rest = (Add + 2 * ud * (-phd * ej) + 2 * vd * (phd * ei)
                    + (1 + u) * (-phdd * ej - phd**2 * ei) + v * (phdd * ei - phd**2 * ej))
        G[2, j], G[2, j + 1] = 2 * P @ ei, 2 * P @ ej
        g[2] = P @ P - rc**2
        gd[2] = 2 * P @ Pd
        gamma[2] = 2 * Pd @ Pd + 2 * P @ Pdd_rest
        return G, g, gd, gamma

    def _solve(self, t, y):
        """(qdd, lambda, kin): M qdd = f + G^T lambda and G qdd = -gamma - 2 alpha gd - alpha^2 g
        (the second time derivative of g = 0, Baumgarte-stabilised)."""
        q, qd, theta = y[:self.ndof], y[self.ndof:2 * self.ndof], y[-1]
        kin = self.crank(t, theta)
        G, g, gd, gamma = self.constraints(t, q, qd, kin)
        Minv_f = self.Minv @ self.forces(t, q, qd, kin)
        Minv_Gt = self.Minv @ G.T
        target = -gamma - 2 * self.alpha * gd - self.alpha**2 * g
        lam = np.linalg.solve(G @ Minv_Gt, target - G @ Minv_f)
        return Minv_f + Minv_Gt @ lam, lam, kin

    def rhs(self, t, y):
        qdd, _, kin = self._solve(t, y)
        return np.concatenate([y[self.ndof:2 * self.ndof], qdd, [kin[1]]])

    def reactions(self, t, y):
        """(torque, pin force (X, Y), end force (X, Y)): the multipliers as the forces of the crank
        pin and of the guide on the rod (the end node with its mass) in the inertial frame, and the
        driving torque a e_r x F_pin."""
        q, qd = y[:self.ndof], y[self.ndof:2 * self.ndof]
        _, lam, kin = self._solve(t, y)
        th, _, _, ph, _, _ = kin
        G = self.constraints(t, q, qd, kin)[0]
        j = 3 * self.n
        ei, ej = np.array([math.cos(ph), -math.sin(ph)]), np.array([math.sin(ph), math.cos(ph)])
        pin = lam[0] * ei + lam[1] * ej
        end = lam[2] * (G[2, j] * ei + G[2, j + 1] * ej)
        torque = self.a * (math.cos(th) * pin[1] - math.sin(th) * pin[0])
        return np.array([torque, pin[0], pin[1], end[0], end[1]])

    def outputs(self, y):
        """v* at x = 1/2, u*(1) = u_n / eps^2 and the extension u_n + (1/2) int v_x^2 dx."""
        q = y[:self.ndof]
        e = min(int(0.5 * self.n), self.n - 1)
        z = 0.5 * self.n - e
        Nv = hermite(np.array([z]), self.l)[2][0]
        v_mid = q[self.dofs[e]] @ Nv
        psi = self._elements(q) @ self.Nvx.T
        return np.array([v_mid / self.eps, q[3 * self.n] / self.eps**2,
                         q[3 * self.n] + 0.5 * np.sum(psi**2 * self.wl)])

    def simulate(self, t_eval, rtol=1e-11, atol=1e-14, forces=False):
        """From rest, undeformed, at t = 0 (theta = 0): outputs (len(t_eval), 3) (with forces: 8,
        the reactions appended) and the largest constraint violation."""
        y0 = np.zeros(2 * self.ndof + 1)
        sol = solve_ivp(self.rhs, (0.0, t_eval[-1]), y0, method="DOP853", t_eval=t_eval,
                        rtol=rtol, atol=atol)
        assert sol.success, sol.message
        out = np.array([self.outputs(y) for y in sol.y.T])
        if forces:
            out = np.concatenate([out, np.array([self.reactions(t, y) for t, y in zip(sol.t, sol.y.T)])], 1)
        drift = max(np.max(np.abs(self.constraints(t, y[:self.ndof], y[self.ndof:2 * self.ndof],
                                                   self.crank(t, y[-1]))[1]))
                    for t, y in zip(sol.t, sol.y.T))
        return out, drift
