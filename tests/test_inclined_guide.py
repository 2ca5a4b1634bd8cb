"""An inclined straight guide: the slider's line Y = e turned by an angle alpha about the crank's
axis.  The whole mechanism turned by alpha is the slider-crank (the independent truth): with the
crank started alpha further on and gravity turned with it, the rod moves in its own frame exactly
as the horizontal slider-crank's, and its end is that one's turned by alpha."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.declaration import schema
from crankgen.declaration.cases import Case

ALPHA, E, THETA0 = 0.35, 0.04, 0.2
TINY = dict(n_elements=4, steps_per_rev=60, omega=0.7, a=0.15)


def turned(vector, angle):
    c, s = math.cos(angle), math.sin(angle)
    x, y = vector
    return (c * x - s * y, s * x + c * y)


def test_the_inclined_slider_crank_is_the_slider_crank_turned():
    g = (2e-3, -5e-3)
    line = Case(guide="line", offset=E, theta0=THETA0, gravity=g, **TINY)
    incline = Case(guide="incline", offset=E, inclination=ALPHA, theta0=THETA0 + ALPHA,
                   gravity=turned(g, ALPHA), **TINY)
    a, b = (crankgen.simulate(case=c, revolutions=2) for c in (line, incline))
    scale = np.max(np.abs(a.v_mid))
    np.testing.assert_allclose(b.v_mid, a.v_mid, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(b.u_end, a.u_end, rtol=0, atol=1e-9 * np.max(np.abs(a.u_end)))
    X, Y = turned((a.slider_position, a.end_height), ALPHA)
    np.testing.assert_allclose(b.slider_position, X, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.end_height, Y, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.chord_angle, a.chord_angle + ALPHA, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.torque, a.torque, rtol=0, atol=1e-8 * np.max(np.abs(a.torque)))
    # the joint forces at A and B are the slider-crank's turned by alpha
    for joint in ("crank_on_rod", "rod_on_slider", "guide_on_slider"):
        fa = (getattr(a, joint + "_x"), getattr(a, joint + "_y"))
        fb = (getattr(b, joint + "_x"), getattr(b, joint + "_y"))
        size = max(np.max(np.abs(fa[0])), np.max(np.abs(fa[1])))
        for want, got in zip(turned(fa, ALPHA), fb):
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-8 * size, err_msg=joint)


def test_the_incline_is_declared_as_data():
    g = schema.GUIDES["incline"]
    assert g.closure == "closed-form" and "inclination" in g.parameters
    assert crankgen.Incline(inclination=0.1).values == {"inclination": 0.1}
    with pytest.raises(crankgen.ParameterError, match="full revolution"):
        Case(guide="incline", a=0.6, offset=0.5, inclination=0.3)
