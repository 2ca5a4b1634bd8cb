"""Term groups of the consistent model (audit sections 4-5): kernels, switches, weights, backbone."""

import math

import numpy as np
import pytest

import reference as ref
from crankgen.declaration import ingredients
from crankgen._generated import elements as E
from crankgen._generated import groups
from crankgen.declaration.ingredients import SWITCHABLE_GROUPS
from kernel_api import _kin, coef, vec
from crankgen.audit.backbone import backbone
from crankgen.declaration.cases import Case
from crankgen.errors import ParameterError
from crankgen.analyses.steady import steady_state, steady_states
from crankgen.audit.term_weights import consistent_case, group_weights


def _parts(prefix):
    return [getattr(groups, n) for n in groups.__all__ if n.startswith(prefix + "__")]


@pytest.fixture
def data():
    rng = np.random.default_rng(5)
    n = 5
    kin = _kin(0.2, rng.uniform(0, 6, n), 0.8, rng.uniform(-0.2, 0.2, n), rng.uniform(-0.3, 0.3, n),
               rng.uniform(-0.3, 0.3, n))
    return dict(q=ref.random_nodal(rng, (n,)), qd=ref.random_nodal(rng, (n,)),
                qdd=ref.random_nodal(rng, (n,)), geo=vec(rng.uniform(0.05, 0.5, n), rng.uniform(0, 0.9, n)),
                coef=coef(rhoA=1.0, rhoI=1e-3, EA=100.0, EI=0.01, mu=0.3, ms=0.7), kin=kin)


def _sum_parts(parts, *args):
    outs = [p(*args) for p in parts]
    return [sum(o[k] for o in outs) for k in range(len(outs[0]))]


SOURCES = [("rod_inertia", E.inertia_lagrange), ("slider_inertia", E.slider_inertia_lagrange),
           ("rod_elastic_A", E.elastic_lagrange_A), ("rod_elastic_A_averaged", E.elastic_lagrange_A_averaged),
           ("kelvin_voigt_A", E.dissipation_kelvin_voigt_A),
           ("kelvin_voigt_A_averaged", E.dissipation_kelvin_voigt_A_averaged)]


@pytest.mark.parametrize("source,kernel", SOURCES, ids=[s for s, _ in SOURCES])
def test_groups_add_up_to_the_full_kernels(data, source, kernel):
    """Each group split is a partition: the parts sum to the kernel they come from (r and tangents)."""
    args = (data["q"], data["qd"], data["qdd"], data["geo"], data["coef"], data["kin"])
    for full, total in zip(kernel(*args)[:4], _sum_parts(_parts(source), *args)):
        np.testing.assert_allclose(total, full, rtol=1e-12, atol=1e-13 * max(np.abs(full).max(), 1e-300))


@pytest.mark.parametrize("group", SWITCHABLE_GROUPS)
def test_a_switched_off_group_is_removed_from_the_kernels(data, group):
    """Weight 0 on a group (a term mask on the declared families) gives the full kernel minus that
    group's part, computed independently by the audit's group kernels; nothing else changes."""
    args = (data["q"], data["qd"], data["qdd"], data["geo"])
    off = data["coef"].copy()
    off[ingredients.COEFFICIENTS.index(f"w_{group}")] = 0.0
    touched = 0
    for source, kernel in SOURCES[:4]:
        part = getattr(groups, f"{source}__{group}", None)
        full = kernel(*args, data["coef"], data["kin"])[:4]
        masked = kernel(*args, off, data["kin"])[:4]
        removed = part(*args, data["coef"], data["kin"]) if part is not None else [0 * x for x in full]
        touched += part is not None
        for f, m, g in zip(full, masked, removed):
            np.testing.assert_allclose(m, f - g, rtol=1e-11, atol=1e-12 * max(np.abs(f).max(), 1e-300))
    assert touched >= 1


def test_quartic_group_is_the_gradient_of_the_quartic_energy(data):
    """Independent check of one group: the quartic force is d/dq of EA/8 int v_x^4 (quadrature)."""
    d = data
    l = d["geo"][:, 0]
    z = 0 * d["q"]
    r = groups.rod_elastic_A__quartic(d["q"], z, z, d["geo"], coef(EA=100.0, EI=0.01), d["kin"])[0]
    h = 1e-7
    for k in range(ref.NDOF):
        e = np.zeros(ref.NDOF)
        e[k] = h

        def quartic(q):
            f = ref.element_fields(q, 0 * q, l)
            return ref.integrate(100.0 / 8 * f["v_x"] ** 4, l)
        fd = (quartic(d["q"] + e) - quartic(d["q"] - e)) / (2 * h)
        np.testing.assert_allclose(r[:, k], fd, rtol=1e-6, atol=1e-9 * np.abs(r).max())


def test_switch_validation():
    with pytest.raises(ParameterError):
        Case(groups_off="gravity")
    with pytest.raises(ParameterError):
        Case(groups_off="quartic", formulation="paper")
    with pytest.raises(ParameterError):
        Case(groups_off="quartic", approach="B")         # B has no quartic term to switch off
    assert Case(groups_off="quartic, gyroscopic").groups_off == "gyroscopic,quartic"


def test_switching_off_a_group_changes_only_that_group():
    """A without its quartic group is exactly B (eq. 2 without the quartic term; same strain-rate
    damping): the switch removes that group and nothing else.  Switching off the cubic axial
    group changes the response."""
    base = consistent_case(0.01, 0.6, n_elements=4)
    wide = consistent_case(0.05, 0.6, n_elements=4)        # B diverges at eps = 0.01
    a, c, no_quartic, b = steady_states([
        base, Case(**{**base.as_dict(), "groups_off": "cubic_axial"}),
        Case(**{**wide.as_dict(), "groups_off": "quartic"}), Case(**{**wide.as_dict(), "approach": "B"})])
    assert a.ok and c.ok and no_quartic.ok and b.ok
    np.testing.assert_allclose(no_quartic.v_mid, b.v_mid, rtol=0, atol=1e-10 * b.amplitude)
    np.testing.assert_allclose(no_quartic.u_end, b.u_end, rtol=0, atol=1e-10 * np.abs(b.u_end).max())
    assert abs(c.amplitude - a.amplitude) > 0.05 * a.amplitude


def test_group_forces_balance_on_a_converged_trajectory():
    """All groups together are the residual of the equations of motion, ~0 along the solution."""
    case = consistent_case(0.01, 0.6, n_elements=4)
    st = steady_state(case=case)
    w = group_weights(case, st)
    assert w.balance < 1e-8
    assert w.transverse["inertia"] > 1e-3 and w.axial["stiffness"] > 0.1


def duffing_frequency(amplitude, eps):
    """Free vibration of the single mode v = A sin(pi x) of a rod whose axial displacement stays
    zero (no axial relief): m A'' + k A + k3 A^3 = 0 with m = (1 + pi^2 eps^2)/2 (rotary inertia),
    k = EI pi^4 / 2 = 1/2, k3 = 3 EA pi^4 / 16 (from EA/8 int v_x^4); exact period by quadrature."""
    from scipy.integrate import quad
    m, k, k3A2 = 0.5 * (1 + (math.pi * eps) ** 2), 0.5, 3 / (16 * eps**2) * (amplitude * eps) ** 2
    period = 4 * quad(lambda s: 1 / math.sqrt((k + k3A2 * (1 + math.sin(s) ** 2) / 2) / m), 0, math.pi / 2)[0]
    return 2 * math.pi / period


def test_backbone_small_amplitudes_and_linear_model():
    eps = 0.01
    exact = 1 / math.sqrt(1 + (math.pi * eps) ** 2)
    lin = backbone([0.1, 5.0], eps=eps, approach="C", n_elements=8)
    assert all(abs(p.frequency - exact) < 2e-4 for p in lin)          # linear: amplitude-independent
    small = backbone([0.05], eps=eps, approach="A", n_elements=8)[0]
    assert abs(small.frequency - exact) < 2e-4
    # the printed form stiffens: P_i = EA B_u^T q gets no v_x^2 from the bending, so u stays 0 at
    # rest and the quartic term acts in full (an axially immovable rod): the single-mode Duffing
    # oscillator, exact; the other modes soften it slightly (0.8 % at v* = 2)
    paper = backbone([2.0], eps=eps, approach="A", formulation="paper", n_elements=8)[0]
    duffing = duffing_frequency(2.0, eps)
    assert duffing > 1.4
    assert 0 < duffing - paper.frequency < 0.015 * duffing
