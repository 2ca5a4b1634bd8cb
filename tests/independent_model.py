"""A second, independent model of the flexible slider-crank (test helper; imports nothing of
crankgen or derive/).

Same physics as crankgen's lagrange formulation, other coordinates and another derivation:

* the rod is described in the frame that the RIGID mechanism's chord defines (origin at the crank
  pin, e_i towards the rigid slider), with ALL nodal co-ordinates (u, v, psi) of the n + 1 nodes
  free: nothing is eliminated;
* the crank pin (u = v = 0 at x = 0) and the guide (the slider end stays on the X axis,
  -sin(phi) u_n + cos(phi) v_n = 0) are enforced by Lagrange multipliers, the index-1 form with
  Baumgarte stabilisation;
* the equations of motion come from d'Alembert's principle: the inertial acceleration of every
  centre-line point and of every cross-section (rotary inertia, switchable), written out here from
  R = a e_r + (x + u - y v_x) e_i + (y + v) e_j, projected on the virtual displacements; elastic and
  Kelvin-Voigt forces are the hand-differentiated gradients of the strain energy (eq. 2 for A, the
  linear strain for C) and of the Rayleigh function; Gauss quadrature;
* it is integrated with scipy's explicit DOP853 at tight tolerances (no Newmark).

Units as crankgen's: L = 1, rho A = 1, time 1/omega_b: EI = 1/pi^4, EA = 1/(pi^4 eps^2),
rho I = eps^2.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

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
    """n equal elements; approach "A" (eq. 2) or "C" (linear strain); Kelvin-Voigt damping mu."""

    def __init__(self, a, eps, ms, mu, omega, n, approach="A", rotary_inertia=True, baumgarte=20.0):
        assert approach in ("A", "C")
        self.a, self.eps, self.ms, self.mu, self.omega, self.n = a, eps, ms, mu, omega, n
        self.approach, self.alpha = approach, baumgarte
        self.EI, self.EA = 1 / math.pi**4, 1 / (math.pi**4 * eps**2)
        self.rhoI = eps**2 if rotary_inertia else 0.0
        self.l = l = 1.0 / n
        self.ndof = 3 * (n + 1)
        self.Nu, self.Nux, self.Nv, self.Nvx, self.Nvxx = hermite(ZETA, l)
        self.x = (np.arange(n)[:, None] + ZETA[None, :]) * l                 # (n, g)
        self.wl = W * l
        self.dofs = np.array([[3 * e + k for k in range(6)] for e in range(n)])
        # constant mass matrix: rho A (N_u N_u + N_v N_v) + rho I N_v' N_v', slider at node n
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

    def crank(self, t):
        """theta, thetad, phi, phid, phidd of the rigid mechanism (sin phi = a sin theta)."""
        th, thd = self.omega * t, self.omega
        sphi = self.a * math.sin(th)
        cphi = math.sqrt(1 - sphi**2)
        phd = self.a * thd * math.cos(th) / cphi
        phdd = (phd**2 * sphi - self.a * thd**2 * math.sin(th)) / cphi
        return th, thd, math.asin(sphi), phd, phdd

    def _elements(self, vec):
        return vec[self.dofs]                                                 # (n, 6)

    def forces(self, t, q, qd):
        """Generalized forces f(t, q, qd) with M qdd = f + G^T lambda."""
        th, thd, ph, phd, phdd = self.crank(t)
        qe, qde = self._elements(q), self._elements(qd)
        u, ud = qe @ self.Nu.T, qde @ self.Nu.T
        v, vd = qe @ self.Nv.T, qde @ self.Nv.T
        psi = qe @ self.Nvx.T
        ux, uxd = qe @ self.Nux.T, qde @ self.Nux.T
        psid = qde @ self.Nvx.T
        vxx, vxxd = qe @ self.Nvxx.T, qde @ self.Nvxx.T
        x = self.x
        # absolute acceleration of a centre-line point without its qdd part, on (e_i, e_j):
        # crank pin -a thd^2 e_r, with e_r . e_i = cos(theta + phi), e_r . e_j = sin(theta + phi),
        # frame rates d e_i/dt = -phid e_j, d e_j/dt = phid e_i
        ai_p, aj_p = -self.a * thd**2 * math.cos(th + ph), -self.a * thd**2 * math.sin(th + ph)

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

    def constraints(self, t):
        """G, Gd, Gdd (3, ndof): pin u_0 = v_0 = 0 and the guide -sin(phi) u_n + cos(phi) v_n = 0."""
        _, _, ph, phd, phdd = self.crank(t)
        G, Gd, Gdd = (np.zeros((3, self.ndof)) for _ in range(3))
        G[0, 0] = G[1, 1] = 1.0
        j = 3 * self.n
        G[2, j], G[2, j + 1] = -math.sin(ph), math.cos(ph)
        Gd[2, j], Gd[2, j + 1] = -math.cos(ph) * phd, -math.sin(ph) * phd
        Gdd[2, j] = math.sin(ph) * phd**2 - math.cos(ph) * phdd
        Gdd[2, j + 1] = -math.cos(ph) * phd**2 - math.sin(ph) * phdd
        return G, Gd, Gdd

    def rhs(self, t, y):
        """qdd from M qdd = f + G^T lambda and G qdd = -2 Gd qd - Gdd q - 2 alpha gd - alpha^2 g
        (the second time derivative of G q = 0, Baumgarte-stabilised)."""
        q, qd = y[:self.ndof], y[self.ndof:]
        G, Gd, Gdd = self.constraints(t)
        g, gd = G @ q, G @ qd + Gd @ q
        Minv_f = self.Minv @ self.forces(t, q, qd)
        Minv_Gt = self.Minv @ G.T
        target = -2 * Gd @ qd - Gdd @ q - 2 * self.alpha * gd - self.alpha**2 * g
        lam = np.linalg.solve(G @ Minv_Gt, target - G @ Minv_f)
        return np.concatenate([qd, Minv_f + Minv_Gt @ lam])

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

    def simulate(self, t_eval, rtol=1e-11, atol=1e-14):
        """From rest, undeformed, at t = 0: outputs (len(t_eval), 3) and the largest constraint
        violation."""
        y0 = np.zeros(2 * self.ndof)
        sol = solve_ivp(self.rhs, (0.0, t_eval[-1]), y0, method="DOP853", t_eval=t_eval,
                        rtol=rtol, atol=atol)
        assert sol.success, sol.message
        out = np.array([self.outputs(y) for y in sol.y.T])
        drift = max(np.max(np.abs(self.constraints(t)[0] @ y[:self.ndof])) for t, y in zip(sol.t, sol.y.T))
        return out, drift
