"""The rod's loads in the files a designer reads (crankgen.analyses.rod_loads): the axial force and both
outer-fibre stresses along the rod in simulation.csv, their peaks, the Euler buckling margin and the
bearing loads as magnitude and direction, checked against the section forces computed here from
the stored state (nodes.csv: u, v and the slope of every node, in m) with this file's own element:
N = EA e (e = u_x + <v_x^2>/2, the element mean of the consistent model's membrane strain) and
M = EI kappa (kappa = v_xx of the cubic Hermite element), sigma = N/A -+ M c/I."""

import json
import math

import numpy as np
import pytest

from crankgen.cli.main import main
from helpers import check_csv

E, RHO, B, H, L = 2.1e11, 7850.0, 0.01, 0.01, 0.25
A, I = B * H, B * H ** 3 / 12
PRESS = dict(L=L, E=E, rho=RHO, A=A, I=I, a=0.05, slider_mass=0.5, crank_speed=314.16, damping=2e-4)
N_EL = 4
GAUSS = np.polynomial.legendre.leggauss(3)           # exact for <v_x^2> (degree 4)


def _hermite_slope(xi, l):
    """d/dx of the Hermite shape functions (v1, psi1, v2, psi2) at xi in [0, 1] of an element of length l."""
    return np.array([(-6 * xi + 6 * xi ** 2) / l, 1 - 4 * xi + 3 * xi ** 2, (6 * xi - 6 * xi ** 2) / l,
                     -2 * xi + 3 * xi ** 2])


def _hermite_curvature(xi, l):
    return np.array([(-6 + 12 * xi) / l ** 2, (-4 + 6 * xi) / l, (6 - 12 * xi) / l ** 2, (-2 + 6 * xi) / l])


def _section_forces(nodes, n):
    """(N, M) per step at the nodes (steps, n + 1): each element's N = EA (u_x + <v_x^2>/2) and its
    M = EI v_xx at its ends; at an interior node the mean of the two elements' values."""
    l = L / n
    u = np.stack([nodes[f"u{i}_m"] for i in range(n + 1)], axis=1)
    v = np.stack([nodes[f"v{i}_m"] for i in range(n + 1)], axis=1)
    psi = np.stack([nodes[f"psi{i}_rad"] for i in range(n + 1)], axis=1)
    N_el, M_ends = [], []
    for e in range(n):
        q = np.stack([v[:, e], psi[:, e], v[:, e + 1], psi[:, e + 1]], axis=1)
        mean_sq = sum(w / 2 * (q @ _hermite_slope((x + 1) / 2, l)) ** 2 for x, w in zip(*GAUSS))
        N_el.append(E * A * ((u[:, e + 1] - u[:, e]) / l + mean_sq / 2))
        M_ends.append((E * I * (q @ _hermite_curvature(0.0, l)), E * I * (q @ _hermite_curvature(1.0, l))))
    N = np.stack([N_el[0]] + [(N_el[k - 1] + N_el[k]) / 2 for k in range(1, n)] + [N_el[-1]], axis=1)
    M = np.stack([M_ends[0][0]] + [(M_ends[k - 1][1] + M_ends[k][0]) / 2 for k in range(1, n)] + [M_ends[-1][1]],
                 axis=1)
    return N, M, np.stack(N_el, axis=1)


@pytest.fixture(scope="module")
def press_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("press")
    path = folder / "press.json"
    path.write_text(json.dumps(PRESS))
    out = folder / "run"
    assert main(["simulate", "--si", str(path), "--section", f"rectangle:{B},{H}", "--nodes", "--revolutions", "1",
                 "--elements", str(N_EL), "--steps-per-rev", "40", "--out", str(out), "--quiet"]) == 0
    return check_csv(out / "simulation.csv"), check_csv(out / "nodes.csv"), check_csv(out / "summary.csv")


def test_the_stress_and_axial_force_along_the_rod_are_EA_e_and_EI_kappa_of_the_stored_state(press_run):
    sim, nodes, _ = press_run
    N, M, _ = _section_forces(nodes, N_EL)
    scale_N, scale_s = np.max(np.abs(N)), np.max(np.abs(N / A)) + np.max(np.abs(M * H / 2 / I))
    for i in range(N_EL + 1):
        x = f"{i * L / N_EL:g}m"
        np.testing.assert_allclose(sim[f"axial_force_at_{x}_N"], N[:, i], rtol=0, atol=1e-9 * scale_N)
        top, bottom = N[:, i] / A - M[:, i] * (H / 2) / I, N[:, i] / A + M[:, i] * (H / 2) / I   # y = +-H/2
        np.testing.assert_allclose(sim[f"stress_top_at_{x}_Pa"], top, rtol=0, atol=1e-9 * scale_s)
        np.testing.assert_allclose(sim[f"stress_bottom_at_{x}_Pa"], bottom, rtol=0, atol=1e-9 * scale_s)
    assert np.max(np.abs(M)) > 1.0 and scale_N > 100.0          # the check is not of zeros: N m, N


def test_the_bearing_loads_are_given_as_magnitude_and_direction(press_run):
    sim, _, _ = press_run
    for joint in ("crank_on_rod", "rod_on_slider", "guide_on_slider"):
        fx, fy = sim[f"{joint}_x_N"], sim[f"{joint}_y_N"]
        np.testing.assert_allclose(sim[f"{joint}_magnitude_N"], np.hypot(fx, fy), rtol=1e-14)
        angle = sim[f"{joint}_angle_rad"]                        # radians in SI, as the crank angle
        np.testing.assert_allclose(np.cos(angle) * np.hypot(fx, fy), fx, atol=1e-9 * np.max(np.hypot(fx, fy)))
        np.testing.assert_allclose(np.sin(angle) * np.hypot(fx, fy), fy, atol=1e-9 * np.max(np.hypot(fx, fy)))


def test_the_summary_holds_the_peaks_where_and_when_and_the_buckling_margin(press_run):
    sim, nodes, summary = press_run
    row = summary.iloc[0]
    _, _, N_el = _section_forces(nodes, N_EL)            # the element values: the peaks lie there
    k, e = np.unravel_index(np.argmin(N_el), N_el.shape)
    assert row["peak_compression_N"] == pytest.approx(-N_el[k, e], rel=1e-9)
    assert row["peak_compression_x_m"] == pytest.approx((e + 0.5) * L / N_EL, abs=0.5 * L / N_EL + 1e-12)
    assert row["peak_compression_crank_angle_deg"] == pytest.approx(math.degrees(sim["theta_rad"][k]) % 360, abs=1e-6)
    k, e = np.unravel_index(np.argmax(N_el), N_el.shape)
    assert row["peak_tension_N"] == pytest.approx(N_el[k, e], rel=1e-9)
    euler = math.pi ** 2 * E * I / L ** 2                    # the pinned-pinned rod's Euler load
    assert row["buckling_margin"] == pytest.approx(euler / row["peak_compression_N"], rel=1e-9)
    for joint in ("crank_on_rod", "rod_on_slider"):
        magnitude = np.hypot(sim[f"{joint}_x_N"], sim[f"{joint}_y_N"])
        k = int(np.argmax(magnitude))
        assert row[f"peak_{joint}_N"] == pytest.approx(magnitude[k], rel=1e-12)
        assert row[f"peak_{joint}_angle_deg"] == pytest.approx(
            math.degrees(math.atan2(sim[f"{joint}_y_N"][k], sim[f"{joint}_x_N"][k])), abs=1e-9)
    stress = np.stack([sim[c] for c in sim.columns if c.startswith("stress_")], axis=1)
    assert row["peak_stress_Pa"] >= stress.max() * (1 - 1e-12) and row["min_stress_Pa"] <= stress.min() * (1 - 1e-12)
    assert row["peak_stress_fibre"] in ("top", "bottom") and 0 <= row["peak_stress_x_m"] <= L
    assert row["verdict"] == "trust this model here" and 0 <= row["model_error"] < 0.01


def test_steady_writes_the_stresses_along_the_rod_and_their_peaks(tmp_path):
    path = tmp_path / "press.json"
    path.write_text(json.dumps(PRESS))
    assert main(["steady", "--si", str(path), "--section", f"rectangle:{B},{H}", "--elements", "2",
                 "--steps-per-rev", "40", "--out", str(tmp_path / "s"), "--quiet"]) == 0
    orbit, steady = check_csv(tmp_path / "s" / "orbit.csv"), check_csv(tmp_path / "s" / "steady.csv")
    columns = [f"stress_{f}_at_{x:g}m_Pa" for f in ("top", "bottom") for x in (0, L / 2, L)]
    assert set(columns) <= set(orbit.columns)
    assert {"axial_force_at_0m_N", "axial_force_at_0.25m_N", "crank_on_rod_magnitude_N"} <= set(orbit.columns)
    row = steady.iloc[0]
    for name in ("peak_stress_Pa", "peak_stress_x_m", "peak_stress_crank_angle_deg", "min_stress_Pa",
                 "stress_range_Pa", "peak_compression_N", "buckling_margin", "peak_crank_on_rod_N",
                 "peak_rod_on_slider_angle_deg", "verdict", "model_error"):
        assert name in steady.columns and row[name] == row[name], name        # present, a value
    assert row["peak_stress_Pa"] >= orbit[columns].to_numpy().max() * (1 - 1e-12)
