"""Sections and the stresses at the rod's outer fibres (crankgen.sections, crankgen.stress) against
closed forms: a steel rod sagging under its weight (a pinned-roller beam, M = q L^2 / 8) and
hanging from the crank pin (N = rho A g (L - x) + m_s g), both settled from a damped run at a
crank that barely turns; the stress of a steady orbit against its declared section forces and
surface strain; its range per revolution is max - min of its stress history."""

import dataclasses
import functools
import math

import numpy as np
import pytest

import crankgen
from crankgen.declaration import sections


def test_sections_are_the_textbooks():
    r = sections.rectangle(0.02, 0.01)
    assert (r.A, r.I, r.c_top, r.c_bottom) == pytest.approx((2e-4, 0.02 * 0.01 ** 3 / 12, 0.005, 0.005))
    c = sections.circle(0.01)
    assert c.I == pytest.approx(math.pi * 0.01 ** 4 / 64) and c.radius_of_gyration == pytest.approx(0.0025)
    solid = sections.tube(0.01, 0.005)
    assert (solid.A, solid.I) == pytest.approx((c.A, c.I))
    t = sections.tube(0.02, 0.001)
    assert t.I == pytest.approx(math.pi * (0.02 ** 4 - 0.018 ** 4) / 64)
    assert sections.parse("rectangle:0.02,0.01") == r and sections.parse("tube:0.01,0.005").I == solid.I
    given = sections.parse("1e-4,2e-9,0.003,0.005")
    assert given.fibres == {"top": 0.003, "bottom": -0.005}
    for bad in ("rectangle:1", "box:1", "1,2", "circle:-1", "tube:0.01,0.006"):
        with pytest.raises(crankgen.ParameterError):
            sections.parse(bad)


SECTION = sections.rectangle(0.008, 0.008)
STEEL = crankgen.SIMechanism(L=0.3, a=0.15, E=2e11, rho=7870, A=SECTION.A, I=SECTION.I,
                             slider_mass=0.0756, crank_speed=150.0)


@functools.lru_cache(maxsize=None)
def _settled_run(gravity):
    """The steel rod at theta = 0 (along the guide) under gravity (m/s^2), damped (mu* = 1) from
    rest to its static state: t* = 40, the crank turning at Omega* = 1e-6 (4e-5 rad in all); built
    and run in SI (gravity in m/s^2, damping in s, crank speed in rad/s, the time in s)."""
    omega_b = (math.pi / STEEL.L) ** 2 * math.sqrt(STEEL.E * STEEL.I / (STEEL.rho * STEEL.A))  # rad/s
    rest = dataclasses.replace(STEEL, gravity=gravity, damping=1.0 / omega_b, crank_speed=1e-6 * omega_b)
    return crankgen.simulate(rest, units="si", times=[40.0 / omega_b], steps_per_rev=int(2 * math.pi / 1e-6 / 0.05),
                             n_elements=16)


def _settled(gravity):
    return crankgen.stress(_settled_run(gravity).at_times, SECTION)


def test_a_rod_sagging_under_its_weight_has_the_beams_bending_stress():
    s = _settled((0.0, -9.81))
    assert s.units == "Pa"
    q = STEEL.rho * STEEL.A * 9.81
    closed = q * STEEL.L ** 2 / 8 * SECTION.c_top / SECTION.I          # 0.65 MPa at mid-span
    mid = int(np.argmin(np.abs(s.x - STEEL.L / 2)))
    assert s.top[-1, mid] == pytest.approx(-closed, rel=5e-3)          # sagging: the top in compression
    assert s.bottom[-1, mid] == pytest.approx(closed, rel=5e-3)
    exact = q * s.x * (STEEL.L - s.x) / 2 * SECTION.c_top / SECTION.I
    np.testing.assert_allclose(s.bottom[-1], exact, rtol=0, atol=5e-3 * closed)


def test_gravity_in_si_sags_the_rod_as_the_closed_form_beam():
    """g = 9.81 m/s^2 given in SI on the real steel rod: its static deflection from the chord is the
    pinned-roller beam's under its weight, v(x) = -q x (L^3 - 2 L x^2 + x^3) / (24 E I), 5 q L^4 /
    (384 E I) = 7.6 um at mid-span (in metres, from the SI view)."""
    run = _settled_run((0.0, -9.81)).at_times
    L, EI, q = STEEL.L, STEEL.E * STEEL.I, STEEL.rho * STEEL.A * 9.81
    x = np.linspace(0.0, L, 9)
    closed = -q * x * (L ** 3 - 2 * L * x ** 2 + x ** 3) / (24 * EI)
    assert closed[4] == pytest.approx(-5 * q * L ** 4 / (384 * EI)) and -closed[4] > 7e-6
    np.testing.assert_allclose(run.si.chord_deflection(x)[-1], closed, rtol=0, atol=5e-3 * abs(closed[4]))
    assert run.si.units("chord_deflection") == "m"


def test_a_rod_hanging_from_the_crank_pin_has_the_bars_axial_stress():
    s = _settled((9.81, 0.0))
    mids = np.arange(1, len(s.x), 2)                 # element midpoints: the element's constant N is exact there
    N = STEEL.rho * STEEL.A * 9.81 * (STEEL.L - s.x[mids]) + STEEL.slider_mass * 9.81
    np.testing.assert_allclose(s.top[-1, mids], N / SECTION.A, rtol=5e-3)
    np.testing.assert_allclose(s.bottom[-1, mids], N / SECTION.A, rtol=5e-3)


@pytest.fixture(scope="module")
def orbit():
    return crankgen.steady_state(crankgen.Mechanism(eps=0.02), omega=0.5, n_elements=8)


def test_the_stress_of_an_orbit_is_its_section_forces(orbit):
    """sigma / E = N* eps^2 - M* eps y / r from the declared axial_force and bending_moment, and
    the declared surface strain at the outer fibre y = c (fiber = c / r)."""
    section = sections.Section(A=1.0, I=0.25, c_top=0.6, c_bottom=0.4)          # r = 0.5
    s = crankgen.stress(orbit, section)
    assert s.units == "E" and s.top.shape == (len(orbit.t), 17)
    x = np.linspace(0, 1, 17)
    N, M = orbit.axial_force(x), orbit.bending_moment(x)
    np.testing.assert_allclose(s.top, N * 0.02 ** 2 - M * 0.02 * 0.6 / 0.5, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(s.bottom, orbit.surface_strain(x, fiber=-0.4 / 0.5), rtol=1e-9, atol=1e-14)
    hi = s.maximum
    values = {"top": s.top, "bottom": s.bottom}[hi.fibre]
    assert hi.value == values.max() == max(s.top.max(), s.bottom.max())
    k, j = np.unravel_index(np.argmax(values), values.shape)
    assert (hi.t, hi.theta, hi.x) == (orbit.t[k], orbit.theta[k], x[j])
    assert s.minimum.value == min(s.top.min(), s.bottom.min())


def test_the_stress_range_of_an_orbit_is_max_minus_min_of_its_history(orbit):
    s = crankgen.stress(orbit, sections.circle(1.0))
    (one,) = s.ranges()
    assert one.complete and one.revolution == 1
    spans = np.concatenate([s.top.max(axis=0) - s.top.min(axis=0), s.bottom.max(axis=0) - s.bottom.min(axis=0)])
    assert s.range == one.range == spans.max()
    assert one.range > 0.01                                    # a strain range of 1.6 % at eps = 0.02


def test_a_runs_ranges_are_per_revolution():
    run = crankgen.simulate(crankgen.Mechanism(), omega=0.8, revolutions=2.5, n_elements=4, steps_per_rev=40)
    s = crankgen.stress(run, sections.circle(1.0))
    r = s.ranges()
    assert [x.revolution for x in r] == [1, 2, 3] and [x.complete for x in r] == [True, True, False]
    first = (run.theta - run.theta[0]) <= 2 * np.pi + 1e-9
    assert r[0].range == pytest.approx(max((s.top[first].max(0) - s.top[first].min(0)).max(),
                                           (s.bottom[first].max(0) - s.bottom[first].min(0)).max()))
    assert s.range == max(r[0].range, r[1].range)


def test_a_section_that_is_not_the_rods_is_refused():
    run = crankgen.simulate(STEEL, units="si", revolutions=0.1, n_elements=2, steps_per_rev=40, approach="C")
    crankgen.stress(run, SECTION)                                             # the run's own scales
    with pytest.raises(crankgen.ParameterError, match="radius of gyration"):
        crankgen.stress(run, sections.rectangle(0.008, 0.01))
    with pytest.raises(crankgen.ParameterError, match="section's A"):
        crankgen.stress(run, sections.rectangle(0.01, 0.008), si=STEEL)
    with pytest.raises(crankgen.ParameterError, match="Section"):
        crankgen.stress(run, "circle:1")
    loads = crankgen.peak_loads(run, run.scales)
    assert [p.name for p in loads] == ["torque", "pin force at A (crank on rod)", "pin force at B (rod on slider)",
                                       "guide force (on slider)"] and loads[0].units == "N m"
    torque = run.si.torque
    assert abs(loads[0].value) == np.max(np.abs(torque)) and loads[1].units == "N"


def test_the_steady_command_prints_peak_loads_and_stress(tmp_path, capsys):
    from crankgen.cli import main
    assert main(["steady", "--omega", "0.5", "--eps", "0.02", "--elements", "4", "--section", "circle:1",
                 "--out", str(tmp_path / "s"), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "peak loads: torque" in out and "pin force" in out and "stress: max" in out
    assert "largest range per revolution" in out
    assert main(["steady", "--section", "box:1", "--out", str(tmp_path / "x")]) == 2
    assert "rectangle:B,H" in capsys.readouterr().err and not (tmp_path / "x").exists()
