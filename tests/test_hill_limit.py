"""The linear limit: a Hill equation, solved here without crankgen.

Approach B (strain u_x + v_x^2/2 without the quartic term) with a tiny crank (a* = 1e-5) and a
heavy slider (ms* = 500): the rod barely turns, so the transverse forcing of the rigid motion and
every term of the rod's rotation are O(a*) and the orbit's deflection is tiny; what is left of the
transverse equation, linearized about the orbit, is a Hill equation,
    rho A v_tt + EI (v_xxxx + mu v_xxxxt) - (N(x, t) v_x)_x = 0,   v = v_xx = 0 at both ends,
with N the periodic axial force of the rod carrying the slider: the axial wave equation
rho A (u_tt + A_i) = EA (u_xx + mu u_xxt), u(0) = 0, ms (X_tt + u_tt(1)) = -N(1), under the crank
pin's axial acceleration A_i = -a* Omega^2 cos(Omega t) (to first order), solved in closed form in
complex amplitudes.  Its Floquet multipliers come from integrating the Galerkin equations of the
pinned-pinned sine modes over one period with scipy (DOP853), the monodromy matrix column by
column; its period-doubling boundaries (a multiplier at -1: the edges of the principal parametric
resonance near Omega* = 2) by Brent's method.  crankgen's multipliers (the continuation's), its
period doublings in Omega* and its period-doubling curve in (Omega*, ms*) (crankgen.follow) must
agree on a 6-element mesh.  At a* = 1e-4 (ms* = 50) the boundary differs by 4.5e-4 in Omega*, at
1e-5 by 1e-5: the difference is of the neglected order.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import crankgen

EI = 1 / math.pi**4
A, EPS, MS, MU = 1e-5, 0.001, 500.0, 0.02
MODEL = dict(approach="B", formulation="lagrange", damping="kelvin-voigt", membrane="pointwise",
             rotary_inertia=False, n_elements=6, steps_per_rev=200)


def hill_multipliers(omega, ms=MS, modes=3):
    """Floquet multipliers of the Galerkin Hill system (by decreasing modulus)."""
    EA = 1 / (math.pi**4 * EPS**2)
    E = EA * (1 + 1j * MU * omega)                      # Kelvin-Voigt: complex modulus
    k = np.sqrt(omega**2 / E + 0j)
    # U(x) = A (cos kx - 1) + B sin kx, E U'(1) = ms Omega^2 (A + U(1))
    B = A * (E * k * np.sin(k) + ms * omega**2 * np.cos(k)) / (E * k * np.cos(k) - ms * omega**2 * np.sin(k))
    xg, wg = np.polynomial.legendre.leggauss(40)
    x, w = (xg + 1) / 2, wg / 2
    N = E * (-A * k * np.sin(k * x) + B * k * np.cos(k * x))        # N(x, t) = Re(N(x) e^{i Omega t})
    j = np.arange(1, modes + 1)
    dphi = j[:, None] * np.pi * np.cos(j[:, None] * np.pi * x[None])
    G = np.einsum("p,ip,jp->ij", w * N, dphi, dphi)
    stiff = EI * (j * np.pi) ** 4 / 2                    # modal mass 1/2

    def rhs(t, y):
        y = y.reshape(2 * modes, -1)
        q, qd = y[:modes], y[modes:]
        qdd = -(stiff[:, None] * (q + MU * qd) + (G * np.exp(1j * omega * t)).real @ q) / 0.5
        return np.concatenate([qd, qdd]).ravel()
    sol = solve_ivp(rhs, (0, 2 * math.pi / omega), np.eye(2 * modes).ravel(), method="DOP853",
                    rtol=1e-10, atol=1e-12)
    mu = np.linalg.eigvals(sol.y[:, -1].reshape(2 * modes, 2 * modes))
    return mu[np.argsort(-np.abs(mu))]


def flip_margin(omega, ms=MS):
    """1 + the smallest real multiplier (0 at a period doubling; 1 without a real one)."""
    mu = hill_multipliers(omega, ms)
    real = mu[np.abs(mu.imag) < 1e-9].real
    return float(real.min() + 1) if real.size else 1.0


@pytest.fixture(scope="module")
def diagram():
    return crankgen.continuation(crankgen.Mechanism(a=A, eps=EPS, ms=MS, mu=MU), "omega", 1.7, 2.4,
                                 max_period=1, **MODEL)


@pytest.mark.slow
def test_multipliers_are_the_hill_equations(diagram):
    (branch,) = diagram.branches
    for omega in (1.8, 2.0, 2.2):
        i = int(np.argmin(np.abs(branch.parameter - omega)))
        hill = hill_multipliers(branch.parameter[i])
        got = branch.multipliers[i]
        for m in hill[:2]:                       # the first bending mode's pair
            assert np.min(np.abs(got - m)) < 2e-4, (branch.parameter[i], m, got[:4])


@pytest.mark.slow
def test_period_doubling_boundaries_are_the_hill_equations(diagram):
    pds = sorted(s.parameter for s in diagram.special_points if s.kind == "period-doubling")
    assert len(pds) == 2
    left, right = brentq(flip_margin, 1.7, 2.0, xtol=1e-10), brentq(flip_margin, 2.0, 2.4, xtol=1e-10)
    assert abs(pds[0] - left) < 1e-4 and abs(pds[1] - right) < 1e-4, (pds, left, right)


@pytest.mark.slow
def test_period_doubling_curve_in_the_slider_mass_is_the_hill_equations(diagram):
    """The left edge of the resonance tongue followed in ms*: at both ends of the box the curve's
    Omega* is the Hill equation's boundary for that slider mass."""
    left = min((s for s in diagram.special_points if s.kind == "period-doubling"), key=lambda s: s.parameter)
    curve = crankgen.follow(left, "ms", 400.0, 650.0)
    assert set(curve.stop_reasons) == {"reached ms = 400", "reached ms = 650"}
    for end in (0, -1):
        ms, omega = curve["ms"][end], curve["omega"][end]
        hill = brentq(lambda w: flip_margin(w, ms), omega - 0.05, omega + 0.05, xtol=1e-10)
        assert abs(hill - omega) < 1e-4, (ms, omega, hill)
    # a heavier slider loads the rod more: the tongue widens, its left edge moves down
    assert np.all(np.diff(curve["omega"][np.argsort(curve["ms"])]) < 0)
