"""Defining systems of codimension-one points of a map in two parameters (minimally augmented).

The fixed points of P^k carry one condition more.  With A = dP^k/dx - lambda I, lambda = +1 (fold),
-1 (period doubling) or e^{i theta} (Neimark-Sacker, theta in (0, pi) one more unknown), and the
bordered matrix
    M = [[A, b], [c^H, 0]],   M [v; sigma] = [0; 1],   M^H [w; s] = [0; 1],
sigma(x, p[, theta]) vanishes exactly where A is singular (b, c: vectors near the left and right
null vectors of A, updated to w, v after every accepted point so that M stays regular).  The system
    P^k(x, p) - x = 0,   sigma = 0              (fold, period doubling: real sigma)
    P^k(x, p) - x = 0,   Re sigma = Im sigma = 0   (Neimark-Sacker)
has one unknown more than equations: a curve in (x, p1, p2[, theta]).  This is Govaerts' minimally
augmented system, the one MatCont and BifurcationKit continue; the Neimark-Sacker form with
e^{i theta} is BifurcationKit's.

Derivatives.  dP^k/dx and dP^k/dp are exact (the map's, for the mechanism the engine's
linearized steps).  sigma_z = -w^H A_z v needs second derivatives of P, which nothing supplies
exactly: by the symmetry of mixed partial derivatives,
    w^H (d/dz dP/dx) d = d/dh [w^H (dP/dx, dP/dp)(x + h d, p)]  at h = 0,
so the gradient of sigma over every unknown at once is a central difference of the exact
Jacobians at x + h d and x - h d, d = v (real) or Re v and Im v (complex), h = fd_step (1 + max|x|)
/ max|d| (truncation ~h^2, the Jacobians' Newton noise ~1e-10 / h).  sigma_theta = i e^{i theta}
w^H v exactly.  Only the corrector's convergence and the tangent use these derivatives; the points
themselves satisfy the exact residual.

Parameters enter scaled, q = p / scale (the chart's widths), so that both are of order one.
"""

import cmath
import math

import numpy as np

from .maps import MapError

KINDS = ("fold", "period-doubling", "neimark-sacker")


class Evaluation:
    """The defining system at Z: F (equations), DF (their Jacobian, None when not asked), P, jx,
    jp (scaled parameters), v, w, sigma, the multipliers mu (by decreasing modulus)."""

    __slots__ = ("Z", "F", "DF", "P", "jx", "jp", "v", "w", "sigma", "sigma_z", "_mu", "_map")

    def __init__(self, **kw):
        self._mu = None
        for k, v in kw.items():
            setattr(self, k, v)

    @property
    def mu(self):
        if self._mu is None:
            self._mu = self._map.multipliers(self.jx)
        return self._mu


class Defining:
    """The defining system of one kind of point for a PlaneMap at period k.  Unknowns Z = (x,
    q1, q2[, theta]), q = p / scale."""

    def __init__(self, kind, fmap, period, scale, fd_step=1e-5):
        if kind not in KINDS:
            raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
        self.kind, self.map, self.period = kind, fmap, int(period)
        self.scale = np.asarray(scale, dtype=float)
        self.fd_step = float(fd_step)
        self.n = fmap.dim
        self.complex = kind == "neimark-sacker"
        self.size = self.n + 2 + (1 if self.complex else 0)      # unknowns
        self.b = self.c = None

    # -- the unknowns -----------------------------------------------------------------------------
    def x(self, Z):
        return Z[:self.n]

    def p(self, Z):
        return Z[self.n:self.n + 2] * self.scale

    def theta(self, Z):
        return float(Z[-1]) if self.complex else None

    def lam(self, Z):
        if self.kind == "fold":
            return 1.0
        if self.kind == "period-doubling":
            return -1.0
        return cmath.exp(1j * Z[-1])

    def unknowns(self, x, p, theta=None):
        z = np.concatenate([np.asarray(x, dtype=float), np.asarray(p, dtype=float) / self.scale])
        return np.append(z, theta) if self.complex else z

    # -- borders ----------------------------------------------------------------------------------
    def critical(self, jx, theta=None):
        """The critical multiplier of jx for this kind (for Neimark-Sacker the one of positive
        imaginary part nearest e^{i theta}, or nearest the unit circle without theta)."""
        mu = np.linalg.eigvals(jx)
        if self.kind == "fold":
            return complex(mu[np.argmin(np.abs(mu - 1.0))])
        if self.kind == "period-doubling":
            return complex(mu[np.argmin(np.abs(mu + 1.0))])
        upper = mu[mu.imag > 1e-12 * np.maximum(1.0, np.abs(mu))]
        if upper.size == 0:
            raise MapError("no complex multiplier for a Neimark-Sacker point")
        if theta is None:
            return complex(upper[np.argmin(np.abs(np.abs(upper) - 1.0))])
        return complex(upper[np.argmin(np.abs(upper - cmath.exp(1j * theta)))])

    def set_borders(self, jx, theta=None):
        """b, c from the left and right eigenvectors of jx for its critical multiplier."""
        mu_c = self.critical(jx, theta)
        target = mu_c if self.complex else mu_c.real
        dtype = complex if self.complex else float
        vals, vecs = np.linalg.eig(jx)
        v = vecs[:, np.argmin(np.abs(vals - target))]
        vals, vecs = np.linalg.eig(jx.conj().T)
        w = vecs[:, np.argmin(np.abs(vals - np.conj(target)))]
        if not self.complex:
            v, w = np.real(v), np.real(w)
        self.c = np.asarray(v / np.linalg.norm(v), dtype=dtype)
        self.b = np.asarray(w / np.linalg.norm(w), dtype=dtype)
        return mu_c

    def update_borders(self, ev):
        """After an accepted point: the borders become its null vectors (M stays regular)."""
        self.c = ev.v / np.linalg.norm(ev.v)
        self.b = ev.w / np.linalg.norm(ev.w)

    def _bordered(self, A):
        n = self.n
        M = np.zeros((n + 1, n + 1), dtype=A.dtype)
        M[:n, :n] = A
        M[:n, n] = self.b
        M[n, :n] = np.conj(self.c)
        e = np.zeros(n + 1, dtype=A.dtype)
        e[n] = 1.0
        try:
            sol = np.linalg.solve(M, e)
            adj = np.linalg.solve(M.conj().T, e)
        except np.linalg.LinAlgError:
            raise MapError("the bordered matrix of the defining system is singular")
        return sol[:n], adj[:n], sol[n]

    # -- evaluation -------------------------------------------------------------------------------
    def evaluate(self, Z, jacobian=True):
        """The Evaluation at Z (DF with jacobian)."""
        n = self.n
        x, p = self.x(Z), self.p(Z)
        P, jx, jp = self.map.jacobians([(x, p)], self.period, dp=jacobian)[0]
        lam = self.lam(Z)
        v, w, sigma = self._bordered(jx - lam * np.eye(n))
        F = np.concatenate([P - x, [sigma.real, sigma.imag] if self.complex else [sigma]])
        ev = Evaluation(Z=np.array(Z, dtype=float), F=F, DF=None, P=P, jx=jx,
                        jp=None if jp is None else jp * self.scale, v=v, w=w, sigma=sigma,
                        sigma_z=None, _map=self.map)
        if jacobian:
            self._jacobian(ev)
        return ev

    def _jacobian(self, ev):
        n = self.n
        x, p = self.x(ev.Z), self.p(ev.Z)
        dirs = [ev.v.real, ev.v.imag] if self.complex else [ev.v]
        size = 1.0 + float(np.max(np.abs(x)))
        steps = [self.fd_step * size / max(float(np.max(np.abs(d))), 1e-300) for d in dirs]
        requests = []
        for d, h in zip(dirs, steps):
            requests += [(x + h * d, p), (x - h * d, p)]
        out = self.map.jacobians(requests, self.period, dp=True)
        wh = np.conj(ev.w)
        grads = []
        for k, h in enumerate(steps):
            (_, jxp, jpp), (_, jxm, jpm) = out[2 * k], out[2 * k + 1]
            full_p = np.hstack([jxp, jpp * self.scale])
            full_m = np.hstack([jxm, jpm * self.scale])
            grads.append((wh @ full_p - wh @ full_m) / (2 * h))
        sigma_z = -(grads[0] + 1j * grads[1]) if self.complex else -grads[0]
        DF = np.zeros((n + (2 if self.complex else 1), self.size))
        DF[:n, :n] = ev.jx - np.eye(n)
        DF[:n, n:n + 2] = ev.jp
        if self.complex:
            sigma_t = 1j * cmath.exp(1j * ev.Z[-1]) * (wh @ ev.v)
            row = np.append(sigma_z, sigma_t)
            DF[n] = row.real
            DF[n + 1] = row.imag
        else:
            DF[n] = sigma_z
        ev.sigma_z = sigma_z
        ev.DF = DF

    # -- quantities of a point --------------------------------------------------------------------
    def normal_form_fold(self, ev):
        """w^T B(v, v) / (|w| |v|^2) of a fold point, B the second derivative of P^k: the fold's
        quadratic coefficient, which vanishes at a cusp (= -sigma_x . v)."""
        if ev.sigma_z is None:
            return math.nan
        sx = np.real(ev.sigma_z[:self.n])
        v, w = np.real(ev.v), np.real(ev.w)
        return float(-(sx @ v) / (np.linalg.norm(w) * np.linalg.norm(v) ** 2))
