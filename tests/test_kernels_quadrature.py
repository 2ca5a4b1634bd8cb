"""Generated element kernels against hand-written quadrature of their defining integrands.

The reference (tests/reference.py) is written from the physics: shape functions typed in from
Appendix A, Gauss-Legendre quadrature, d'Alembert inertia forces, hand-differentiated energy
densities and the printed Appendix B matrices with the errata applied.  Nothing here imports the
SymPy derivation.
"""

import inspect
import sys
import zlib

import numpy as np
import pytest

from crankgen.declaration import ingredients, schema
from crankgen._generated import elements as gen_elements
from crankgen._generated import energy as gen_energy
from crankgen._generated import fields as gen_fields
from crankgen._generated import groups as gen_groups
from crankgen._generated import kinematics as gen_kinematics
from crankgen._generated import schema as dispatch
from crankgen._generated import shape
from crankgen._generated import shape as gen_shape
from kernel_api import damping, energy, lagrange, paper

import reference as ref
from reference import APPROACHES, assert_close, pick

RTOL = 1e-10
SEEDS = (0, 1, 2)


@pytest.fixture(params=SEEDS, ids=lambda s: f"seed{s}")
def elems(request):
    return ref.random_elements(np.random.default_rng(1000 + request.param), n=7)


# --------------------------------------------------------------------------------------------
# shape functions
# --------------------------------------------------------------------------------------------

def test_reference_slopes_are_derivatives_of_reference_shapes():
    """Sanity of the reference itself: N_psi = B_v = dN_v/dx, B_u = dN_u/dx, B_psi = dN_psi/dx."""
    rng = np.random.default_rng(7)
    z, l = rng.uniform(0.05, 0.95, 20), rng.uniform(0.05, 0.5, 20)
    n_u, n_v, n_psi, b_u, b_v, b_psi = ref.shape_at(z, l)
    h = 1e-4
    d_dx = lambda k: ref.fd_derivative(lambda zz: ref.shape_at(zz, l)[k], z, h) / l[:, None]
    assert_close(n_psi, b_v, 1e-13, 1, "N_psi vs B_v")
    assert_close(d_dx(0), b_u, 1e-9, 1, "dN_u/dx")
    assert_close(d_dx(1), b_v, 1e-9, 1, "dN_v/dx")
    assert_close(d_dx(2), b_psi, 1e-9, 1, "dN_psi/dx")
    # nodal values: u, v, psi interpolate the nodal vector (8 slots: u, v, psi, chi of each node)
    ends = ref.shape_at(np.array([0.0, 1.0]), np.array([0.3, 0.3]))
    unit = np.eye(ref.NDOF)
    np.testing.assert_allclose(ends[0], unit[[ref.U0, ref.U1]], atol=1e-15)
    np.testing.assert_allclose(ends[1], unit[[ref.V0, ref.V1]], atol=1e-15)
    np.testing.assert_allclose(ends[2], unit[[ref.PSI0, ref.PSI1]], atol=1e-15)
    for column in ends + ref.shape_at(z, l):            # linear u: nothing in the chi slots
        assert not column[..., ref.CHIS].any()
    # the exact rod's cubic u: B_u = dN_u/dx, its derivative likewise, and (u, u_x) interpolate
    # (u, chi) at the nodes
    n_c, b_c, b_cc = ref.cubic_u_at(z, l)
    d_dx_cubic = lambda k: ref.fd_derivative(lambda zz: ref.cubic_u_at(zz, l)[k], z, h) / l[:, None]
    assert_close(d_dx_cubic(0), b_c, 1e-9, 1, "dN_u_cubic/dx")
    assert_close(d_dx_cubic(1), b_cc, 1e-9, 1, "dB_u_cubic/dx")
    n_c, b_c, _ = ref.cubic_u_at(np.array([0.0, 1.0]), np.array([0.3, 0.3]))
    np.testing.assert_allclose(n_c, unit[[ref.U0, ref.U1]], atol=1e-15)
    np.testing.assert_allclose(b_c, unit[[ref.CHI0, ref.CHI1]], atol=1e-15)


def test_shape_functions():
    rng = np.random.default_rng(3)
    z = np.concatenate([[0.0, 1.0, 0.5], rng.uniform(0, 1, 12)])
    l = rng.uniform(0.05, 0.5, z.shape)
    n_u, n_v, n_psi, n_u_cubic = shape.shape_functions(z, l)
    e_u, e_v, e_psi = ref.shape_at(z, l)[:3]
    assert_close(n_u, e_u, 1e-13, 1, "N_u")
    assert_close(n_v, e_v, 1e-13, 1, "N_v")
    assert_close(n_psi, e_psi, 1e-13, 1, "N_psi")
    assert_close(n_u_cubic, ref.cubic_u_at(z, l)[0], 1e-13, 1, "N_u_cubic (the exact rod)")


def test_slope_gram():
    l = np.random.default_rng(4).uniform(0.05, 0.5, 7)
    b_v = ref.element_shapes(l)[4]
    expected = ref.integrate(ref.outer(b_v, b_v), l, 2)
    G = shape.slope_gram(l)
    assert_close(G, expected, RTOL, 2, "slope_gram")
    # int v_x^2 dx = q^T G q for a random q
    q = ref.random_nodal(np.random.default_rng(5), (7,))
    f = ref.element_fields(q, q, l)
    np.testing.assert_allclose(np.einsum("ni,nij,nj->n", q, G, q), ref.integrate(f["v_x"] ** 2, l),
                               rtol=1e-11)


# --------------------------------------------------------------------------------------------
# energies
# --------------------------------------------------------------------------------------------

def test_rod_kinetic_energy(elems):
    args = pick(elems, *ref.ROD_T_ARGS)
    assert_close(energy.rod_kinetic_energy(*args), ref.rod_kinetic_energy(*args), RTOL, 0,
                 "rod_kinetic_energy")


def test_rod_kinetic_energy_rotary_part(elems):
    """With rhoA = 0 only the rotary inertia rhoI/2 [(phid - psid)^2 + (psi phid)^2] remains."""
    e = dict(elems, rhoA=np.zeros(7))
    args = pick(e, *ref.ROD_T_ARGS)
    expected = ref.rod_kinetic_energy(*args)
    assert np.all(expected > 0)
    assert_close(energy.rod_kinetic_energy(*args), expected, RTOL, 0, "rotary kinetic energy")


def test_slider_kinetic_energy(elems):
    args = pick(elems, *ref.SLIDER_T_ARGS)
    assert_close(energy.slider_kinetic_energy(*args), ref.slider_kinetic_energy(*args), RTOL, 0,
                 "slider_kinetic_energy")


@pytest.mark.parametrize("approach", APPROACHES)
def test_strain_energy(approach, elems):
    q, l, EA, EI = pick(elems, "q", "l", "EA", "EI")
    U = getattr(energy, f"strain_energy_{approach}")(q, l, EA, EI)
    assert_close(U, ref.strain_energy(approach, q, l, EA, EI), RTOL, 0, f"strain_energy_{approach}")


@pytest.mark.parametrize("approach", APPROACHES)
def test_strain_energy_large_slopes_distinguish_approaches(approach):
    """Slopes of order one make the v_x^4 and u_x v_x^2 terms dominant: A, B, C must differ."""
    rng = np.random.default_rng(11)
    q = rng.uniform(-1, 1, (5, ref.NDOF)) * [0.05, 0.3, 1.0, 0.05, 0.05, 0.3, 1.0, 0.05]
    l, EA, EI = rng.uniform(0.1, 0.5, 5), rng.uniform(10, 100, 5), rng.uniform(0.01, 0.1, 5)
    U = getattr(energy, f"strain_energy_{approach}")(q, l, EA, EI)
    assert_close(U, ref.strain_energy(approach, q, l, EA, EI), RTOL, 0, f"strain_energy_{approach}")
    others = [ref.strain_energy(ap, q, l, EA, EI) for ap in APPROACHES if ap != approach]
    for other in others:
        assert np.all(np.abs(U - other) > 1e-6 * np.abs(U))


@pytest.mark.parametrize("approach", APPROACHES)
def test_dissipation(approach, elems):
    q, qd, l, EA, EI, mu = pick(elems, "q", "qd", "l", "EA", "EI", "mu")
    D = getattr(energy, f"dissipation_{approach}")(q, qd, l, EA, EI, mu)
    assert_close(D, ref.dissipation(approach, q, qd, l, EA, EI, mu), RTOL, 0,
                 f"dissipation_{approach}")


# --------------------------------------------------------------------------------------------
# exact Lagrange forces
# --------------------------------------------------------------------------------------------

OUTPUT_NAMES = ("r", "K", "C", "M")


def _compare_outputs(got, expected, what, names=OUTPUT_NAMES, rtol=RTOL):
    assert len(got) == len(expected)
    for name, g, e in zip(names, got, expected):
        assert_close(g, e, rtol, np.ndim(e) - 1, f"{what}.{name}", atol=1e-300)


def test_lagrange_rod_inertia_is_dalembert(elems):
    args = pick(elems, *ref.ROD_INERTIA_ARGS)
    _compare_outputs(lagrange.rod_inertia(*args), ref.rod_inertia(*args), "lagrange.rod_inertia")


def test_lagrange_rod_inertia_mass_matrix(elems):
    """M = int rhoA (N_u N_u^T + N_v N_v^T) + rhoI N_psi N_psi^T dx (B1), symmetric positive."""
    args = pick(elems, *ref.ROD_INERTIA_ARGS)
    M = lagrange.rod_inertia(*args)[3]
    n_u, n_v, n_psi = ref.element_shapes(elems["l"])[:3]
    rA = elems["rhoA"][:, None, None, None]
    rI = elems["rhoI"][:, None, None, None]
    m1 = ref.integrate(rA * (ref.outer(n_u, n_u) + ref.outer(n_v, n_v)) + rI * ref.outer(n_psi, n_psi),
                       elems["l"], 2)
    assert_close(M, m1, RTOL, 2, "lagrange.rod_inertia.M")
    # positive on the six nodal unknowns of a linear-u element; nothing on the chi slots it lacks
    live = [k for k in range(ref.NDOF) if k not in ref.CHIS]
    assert np.all(np.linalg.eigvalsh(M[:, live][:, :, live]) > 0)
    assert not M[:, ref.CHIS].any() and not M[:, :, ref.CHIS].any()


@pytest.mark.parametrize("term", ["rhoA", "rhoI", "crank", "phid", "phidd"])
def test_lagrange_rod_inertia_single_effects(term, elems):
    """Switch on one physical effect at a time, so that a small wrong term cannot hide."""
    e = dict(elems)
    zero = np.zeros(7)
    if term == "rhoA":
        e.update(rhoI=zero)
    elif term == "rhoI":
        e.update(rhoA=zero)
    elif term == "crank":
        e.update(phid=zero, phidd=zero, qd=0 * e["qd"], qdd=0 * e["qdd"], rhoI=zero)
    elif term == "phid":
        e.update(a=zero, phidd=zero, qdd=0 * e["qdd"])
    elif term == "phidd":
        e.update(a=zero, phid=zero, qd=0 * e["qd"], qdd=0 * e["qdd"])
    args = pick(e, *ref.ROD_INERTIA_ARGS)
    got, expected = lagrange.rod_inertia(*args), ref.rod_inertia(*args)
    assert np.all(np.linalg.norm(expected[0], axis=-1) > 0)
    _compare_outputs(got, expected, f"lagrange.rod_inertia[{term} only]")


def test_lagrange_slider_inertia(elems):
    args = pick(elems, *ref.SLIDER_INERTIA_ARGS)
    _compare_outputs(lagrange.slider_inertia(*args), ref.slider_inertia(*args),
                     "lagrange.slider_inertia")


@pytest.mark.parametrize("approach", APPROACHES)
def test_lagrange_rod_elastic(approach, elems):
    q, l, EA, EI = pick(elems, "q", "l", "EA", "EI")
    got = getattr(lagrange, f"rod_elastic_{approach}")(q, l, EA, EI)
    _compare_outputs(got, ref.rod_elastic(approach, q, l, EA, EI), f"lagrange.rod_elastic_{approach}")
    assert_close(got[1], np.swapaxes(got[1], -1, -2), 1e-13, 2, "K symmetric")


# --------------------------------------------------------------------------------------------
# printed (paper) form
# --------------------------------------------------------------------------------------------

def test_paper_rod_inertia(elems):
    args = pick(elems, *ref.ROD_INERTIA_ARGS)
    _compare_outputs(paper.rod_inertia(*args), ref.paper_rod_inertia(*args), "paper.rod_inertia")


@pytest.mark.parametrize("which", ["rhoA", "rhoI"])
def test_paper_rod_inertia_parts(which, elems):
    """The rho A and rho I (errata B3: -rhoI phid N_psi) parts separately."""
    e = dict(elems, **{("rhoI" if which == "rhoA" else "rhoA"): np.zeros(7)})
    args = pick(e, *ref.ROD_INERTIA_ARGS)
    _compare_outputs(paper.rod_inertia(*args), ref.paper_rod_inertia(*args),
                     f"paper.rod_inertia[{which}]")


def test_paper_rod_inertia_misses_only_gyroscopic_and_phidd_coupling(elems):
    """Lagrange minus printed form = rhoA int (N_u N_v^T - N_v N_u^T) dx (2 phid qd + phidd q).

    Worked out by hand: with errata applied, the printed forcing m4 - d/dt m3 equals the exact
    kinematic forcing; what the printed eq. (20) lacks are the Coriolis and phidd couplings
    between axial and transverse motion.
    """
    args = pick(elems, *ref.ROD_INERTIA_ARGS)
    exact, printed = lagrange.rod_inertia(*args)[0], paper.rod_inertia(*args)[0]
    n_u, n_v = ref.element_shapes(elems["l"])[:2]
    skew = ref.integrate(ref.outer(n_u, n_v) - ref.outer(n_v, n_u), elems["l"], 2)
    rA = elems["rhoA"][:, None, None]
    missing = rA * (2 * elems["phid"][:, None, None] * skew)
    missing = ref.matvec(missing, elems["qd"]) + ref.matvec(
        rA * elems["phidd"][:, None, None] * skew, elems["q"])
    assert_close(exact - printed, missing, 1e-8, 1, "lagrange - paper rod inertia")


def test_paper_slider_inertia(elems):
    args = pick(elems, *ref.SLIDER_INERTIA_ARGS)
    _compare_outputs(paper.slider_inertia(*args), ref.paper_slider_inertia(*args),
                     "paper.slider_inertia")


@pytest.mark.parametrize("approach", APPROACHES)
def test_paper_rod_elastic(approach, elems):
    q, l, EA, EI = pick(elems, "q", "l", "EA", "EI")
    r, K, K_sec = getattr(paper, f"rod_elastic_{approach}")(q, l, EA, EI)
    e_r, e_K, e_sec = ref.paper_rod_elastic(approach, q, l, EA, EI)
    assert_close(r, e_r, RTOL, 1, f"paper.rod_elastic_{approach}.r")
    assert_close(K_sec, e_sec, RTOL, 2, f"paper.rod_elastic_{approach}.K_sec")
    assert_close(K, e_K, RTOL, 2, f"paper.rod_elastic_{approach}.K")
    assert_close(ref.matvec(K_sec, q), r, 1e-12, 1, "r = K_sec q")


def test_paper_elastic_C_equals_lagrange_elastic_C(elems):
    """Linear strain: the printed k_uu + k_psipsi is the exact stiffness, so C forms coincide."""
    q, l, EA, EI = pick(elems, "q", "l", "EA", "EI")
    r_p, K_p, _ = paper.rod_elastic_C(q, l, EA, EI)
    r_l, K_l = lagrange.rod_elastic_C(q, l, EA, EI)
    assert_close(r_p, r_l, RTOL, 1, "paper vs lagrange C: r")
    assert_close(K_p, K_l, RTOL, 2, "paper vs lagrange C: K")


# --------------------------------------------------------------------------------------------
# damping
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("approach", APPROACHES)
def test_kelvin_voigt(approach, elems):
    q, qd, l, EA, EI, mu = pick(elems, "q", "qd", "l", "EA", "EI", "mu")
    got = getattr(damping, f"kelvin_voigt_{approach}")(q, qd, l, EA, EI, mu)
    expected = ref.kelvin_voigt(approach, q, qd, l, EA, EI, mu)
    if approach == "C":
        assert np.all(got[1] == 0), "linear strain rate: K must vanish"
        got, expected, names = (got[0], got[2]), (expected[0], expected[2]), ("r", "C")
    else:
        names = ("r", "K", "C")
    _compare_outputs(got, expected, f"damping.kelvin_voigt_{approach}", names)


@pytest.mark.parametrize("approach", APPROACHES)
def test_paper_damping(approach, elems):
    q, qd, l, EA, EI, rhoA, rhoI, phid, mu = pick(
        elems, "q", "qd", "l", "EA", "EI", "rhoA", "rhoI", "phid", "mu")
    r, K, C = getattr(damping, f"paper_{approach}")(q, qd, l, EA, EI, rhoA, rhoI, phid, mu)
    e_r, e_K, e_C = ref.paper_damping(approach, q, qd, l, EA, EI, rhoA, rhoI, phid, mu)
    assert_close(r, e_r, RTOL, 1, f"damping.paper_{approach}.r")
    assert_close(C, e_C, RTOL, 2, f"damping.paper_{approach}.C")
    if approach == "C":
        assert np.all(K == 0)
    else:
        assert_close(K, e_K, RTOL, 2, f"damping.paper_{approach}.K")


def test_paper_damping_contains_minus_m2(elems):
    """Eq. (22) K_lin includes -m2: with EA = EI = 0 the damping force is -mu m2 qd."""
    q, qd, l, rhoA, rhoI, phid, mu = pick(elems, "q", "qd", "l", "rhoA", "rhoI", "phid", "mu")
    zero = np.zeros(7)
    n_u, n_v, n_psi = ref.element_shapes(l)[:3]
    m2 = ref.integrate((phid**2)[:, None, None, None]
                       * (rhoA[:, None, None, None] * (ref.outer(n_u, n_u) + ref.outer(n_v, n_v))
                          + rhoI[:, None, None, None] * ref.outer(n_psi, n_psi)), l, 2)
    for approach in APPROACHES:
        r = getattr(damping, f"paper_{approach}")(q, qd, l, zero, zero, rhoA, rhoI, phid, mu)[0]
        assert_close(r, -mu[:, None] * ref.matvec(m2, qd), RTOL, 1, f"paper_{approach} mass part")


def test_paper_slider_damping(elems):
    qsd, ms, phid, mu = pick(elems, "qsd", "ms", "phid", "mu")
    got = damping.paper_slider(qsd, ms, phid, mu)
    expected = ref.paper_slider_damping(qsd, ms, phid, mu)
    assert_close(got[0], expected[0], RTOL, 1, "paper_slider.r")
    assert np.all(got[1] == 0)
    assert_close(got[2], expected[2], RTOL, 2, "paper_slider.C")


# --------------------------------------------------------------------------------------------
# broadcasting: a leading batch axis behaves like a loop
# --------------------------------------------------------------------------------------------

VARIANTS = ("_into", "_element", "_lanes")   # one-element and lane variants
GENERATED = (gen_shape, gen_kinematics, gen_elements, gen_energy, gen_fields, gen_groups)
ALL_KERNELS = [(mod.__name__.rsplit(".", 1)[-1], name, getattr(mod, name))
               for mod in GENERATED for name in mod.__all__ if not name.endswith(VARIANTS)]

VECTOR_SIZE = {"q": ref.NDOF, "qd": ref.NDOF, "qdd": ref.NDOF}
ELEMENT_RANGES = {"l": (0.05, 0.5), "x0": (0.0, 0.9)}          # geo = (l, x0)
COEF_RANGES = {"rhoA": (0.5, 2.0), "rhoI": (0.01, 0.1), "EA": (10.0, 1000.0), "EI": (0.005, 0.05),
               "mu": (0.01, 0.5), "ms": (0.1, 1.0), "gX": (-1.0, 1.0), "gY": (-1.0, 1.0)}
KIN_RANGES = {"a": (0.05, 0.3), "theta": (0.0, 6.3), "thetad": (0.2, 3.0), "phi": (-0.3, 0.3),
              "phid": (-1.0, 1.0), "phidd": (-2.0, 2.0), "thetadd": (-1.0, 1.0), "beta": (0.5, 2.5),
              "betad": (-1.0, 1.0), "betadd": (-2.0, 2.0)}
# the kinematic parameters, in ranges where every guide closes and every motion is defined
PARAM_RANGES = {"a": (0.05, 0.3), "offset": (-0.1, 0.1), "c": (0.7, 0.9), "d": (0.9, 1.1),
                "branch": (1.0, 1.0), "cam_height": (0.0, 0.04), "cam_wavelength": (0.2, 0.4), "inclination": (-1.0, 1.0), "omega": (0.2, 3.0), "omega0": (0.2, 3.0), "ramp": (1.0, 5.0),
                "fluctuation": (-0.5, 0.5), "order": (2.0, 2.0), "theta0": (-3.0, 3.0),
                "stall_torque": (0.01, 1.0), "no_load_speed": (0.2, 3.0), "inertia": (0.01, 1.0),
                "load_torque": (-0.1, 0.1), "initial_speed": (0.0, 3.0),
                "rotor_inertia": (0.01, 1.0), "shaft_stiffness": (1.0, 100.0), "shaft_damping": (0.0, 0.1),
                "gravity[0]": (-0.1, 0.1), "gravity[1]": (-0.1, 0.1), "crank_mass": (0.0, 2.0),
                "crank_centre": (-0.5, 1.0), "crank_inertia": (0.0, 0.1)}
OTHER_VECTORS = {"crank": [(0.0, 6.3), (0.2, 3.0), (-1.0, 1.0)], "send": [(-1e-3, 1e-3), (-0.1, 0.1), (-1.0, 1.0)],
                 "q_end": [(-1e-3, 1e-3)] * 2, "qd_end": [(-1e-2, 1e-2)] * 2, "pin": [(-5.0, 5.0)] * 2,
                 "qdd_end": [(-1e-1, 1e-1)] * 2, "end": [(-5.0, 5.0)] * 2, "rod_end": [(-5.0, 5.0)] * 2,
                 "ground": [(-5.0, 5.0)] * 2,
                 "parameters": None, "z": None, "z0": None}
# a driven motion's co-ordinates (values, rates, accelerations): as many as its docstring says
SCALAR_RANGE = {"zeta": (0.0, 1.0), "l": (0.05, 0.5), "t": (0.0, 10.0), "eps": (0.005, 0.1),
                "s": (-1e-3, 1e-3), "fiber": (-2.0, 2.0)}


def _coef(rng, shape):
    cols = [rng.uniform(*COEF_RANGES[n], shape) if n in COEF_RANGES else rng.uniform(0.5, 1.5, shape)
            for n in ingredients.COEFFICIENTS]               # term weights: any value acts linearly
    return np.stack(cols, axis=-1)


def _kin(rng, shape):
    return np.stack([rng.uniform(*KIN_RANGES[n], shape) for n in schema.KINEMATICS], axis=-1)


def _params(rng, shape, size):
    """The kinematic parameter vector, or (size one less) the same without a (beside kin)."""
    names = [n for n in schema.KINEMATIC_PARAMETERS if size == len(schema.KINEMATIC_PARAMETERS) or n != "a"]
    return np.stack([rng.uniform(*PARAM_RANGES[n], shape) for n in names], axis=-1)


def _vector(rng, name, kernel, shape):
    if name == "params":
        return _params(rng, shape, _input_size(kernel, name))
    if OTHER_VECTORS[name] is None:
        return rng.uniform(-1.0, 1.0, shape + (_input_size(kernel, name),))
    ranges = OTHER_VECTORS[name]
    if name == "send" and _input_size(kernel, name) == 2 * len(ranges):    # two reduced co-ordinates (a rocker tip's)
        ranges = [r for r in ranges for _ in range(2)]
    return np.stack([rng.uniform(lo, hi, shape) for lo, hi in ranges], axis=-1)


def _input_size(kernel, name):
    """Length of a vector input, read from the kernel's docstring ("params (..., 10)")."""
    import re
    return int(re.search(rf"\b{name} \(\.\.\., (\d+)\)", kernel.__doc__).group(1))


def _geo(rng, shape):
    return np.stack([rng.uniform(*ELEMENT_RANGES[n], shape) for n in ELEMENT_RANGES], axis=-1)


def test_every_kernel_is_covered():
    """The generic tests below reach every generated kernel, in particular every element kernel the
    dispatch table declares."""
    names = {f"{m}.{n}" for m, n, _ in ALL_KERNELS}
    expected = {"shape.shape_functions", "shape.slope_gram", "energy.rod_kinetic_energy",
                "energy.slider_kinetic_energy", "energy.rod_gravity_potential",
                "energy.slider_gravity_potential",
                "energy.rocker_spring_potential",                 # tests/test_rocker_spring.py
                "energy.rocker_kinetic_energy", "energy.rocker_gravity_potential"}   # tests/test_rocker_mass.py
    for g, record in schema.GUIDES.items():
        check = "margins" if record.closure == "closed-form" else "closure"      # a numerical closure is sampled
        expected |= {f"kinematics.{k}_{g}" for k in ("guide", "end_map", "rigid_end", check, "end_scale")}
        if record.pivot:                                     # a flexible rocker's tip (tests/test_flexible_rocker.py)
            expected.add(f"kinematics.end_map_{g}_flexible")
    for m in schema.MOTIONS:
        expected |= {f"kinematics.{k}_{m}" for k in ("motion", "period", "step_period")}
        if schema.MOTIONS[m].driven:                         # a driven crank's co-ordinates: equations, start
            expected |= {f"kinematics.coordinates_{m}", f"kinematics.start_{m}"}
    expected |= {f"elements.{k}" for k in dispatch.ELEMENT_KERNELS}
    for ap in APPROACHES:
        expected |= {f"energy.strain_energy_{ap}", f"energy.dissipation_{ap}"}
    for ap in ("A", "B"):                # the exact rod has no averaged membrane (its strain is pointwise)
        expected |= {f"energy.strain_energy_{ap}_averaged", f"energy.dissipation_{ap}_averaged"}
    expected |= {"energy.strain_energy_exact", "energy.dissipation_exact", "energy.rod_kinetic_energy_exact",
                 "energy.rod_gravity_potential_exact"}
    assert expected <= names
    assert {n.split(".")[0] for n in names - expected} <= {"fields", "groups"}


@pytest.mark.parametrize("element_data", ["shared", "batched"])
@pytest.mark.parametrize("module,name,kernel", ALL_KERNELS, ids=[f"{m}.{n}" for m, n, _ in ALL_KERNELS])
def test_batch_axis_matches_loop(module, name, kernel, element_data):
    """Vectors (B, n, k), coefficients and kinematics (B, 1, k), geo (n, 2) or (B, n, 2), scalars
    (B, 1)."""
    rng = np.random.default_rng(zlib.crc32(f"{module}.{name}.{element_data}".encode()))
    B, n = 3, 4
    batched, per_b = [], []
    has_batch = False
    for arg in inspect.signature(kernel).parameters:
        if arg in VECTOR_SIZE:
            # any slopes (the exact rod's section rotation atan2(v_x, 1 + u_x) has no limit)
            v = ref.random_nodal(rng, (B, n))
            batched.append(v)
            per_b.append(lambda b, v=v: v[b])
            has_batch = True
        elif arg == "geo":
            if element_data == "shared":
                v = _geo(rng, (n,))
                per_b.append(lambda b, v=v: v)
            else:
                v = _geo(rng, (B, n))
                per_b.append(lambda b, v=v: v[b])
                has_batch = True
            batched.append(v)
        elif arg in ("coef", "kin"):
            v = (_coef if arg == "coef" else _kin)(rng, (B, 1))
            batched.append(v)
            per_b.append(lambda b, v=v: v[b, 0])
            has_batch = True
        elif arg in ("params",) + tuple(OTHER_VECTORS):
            v = _vector(rng, arg, kernel, (B, 1))
            batched.append(v)
            per_b.append(lambda b, v=v: v[b, 0])
            has_batch = True
        elif arg == "l" and module == "shape":
            lo, hi = SCALAR_RANGE[arg]
            if element_data == "shared":
                v = rng.uniform(lo, hi, n)
                per_b.append(lambda b, v=v: v)
            else:
                v = rng.uniform(lo, hi, (B, n))
                per_b.append(lambda b, v=v: v[b])
                has_batch = True
            batched.append(v)
        else:
            lo, hi = SCALAR_RANGE[arg]
            v = rng.uniform(lo, hi, (B, 1))
            batched.append(v)
            per_b.append(lambda b, v=v: float(v[b, 0]))
            has_batch = True
    out = kernel(*batched)
    out = out if isinstance(out, tuple) else (out,)
    for b in range(B):
        single = kernel(*[f(b) for f in per_b])
        single = single if isinstance(single, tuple) else (single,)
        assert len(single) == len(out)
        for k, (o, s) in enumerate(zip(out, single)):
            if has_batch:
                ob = o[b]
                if ob.shape != s.shape and ob.size == s.size:     # scalar inputs (B, 1)
                    ob = ob.reshape(s.shape)
            else:                       # slope_gram with shared l: nothing carries the batch
                ob = o
            assert ob.shape == s.shape, f"{module}.{name} output {k}: shape {o.shape}"
            assert np.all(np.isfinite(s)), f"{module}.{name} output {k}: not finite (NaN compares equal)"
            np.testing.assert_allclose(ob, s, rtol=1e-12, atol=1e-14 * np.max(np.abs(s)) + 1e-300,
                                       err_msg=f"{module}.{name} output {k}, batch {b}")


# --------------------------------------------------------------------------------------------
# the one-element variants (compiled with numba at run time) equal the vectorized ones
# --------------------------------------------------------------------------------------------

def _random_arguments(kernel, seed_text):
    """One element's arguments of kernel, drawn in the physical ranges."""
    rng = np.random.default_rng(zlib.crc32(seed_text.encode()))
    args = []
    for arg in inspect.signature(kernel).parameters:
        if arg in VECTOR_SIZE:
            args.append(ref.random_nodal(rng, (1,))[0])
        elif arg == "geo":
            args.append(_geo(rng, ()))
        elif arg == "coef":
            args.append(_coef(rng, ()))
        elif arg == "kin":
            args.append(_kin(rng, ()))
        elif arg in ("params",) + tuple(OTHER_VECTORS):
            args.append(_vector(rng, arg, kernel, ()))
        else:
            args.append(float(rng.uniform(*SCALAR_RANGE[arg])))
    return args


INTO_KERNELS = [(m, n, k) for m, n, k in ALL_KERNELS if hasattr(sys.modules[k.__module__], n + "_into")]


def test_the_engine_kernels_have_one_element_variants():
    assert {m for m, _, _ in INTO_KERNELS} == {"kinematics"}     # the engine compiles the kinematics ones


@pytest.mark.parametrize("module,name,kernel", INTO_KERNELS, ids=[f"{m}.{n}" for m, n, _ in INTO_KERNELS])
def test_into_variant_matches_vectorized(module, name, kernel):
    """`<name>_into(inputs..., outputs...)` fills every entry of preallocated outputs with the same
    numbers as the vectorized kernel (pure Python here; the runtime compiles it with numba)."""
    into = getattr(sys.modules[kernel.__module__], name + "_into")
    args = _random_arguments(kernel, f"into.{module}.{name}")
    expected = kernel(*args)
    expected = expected if isinstance(expected, tuple) else (expected,)
    outs = [np.full(np.shape(e) if np.ndim(e) else (1,), np.nan) for e in expected]
    into(*args, *outs)
    for e, o in zip(expected, outs):
        np.testing.assert_allclose(o.reshape(np.shape(e)), e, rtol=1e-12,
                                   atol=1e-14 * np.max(np.abs(e)) + 1e-300)


# --------------------------------------------------------------------------------------------
# the accumulating variants of the element kernels: r += r_e, tangents +=, S += M + cv C + cd K
# --------------------------------------------------------------------------------------------

RESIDUAL_KERNELS = [(m, n, k) for m, n, k in ALL_KERNELS
                    if hasattr(sys.modules[k.__module__], n + "_element")]
MODE = {name: k for k, name in enumerate(dispatch.ELEMENT_MODES)}


def test_element_kernels_have_one_element_functions():
    names = {n for m, n, _ in RESIDUAL_KERNELS}
    assert names == set(dispatch.ELEMENT_KERNELS)


@pytest.mark.parametrize("module,name,kernel", RESIDUAL_KERNELS,
                         ids=[f"{m}.{n}" for m, n, _ in RESIDUAL_KERNELS])
def test_one_element_function_modes_match_vectorized(module, name, kernel):
    """`<name>_element(mode, ..., cv, cd, r, K, C, M, S)` adds, onto whatever the outputs already
    hold: "full" r, K, C, M; "printed" the same with K_printed for K (the exact K for a kernel
    without one); "residual" r only; "newmark" r and M + cv C + cd K (the exact tangents); and
    leaves the other outputs alone."""
    element = getattr(sys.modules[kernel.__module__], name + "_element")
    args = _random_arguments(kernel, f"add.{module}.{name}")
    out = kernel(*args)
    outputs = dict(zip(("r", "K", "C", "M", "K_printed"), out))
    r = outputs["r"]
    cv, cd = 0.037, 2.9e-4
    S = outputs["M"] + cv * outputs["C"] + cd * outputs["K"]
    rng = np.random.default_rng(zlib.crc32(name.encode()))
    wants = {"full": (r, outputs["K"], outputs["C"], outputs["M"], None),
             "printed": (r, outputs.get("K_printed", outputs["K"]), outputs["C"], outputs["M"], None),
             "residual": (r, None, None, None, None),
             "newmark": (r, None, None, None, S)}
    for mode, want in wants.items():
        start = [rng.standard_normal(x.shape) for x in (r, S, S, S, S)]
        got = [x.copy() for x in start]
        element(MODE[mode], *args, cv, cd, *got)
        for g, x0, w in zip(got, start, want):
            if w is None:
                assert np.array_equal(g, x0), mode                 # untouched
            else:
                np.testing.assert_allclose(g - x0, w, rtol=1e-11, atol=1e-13 * (1 + np.max(np.abs(w))),
                                           err_msg=mode)


@pytest.mark.parametrize("module,name,kernel", RESIDUAL_KERNELS,
                         ids=[f"{m}.{n}" for m, n, _ in RESIDUAL_KERNELS])
def test_lane_function_is_the_one_element_function_on_each_lane(module, name, kernel):
    """`<name>_lanes(mode, b, coef, kin, cv, cd)` adds, for each of the LANES elements of the lane
    buffer b (its own q, qd, qdd, geo; coef and kin shared), what the vectorized kernel gives for
    that element in each mode, into that element's lane of the rows LANE_ROWS names, and leaves every
    other value of b alone."""
    lanes = getattr(sys.modules[kernel.__module__], name + "_lanes")
    L, rows = dispatch.LANES, dispatch.LANE_ROWS
    per_lane = [_random_arguments(kernel, f"lanes.{module}.{name}.{j}") for j in range(L)]
    coef, kin = per_lane[0][4], per_lane[0][5]
    outputs = [dict(zip(("r", "K", "C", "M", "K_printed"), kernel(*a[:4], coef, kin))) for a in per_lane]
    cv, cd = 0.037, 2.9e-4
    rng = np.random.default_rng(zlib.crc32(("lanes" + name).encode()))
    for mode in dispatch.ELEMENT_MODES:
        b = rng.standard_normal(dispatch.LANE_SIZE)
        for j, a in enumerate(per_lane):
            for block, value in zip(("q", "qd", "qdd", "geo"), a[:4]):
                for k, x in enumerate(value):
                    b[(rows[block] + k) * L + j] = x
        start = b.copy()
        lanes(MODE[mode], b, coef, kin, cv, cd)
        touched = np.zeros(b.size, dtype=bool)
        for j, out in enumerate(outputs):
            K = out.get("K_printed", out["K"]) if mode == "printed" else out["K"]
            want = {"r": out["r"]}
            if mode in ("full", "printed"):
                want.update(K=K, C=out["C"], M=out["M"])
            elif mode == "newmark":
                want["S"] = out["M"] + cv * out["C"] + cd * out["K"]
            for block, w in want.items():
                at = (rows[block] + np.arange(w.size)) * L + j
                touched[at] = True
                np.testing.assert_allclose(b[at] - start[at], w.ravel(), rtol=1e-11,
                                           atol=1e-13 * (1 + np.max(np.abs(w))), err_msg=f"{mode} {block} lane {j}")
        assert np.array_equal(b[~touched], start[~touched]), mode
