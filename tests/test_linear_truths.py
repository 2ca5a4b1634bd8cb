"""Linear analytic truths with the crank turning (approach C).

1. Small crank (a* -> 0): to first order in a* the rod is a simply supported Rayleigh beam
   (pin v = 0; the slider end's v = u tan(phi) is of second order) loaded by the transverse
   inertia of the rigid motion, -rho A (-a Omega^2 sin(theta + phi) - x phidd) = rho A a* Omega^2
   sin(theta) (1 - x) + O(a*^2).  Its sine modes are exact: modal mass rho A/2 + rho I (k pi)^2/2,
   stiffness EI (k pi)^4/2, strain-rate damping mu times the stiffness, modal force
   rho A a* Omega^2 / (k pi).  The steady response is the sum of the modes' steady responses.
2. Quasi-static limit (Omega* -> 0): the elastic rod follows the rigid mechanism's inertia loads
   statically (exact in a*): EI v'''' = -rho A A_j(x), EA u'' = rho A A_i(x) with the rigid
   accelerations A_i = -a Omega^2 cos(theta + phi) - phid^2 x, A_j = -a Omega^2 sin(theta + phi)
   - phidd x; pin u = v = 0, free moments, the slider end on the guide (v(1) = u(1) tan phi) with
   the slider's inertia and the section's rotary inertia in the force balance along the guide.
"""

import math

import numpy as np
import pytest

import crankgen

EI = 1 / math.pi**4


def modal_steady_vmid(theta, a, eps, omega, mu, modes=60):
    """v*(1/2) of the first-order linear problem's steady response (damping mu * stiffness)."""
    rhoI = eps**2
    v = np.zeros_like(theta)
    for k in range(1, modes + 1):
        kp = k * math.pi
        m, kk = 0.5 + 0.5 * rhoI * kp**2, 0.5 * EI * kp**4
        amp = (a * omega**2 / kp) / (kk - m * omega**2 + 1j * mu * kk * omega)
        v += np.imag(amp * np.exp(1j * theta)) * math.sin(kp / 2)
    return v / eps


def quasi_static(theta, a, eps, ms, omega):
    """(v*(1/2), u*(1)) of the static rod under the rigid mechanism's inertia loads."""
    EA, rhoI = 1 / (math.pi**4 * eps**2), eps**2
    phi = np.arcsin(a * np.sin(theta))
    phid = a * omega * np.cos(theta) / np.cos(phi)
    phidd = (phid**2 * np.sin(phi) - a * omega**2 * np.sin(theta)) / np.cos(phi)
    alpha, beta = -a * omega**2 * np.sin(theta + phi), -phidd        # A_j = alpha + beta x
    gamma, delta = -a * omega**2 * np.cos(theta + phi), -phid**2     # A_i = gamma + delta x
    # simply supported beam, load q = -(alpha + beta x): midspan deflection of the mean load,
    # end shear EI v'''(1) = int_0^1 x q dx
    v_mid_pinned = 5 * (-(alpha + beta / 2)) / (384 * EI)
    shear_end = -(alpha / 2 + beta / 3)
    slider_X = ms * ((gamma + delta) * np.cos(phi) + (alpha + beta) * np.sin(phi))
    # along the guide: EA u'(1) cos(phi) + (-EI v'''(1) - rhoI phidd) sin(phi) + ms A_X = 0
    du_end = -((-shear_end - rhoI * phidd) * np.sin(phi) + slider_X) / (EA * np.cos(phi))
    u_end = du_end - (gamma / 2 + delta / 3) / EA
    v_end = u_end * np.tan(phi)
    return (v_mid_pinned + v_end / 2) / eps, u_end / eps**2


@pytest.mark.parametrize("formulation", ["lagrange", "paper"])
def test_small_crank_matches_the_modal_solution(formulation):
    """The relative difference is O(a*): 3e-4 at a* = 1e-3 and ten times more at 1e-2 (the printed
    form has the same first-order terms)."""
    eps, omega, mu = 0.01, 0.8, 0.5
    errors = []
    for a in (1e-3, 1e-2):
        st = crankgen.steady_state(crankgen.Mechanism(a=a, eps=eps, ms=0.5, mu=mu), omega=omega,
                                   approach="C", formulation=formulation, damping="kelvin-voigt",
                                   n_elements=8, steps_per_rev=400)
        assert st.ok, st.message
        exact = modal_steady_vmid(st.theta, a, eps, omega, mu)
        errors.append(np.max(np.abs(st.v_mid - exact)) / np.max(np.abs(exact)))
    assert errors[0] < 1e-3
    assert 5 < errors[1] / errors[0] < 20


def test_quasi_static_limit_is_the_rigid_mechanism_inertia_loading():
    """a* = 0.3 (the geometry far from linear in a*), light damping mu* = 0.005: v*(1/2) and u*(1)
    approach the static response to the rigid-body inertia at O(Omega*^2) (the dynamic
    amplification of the lowest mode; the damping lag adds O(mu* Omega*)): v* 1e-3 off at
    Omega* = 0.02, four times more at 0.04; u*(1) 1e-4 and 3e-4."""
    a, eps, ms = 0.3, 0.01, 2.0
    errors = []
    for omega in (0.04, 0.02):
        st = crankgen.steady_state(crankgen.Mechanism(a=a, eps=eps, ms=ms, mu=0.005), omega=omega,
                                   approach="C", formulation="lagrange", damping="kelvin-voigt",
                                   n_elements=8, steps_per_rev=200)
        assert st.ok, st.message
        v_mid, u_end = quasi_static(st.theta, a, eps, ms, omega)
        errors.append([np.max(np.abs(got - want)) / np.max(np.abs(want))
                       for got, want in ((st.v_mid, v_mid), (st.u_end, u_end))])
    errors = np.array(errors)
    assert np.all(errors[1] < 1.5e-3), errors
    assert errors[0, 0] / errors[1, 0] > 3, errors          # v*: O(Omega*^2)
    assert np.all(errors[:, 1] < 5e-4), errors              # u*(1): the axial modes are stiff
