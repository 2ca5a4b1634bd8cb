"""The rigid mechanism of crankgen.rigid against the rigid slider-crank's inverse dynamics written out
here (Newton-Euler for the rod and the slider, the kinematics differentiated by central differences),
and its bending moment against the pinned-pinned beam under the rigid rod's transverse inertia
load (statics by hand); then the comparison as one call and one command."""

import json
import math

import numpy as np
import pytest

import crankgen
from crankgen.analyses import rigid
from crankgen.cli.main import main
from helpers import check_csv

A_STAR, MS, EPS = 0.1, 0.5, 0.01


def _positions(theta):
    """Crank pin A, slider B and the rod's angle phi of the rigid slider-crank (L = 1, offset 0)."""
    ax, ay = A_STAR * np.cos(theta), A_STAR * np.sin(theta)
    phi = -np.arcsin(ay)
    return ax, ay, ax + np.cos(phi), phi


def _rates(f, t, omega, h=1e-3):
    """Value, first and second time derivatives of f(theta = omega t) by central differences (h^4)."""
    values = [np.asarray(f(omega * (t + k * h))) for k in (-2, -1, 0, 1, 2)]
    first = (values[0] - 8 * values[1] + 8 * values[3] - values[4]) / (12 * h)
    second = (-values[0] + 16 * values[1] - 30 * values[2] + 16 * values[3] - values[4]) / (12 * h * h)
    return values[2], first, second


def rigid_inverse_dynamics(t, omega, rotary=True):
    """(torque, crank on rod (X, Y), rod on slider (X, Y)) of the rigid slider-crank in crankgen's
    units (rod mass 1, length 1; its moment of inertia about its centre 1/12, plus eps^2 of its
    sections' rotary inertia)."""
    (ax, ay, bx, phi), (vax, vay, vbx, dphi), (aax, aay, abx, ddphi) = (
        [np.asarray(x) for x in zip(*[_rates(lambda th, k=k: _positions(th)[k], t, omega, h=1e-2)
                                      for k in range(4)])])
    del vax, vay, vbx, dphi
    slider_x = MS * abx                                     # the rod's force on the slider, X (no friction)
    gx, gy = (aax + abx) / 2, aay / 2                       # the rod's centre's acceleration (B_y = 0)
    inertia = 1 / 12 + (EPS ** 2 if rotary else 0.0)
    # rod: F_A + F_B = m a_G with F_B = -(slider_x, s_y); moment about G:
    # inertia ddphi = (A - G) x F_A + (B - G) x F_B; unknowns F_A (2) and s_y
    rx_a, ry_a = ax - (ax + bx) / 2, ay - ay / 2
    rx_b, ry_b = bx - (ax + bx) / 2, -ay / 2
    out = []
    for k in range(len(t)):
        M = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, -1.0], [-ry_a[k], rx_a[k], -rx_b[k]]])
        rhs = np.array([gx[k] + slider_x[k], gy[k], inertia * ddphi[k] + ry_b[k] * (-slider_x[k])])
        out.append(np.linalg.solve(M, rhs))
    fax, fay, sy = np.array(out).T
    torque = A_STAR * (np.cos(omega * t) * fay - np.sin(omega * t) * fax)
    return torque, (fax, fay), (slider_x, sy)


def test_the_rigid_mechanism_is_the_rigid_slider_cranks_inverse_dynamics():
    omega = 0.05                # slow: the quasi-static deflection, 2e-4 of L, changes the geometry by that
    case = crankgen.Case(a=A_STAR, ms=MS, eps=EPS, omega=omega, n_elements=8)
    t = np.linspace(0, 2 * math.pi / omega, 37)
    r = rigid.kineto_static(case, t)
    torque, pin_a, pin_b = rigid_inverse_dynamics(t, omega)
    scale = np.max(np.abs(torque))
    np.testing.assert_allclose(r.torque, torque, atol=2e-4 * scale)
    for (x, y), got in ((pin_a, ("crank_on_rod_x", "crank_on_rod_y")), (pin_b, ("rod_on_slider_x", "rod_on_slider_y"))):
        f = np.max(np.hypot(x, y))
        np.testing.assert_allclose(r.quantity(got[0]), x, atol=2e-4 * f)
        np.testing.assert_allclose(r.quantity(got[1]), y, atol=2e-4 * f)
    assert np.max(np.abs(r.states)) < 1e-3 and scale > 1e-5


def test_the_rigid_rods_bending_moment_is_the_beams_under_its_inertia_load():
    """The rod's transverse acceleration is linear along it, a_n(x) = a_A.e_j + phi'' x (rigid body);
    the load -rho A a_n(x) on a pinned-pinned beam gives M(x) by statics (crankgen's M = EI v_xx: the
    sagging moment with a minus sign).  Slow (Omega* = 0.05), without slider, so that the axial
    force's P-delta effect stays below 1e-3; rotary inertia off (its distributed moment)."""
    omega = 0.05
    errors = []
    for n in (8, 16):               # M = EI v_xx of the cubic element at a node: second order in the mesh
        case = crankgen.Case(a=A_STAR, ms=0.0, eps=EPS, omega=omega, n_elements=n, rotary_inertia=False)
        t = np.linspace(0, 2 * math.pi / omega, 25)
        r = rigid.kineto_static(case, t)
        (ax, ay, bx, phi), _, (aax, aay, abx, ddphi) = (
            [np.asarray(x) for x in zip(*[_rates(lambda th, k=k: _positions(th)[k], t, omega, h=1e-2)
                                          for k in range(4)])])
        a_n = -np.sin(phi) * aax + np.cos(phi) * aay             # a_A . e_j, e_j = (-sin phi, cos phi)
        x = 0.5
        # w(s) = -(a_n + ddphi s); R_A = int w (1 - s) ds; M_sag(x) = R_A x - int_0^x w (x - s) ds
        r_a = -(a_n / 2 + ddphi / 6)
        sag = r_a * x + (a_n * x ** 2 / 2 + ddphi * x ** 3 / 6)
        exact = -sag * math.pi ** 4                                 # M* = M L / EI, EI = 1/pi^4
        errors.append(np.max(np.abs(r.bending_moment(x) - exact)) / np.max(np.abs(exact)))
    assert errors[1] < 5e-3 and errors[1] < errors[0] / 3.5, errors


def test_the_comparison_as_one_call_and_one_command(tmp_path, capsys):
    """At Omega* = 0.8 the consistent model's rod vibrates: its peak torque is 1.46 times the rigid
    one's and its mid-span moment twice; at the press's 0.13 they agree within 2 %."""
    c = rigid.compare(crankgen.Mechanism(), 0.8, n_elements=4)
    assert c.row("peak torque")["ratio"] > 1.3 and c.row("peak bending moment")["ratio"] > 1.5
    assert c.row("peak torque")["rigid"] == pytest.approx(np.max(np.abs(c.rigid.torque)), rel=1e-12)
    press = dict(L=0.25, E=2.1e11, rho=7850, A=1e-4, I=1e-8 / 12, a=0.05, slider_mass=0.5, damping=2e-4)
    path = tmp_path / "press.json"
    path.write_text(json.dumps(press))
    assert main(["compare", "--si", str(path), "--rpm", "3000", "--section", "rectangle:0.01,0.01",
                 "--elements", "4", "--out", str(tmp_path / "c"), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "peak stress" in text and "MPa" in text and "model: trust this model here" in text
    table = check_csv(tmp_path / "c" / "compare.csv")
    rows = {q: r for q, r in zip(table["quantity"], table.to_dict("records"))}
    assert rows["peak torque"]["units"] == "N m" and rows["peak stress"]["units"] == "Pa"
    for quantity in ("peak torque", "peak crank on rod force", "peak rod on slider force", "peak stress"):
        assert abs(rows[quantity]["ratio"] - 1) < 0.025, quantity
    assert (tmp_path / "c" / "compare.png").stat().st_size > 10000
