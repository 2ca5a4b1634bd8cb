"""The four ingredients that prove the model-as-data seam, against independent physical truths:
gravity (simply supported beam under its own weight; the weight carried along the guide), the
guide offset (rigid offset slider-crank), rotary inertia switched off (Euler-Bernoulli frequency),
and the declared section quantities (against the strain energy density)."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.declaration import ingredients, schema
from crankgen.declaration.cases import Case
from crankgen.errors import ParameterError
from crankgen.discrete.system import Model
from crankgen.discrete.newmark import integrate
from crankgen.results.outputs import StateHistory, mid_deflection
from crankgen.analyses.steady import steady_state

import reference as ref
from helpers import bending_mode_state, observed_order, zero_crossing_frequency

PI4 = math.pi ** 4


def _quasi_static(n, **mech):
    """Steady revolution at Omega* = 0.002, consistent model: the rigid-body accelerations, about
    a* Omega*^2 = 4e-7, are below 1e-3 of the gravity used here."""
    st = steady_state(crankgen.Mechanism(mu=0.5, **mech), omega=0.002, n_elements=n, steps_per_rev=800,
                      damping="kelvin-voigt", membrane="averaged", tol=1e-10)
    assert st.status == "periodic", st.message
    return st


def test_gravity_across_the_guide_bends_the_rod_like_a_simply_supported_beam():
    """theta = 0: the rod lies on the guide, pinned at the crank, sliding at the slider: a simply
    supported beam under its weight q = rho A g.  v(L/2) = -5 q L^4 / (384 EI) (crankgen's units:
    rho A = 1, EI = 1/pi^4, L = 1), M(L/2) = q L^2 / 8, i.e. M* = M L / EI = pi^4 g / 8."""
    g = 1e-3
    st = _quasi_static(8, gravity=(0.0, -g))
    v_exact = -5 * g * PI4 / 384 / st.case.eps            # v* = v / r
    assert st.v_mid[0] == pytest.approx(v_exact, rel=2e-3)
    m_exact = g * PI4 / 8              # M = EI v_xx; v = -(g/24EI)(x - 2x^3 + x^4): v_xx(1/2) = g/(8 EI)
    errors = []
    for n in (4, 8):
        st = _quasi_static(n, gravity=(0.0, -g))
        errors.append(abs(st.bending_moment(0.5)[0] - m_exact) / abs(m_exact))
    assert errors[-1] < 0.02
    assert errors[1] < errors[0] / 3                       # the nodal average converges, O(h^2)


def test_gravity_along_the_guide_is_carried_by_the_rod_as_axial_force():
    """theta = 0, gravity along the guide towards the slider: N(x) = g (rho A (L - x) + m_s), the
    weight of the rod beyond x plus the slider's (the guide carries only normal forces).  The linear
    axial element has a constant force, exact at its middle; at interior nodes the mean of the two
    elements is exact too (N is linear in x)."""
    g, ms = 1e-3, 0.5
    st = _quasi_static(4, gravity=(g, 0.0), ms=ms)
    for x in (0.125, 0.25, 0.375, 0.5, 0.75, 0.875):
        exact = g * ((1.0 - x) + ms) * PI4                 # N* = N L^2 / EI
        assert st.axial_force(x)[0] == pytest.approx(exact, rel=2e-3), x


def test_gravity_potential_keeps_the_energy_constant_without_crank_motion_or_damping():
    """Omega = 0, mu = 0, gravity on: T + U + V is conserved to O(dt^2) (C: exactly, linear)."""
    mech = crankgen.Mechanism(eps=0.05, mu=0.0, gravity=(0.3, -0.5))
    drifts = []
    for steps in (40, 80):
        model = Model.build(mech, 0.0, 4, "lagrange", "C", "kelvin-voigt")
        d0 = bending_mode_state(model.mesh, 0.05)
        hist = integrate(model, d0, np.zeros_like(d0), 0.0, 2 * math.pi / steps, 2 * steps)
        E = np.array([sum(model.energies(t, d, v)) for t, d, v in zip(hist.t, hist.d, hist.v)])
        drifts.append(np.max(np.abs(E - E[0])) / np.max(np.abs(E)))
    assert max(drifts) < 1e-10
    without = Model.build(crankgen.Mechanism(eps=0.05, mu=0.0), 0.0, 4, "lagrange", "C", "kelvin-voigt")
    assert abs(sum(model.energies(0.0, d0, 0 * d0)) - sum(without.energies(0.0, d0, 0 * d0))) > 1e-4


def test_offset_guide_moves_the_slider_like_the_rigid_offset_mechanism():
    """Quasi-static: the slider's X / L equals the rigid offset slider-crank's,
    a cos theta + sqrt(1 - (a sin theta - e)^2), up to the rod's static axial strain."""
    a, e = 0.3, 0.25
    st = _quasi_static(4, a=a, offset=e)
    theta = st.theta
    rigid = a * np.cos(theta) + np.sqrt(1 - (a * np.sin(theta) - e) ** 2)
    assert np.max(np.abs(st.slider_position - rigid)) < 1e-6
    st0 = _quasi_static(4, a=a)
    assert np.max(np.abs(st0.slider_position - rigid)) > 1e-2        # the offset acts


def test_offset_that_stops_the_crank_is_refused():
    with pytest.raises(ParameterError, match="full revolution"):
        crankgen.Mechanism(a=0.6, offset=0.45)
    with pytest.raises(ParameterError, match="full revolution"):
        Case(a=0.2, offset=-0.8)
    crankgen.Mechanism(a=0.6, offset=0.35)


def test_without_rotary_inertia_the_rod_vibrates_at_omega_b():
    """Stationary crank, no damping: with rotary inertia off, the pinned / sliding Euler-Bernoulli
    rod vibrates at omega_b (= 1) in the limit of fine meshes, not at 1/sqrt(1 + pi^2 eps^2)."""
    mech = crankgen.Mechanism(eps=0.05, mu=0.0)
    steps, periods = 200, 4
    dt = 2 * math.pi / steps
    errors = []
    for n in (2, 4, 8):
        model = Model.build(mech, 0.0, n, "lagrange", "A", "kelvin-voigt", rotary_inertia=False)
        d0 = bending_mode_state(model.mesh, 1e-7)
        hist = integrate(model, d0, np.zeros_like(d0), 0.0, dt, steps * periods)
        q = StateHistory(model.case, hist.t, hist.d).element_vectors()
        w = zero_crossing_frequency(hist.t, mid_deflection(model.mesh, q, mech.eps))
        errors.append(abs(2 / dt * math.tan(w * dt / 2) - 1.0))
    assert errors[-1] < 1e-4
    assert observed_order([2, 1], errors[:2]) > 3.5
    rayleigh = 1 / math.sqrt(1 + (math.pi * mech.eps) ** 2)
    assert abs(1.0 - rayleigh) > 100 * errors[-1]          # the two limits are told apart


@pytest.mark.parametrize("approach,membrane", [("A", "pointwise"), ("B", "pointwise"), ("C", "pointwise"),
                                               ("A", "averaged")])
def test_section_quantities_are_derivatives_of_the_strain_energy_density(approach, membrane):
    """N = dW/du_x and M = dW/dv_xx of the strain energy density W (tests/reference.py, eq. 2 and
    its reductions; for the averaged element, dU/du_{i+1} = mean N over the element), by central
    differences; the surface strain is e_m - fiber r v_xx."""
    rng = np.random.default_rng(7)
    eps = 0.02
    case = Case(eps=eps, approach=approach, membrane=membrane, n_elements=1)
    EA, EI = 1 / (PI4 * eps**2), 1 / PI4
    q = 0.05 * rng.standard_normal(ref.NDOF)                 # chi slots too: no field of A, B, C
    l = 1.0
    coef = case.coefficients
    geo = np.array([l, 0.0])
    N_kernel = ingredients.field_kernel("axial_force", case.options)
    M_kernel = ingredients.field_kernel("bending_moment", case.options)
    S_kernel = ingredients.field_kernel("surface_strain", case.options)
    f = ref.element_fields(q, 0 * q, l)
    h = 1e-6
    if membrane == "pointwise":
        for k in range(f["u_x"].shape[-1]):
            point = {name: f[name][..., k] for name in ("u_x", "v_x", "v_xx")}

            def W(**shift):
                g = {name: point[name] + shift.get(name, 0.0) for name in point}
                return ref.strain_energy_density(approach, g, EA, EI)
            dW_du = (W(u_x=h) - W(u_x=-h)) / (2 * h)
            dW_dv = (W(v_xx=h) - W(v_xx=-h)) / (2 * h)
            zeta = float(ref.ZETA[k])
            assert N_kernel(q, zeta, geo, coef) * EI == pytest.approx(dW_du, rel=1e-6)
            assert M_kernel(q, zeta, geo, coef) * EI == pytest.approx(dW_dv, rel=1e-6)
    else:
        e = np.zeros(ref.NDOF)
        e[ref.U1] = h
        U = lambda qq: ref.strain_energy_averaged(approach, qq, l, EA, EI)   # noqa: E731
        dU = (U(q + e) - U(q - e)) / (2 * h)                 # = int N B_u dx = mean N (B_u = 1/l)
        assert N_kernel(q, 0.3, geo, coef) * EI == pytest.approx(dU, rel=1e-6)
    fiber = math.sqrt(3)
    m, n_ = M_kernel(q, 0.4, geo, coef), N_kernel(q, 0.4, geo, coef)
    assert S_kernel(q, 0.4, geo, coef, fiber) == pytest.approx(n_ * EI / EA - fiber * eps * m, rel=1e-12)


def test_field_outputs_average_the_two_elements_at_a_node_and_refuse_bad_input():
    r = crankgen.simulate(crankgen.Mechanism(), omega=0.8, n_elements=4, steps_per_rev=40, revolutions=1,
                          damping="kelvin-voigt")
    left = r.bending_moment(0.5 - 1e-9)
    right = r.bending_moment(0.5 + 1e-9)
    np.testing.assert_allclose(r.bending_moment(0.5), (left + right) / 2, rtol=1e-6, atol=1e-12)
    assert r.bending_moment([0.1, 0.5]).shape == (len(r.t), 2)
    assert r.quantity("axial_force", 0.3).shape == r.t.shape
    with pytest.raises(ParameterError):
        r.axial_force(1.5)
    with pytest.raises(ParameterError):
        r.surface_strain(0.5)                                # fiber missing
    with pytest.raises(ParameterError):
        r.quantity("torque", 0.5)
    np.testing.assert_allclose(r.slider_position[0], 1.1, rtol=1e-12)   # a + L at theta = 0, at rest


def test_every_combination_of_options_selects_one_variant_of_each_family():
    """The declaration is consistent: for every combination of the options that is not excluded
    (the exact rod has no printed form or damping: refused by name), each family has at most one
    variant (variants exclude each other), inertia, elastic force, dissipation and the slider's
    inertia are always present, and the slider's dissipation exactly with eq. (24)."""
    import itertools
    names = ingredients.OPTION_NAMES
    refused = 0
    for values in itertools.product(*(ingredients.CHOICES[n] for n in names)):
        options = dict(zip(names, values))
        if any(all(options[k] == v for k, v in x.options.items()) for x in schema.EXCLUSIONS):
            with pytest.raises(ParameterError, match="approach 'exact' has no printed"):
                ingredients.check_options(options)
            refused += 1
            continue
        sel = ingredients.select(options)                       # raises if two variants match
        present = {f for f, k in zip(ingredients.FAMILIES, sel.families) if k >= 0}
        assert {"inertia", "elastic", "dissipation", "slider_inertia", "gravity",
                "slider_gravity"} <= present, options
        assert ("slider_dissipation" in present) == (options["damping"] == "paper"), options
    assert refused == 3 * 2 * 2                  # exact with formulation or damping paper (membrane, rho I)


def test_unknown_or_incompatible_options_are_refused_by_name():
    with pytest.raises(ParameterError, match="approach"):
        Case(approach="D")
    with pytest.raises(ParameterError, match="rotary_inertia"):
        Case(rotary_inertia="no")
    with pytest.raises(ParameterError, match="unknown model option 'stiffening'"):
        ingredients.check_options({"stiffening": True})
    with pytest.raises(ParameterError, match="cubic_axial"):
        Case(groups_off="cubic_axial", approach="C")            # C has no cubic terms
