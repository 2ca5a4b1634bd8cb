"""The quadrature path of the derivation (derive/quadrature.py), proven on known ground: asked to
integrate the polynomial energies of approaches A, B and C by a Gauss rule exact for their degree,
it reproduces their closed-form generated kernels (r, K, C, M) to round-off.

Each kernel is built here as the exact rod's are (declaration.by_quadrature, on the point space of a
linear u): the element energy over the points of a rule (derive/energies.py), its generalized point
forces and their tangents by SymPy at the points (derive/quadrature.py), the emitter's staged common subexpressions (derive/emit.py); the emitted
NumPy source is executed and compared with crankgen's committed closed-form kernel, which
integrates the same densities exactly (shape_functions.integrate_element)."""

import numpy as np
import pytest

from crankgen._derive import declaration, emit, kernels, quadrature
from crankgen._derive import energies as en
from crankgen._generated import elements as E
from reference import assert_close

def _linear_u_quadrature(kind, element_energy, rule):
    """declaration.by_quadrature's build on approaches A, B and C's point space (their linear u:
    energies.field_columns() without an approach) instead of the exact rod's (cubic u)."""
    space = quadrature.PointSpace(rule, en.QUANTITIES, en.ELEMENT_FIELDS, en.POINT_FIELDS, en.field_columns())
    r, K, C, M, definitions = space.element_terms(space.generalized_forces(kind, element_energy(space)))
    return declaration.Term(r, "exact", (K, C, M), definitions)


def _kernel(kind, element_energy, rule):
    term = _linear_u_quadrature(kind, element_energy, rule)
    spec = kernels.Kernel("by_quadrature", "", kernels.ELEMENT_INPUTS,
                          kernels._residual_outputs(term.residual, term.printed_stiffness, term.tangents),
                          definitions=term.definitions)
    namespace = {}
    exec("import math\nimport numpy\n" + emit.emit_kernel(spec), namespace)
    return namespace["by_quadrature"]


def _arguments(seed=5, n=6):
    rng = np.random.default_rng(seed)
    q = rng.uniform(-1, 1, (n, 8)) * [0.05, 0.2, 0.6, 0.05, 0.05, 0.2, 0.6, 0.05]   # (u, v, psi, chi) x 2
    qd, qdd = rng.uniform(-1, 1, (n, 8)), rng.uniform(-1, 1, (n, 8))
    geo = np.stack([rng.uniform(0.1, 0.4, n), rng.uniform(0.0, 0.6, n)], -1)
    # rhoA, rhoI, EA, EI, mu, ms, gX, gY random; the switchable groups' weights 1 (every model's)
    coef = np.r_[rng.uniform(0.2, 2.0, 8), np.ones(6)]
    kin = np.r_[rng.uniform(-1.0, 1.0, 7), np.zeros(3)]
    return q, qd, qdd, geo, coef, kin


# every approach and every kind of energy, each with the fewest Gauss points exact for its
# integrand's degree (A's v_x^4 and (u_x + v_x v_x')^2: 8; B's u_x v_x^2: 4; C: 2; the kinetic
# energy: 6); A with the element-mean membrane strain (element fields of the rule's points),
# the others pointwise; the remaining combinations are the same path on the same densities (and
# test_a_rule_below_the_integrands_degree_does_not builds A's pointwise one)
CASES = [
    ("elastic_lagrange_A_averaged", "potential", 8, lambda space: en.element_strain_energy(space, "A", "averaged")),
    ("elastic_lagrange_B", "potential", 4, lambda space: en.element_strain_energy(space, "B", "pointwise")),
    ("elastic_lagrange_C", "potential", 2, lambda space: en.element_strain_energy(space, "C", "pointwise")),
    ("dissipation_kelvin_voigt_A_averaged", "dissipation", 8,
     lambda space: en.element_dissipation(space, "A", "averaged")),
    ("dissipation_kelvin_voigt_C", "dissipation", 2, lambda space: en.element_dissipation(space, "C", "pointwise")),
    ("inertia_lagrange", "kinetic", 6, lambda space: en.element_kinetic_energy(space, "A")),
]


@pytest.mark.slow
@pytest.mark.parametrize("name, kind, degree, energy", CASES, ids=[c[0] for c in CASES])
def test_quadrature_path_reproduces_the_closed_form_kernels(name, kind, degree, energy):
    args = _arguments()
    got, want = _kernel(kind, energy, quadrature.gauss(degree))(*args), getattr(E, name)(*args)[:4]
    for label, g, w in zip("rKCM", got, want):
        assert_close(g, w, 1e-12, np.ndim(w) - 1, f"{name}.{label} by quadrature", atol=1e-14 * np.max(np.abs(w)))


def test_a_rule_below_the_integrands_degree_does_not():
    """The comparison is not blind: two points (degree 3) miss A's v_x^4 and u_x v_x^2 terms."""
    args = _arguments()
    got = _kernel("potential", lambda space: en.element_strain_energy(space, "A", "pointwise"),
                  quadrature.gauss(3))(*args)[0]
    want = E.elastic_lagrange_A(*args)[0]
    assert np.max(np.abs(got - want)) > 1e-6 * np.max(np.abs(want))
