"""The element option membrane="averaged" (element-mean membrane strain): kernels against an
independent reference, and the cure of membrane locking as the mesh is refined."""

import numpy as np
import pytest

import reference as ref
from kernel_api import damping, energy, lagrange
from crankgen.declaration.cases import Case
from crankgen.analyses.steady import steady_states


@pytest.fixture
def batch():
    rng = np.random.default_rng(11)
    n = 6
    return dict(q=ref.random_nodal(rng, (n,)), qd=ref.random_nodal(rng, (n,)),
                l=rng.uniform(0.05, 0.5, n), EA=rng.uniform(10, 1000, n),
                EI=rng.uniform(0.005, 0.05, n), mu=rng.uniform(0.01, 0.5, n))


def _fd_grad(f, x, h=1e-7):
    g = np.zeros_like(x)
    for k in range(x.shape[-1]):
        e = np.zeros_like(x)
        e[..., k] = h * np.maximum(1.0, np.abs(x[..., k]))
        g[..., k] = (f(x + e) - f(x - e)) / (2 * e[..., k])
    return g


@pytest.mark.parametrize("approach", ["A", "B"])
def test_energies_match_reference(batch, approach):
    b = batch
    U = getattr(energy, f"strain_energy_{approach}_averaged")(b["q"], b["l"], b["EA"], b["EI"])
    np.testing.assert_allclose(U, ref.strain_energy_averaged(approach, b["q"], b["l"], b["EA"], b["EI"]),
                               rtol=1e-11)
    D = getattr(energy, f"dissipation_{approach}_averaged")(b["q"], b["qd"], b["l"], b["EA"], b["EI"], b["mu"])
    np.testing.assert_allclose(D, ref.dissipation_averaged(approach, b["q"], b["qd"], b["l"], b["EA"],
                                                           b["EI"], b["mu"]), rtol=1e-11)


@pytest.mark.parametrize("approach", ["A", "B"])
def test_forces_are_gradients_and_tangents_are_derivatives(batch, approach):
    b = batch
    kern = getattr(lagrange, f"rod_elastic_{approach}_averaged")
    r, K = kern(b["q"], b["l"], b["EA"], b["EI"])
    g = _fd_grad(lambda q: ref.strain_energy_averaged(approach, q, b["l"], b["EA"], b["EI"]), b["q"])
    np.testing.assert_allclose(r, g, rtol=1e-6, atol=1e-8 * np.abs(g).max())
    for k in range(ref.NDOF):
        col = _fd_grad(lambda q: kern(q, b["l"], b["EA"], b["EI"])[0][..., k], b["q"])
        np.testing.assert_allclose(K[..., k, :], col, rtol=1e-6, atol=1e-7 * np.abs(K).max())
    kv = getattr(damping, f"kelvin_voigt_{approach}_averaged")
    rd, Kd, Cd = kv(b["q"], b["qd"], b["l"], b["EA"], b["EI"], b["mu"])
    gd = _fd_grad(lambda qd: ref.dissipation_averaged(approach, b["q"], qd, b["l"], b["EA"], b["EI"],
                                                      b["mu"]), b["qd"])
    np.testing.assert_allclose(rd, gd, rtol=1e-6, atol=1e-8 * np.abs(gd).max())
    for k in range(ref.NDOF):
        col_q = _fd_grad(lambda q: kv(q, b["qd"], b["l"], b["EA"], b["EI"], b["mu"])[0][..., k], b["q"])
        col_qd = _fd_grad(lambda qd: kv(b["q"], qd, b["l"], b["EA"], b["EI"], b["mu"])[0][..., k], b["qd"])
        np.testing.assert_allclose(Kd[..., k, :], col_q, rtol=1e-6, atol=1e-7 * np.abs(Kd).max())
        np.testing.assert_allclose(Cd[..., k, :], col_qd, rtol=1e-6, atol=1e-7 * np.abs(Cd).max())


@pytest.mark.parametrize("approach", ["A", "B"])
def test_equal_to_plain_element_when_the_slope_is_constant(batch, approach):
    """With v linear in the element, v_x^2 equals its mean: both elements give the same energy."""
    b = batch
    q = b["q"].copy()
    slope = q[:, ref.PSI0]
    q[:, ref.V1] = q[:, ref.V0] + slope * b["l"]
    q[:, ref.PSI1] = slope
    plain = getattr(energy, f"strain_energy_{approach}")(q, b["l"], b["EA"], b["EI"])
    avg = getattr(energy, f"strain_energy_{approach}_averaged")(q, b["l"], b["EA"], b["EI"])
    np.testing.assert_allclose(avg, plain, rtol=1e-12)


def test_averaged_element_removes_membrane_locking():
    """Consistent model (lagrange, Kelvin-Voigt) at Omega* = 0.8: the plain element converges slowly
    (membrane locking), the averaged one fast, and the plain element approaches its limit."""
    ns = (2, 4, 8, 16)
    cases = [Case(omega=0.8, n_elements=n, formulation="lagrange", damping="kelvin-voigt",
                  membrane=m) for m in ("pointwise", "averaged") for n in ns]
    res = steady_states(cases + [Case(omega=0.8, n_elements=32, formulation="lagrange",
                                      damping="kelvin-voigt", membrane="averaged")])
    assert all(r.ok for r in res)
    plain = np.array([r.amplitude for r in res[:4]])
    avg = np.array([r.amplitude for r in res[4:8]])
    limit = res[8].amplitude
    err_plain, err_avg = np.abs(plain - limit) / limit, np.abs(avg - limit) / limit
    assert err_avg[1] < 0.01 and err_avg[-1] < 1e-4          # converged with 4 elements
    assert err_plain[-1] > 0.05                              # still locked with 16
    assert np.all(np.diff(err_plain) < 0)                    # but converging to the same limit
