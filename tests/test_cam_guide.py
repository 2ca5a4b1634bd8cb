"""A guide through the numerical closure: the cam track Y = e + h cos(2 pi X / lambda) (a slider on
a wavy guide), declared as a parametric curve with no closed-form closure; its closure is solved by
Newton at run time.  Against a closure computed here (brentq on |C(beta) - A| = L), its rates
against differences of that closure in time, the end kept on the track by the end map, a flat
track against the slider-crank, and a track the rod cannot follow refused."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import crankgen
from crankgen.declaration import schema
from crankgen.declaration.cases import Case
from crankgen.discrete.kinematics import case_state

A, E, H, LAM, OMEGA = 0.15, 0.05, 0.03, 0.3, 0.8


def closure(theta):
    """(beta, phi) of the rigid mechanism at crank angle theta, computed here: the track's point at
    the rod's length from the crank pin, right of the pin."""
    k = 2 * math.pi / LAM

    def residual(beta):
        return (beta - A * math.cos(theta)) ** 2 + (E + H * math.cos(k * beta) - A * math.sin(theta)) ** 2 - 1.0
    x0 = A * math.cos(theta)
    beta = brentq(residual, x0 + 0.5, x0 + 1.0, xtol=1e-15, rtol=1e-15)
    phi = math.atan2(-(E + H * math.cos(k * beta) - A * math.sin(theta)), beta - A * math.cos(theta))
    return beta, phi


def case(**kw):
    return Case(guide="cam", a=A, offset=E, cam_height=H, cam_wavelength=LAM, omega=OMEGA, **kw)


def test_the_cam_is_a_guide_of_the_schema_without_a_closed_form():
    g = schema.GUIDES["cam"]
    assert g.closure == "numerical" and g.margins == () and "cam_height" in g.parameters
    assert crankgen.Cam(cam_height=0.01).values == {"cam_height": 0.01}
    assert schema.PARAMETERS["cam_height"].readers == ("cam",)
    with pytest.raises(crankgen.ParameterError, match="cam_height .* applies to the cam guide only"):
        Case(cam_height=0.01)


def test_the_newton_closure_is_the_closure_and_its_rates_its_derivatives():
    c = case()
    t = np.linspace(0.0, 2 * math.pi / OMEGA, 37)
    kin = case_state(c, t)
    theta = OMEGA * t
    expected = np.array([closure(th) for th in theta])
    np.testing.assert_allclose(kin.beta, expected[:, 0], rtol=0, atol=1e-13)
    np.testing.assert_allclose(kin.phi, expected[:, 1], rtol=0, atol=1e-13)
    h = 1e-4                                                # rates: central differences in time
    plus = np.array([closure(th + OMEGA * h) for th in theta])
    minus = np.array([closure(th - OMEGA * h) for th in theta])
    k = schema.KIN
    np.testing.assert_allclose(kin.vector[:, k["betad"]], (plus[:, 0] - minus[:, 0]) / (2 * h), atol=2e-7)
    np.testing.assert_allclose(kin.phid, (plus[:, 1] - minus[:, 1]) / (2 * h), atol=2e-7)
    np.testing.assert_allclose(kin.vector[:, k["betadd"]], (plus[:, 0] - 2 * expected[:, 0] + minus[:, 0]) / h**2,
                               atol=2e-4)
    np.testing.assert_allclose(kin.phidd, (plus[:, 1] - 2 * expected[:, 1] + minus[:, 1]) / h**2, atol=2e-4)


def test_the_rods_end_stays_on_the_track_and_the_engine_agrees_with_the_reference():
    c = case(n_elements=4, steps_per_rev=60)
    run = crankgen.simulate(case=c, revolutions=2)
    X, Y = run.slider_position, run.end_height
    np.testing.assert_allclose(Y, E + H * np.cos(2 * math.pi * X / LAM), rtol=0, atol=1e-13)
    assert np.ptp(Y) > H                                     # the end rides the waves
    ref = crankgen.simulate(case=c, revolutions=0.5, engine="numpy")
    n = len(ref.t)
    np.testing.assert_allclose(run.v_mid[:n], ref.v_mid, rtol=1e-7, atol=1e-9 * np.max(np.abs(ref.v_mid)))


def test_a_flat_track_is_the_slider_crank():
    flat = Case(guide="cam", a=A, offset=E, cam_height=0.0, omega=OMEGA, n_elements=4, steps_per_rev=60)
    line = Case(guide="line", a=A, offset=E, omega=OMEGA, n_elements=4, steps_per_rev=60)
    a, b = (crankgen.simulate(case=x, revolutions=1) for x in (flat, line))
    np.testing.assert_allclose(a.v_mid, b.v_mid, rtol=1e-9, atol=1e-12 * np.max(np.abs(b.v_mid)))
    np.testing.assert_allclose(a.slider_position, b.slider_position, rtol=1e-13)


def test_a_track_the_rod_cannot_follow_is_refused():
    with pytest.raises(crankgen.ParameterError, match="full revolution: the cam guide needs the closure"):
        Case(guide="cam", a=0.3, cam_height=0.4, cam_wavelength=0.1)
