"""Outputs declared in derive/outputs.py against hand computations from the stored nodal states."""

import numpy as np

import crankgen


def test_the_transmission_angle_is_the_angle_between_coupler_and_rocker():
    """A new output costs one declaration: the four-bar's transmission angle, computed here from the
    end node's inertial position (pin + (L + u) e_i + v e_j of the nodal history) and the pivot."""
    d, e, c = 1.0, 0.05, 0.8
    mech = crankgen.Mechanism(a=0.15, guide=crankgen.Circle(center=(d, e), radius=c))
    r = crankgen.simulate(mech, omega=0.6, n_elements=3, steps_per_rev=40, revolutions=1.5,
                          store_nodes=True)
    from crankgen.discrete.kinematics import case_state
    kin = case_state(r.case, r.t)
    u, v = r.nodes[:, -4], r.nodes[:, -3]                      # the end node's (u, v) of its (u, v, psi, chi)
    e_i = np.stack([np.cos(kin.phi), -np.sin(kin.phi)], -1)
    e_j = np.stack([np.sin(kin.phi), np.cos(kin.phi)], -1)
    A = 0.15 * np.stack([np.cos(kin.theta), np.sin(kin.theta)], -1)
    B = A + (1 + u)[:, None] * e_i + v[:, None] * e_j
    np.testing.assert_allclose(np.linalg.norm(B - np.array([d, e]), axis=1), c, rtol=1e-12)  # on the circle
    BA, BD = A - B, np.array([d, e]) - B
    cosine = np.sum(BA * BD, axis=1) / (np.linalg.norm(BA, axis=1) * np.linalg.norm(BD, axis=1))
    np.testing.assert_allclose(r.transmission_angle, np.arccos(cosine), rtol=0, atol=1e-10)
    assert np.ptp(r.transmission_angle) > 0.1                  # it does change over a revolution
