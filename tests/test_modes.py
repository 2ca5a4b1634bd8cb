"""Natural frequencies of the frozen mechanism (crankgen.modes) and the Campbell diagram
(crankgen.campbell) against independent truths: the pinned-pinned rod's bending frequencies
(Euler-Bernoulli, and Rayleigh with rotary inertia), the axial frequencies of a bar fixed at one
end with a mass at the other (tan(beta) = 1 / (ms* beta)), a Rayleigh quotient with the axial
force of the rigid motion computed here from the closed-form kinematics, and the resonance peak
a sweep of steady states finds."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import crankgen
from helpers import check_csv


def _bar_with_end_mass(ms, count):
    """beta_k of a bar fixed at x = 0 with the end mass ms* at x = L: cot(beta) = ms* beta."""
    f = lambda b: math.cos(b) - ms * b * math.sin(b)             # noqa: E731
    return [brentq(f, k * math.pi + 1e-9, k * math.pi + math.pi / 2) for k in range(count)]


@pytest.mark.parametrize("rotary_inertia", [False, True])
def test_at_rest_the_rod_has_the_pinned_pinned_bending_frequencies(rotary_inertia):
    """At rest and at theta = 0 the rod lies along its guide: pinned at the crank, its end free
    to slide along the rod's axis but held across it (a pinned-roller beam in bending: the
    pinned-pinned frequencies, the end mass moving only axially)."""
    mech = crankgen.Mechanism(eps=0.02, ms=0.5)
    m = crankgen.modes(mech, omega=0.0, theta=0.0, count=10, n_elements=16, rotary_inertia=rotary_inertia)
    bending = m.frequencies[np.array(m.kinds) == "bending"][:5]
    rhoA, EI, rhoI = mech.rhoA, mech.EI, mech.rhoI if rotary_inertia else 0.0
    k = np.arange(1, 6)
    exact = (k * np.pi) ** 2 * np.sqrt(EI / rhoA) / np.sqrt(1 + (k * np.pi) ** 2 * rhoI / rhoA)
    np.testing.assert_allclose(bending, exact, rtol=5e-3)
    # the first mode is the half sine, up to the mesh
    v = m.shapes[0][:, 1]
    np.testing.assert_allclose(v, np.sin(np.pi * np.linspace(0, 1, 17)), atol=2e-3)


def test_at_rest_the_axial_modes_carry_the_end_mass():
    mech = crankgen.Mechanism(eps=0.02, ms=0.5)
    m = crankgen.modes(mech, omega=0.0, theta=0.0, count=12, n_elements=16)
    axial = m.frequencies[np.array(m.kinds) == "axial"][:2]
    beta = np.array(_bar_with_end_mass(mech.ms / mech.rhoA, 2))
    exact = beta * np.sqrt(mech.EA / mech.rhoA)                                # L = 1
    np.testing.assert_allclose(axial, exact, rtol=5e-3)
    assert np.all(m.axial_share[np.array(m.kinds) == "axial"] > 0.99)


def _axial_force_and_rod_rate(a, omega, theta, ms, x):
    """N(x) of the rigid slider-crank (line guide, no offset) at crank angle theta, from the
    closed-form positions differentiated numerically in time, and the rod's angular velocity:
    the force that holds the rod's part beyond x and the slider on their rigid accelerations
    (positive: tension)."""
    h = 1e-4 / max(omega, 1e-9)

    def points(t):
        th = theta + omega * t
        A = np.array([a * math.cos(th), a * math.sin(th)])
        B = np.array([a * math.cos(th) + math.sqrt(1 - (a * math.sin(th)) ** 2), 0.0])
        return A, B, math.atan2(B[1] - A[1], B[0] - A[0])
    (A0, B0, p0), (A1, B1, _), (A2, B2, p2) = points(-h), points(0.0), points(h)
    axis = (B1 - A1) / np.linalg.norm(B1 - A1)
    acc = lambda P0, P1, P2: (P0 - 2 * P1 + P2) / h ** 2        # noqa: E731
    accA, accB = acc(A0, A1, A2), acc(B0, B1, B2)
    along = lambda s: float(((1 - s) * accA + s * accB) @ axis)   # noqa: E731  (rigid rod: linear in s)
    N = np.array([-ms * along(1.0) - (along(xi) + along(1.0)) / 2 * (1 - xi) for xi in x])
    return N, (p2 - p0) / (2 * h)


@pytest.mark.parametrize("theta", [0.0, math.pi])
def test_at_speed_the_first_frequency_moves_as_the_axial_load_says(theta):
    """At the outer dead centre (theta = 0) the slider's and the rod's inertia pull the rod: its
    first bending frequency rises; at the inner one (pi) they push it: it falls.  The size: the
    Rayleigh quotient of the half sine with the axial force of the rigid motion and the rod's
    centrifugal softening, lambda = 1 + 2 pi^2 int N cos^2(pi x) dx - phi'^2 (units of omega_b,
    EI = 1/pi^4, rho A = 1), within 3 % of the shift."""
    a, omega, ms = 0.1, 0.8, 0.5
    m = crankgen.modes(crankgen.Mechanism(a=a, ms=ms), omega=omega, theta=theta, count=2,
                       n_elements=16, rotary_inertia=False)
    x = np.linspace(0, 1, 2001)
    N, rate = _axial_force_and_rod_rate(a, omega, theta, ms, x)
    EI = 1 / math.pi ** 4
    weight = np.cos(np.pi * x) ** 2
    integral = float(np.sum((N * weight)[1:] + (N * weight)[:-1]) / 2 * (x[1] - x[0]))
    rayleigh = 1.0 + 2 * np.pi ** 2 * integral - rate ** 2
    shift, expected = m.omega_squared[0] - 1.0, rayleigh - 1.0
    assert np.sign(shift) == np.sign(expected) == (1 if theta == 0.0 else -1)
    assert abs(shift - expected) < 0.03 * abs(expected), (shift, expected)
    assert abs(expected) > 0.3                                   # a large effect at Omega* = 0.8
    # the frozen state's axial force is that of the rigid motion (N* = N L^2 / EI per element)
    mids = (np.arange(16) + 0.5) / 16
    np.testing.assert_allclose(m.axial_force * EI, np.interp(mids, x, N), rtol=0, atol=2e-3 * np.max(np.abs(N)))


def test_modes_in_si_are_the_steel_rods():
    """The Test Set for IVP Solvers' steel rod (0.3 m, 8 mm square): at rest, its first bending
    frequency is omega_b and its first axial one that of the bar with the slider's mass."""
    si = crankgen.SIMechanism(L=0.3, a=0.15, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10,
                              slider_mass=0.0756, crank_speed=150.0)
    m = crankgen.modes(si, omega=0.0, units="si", count=6, n_elements=16, rotary_inertia=False)
    assert m.frequencies_si[0] == pytest.approx(si.omega_b, rel=1e-3)
    beta = _bar_with_end_mass(si.slider_mass / (si.rho * si.A * si.L), 1)[0]
    axial = m.frequencies_si[np.array(m.kinds) == "axial"][0]
    assert axial == pytest.approx(beta / si.L * math.sqrt(si.E / si.rho), rel=5e-3)
    assert m.hz[0] == pytest.approx(si.omega_b / (2 * math.pi), rel=1e-3)
    with pytest.raises(crankgen.ParameterError, match="units='si'"):
        m.__class__.frequencies_si.fget(crankgen.modes(crankgen.Mechanism(), omega=0.0, count=1))


def test_modes_refuse_what_they_cannot_freeze():
    with pytest.raises(crankgen.ParameterError, match="constant crank speed"):
        crankgen.modes(crankgen.Mechanism(), crank=crankgen.RunUp(start=0.2, stop=0.8, revolutions=5))
    with pytest.raises(crankgen.ParameterError, match="theta"):
        crankgen.modes(crankgen.Mechanism(), omega=0.5, theta=float("nan"))


def test_campbell_bands_orders_and_crossings(tmp_path):
    from crankgen.plots.figures import layout_problems
    from crankgen.plots.campbell import campbell_figure

    d = crankgen.campbell(crankgen.Mechanism(), speeds=np.linspace(0, 1.2, 25), angles=12, count=3,
                          n_elements=4)
    assert d.frequencies.shape == (25, 12, 3)
    # at rest only the geometry changes over a revolution (the guide's angle to the rod): a narrow band
    np.testing.assert_allclose(d.low[0], d.high[0], rtol=1e-3)
    assert np.all(d.high[1:, 0] > d.low[1:, 0])
    for c in d.crossings:                   # each crossing lies on its order line and its band edge
        band = np.interp(c.speed, d.speeds, d.band(c.edge)[:, c.mode - 1])
        assert c.frequency == pytest.approx(c.order * c.speed) and band == pytest.approx(c.frequency, rel=1e-9)
    two = [c for c in d.crossings if (c.order, c.mode, c.edge) == (2, 1, "mean")]
    assert len(two) == 1 and two[0].speed == pytest.approx(0.5, abs=0.01)  # 2 Omega* = the first mode, ~1
    assert d.divergent[-1, 0] > 0 and d.low[-1, 0] == 0                # buckles near the inner dead centre
    paths = d.to_csv(tmp_path)
    table = check_csv(paths[0])
    assert list(table.columns[:2]) == ["omega", "mode"] and len(table) == 25 * 3
    crossings = check_csv(paths[1])
    assert len(crossings) == len(d.crossings)
    assert layout_problems(campbell_figure(d)) == []


@pytest.mark.slow
@pytest.mark.parametrize("eps", [0.01, 0.1])
def test_the_sweeps_resonance_peak_sits_where_1x_crosses_the_first_mode(eps):
    """The steady amplitude of a fine sweep peaks where the crank order 1x crosses the first
    mode's mean frequency over the revolution (eps = 0.01: 0.93 against 0.934 at 8 elements;
    eps = 0.1: 0.88 against 0.882; here at 4 elements)."""
    speeds = np.round(np.arange(0.78, 1.02, 0.01), 3)
    cases = [crankgen.Case(eps=eps, omega=float(w), n_elements=4) for w in speeds]
    amplitude = np.array([s.amplitude for s in crankgen.steady_states(cases)])
    peak = speeds[np.argmax(amplitude)]
    assert 0 < np.argmax(amplitude) < len(speeds) - 1                   # a peak inside the range
    d = crankgen.campbell(crankgen.Mechanism(eps=eps), speeds=np.linspace(0.7, 1.1, 41), count=1,
                          orders=(1,), n_elements=4)
    mean = [c.speed for c in d.crossings if c.edge == "mean"]
    assert len(mean) == 1 and abs(peak - mean[0]) <= 0.02, (peak, mean)


def test_the_modes_and_campbell_commands(tmp_path, capsys):
    import json

    from crankgen.cli import main
    assert main(["modes", "--omega", "0", "--count", "3", "--elements", "4", "--rotary-inertia", "off",
                 "--out", str(tmp_path / "m"), "--quiet"]) == 0
    table = check_csv(tmp_path / "m" / "modes.csv")
    api = crankgen.modes(crankgen.Mechanism(), omega=0.0, count=3, n_elements=4, rotary_inertia=False)
    np.testing.assert_allclose(table["frequency"], api.frequencies, rtol=1e-12)
    shapes = check_csv(tmp_path / "m" / "shapes.csv")
    assert list(shapes.columns) == ["mode", "node", "x_L", "u", "v", "psi"] and len(shapes) == 3 * 5
    assert "mode 1: bending" in capsys.readouterr().out
    si = tmp_path / "steel.json"
    si.write_text(json.dumps(dict(L=0.3, a=0.15, E=2e11, rho=7870, A=6.4e-5, I=3.41e-10,
                                  slider_mass=0.0756, crank_speed=150.0)))
    assert main(["campbell", "--si", str(si), "--to", "300", "--speeds", "4", "--angles", "4",
                 "--modes", "2", "--elements", "2", "--out", str(tmp_path / "c"), "--quiet"]) == 0
    camp = check_csv(tmp_path / "c" / "campbell.csv")
    assert camp["crank_speed_rad_per_s"].max() == pytest.approx(300.0)
    assert camp["crank_speed_rpm"].max() == pytest.approx(300 * 60 / (2 * np.pi))
    assert {"low_Hz", "mean_Hz", "high_Hz"} <= set(camp.columns)
    check_csv(tmp_path / "c" / "crossings.csv")
    capsys.readouterr()
    assert main(["modes", "--si", str(si), "--omega", "1", "--out", str(tmp_path / "x")]) == 2
    assert "leave out --omega" in capsys.readouterr().err
    assert main(["campbell", "--from", "1", "--to", "0.5", "--out", str(tmp_path / "y")]) == 2
    assert "--to must exceed --from" in capsys.readouterr().err
    assert not (tmp_path / "x").exists() and not (tmp_path / "y").exists()
