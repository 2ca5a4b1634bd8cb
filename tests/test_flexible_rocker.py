"""A four-bar with a flexible rocker beside the flexible coupler (the body "rocker", rocker_elements
> 0): its limits, its frozen frequencies against an exact frame solution built independently
(tests/linkage_frequencies.py, the dynamic stiffness method), the compiled engine against the NumPy
reference, and the DOF map's band."""

import numpy as np
import pytest

import crankgen
from crankgen.analyses.modes import FrozenModel
from crankgen.declaration.cases import make_case
from crankgen.discrete import kinematics
from crankgen.discrete.assembly import BandedAssembler
from crankgen.discrete.mesh import Mesh
from crankgen.errors import ParameterError

from linkage_frequencies import frequencies

FOUR_BAR = dict(a=0.1, c=0.8, d=1.0, offset=0.0)


def four_bar(**rocker):
    return crankgen.Mechanism(a=FOUR_BAR["a"], guide=crankgen.Circle(c=FOUR_BAR["c"], d=FOUR_BAR["d"], **rocker))


@pytest.mark.parametrize("approach", ["A", "exact"])
def test_the_dof_map_keeps_the_band_of_one_rod(approach):
    """The rocker's nodes follow the rod's from its tip: every element spans as few unknowns as the
    rod's own (half-bandwidth 5 without chi, 7 with it), the rocker tip's (u, v) are the tip
    constraint's reduced co-ordinates, and the pivot's (u, v) are gone."""
    components = ("u", "v", "psi", "chi") if approach == "exact" else ("u", "v", "psi")
    rod = Mesh(6, components=components)
    both = Mesh(6, components=components, rocker_elements=4, rocker_length=0.8)
    assert BandedAssembler(both).bandwidth == BandedAssembler(rod).bandwidth
    per_node = len(components)
    # the tip's (u, v) replace s; the rocker's 5 nodes, less the tip's (u, v) (shared) and the pivot's (pinned)
    assert both.n_rod == rod.n_rod + 1 + 5 * per_node - 4
    tip = both.reduced_coordinates()
    assert tip == (both.reduced_index(("rocker", 4), 0), both.reduced_index(("rocker", 4), 1))
    assert both.element_dofs[5, 4:6].tolist() == list(tip)     # the rod's end node (u, v) slots
    assert both.reduced_index(("rocker", 0), 0) is None and both.reduced_index(("rocker", 0), 1) is None
    assert sorted(set(both.element_dofs.ravel()) - {both.dummy}) == list(range(both.n_rod))


def test_the_tips_end_map_holds_the_rods_end_on_the_rocker_tip():
    """end_map_circle_flexible against the geometry written out here: the rod's end displacement
    u e_i + v e_j equals the rocker tip's u_r e_ir + v_r e_jr (e_i = (cos phi, -sin phi), e_ir = (cos
    beta, sin beta)), its rates are the time derivatives of that along a motion (central
    differences), its g_s columns the derivatives in (u_r, v_r), its curvature rows zero."""
    case = make_case(a=0.1, guide="circle", c=0.8, d=1.0, omega=0.7, rocker_elements=2)

    def tip(t):                                    # a smooth motion of the rocker's tip
        return np.array([1e-4 * np.sin(3 * t) + 2e-5, 3e-3 * np.cos(2 * t)])

    def rod_end(t, z):                             # (u, v) of the rod's end: independent geometry
        k = kinematics.case_state(case, t).vector
        phi, beta = k[3], k[7]
        e_i, e_j = np.array([np.cos(phi), -np.sin(phi)]), np.array([np.sin(phi), np.cos(phi)])
        disp = z[0] * np.array([np.cos(beta), np.sin(beta)]) + z[1] * np.array([-np.sin(beta), np.cos(beta)])
        return np.array([disp @ e_i, disp @ e_j])

    t, h = 1.3, 1e-4
    z, zd, zdd = tip(t), (tip(t + h) - tip(t - h)) / (2 * h), (tip(t + h) - 2 * tip(t) + tip(t - h)) / h**2
    E = kinematics.end_map(case, kinematics.case_state(case, t).vector, z, zd, zdd)
    assert E.shape == (15, 2)
    np.testing.assert_allclose(E[0], rod_end(t, z), rtol=1e-12, atol=1e-15)
    qd = (rod_end(t + h, tip(t + h)) - rod_end(t - h, tip(t - h))) / (2 * h)
    qdd = (rod_end(t + h, tip(t + h)) - 2 * rod_end(t, z) + rod_end(t - h, tip(t - h))) / h**2
    np.testing.assert_allclose(E[1], qd, rtol=1e-6, atol=1e-9 * np.abs(qd).max())
    np.testing.assert_allclose(E[2], qdd, rtol=1e-4, atol=1e-5 * np.abs(qdd).max())
    for j in range(2):
        dz = np.eye(2)[j] * 1e-6
        g_s = (rod_end(t, z + dz) - rod_end(t, z - dz)) / 2e-6
        np.testing.assert_allclose(E[3 + 4 * j], g_s, rtol=1e-8, atol=1e-12)
    assert not E[11:].any()                        # linear in (u_r, v_r): no curvature


def _frozen_frequencies(ms, theta, n, n_r, eps=0.02):
    case = make_case(a=FOUR_BAR["a"], guide="circle", c=FOUR_BAR["c"], d=FOUR_BAR["d"], eps=eps, ms=ms,
                     omega=1e-6, n_elements=n, rocker_elements=n_r, rotary_inertia=False)
    model = FrozenModel(case)
    kin, _, lam, _, _ = model.eigen(np.array([theta]))
    k = kin.vector[0]
    A = FOUR_BAR["a"] * np.array([np.cos(theta), np.sin(theta)])
    phi = k[list(crankgen.declaration.schema.KINEMATICS).index("phi")]
    B = A + np.array([np.cos(phi), -np.sin(phi)])
    D = np.array([FOUR_BAR["d"], FOUR_BAR["offset"]])
    u, w = A - B, D - B
    gamma = np.arccos(u @ w / np.linalg.norm(u) / np.linalg.norm(w))
    return np.sqrt(lam[0, :3]), gamma


@pytest.mark.parametrize("ms", [0.0, 0.5])
def test_frozen_frequencies_of_the_linkage_match_the_exact_frame(ms):
    """Crank locked (Omega* -> 0), no rotary inertia: the coupler and the rocker pinned at A, D and
    to each other at B (end mass ms there) vibrate at the frequencies of the dynamic stiffness
    method's frame (exact Euler-Bernoulli members), first three modes to 0.5 %."""
    eps, theta = 0.02, 1.0
    ours, gamma = _frozen_frequencies(ms, theta, 16, 12, eps)
    EA, EI = 1 / (np.pi**4 * eps**2), 1 / np.pi**4
    exact = frequencies(1.0, 1.0, EA, EI, FOUR_BAR["c"], 1.0, EA, EI, gamma, m_B=ms, n=3)
    assert 0.3 < gamma < 2.8                   # a frame, not the toggle
    np.testing.assert_allclose(ours, exact, rtol=5e-3)


def test_frozen_frequencies_converge_in_each_links_elements():
    """The first three frozen frequencies converge from above as the coupler's and the rocker's
    element counts double (cubic beam elements: the error falls about sixteenfold per halving, h^4)."""
    eps, theta = 0.02, 1.0
    _, gamma = _frozen_frequencies(0.5, theta, 4, 4, eps)
    EA, EI = 1 / (np.pi**4 * eps**2), 1 / np.pi**4
    exact = frequencies(1.0, 1.0, EA, EI, FOUR_BAR["c"], 1.0, EA, EI, gamma, m_B=0.5, n=3)
    errors = []
    for n, n_r in ((4, 3), (8, 6), (16, 12)):
        ours, _ = _frozen_frequencies(0.5, theta, n, n_r, eps)
        errors.append(np.abs(ours / exact - 1))
    errors = np.array(errors)
    assert np.all(errors[1] < errors[0] / 8) and np.all(errors[2] < errors[1] / 8), errors


def _steady_max(mech, omega=0.6, n=8, **settings):
    s = crankgen.steady_state(mech, omega=omega, n_elements=n, steps_per_rev=100, **settings)
    return float(np.max(np.abs(s.v_mid)))


def test_a_stiff_light_rocker_is_the_rigid_massless_rocker():
    """A flexible rocker 10^4 times stiffer than the coupler, its mass 10^-4 of the coupler's per
    length, reproduces the rigid massless rocker's steady max |v*| to 1e-4."""
    rigid = _steady_max(four_bar())
    stiff = _steady_max(four_bar(rocker_elements=4, rocker_bending=1e4, rocker_axial=1e4, rocker_density=1e-4))
    assert abs(stiff / rigid - 1) < 1e-4, (stiff, rigid)
    soft = _steady_max(four_bar(rocker_elements=4))
    assert abs(soft / rigid - 1) > 1e-3            # the coupler's own section: the rocker's flexibility shows


def test_a_stiff_rocker_with_its_mass_is_the_rigid_rocker_of_that_mass():
    """Made 10^4 times stiffer with its real mass (rho A_r = rho A), the flexible rocker reproduces a
    rigid rocker of the same mass c, centre c/2 and inertia m c^2/12 (rotary inertia off for both)."""
    c = FOUR_BAR["c"]
    rigid = _steady_max(four_bar(rocker_mass=c, rocker_centre=0.5, rocker_inertia=c**3 / 12), rotary_inertia=False)
    stiff = _steady_max(four_bar(rocker_elements=4, rocker_bending=1e4, rocker_axial=1e4), rotary_inertia=False)
    massless = _steady_max(four_bar())
    assert abs(stiff / rigid - 1) < 1e-4, (stiff, rigid)
    assert abs(rigid / massless - 1) > 5e-3        # the rocker's mass matters (0.9 % here)


@pytest.mark.parametrize("model", ["consistent", "exact"])
def test_the_compiled_engine_matches_the_numpy_reference(model):
    """Two flexible bodies in the compiled engine (per-body lanes, the rocker's frame and section,
    the tip's two reduced co-ordinates) and in the NumPy reference model: the same run."""
    mech = four_bar(rocker_elements=3, rocker_bending=0.5, rocker_density=2.0)
    runs = [crankgen.simulate(mech, omega=0.6, n_elements=4, steps_per_rev=50, revolutions=1, model=model,
                              engine=engine) for engine in ("compiled", "numpy")]
    np.testing.assert_allclose(runs[0].states, runs[1].states, rtol=0, atol=1e-9 * np.max(np.abs(runs[1].states)))


def test_a_flexible_rocker_refuses_the_rigid_rockers_mass():
    with pytest.raises(ParameterError, match="flexible rocker"):
        crankgen.simulate(four_bar(rocker_elements=3, rocker_mass=0.5), omega=0.5, n_elements=4,
                          steps_per_rev=40, revolutions=1)


def _linkage_energy(result):
    """T + U of the coupler, the rocker and the end mass per stored step, written out here (approach
    A, the pointwise membrane strain, no rotary inertia, no gravity) by Gauss quadrature in the
    inertial frame: R = A + (x + u) e_i + v e_j on the coupler, R = D + (x + u) e_ir + v e_jr on the
    rocker (e_ir = (cos beta, sin beta)), the coupler's end (u, v) written from the rocker tip's
    through their frames; and the crank pin's velocity.  Only the rigid kinematics and the DOF layout
    come from crankgen."""
    import energy_balance as eb
    case = result.case
    mesh = Mesh.of_case(case)
    kin = kinematics.case_state(case, result.t).vector
    a, theta, thetad, phi, phid, beta, betad = (kin[:, i] for i in (0, 1, 2, 3, 4, 7, 8))
    d, v = result.states, result.rates
    q, qd = mesh.gather_all(d), mesh.gather_all(v)
    n, n_r = mesh.n_elements, mesh.rocker_elements
    # the coupler's end from the rocker tip: u e_i + v e_j = u_r e_ir + v_r e_jr, with its rate
    tip, tip_d = d[:, list(mesh.reduced_coordinates())], v[:, list(mesh.reduced_coordinates())]
    g, gd = phi + beta, phid + betad
    cg, sg = np.cos(g), np.sin(g)
    end = np.stack([cg * tip[:, 0] - sg * tip[:, 1], sg * tip[:, 0] + cg * tip[:, 1]], -1)
    end_d = np.stack([cg * tip_d[:, 0] - sg * tip_d[:, 1] - gd * (sg * tip[:, 0] + cg * tip[:, 1]),
                      sg * tip_d[:, 0] + cg * tip_d[:, 1] + gd * (cg * tip[:, 0] - sg * tip[:, 1])], -1)
    q[:, n - 1, 4:6], qd[:, n - 1, 4:6] = end, end_d
    crank_i = -a * thetad * np.sin(theta + phi)          # the crank pin's velocity on (e_i, e_j)
    crank_j = a * thetad * np.cos(theta + phi)
    coef_rod, coef_rocker = case.coefficients, case.body_coefficients("rocker")
    names = list(crankgen.declaration.schema.COEFFICIENTS)
    parts = {"coupler": np.zeros(len(result.t)), "rocker": np.zeros(len(result.t))}
    for body, (lo, hi), coef, length in (("coupler", (0, n), coef_rod, 1.0 / n),
                                         ("rocker", (n, n + n_r), coef_rocker, mesh.rocker_element_length)):
        rhoA, EA, EI = (coef[names.index(k)] for k in ("rhoA", "EA", "EI"))
        Nu, Nux, Nv, Nvx, Nvxx = eb.shapes(eb.ZETA, length)
        for e in range(lo, hi):
            x = (e - lo + eb.ZETA) * length
            u, ud, vv, vd = q[:, e] @ Nu.T, qd[:, e] @ Nu.T, q[:, e] @ Nv.T, qd[:, e] @ Nv.T
            ux, vx, vxx = q[:, e] @ Nux.T, q[:, e] @ Nvx.T, q[:, e] @ Nvxx.T
            if body == "coupler":
                vi = crank_i[:, None] + ud + vv * phid[:, None]
                vj = crank_j[:, None] + vd - (x + u) * phid[:, None]
            else:
                vi = ud - vv * betad[:, None]
                vj = vd + (x + u) * betad[:, None]
            density = rhoA / 2 * (vi**2 + vj**2) + EA / 2 * (ux + vx**2 / 2) ** 2 + EI / 2 * vxx**2
            parts[body] += length * density @ eb.WEIGHTS
    ms = coef_rod[names.index("ms")]
    vb_i = crank_i + end_d[:, 0] + end[:, 1] * phid
    vb_j = crank_j + end_d[:, 1] - (1 + end[:, 0]) * phid
    parts["end mass"] = ms / 2 * (vb_i**2 + vb_j**2)
    pin_velocity = a[:, None] * thetad[:, None] * np.stack([-np.sin(theta), np.cos(theta)], -1)
    return parts, pin_velocity


def test_energy_balance_of_the_two_flexible_links():
    """Undamped (mu* = 0), the paper's Newmark rule: the change of the linkage's energy (coupler,
    rocker, end mass, written out here) equals the work of the crank pin's force (the output
    crank_on_rod, the pin's reaction) along a revolution, up to the work of the moving frames on
    the discretized beams (tests/energy_balance.py: the elements cannot rotate a deformed beam
    exactly; 0.6 % here at Omega* 0.6, 0.05 % at 0.3, the same with half the time step or twice the
    elements); leaving the rocker's energy out breaks the balance many times over."""
    case = make_case(a=0.1, guide="circle", c=0.8, d=1.0, omega=0.6, mu=0.0, n_elements=8, steps_per_rev=200,
                     rocker_elements=4, rocker_bending=0.3, membrane="pointwise", rotary_inertia=False, rho_inf=1.0)
    result = crankgen.simulate(case=case, revolutions=1)
    parts, pin_velocity = _linkage_energy(result)
    force = np.stack([result.quantity("crank_on_rod_x"), result.quantity("crank_on_rod_y")], -1)
    power = np.sum(force * pin_velocity, axis=-1)
    work = np.concatenate([[0.0], np.cumsum((power[1:] + power[:-1]) / 2 * np.diff(result.t))])
    scale = np.sum(np.abs(power[1:] + power[:-1]) / 2 * np.diff(result.t))

    def defect(energy):
        return np.max(np.abs(energy - energy[0] - work)) / scale
    full = defect(sum(parts.values()))
    without_rocker = defect(parts["coupler"] + parts["end mass"])
    assert full < 1e-2 and without_rocker > 10 * full, (full, without_rocker)


def test_the_animation_draws_the_flexible_rocker_from_its_pivot_to_the_rods_end():
    """A frame of the animation: the flexible rocker's curve starts at the ground pivot and ends on
    the rod's (magnified) end, and it bends (it is not the straight rigid rocker)."""
    from crankgen.plots.animation import Frames
    mech = four_bar(rocker_elements=4, rocker_bending=0.05)
    result = crankgen.simulate(mech, omega=0.6, n_elements=6, steps_per_rev=40, revolutions=1)
    frames = Frames(result, frames=8)
    np.testing.assert_allclose(frames.rocker[:, 0], np.broadcast_to(frames.pivot, (len(frames), 2)), atol=1e-12)
    np.testing.assert_allclose(frames.rocker[:, -1], frames.end, atol=1e-9)
    chord = frames.rocker[:, -1] - frames.rocker[:, 0]
    rel = frames.rocker - frames.rocker[:, :1]
    off = (chord[:, None, 0] * rel[..., 1] - chord[:, None, 1] * rel[..., 0]) / np.linalg.norm(chord, axis=-1)[:, None]
    assert np.max(np.abs(off)) > 1e-3


def test_a_continuation_in_the_rockers_own_stiffness_passes_through_its_steady_states():
    """The rocker's bending stiffness is a continuable parameter: a branch point of the continuation
    in rocker_bending is the steady state found directly at that stiffness."""
    mech = crankgen.Mechanism(eps=0.01, ms=0.5, guide=crankgen.Circle(radius=0.5, center=(1, 0), rocker_elements=2))
    diagram = crankgen.continuation(mech, "rocker_bending", 2.0, 0.2, omega=0.7, n_elements=4, steps_per_rev=50)
    branch = diagram.branches[0]
    k = int(np.argmin(np.abs(np.asarray(branch.parameter) - 1.0)))
    at = float(branch.parameter[k])
    direct = crankgen.steady_state(crankgen.Mechanism(eps=0.01, ms=0.5, guide=crankgen.Circle(
        radius=0.5, center=(1, 0), rocker_elements=2, rocker_bending=at)), omega=0.7, n_elements=4, steps_per_rev=50)
    assert min(branch.parameter) < 0.3 and max(branch.parameter) > 1.9
    state = np.asarray(direct.state)
    np.testing.assert_allclose(branch.states[k], state, rtol=0, atol=1e-6 * np.max(np.abs(state)))


def test_the_pin_force_at_b_of_a_stiff_light_rocker_is_the_rigid_massless_rockers():
    """The joint forces at B (rod on tip, rocker on tip: the tip constraint's reaction) of a stiff,
    light flexible rocker equal the rigid massless rocker's (to 5e-4 of their peak; 1.3e-4 here); the
    rigid rocker's momentum balance (ground_on_rocker) is refused for a flexible rocker, whose pivot
    force peak_loads takes from ground_on_flexible_rocker."""
    runs = [crankgen.steady_state(mech, omega=0.6, n_elements=8, steps_per_rev=100) for mech in (
        four_bar(), four_bar(rocker_elements=4, rocker_bending=1e4, rocker_axial=1e4, rocker_density=1e-4))]
    for name in ("rod_on_tip_x", "rod_on_tip_y", "rocker_on_tip_x", "rocker_on_tip_y"):
        rigid, flexible = (np.asarray(r.quantity(name)) for r in runs)
        # the stiff rocker's remaining mass (1e-4 of the coupler's per length) moves them by ~1e-4
        np.testing.assert_allclose(flexible, rigid, rtol=0, atol=5e-4 * np.max(np.abs(rigid)))
    with pytest.raises(ParameterError, match="ground_on_rocker_x"):
        runs[1].quantity("ground_on_rocker_x")
    names = [load.name for load in crankgen.peak_loads(runs[1])]
    assert "pin force at B (rod on rocker tip)" in names and "pivot force (ground on rocker)" in names


def test_the_pivot_force_of_a_flexible_rocker_balances_its_momentum():
    """Newton's law for the whole flexible rocker, written out here: the force of the ground at D
    (ground_on_flexible_rocker, the pivot constraint's reaction) plus the force of the tip mass on
    it (-rocker_on_tip) plus its weight equal the rate of its momentum, int rho A_r R'' dx with
    R = D + (x + u) e_ir + v e_jr (the frame turning at beta), by Gauss quadrature of its nodal
    accelerations."""
    import energy_balance as eb
    mech = crankgen.Mechanism(a=0.1, gravity=(0.0, -0.3), guide=crankgen.Circle(
        c=0.8, d=1.0, rocker_elements=4, rocker_bending=0.3, rocker_density=2.0))
    s = crankgen.simulate(mech, omega=0.6, n_elements=6, steps_per_rev=100, revolutions=1)
    case = s.case
    mesh = Mesh.of_case(case)
    kin = kinematics.case_state(case, s.t).vector
    beta, betad, betadd = kin[:, 7], kin[:, 8], kin[:, 9]
    names = list(crankgen.declaration.schema.COEFFICIENTS)
    rhoA = case.body_coefficients("rocker")[names.index("rhoA")]
    q, qd, qdd = (mesh.gather_all(x)[:, mesh.n_elements:] for x in (s.states, s.rates, s.accelerations))
    l = mesh.rocker_element_length
    Nu, _, Nv, _, _ = eb.shapes(eb.ZETA, l)
    momentum_rate = np.zeros((len(s.t), 2))
    for e in range(mesh.rocker_elements):
        x = (e + eb.ZETA) * l
        u, ud, udd = (y[:, e] @ Nu.T for y in (q, qd, qdd))
        v, vd, vdd = (y[:, e] @ Nv.T for y in (q, qd, qdd))
        bd, bdd = betad[:, None], betadd[:, None]
        a_i = udd - 2 * vd * bd - (x + u) * bd**2 - v * bdd
        a_j = vdd + 2 * ud * bd + (x + u) * bdd - v * bd**2
        for k, (ci, cj) in enumerate(((np.cos(beta), -np.sin(beta)), (np.sin(beta), np.cos(beta)))):
            momentum_rate[:, k] += rhoA * l * ((a_i * ci[:, None] + a_j * cj[:, None]) @ eb.WEIGHTS)
    weight = rhoA * mesh.rocker_length * np.array([0.0, -0.3])
    ground = np.stack([s.quantity("ground_on_flexible_rocker_x"), s.quantity("ground_on_flexible_rocker_y")], -1)
    tip = np.stack([s.quantity("rocker_on_tip_x"), s.quantity("rocker_on_tip_y")], -1)
    np.testing.assert_allclose(ground - tip + weight, momentum_rate, rtol=0, atol=1e-6 * np.max(np.abs(ground)))
    assert np.max(np.abs(momentum_rate)) > 0.05 * np.max(np.abs(ground))     # the rocker's inertia matters here
    with pytest.raises(ParameterError, match="ground_on_flexible_rocker_x"):
        crankgen.steady_state(four_bar(), omega=0.6, n_elements=4, steps_per_rev=50).quantity(
            "ground_on_flexible_rocker_x")
