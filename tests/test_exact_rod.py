"""The geometrically exact rod's element kernels (approach "exact"), against independent truths.

* its energies against tests/exact_reference.py (the cubic u and v typed in by hand, stretch by
  numpy.hypot, rotation by arctan2, curvature and rates by finite differences, the declared Gauss
  rule);
* its forces and tangents against finite differences of those energies and of its own residual,
  its inertia against the Euler-Lagrange operator of its kinetic energy along a trajectory;
* the rigid-body patch test: a translated and turned element has no strain, no elastic force and
  no dissipation, which approaches A and B fail at a finite rotation (measured here);
* the small-rotation limit: on a linear u (chi the element's mean slope) the exact strain energy
  and approach A's differ at fourth order in the amplitude (second order beyond the leading one).
"""

import numpy as np
import pytest

import exact_reference as xr
import reference as ref
from crankgen.declaration import schema
from crankgen._generated import elements as E
from crankgen._generated import energy as En
from crankgen.declaration.cases import Case
from crankgen.errors import ParameterError
from kernel_api import coef, vec
from reference import assert_close
from test_kernel_derivatives import Trajectory, _euler_lagrange


def _kin(a=0.0, theta=0.0, thetad=0.0, phi=0.0, phid=0.0, phidd=0.0):
    values = dict(a=a, theta=theta, thetad=thetad, phi=phi, phid=phid, phidd=phidd)
    return vec(*(values.get(name, 0.0) for name in schema.KINEMATICS))


def large_states(rng, n=6):
    """Elements cut from a rod bent to rotations of up to about 60 degrees, stretched by a few per
    cent (nodal values and slopes consistent with a smooth shape, perturbed), with random rates."""
    l, x0 = rng.uniform(0.1, 0.3, n), rng.uniform(0.0, 0.7, n)
    ends = np.stack([x0, x0 + l], -1)
    A, B, C = rng.uniform(0.1, 0.3), rng.uniform(-0.08, 0.08), rng.uniform(-0.05, 0.05)
    v = A * np.sin(np.pi * ends) + B * np.sin(2 * np.pi * ends)
    v_x = A * np.pi * np.cos(np.pi * ends) + 2 * np.pi * B * np.cos(2 * np.pi * ends)
    u, u_x = C * ends, C * np.ones_like(ends)
    q = xr.nodal(u, v, v_x, u_x)
    q = q + rng.uniform(-1, 1, (n, 8)) * [0.002, 0.002, 0.02, 0.002, 0.002, 0.002, 0.02, 0.002]
    qd = rng.uniform(-1, 1, (n, 8)) * [0.1, 0.5, 1.0, 0.1, 0.1, 0.5, 1.0, 0.1]
    qdd = rng.uniform(-1, 1, (n, 8))
    assert np.all(np.isfinite(xr.rotation(q, l, np.linspace(0, 1, 11))))
    return q, qd, qdd, l, x0


@pytest.fixture(params=(0, 1), ids=lambda s: f"seed{s}")
def states(request):
    return large_states(np.random.default_rng(3000 + request.param))


def test_declared_rule_and_variants():
    """The exact kernels use the quadrature rule the schema declares, and the exact approach
    selects them (the preset: lagrange, Kelvin-Voigt, the pointwise strain); the membrane option
    does not change the exact rod (its strain is pointwise at the rule's points: no averaged
    variant)."""
    assert set(xr.QUADRATURE) == {"inertia_lagrange_exact", "elastic_lagrange_exact",
                                  "dissipation_kelvin_voigt_exact"}
    case = Case(model="exact")
    assert case.model == "exact"
    assert case.selection.kernels[:3] == ("inertia_lagrange_exact", "elastic_lagrange_exact",
                                          "dissipation_kelvin_voigt_exact")
    for membrane in ("pointwise", "averaged"):
        assert Case(approach="exact", membrane=membrane).selection.kernels == case.selection.kernels
    assert not hasattr(E, "elastic_lagrange_exact_averaged") and not hasattr(En, "strain_energy_exact_averaged")
    assert Case(approach="A").selection.kernels[0] == "inertia_lagrange"


@pytest.mark.parametrize("options", [dict(model="exact", formulation="paper"), dict(model="paper", approach="exact"),
                                     dict(approach="exact", damping="paper")])
def test_meaningless_combinations_are_refused_in_one_line(options):
    with pytest.raises(ParameterError, match="approach 'exact' has no printed") as info:
        Case(**options)
    assert "\n" not in str(info.value)


# ---- energies ------------------------------------------------------------------------------------

def test_strain_energy_and_dissipation_match_the_reference(states):
    q, qd, _, l, x0 = states
    EA, EI, mu = 40.0, 0.3, 0.2
    c, geo = coef(EA=EA, EI=EI, mu=mu), vec(l, x0)
    U = En.strain_energy_exact(q, qd, geo, c, _kin())
    D = En.dissipation_exact(q, qd, geo, c, _kin())
    assert_close(U, xr.strain_energy(q, l, EA, EI), 1e-8, 0, "strain energy")
    assert_close(D, xr.dissipation(q, qd, l, EA, EI, mu), 1e-8, 0, "dissipation")


@pytest.mark.parametrize("alpha", [2.4, 3.0, -2.8])
def test_energies_match_the_reference_past_90_degrees(alpha):
    """The same, with the states turned rigidly by alpha about the first node in the moving frame
    (sections up to 170 degrees from e_i, 1 + u_x < 0): the strain and curvature of a rod do not
    depend on how it is turned, so the energies are those of the unturned states, and the
    reference's own."""
    q, qd, _, l, x0 = large_states(np.random.default_rng(3002))
    c_, s_ = np.cos(alpha), np.sin(alpha)

    def turned(q, displacement):
        """Turn the centre line x + u, v (displacement: add the turned material chord) and its
        slopes (1 + chi, psi) by alpha."""
        out = q.copy()
        for node, (u, v, psi, chi) in enumerate(((ref.U0, ref.V0, ref.PSI0, ref.CHI0),
                                                 (ref.U1, ref.V1, ref.PSI1, ref.CHI1))):
            x = node * l if displacement else 0.0
            X, Y = x + q[:, u], q[:, v]
            out[:, u] = c_ * X - s_ * Y - x
            out[:, v] = s_ * X + c_ * Y
            T, S = (1.0 if displacement else 0.0) + q[:, chi], q[:, psi]
            out[:, chi] = c_ * T - s_ * S - (1.0 if displacement else 0.0)
            out[:, psi] = s_ * T + c_ * S
        return out

    q_t, qd_t = turned(q, True), turned(qd, False)
    assert np.any(np.abs(xr.rotation(q_t, l, np.array([0.5]))) > np.radians(120))
    EA, EI, mu = 40.0, 0.3, 0.2
    c, geo = coef(EA=EA, EI=EI, mu=mu), vec(l, x0)
    U, U_t = (En.strain_energy_exact(y, yd, geo, c, _kin()) for y, yd in ((q, qd), (q_t, qd_t)))
    D, D_t = (En.dissipation_exact(y, yd, geo, c, _kin()) for y, yd in ((q, qd), (q_t, qd_t)))
    assert_close(U_t, U, 1e-10, 0, "strain energy of the turned states")
    assert_close(D_t, D, 1e-10, 0, "dissipation of the turned states")
    assert_close(U_t, xr.strain_energy(q_t, l, EA, EI), 1e-8, 0, "strain energy past 90 degrees")
    assert_close(D_t, xr.dissipation(q_t, qd_t, l, EA, EI, mu), 1e-8, 0, "dissipation past 90 degrees")


def test_the_declared_rule_is_accurate_on_a_smooth_large_rotation_shape():
    """The rod bent into v = A sin(pi x) with end rotations of 0.94 rad, u and chi = u_x from
    near-inextensibility, on 8 elements: the declared rule's strain energy is within 1e-4 of a
    12-point rule's."""
    n, A = 8, 0.3
    x = np.linspace(0, 1, n + 1)
    fine = np.linspace(0, 1, 4001)
    slope = A * np.pi * np.cos(np.pi * fine)
    u_fine = np.concatenate([[0], np.cumsum(np.diff(fine) * (np.sqrt(1 - slope**2)[1:] - 1))])
    u, v, psi = np.interp(x, fine, u_fine), A * np.sin(np.pi * x), A * np.pi * np.cos(np.pi * x)
    chi = np.sqrt(1 - psi**2) - 1                                     # u_x of the inextensible bend
    pairs = lambda f: np.stack([f[:-1], f[1:]], -1)
    q = xr.nodal(pairs(u), pairs(v), pairs(psi), pairs(chi))
    l = np.full(n, 1.0 / n)
    U = np.sum(xr.strain_energy(q, l, 1e4, 1.0))
    U_fine = np.sum(xr.strain_energy(q, l, 1e4, 1.0, n=12))
    assert abs(U / U_fine - 1) < 1e-4, (U, U_fine)          # measured 9.4e-5 (deterministic)
    # of which the bending energy, 99.97 % of it, within 3.3e-6 (measured); the rest is the membrane
    # energy of an inextensible bend, the cubic u's interpolation residual (2.6e-4 of the total),
    # which three points see only roughly
    bending, bending_fine = (np.sum(xr.strain_energy(q, l, 0.0, 1.0, n=k)) for k in (xr.N_POINTS, 12))
    assert abs(bending / bending_fine - 1) < 1e-5, (bending, bending_fine)


def test_kinetic_energy_is_the_centre_line_plus_the_exact_section_rotation(states):
    """T_exact = rho A/2 int |R'|^2 dx of the centre line (the cubic u, reference.py) + rho I/2 int
    (theta' - phid)^2 dx: the unit director instead of (-psi, 1)."""
    q, qd, _, l, x0 = states
    rhoA, rhoI, kin = 1.3, 0.07, dict(a=0.2, theta=0.4, thetad=0.9, phi=-0.1, phid=0.3)
    c, geo = coef(rhoA=rhoA, rhoI=rhoI), vec(l, x0)
    T_exact = En.rod_kinetic_energy_exact(q, qd, geo, c, _kin(**kin))
    centre_line = ref.rod_kinetic_energy(q, qd, l, x0, rhoA, 0.0, *kin.values(), cubic_u=True)
    expected = centre_line + xr.rotary_kinetic_energy(q, qd, l, rhoI, kin["phid"])
    assert_close(T_exact, expected, 1e-8, 0, "exact kinetic energy")


# ---- forces and tangents -----------------------------------------------------------------------------

def _check(kernel_out, fd, rtol, what):
    scale = np.max(np.abs(fd))
    assert_close(kernel_out, fd, rtol, kernel_out.ndim - 1, what, atol=1e-9 * scale)


def test_elastic_force_and_tangent_are_derivatives(states):
    q, qd, qdd, l, x0 = states
    c, geo, k = coef(EA=40.0, EI=0.3), vec(l, x0), _kin()
    kernel, U = E.elastic_lagrange_exact, En.strain_energy_exact
    r, K, C, M = kernel(q, qd, qdd, geo, c, k)
    _check(r, ref.fd_jacobian(lambda y: U(y, qd, geo, c, k), q, 1e-4), 1e-7, "r = dU/dq")
    _check(K, ref.fd_jacobian(lambda y: kernel(y, qd, qdd, geo, c, k)[0], q, 1e-4), 1e-7, "K = dr/dq")
    assert not C.any() and not M.any()


def test_kelvin_voigt_force_and_tangents_are_derivatives(states):
    q, qd, qdd, l, x0 = states
    c, geo, k = coef(EA=40.0, EI=0.3, mu=0.2), vec(l, x0), _kin()
    kernel, D = E.dissipation_kelvin_voigt_exact, En.dissipation_exact
    r, K, C, M = kernel(q, qd, qdd, geo, c, k)
    _check(r, ref.fd_jacobian(lambda y: D(q, y, geo, c, k), qd, 1e-4), 1e-7, "r = dD/dqd")
    _check(K, ref.fd_jacobian(lambda y: kernel(y, qd, qdd, geo, c, k)[0], q, 1e-4), 1e-7, "K = dr/dq")
    _check(C, ref.fd_jacobian(lambda y: kernel(q, y, qdd, geo, c, k)[0], qd, 1e-4), 1e-7, "C = dr/dqd")
    assert not M.any()
    # a Rayleigh function quadratic in the rates: qd . dD/dqd = 2 D >= 0
    np.testing.assert_allclose(np.sum(qd * r, -1), 2 * D(q, qd, geo, c, k), rtol=1e-10)


def test_inertia_tangents_are_derivatives(states):
    q, qd, qdd, l, x0 = states
    c, geo = coef(rhoA=1.3, rhoI=0.07), vec(l, x0)
    k = _kin(a=0.2, theta=0.4, thetad=0.9, phi=-0.1, phid=0.3, phidd=-0.4)
    kernel = E.inertia_lagrange_exact
    r, K, C, M = kernel(q, qd, qdd, geo, c, k)
    _check(K, ref.fd_jacobian(lambda y: kernel(y, qd, qdd, geo, c, k)[0], q, 1e-4), 1e-7, "K")
    _check(C, ref.fd_jacobian(lambda y: kernel(q, y, qdd, geo, c, k)[0], qd, 1e-4), 1e-7, "C")
    _check(M, ref.fd_jacobian(lambda y: kernel(q, qd, y, geo, c, k)[0], qdd, 1e-4), 1e-7, "M")


class BentTrajectory(Trajectory):
    """Elements cut from a rod bending and stretching smoothly in time: v(x, t) = A(t) sin(pi x) +
    B(t) sin(2 pi x), u(x, t) = C(t) x (1 - x), with rotations up to about 50 degrees; nodal values
    (u, v, v_x, u_x) at each element's ends, and their exact rates."""

    def __init__(self, l, x0, a, omega):
        self.a, self.omega, self.L = a, omega, 1.0
        self.ends = np.stack([x0, x0 + l], -1)

    def q(self, t):
        def amplitudes(t, k):          # (A, B, C) and their k-th time derivatives
            w = np.array([1.3, 2.1, 0.7])
            phase = np.array([0.4, 1.1, 0.2])
            base = np.array([0.18, 0.06, 0.02])
            if k == 0:
                return np.array([0.1, 0.0, 0.0]) + base * np.sin(w * t + phase)
            return base * w**k * np.sin(w * t + phase + k * np.pi / 2)
        x = self.ends
        out = []
        for k in range(3):
            A, B, C = amplitudes(t, k)
            v = A * np.sin(np.pi * x) + B * np.sin(2 * np.pi * x)
            v_x = A * np.pi * np.cos(np.pi * x) + B * 2 * np.pi * np.cos(2 * np.pi * x)
            u, u_x = C * x * (1 - x), C * (1 - 2 * x)
            out.append(xr.nodal(u, v, v_x, u_x))
        return tuple(out)


@pytest.mark.parametrize("t", [0.3, 2.1])
def test_forces_are_the_euler_lagrange_terms_of_the_energies(t):
    """inertia_lagrange_exact = d/dt dT/dqd - dT/dq of the generated kinetic energy T_exact along a
    trajectory of a turning crank and a bending rod, and with the elastic force that of
    L = T_exact - U_exact; every derivative by finite differences."""
    rng = np.random.default_rng(47)
    n, rhoA, rhoI, EA, EI = 6, 1.2, 0.5, 30.0, 0.4
    l, x0 = rng.uniform(0.1, 0.3, n), rng.uniform(0.0, 0.7, n)
    traj = BentTrajectory(l, x0, a=0.25, omega=2.3)
    c, geo = coef(rhoA=rhoA, rhoI=rhoI, EA=EA, EI=EI), vec(l, x0)
    q, qd, qdd = traj.q(t)
    assert np.max(np.abs(q[:, ref.SLOPES])) > 0.4                # slopes of 25 degrees and more
    k = _kin(*traj.kinematics(t))

    def kinetic(q, qd, s):
        return En.rod_kinetic_energy_exact(q, qd, geo, c, _kin(*traj.kinematics(s)))

    el_T = _euler_lagrange(kinetic, traj, t)
    r_T = E.inertia_lagrange_exact(q, qd, qdd, geo, c, k)[0]
    assert_close(r_T, el_T, 1e-6, 1, f"exact inertia vs Euler-Lagrange of T, t={t}")
    # the exact rotary inertia is in it: leaving it out misses by 100 times the tolerance
    rotary = E.inertia_lagrange_exact(q, qd, qdd, geo, coef(rhoI=rhoI), k)[0]
    assert np.all(np.linalg.norm(rotary, axis=-1) > 1e-4 * np.linalg.norm(el_T, axis=-1))

    def lagrangian(q, qd, s):
        return kinetic(q, qd, s) - En.strain_energy_exact(q, qd, geo, c, _kin())

    el = _euler_lagrange(lagrangian, traj, t)
    r = r_T + E.elastic_lagrange_exact(q, qd, qdd, geo, c, k)[0]
    assert_close(r, el, 1e-6, 1, f"exact Euler-Lagrange residual, t={t}")


# ---- the rigid-body patch test ---------------------------------------------------------------------

@pytest.mark.parametrize("alpha", [0.3, 1.0, 2.5, 3.1, -2.0])
def test_a_rigid_motion_of_the_element_has_no_strain_and_no_elastic_force(alpha):
    """Whatever the angle (2.5, 3.1 and -2.0 rad turn the element past 90 degrees: 1 + u_x < 0)."""
    x0, l, EA, EI, mu = 0.2, 0.25, 1.0 / (np.pi**4 * 0.01**2), 1.0 / np.pi**4, 0.5
    q, qd = xr.rigid_element(x0, l, alpha, cu=0.03, cv=-0.02, rate_alpha=0.7, rate_u=0.2, rate_v=-0.1)
    q, qd = q[None], qd[None]
    c, geo, k, z = coef(EA=EA, EI=EI, mu=mu), vec(np.array([l]), np.array([x0])), _kin(), np.zeros((1, 8))
    scale = EA * l                                   # the elastic force of a unit strain
    U = En.strain_energy_exact(q, qd, geo, c, k)
    r = E.elastic_lagrange_exact(q, qd, z, geo, c, k)[0]
    D = En.dissipation_exact(q, qd, geo, c, k)
    r_d = E.dissipation_kelvin_voigt_exact(q, qd, z, geo, c, k)[0]
    assert abs(U[0]) < 1e-28 * scale and np.max(np.abs(r)) < 1e-13 * scale
    assert abs(D[0]) < 1e-28 * scale and np.max(np.abs(r_d)) < 1e-13 * scale
    # approaches A and B strain a turned element: u_x + v_x^2/2 = cos(alpha) - 1 + sin(alpha)^2/2
    # = -(1 - cos(alpha))^2 / 2, so their elastic force is that strain's EA l B_u (and more)
    e_A = -(1 - np.cos(alpha)) ** 2 / 2
    for approach in ("A", "B", "A_averaged"):
        r = getattr(E, f"elastic_lagrange_{approach}")(q, qd, z, geo, c, k)[0]
        assert np.max(np.abs(r)) > 0.5 * abs(e_A) * scale, approach
    r_A = E.elastic_lagrange_A(q, qd, z, geo, c, k)[0]
    # the axial rows carry EA e_A (times -1, +1): the pull a rigidly turned A element exerts
    np.testing.assert_allclose(r_A[0, ref.AXIAL], EA * e_A * np.array([-1.0, 1.0]), rtol=1e-12)


# ---- the small-rotation limit, element by element -------------------------------------------------

def linear_u(l):
    """T (n, 8, 8): the nodal vector of a linear-u element (chi slots ignored) as the exact rod's,
    chi = (u1 - u0) / l at both nodes (the cubic u then is that linear u)."""
    n = len(l)
    T = np.broadcast_to(np.eye(8), (n, 8, 8)).copy()
    for chi in ref.CHIS:
        T[:, chi, :] = 0
        T[:, chi, ref.U0], T[:, chi, ref.U1] = -1 / l, 1 / l
    return T


def test_exact_and_A_strain_energies_differ_at_fourth_order():
    """States q = a q1 (transverse, rotations ~a) + a^2 q2 (axial, strains ~a^2, u linear: the exact
    rod's chi the element's slope): both energies are of order a^2 and agree to the terms A keeps.
    Over a halving sequence of amplitudes their difference scales as a^4, the forces on the
    transverse DOFs as a^3 (second order beyond the leading terms; the exact rod's forces through
    the chain rule T^T r of the linear-u embedding T).  The axial rows differ at a^2 by -EI kappa^2
    (to leading order EI times the element mean of v_xx^2): the curvature per undeformed length,
    kappa = theta_x, shrinks as the element stretches (kappa = (1 + u_x) v_xx / |r'|^2), so bending
    pulls on the axial DOFs; against the axial force EA e that is of relative size EI/EA = eps^2."""
    rng = np.random.default_rng(11)
    n = 5
    q1 = rng.uniform(-1, 1, (n, 8)) * [0, 1, 1, 0, 0, 1, 1, 0]
    q2 = rng.uniform(-1, 1, (n, 8)) * [1, 0, 0, 0, 1, 0, 0, 0]
    l, x0 = rng.uniform(0.1, 0.4, n), rng.uniform(0.0, 0.6, n)
    T = linear_u(l)
    EA, EI = 50.0, 0.5
    c, geo, k, z = coef(EA=EA, EI=EI), vec(l, x0), _kin(), np.zeros((n, 8))
    amplitudes = 0.03 / 2 ** np.arange(4)
    dU, dr, U = [], [], []
    for a in amplitudes:
        q = a * q1 + a**2 * q2
        q_x = ref.matvec(T, q)
        U_x = En.strain_energy_exact(q_x, z, geo, c, k)
        U_A = En.strain_energy_A(q, z, geo, c, k)
        r_x = ref.matvec(np.swapaxes(T, -1, -2), E.elastic_lagrange_exact(q_x, z, z, geo, c, k)[0])
        r_A = E.elastic_lagrange_A(q, z, z, geo, c, k)[0]
        assert not r_x[:, ref.CHIS].any() and not r_A[:, ref.CHIS].any()
        dU.append(np.abs(U_x - U_A))
        dr.append(np.linalg.norm((r_x - r_A)[:, ref.TRANSVERSE + ref.SLOPES], axis=-1))
        U.append(U_A)
        bending = EI * ref.integrate(ref.element_fields(q, q, l)["v_xx"] ** 2, l) / l
        axial = (r_x - r_A)[:, ref.AXIAL]
    np.testing.assert_allclose(axial, bending[:, None] * [1.0, -1.0], rtol=0.01)     # at the smallest a
    order_U = np.log2(np.array(dU[:-1]) / np.array(dU[1:]))
    order_r = np.log2(np.array(dr[:-1]) / np.array(dr[1:]))
    assert np.all(np.abs(order_U - 4) < 0.1), order_U
    assert np.all(np.abs(order_r - 3) < 0.1), order_r
    assert np.all(dU[-1] < 1e-3 * np.abs(U[-1]))          # and small against the energy itself


# ---- gravity on the cubic u --------------------------------------------------------------------

def test_gravity_potential_and_load_of_the_cubic_u(states):
    """rod_gravity_potential_exact = -rho A int g . R dx with the centre line R = a e_r + (x0 + x + u)
    e_i + v e_j, u the exact rod's cubic (reference.py, 8-point Gauss), e_i = (cos phi, -sin phi),
    e_j = (sin phi, cos phi); gravity_uniform_exact's force is its gradient (finite differences,
    constant in q: the potential is linear in it), and differs from the linear-u load where chi
    is not the element's mean slope."""
    q, qd, qdd, l, x0 = states
    rhoA, gX, gY, kin = 1.3, 0.4, -0.9, dict(a=0.2, theta=0.4, phi=-0.3)
    c, geo, k = coef(rhoA=rhoA, gX=gX, gY=gY), vec(l, x0), _kin(**kin)
    f = ref.element_fields(q, qd, l, cubic_u=True)
    xi, eta = x0[:, None] + l[:, None] * ref.ZETA + f["u"], f["v"]
    a, th, ph = kin["a"], kin["theta"], kin["phi"]
    X = a * np.cos(th) + xi * np.cos(ph) + eta * np.sin(ph)
    Y = a * np.sin(th) - xi * np.sin(ph) + eta * np.cos(ph)
    expected = ref.integrate(-rhoA * (gX * X + gY * Y), l)
    V = En.rod_gravity_potential_exact(q, qd, geo, c, k)
    assert_close(V, expected, 1e-12, 0, "gravity potential (cubic u)")
    r = E.gravity_uniform_exact(q, qd, qdd, geo, c, k)[0]
    _check(r, ref.fd_jacobian(lambda y: En.rod_gravity_potential_exact(y, qd, geo, c, k), q, 1e-3), 1e-9,
           "gravity load = dV/dq")
    r_linear = E.gravity_uniform(q, qd, qdd, geo, c, k)[0]
    assert np.max(np.abs(r[:, ref.CHIS])) > 1e-3 * np.max(np.abs(r)) and not r_linear[:, ref.CHIS].any()
