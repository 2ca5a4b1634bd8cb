"""simulate(initial=...): the start angle theta0, the projection of a given elastic state onto the
mesh, its checks against the pin and the guide, and the default start (the rigid mechanism at
rest), which must not change by a bit."""

import math

import numpy as np
import pytest

import crankgen
from crankgen.discrete.initial import reduced_state
from crankgen.discrete.mesh import PSI, U, V, Mesh

RUN = dict(omega=0.8, n_elements=4, steps_per_rev=40, revolutions=0.5)


def _same(a, b):
    for name in ("t", "theta", "v_mid", "u_end", "extension", "states", "rates", "accelerations"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


@pytest.mark.parametrize("engine", ["compiled", "numpy"])
def test_default_start_is_the_rigid_motion_from_rest_bit_for_bit(engine):
    run = dict(RUN, revolutions=0.3 if engine == "numpy" else 0.5, engine=engine)
    plain = crankgen.simulate(crankgen.Mechanism(), **run)
    N = 3 * RUN["n_elements"]
    assert np.array_equal(plain.states[0], np.zeros(N)) and np.array_equal(plain.rates[0], np.zeros(N))
    for initial in (crankgen.InitialState(), {}, (np.zeros(N), np.zeros(N)),
                    crankgen.InitialState(u=lambda x: 0 * x, v=lambda x: 0 * x, u_t=np.zeros(5),
                                          v_t=lambda x: 0 * x)):
        _same(plain, crankgen.simulate(crankgen.Mechanism(), initial=initial, **run))
    _same(plain, crankgen.simulate(crankgen.Mechanism(), theta0=0.0, **run))


def test_theta0_starts_the_crank_there_and_moves_the_whole_motion():
    """A start at theta0 = Omega t1 at t = 0 is the motion of a start at 0 seen from t1 on: the
    same crank angles, rod angles and (for the constant crank) the same kinematics at every step."""
    t1 = 0.7
    r = crankgen.simulate(crankgen.Mechanism(), theta0=0.8 * t1, **RUN)
    assert r.theta[0] == pytest.approx(0.8 * t1, abs=1e-15)
    np.testing.assert_allclose(r.theta, 0.8 * (r.t + t1), rtol=1e-14)
    # the rod starts in the rigid position at theta0: sin phi = a sin theta0, end at a cos + cos phi
    phi0 = math.asin(0.1 * math.sin(0.8 * t1))
    assert r.slider_position[0] == pytest.approx(0.1 * math.cos(0.8 * t1) + math.cos(phi0), abs=1e-14)
    assert r.chord_angle[0] == pytest.approx(-phi0, abs=1e-14)
    for crank in (crankgen.RunUp(start=0.2, stop=0.8, revolutions=1.0),
                  crankgen.Fluctuation(omega=0.8, amplitude=0.3, order=2)):
        base = crankgen.simulate(crankgen.Mechanism(), crank=crank, **RUN)
        moved = crankgen.simulate(crankgen.Mechanism(), crank=crank, theta0=1.3, **RUN)
        assert moved.theta[0] == pytest.approx(1.3, abs=1e-14)
        if isinstance(crank, crankgen.RunUp):          # a law in time: theta0 only shifts the angle
            np.testing.assert_allclose(moved.theta - base.theta, 1.3, atol=1e-12)
        else:                                          # autonomous: the speed follows the angle
            np.testing.assert_allclose(moved.crank_speed, 0.8 * (1 + 0.3 * np.sin(2 * moved.theta)), rtol=1e-12)


def _hermite(nodes_v, nodes_psi, n, x):
    """v(x) from nodal values and slopes with the cubic Hermite polynomials (written out here)."""
    l = 1.0 / n
    e = np.minimum((x * n).astype(int), n - 1)
    z = x / l - e
    h1, h2 = 1 - 3 * z**2 + 2 * z**3, z * (z - 1) ** 2 * l
    h3, h4 = z**2 * (3 - 2 * z), z**2 * (z - 1) * l
    return h1 * nodes_v[e] + h2 * nodes_psi[e] + h3 * nodes_v[e + 1] + h4 * nodes_psi[e + 1]


def _linear(nodes_u, n, x):
    e = np.minimum((x * n).astype(int), n - 1)
    z = x * n - e
    return (1 - z) * nodes_u[e] + z * nodes_u[e + 1]


def _nodal(mesh, vector, s_value_u, s_value_v):
    """(u, v, psi) nodal arrays from a reduced vector and the end node's (u, v)."""
    n = mesh.n_elements
    out = np.zeros((3, n + 1))
    for k in range(n + 1):
        for c in (U, V, PSI):
            idx = mesh.reduced_index(k, c)
            if idx is not None:
                out[c, k] = vector[idx]
    out[U, n], out[V, n] = s_value_u, s_value_v
    return out


@pytest.mark.parametrize("theta0", [0.0, 0.7])
def test_projection_reproduces_fields_of_the_element_space_exactly(theta0):
    """u piecewise linear and v piecewise cubic with a continuous slope on the mesh (n = 4, knots at
    the nodes), and their rates alike, are reproduced at every x; the end lies on the guide at
    theta0 with its rate along it."""
    n, a, omega = 4, 0.1, 0.8
    case = crankgen.Case(n_elements=n, omega=omega, theta0=theta0)
    phi0 = math.asin(a * math.sin(theta0))                                   # rigid rod angle
    phid0 = a * math.cos(theta0) * omega / math.cos(phi0)
    s, sd = 3e-5, -2e-5                                                      # the end's co-ordinate
    kink = lambda x: np.maximum(x - 0.5, 0.0)                                # noqa: E731
    # u: linear with a kink at the node x = 1/2, ending at s cos phi0
    u = lambda x: 1e-5 * x + 4e-5 * kink(x) + (s * math.cos(phi0) - 1e-5 - 2e-5) * x   # noqa: E731
    u_t = lambda x: 2e-6 * kink(x) + (sd * math.cos(phi0) - s * math.sin(phi0) * phid0 - 1e-6) * x   # noqa: E731
    # v: a cubic plus a cubic that starts at the node 1/4 with zero value and slope (C1 there)
    v = lambda x: 2e-3 * x * (1 - x) * (0.3 + x) + 5e-3 * np.maximum(x - 0.25, 0) ** 3 \
        + (s * math.sin(phi0) - 5e-3 * 0.75**3) * x                          # noqa: E731
    v_t = lambda x: 1e-2 * x**2 * (1 - x) - 4e-3 * np.maximum(x - 0.75, 0) ** 2 * (x - 0.75) \
        + (sd * math.sin(phi0) + s * math.cos(phi0) * phid0 + 4e-3 * 0.25**3) * x   # noqa: E731
    ini = crankgen.InitialState(u=u, v=v, u_t=u_t, v_t=v_t)
    d0, v0 = reduced_state(case, ini)
    mesh = Mesh(n)
    assert d0[mesh.reduced_coordinates()[0]] == pytest.approx(s, rel=1e-12)
    assert v0[mesh.reduced_coordinates()[0]] == pytest.approx(sd, rel=1e-10)
    disp = _nodal(mesh, d0, u(1.0), v(1.0))
    rate = _nodal(mesh, v0, u_t(1.0), v_t(1.0))
    # the end node's (u, v) from the reduced co-ordinate: s (cos phi0, sin phi0), and its rate
    assert disp[U, n] == pytest.approx(s * math.cos(phi0), rel=1e-12)
    x = np.linspace(0.0, 1.0, 97)
    np.testing.assert_allclose(_linear(disp[U], n, x), u(x), rtol=0, atol=1e-19)
    np.testing.assert_allclose(_hermite(disp[V], disp[PSI], n, x), v(x), rtol=0, atol=1e-17)
    np.testing.assert_allclose(_linear(rate[U], n, x), u_t(x), rtol=0, atol=1e-19)
    np.testing.assert_allclose(_hermite(rate[V], rate[PSI], n, x), v_t(x), rtol=0, atol=1e-17)
    # the same state through simulate (compiled engine): its first stored state
    r = crankgen.simulate(case=case, revolutions=0.05, initial=ini)
    assert np.array_equal(r.states[0], d0) and np.array_equal(r.rates[0], v0)


def test_nodal_arrays_and_slopes_give_the_same_state_as_callables():
    n = 4
    case = crankgen.Case(n_elements=n, omega=0.8)
    v = lambda x: 1e-3 * np.sin(math.pi * x)                                 # noqa: E731
    x = np.arange(n + 1) / n
    from_fn = reduced_state(case, crankgen.InitialState(v=v))
    from_nodes = reduced_state(case, crankgen.InitialState(v=v(x), v_x=1e-3 * math.pi * np.cos(math.pi * x)))
    np.testing.assert_allclose(from_fn[0], from_nodes[0], rtol=1e-13, atol=1e-20)


@pytest.mark.parametrize("fields, words", [
    (dict(u=lambda x: 1e-4 + 0 * x), "u(0)"),
    (dict(v=lambda x: 1e-3 * (1 - x)), "v(0)"),
    (dict(v_t=lambda x: 1e-3 + 0 * x), "v_t(0)"),
    (dict(u_t=lambda x: 1e-3 * (1 - x)), "u_t(0)"),
    (dict(v=lambda x: 1e-3 * x), "u, v at x = L"),                 # the end lifted off the guide
    (dict(v_t=lambda x: 1e-3 * x), "u_t, v_t at x = L"),           # the end's velocity off the guide
    (dict(v=np.zeros(5)), "v_x"),                                  # nodal values need their slopes
    (dict(v=lambda x: np.sin(np.real(x) * 0)), "give v_x"),        # no complex step possible
    (dict(u=np.zeros(4)), "5 values"),
    (dict(v_x=np.zeros(5)), "without v"),
    (dict(u=lambda x: np.nan * x), "not finite"),
])
def test_a_state_violating_pin_or_guide_or_malformed_is_refused_naming_the_field(fields, words):
    case = crankgen.Case(n_elements=4, omega=0.8)
    with pytest.raises(crankgen.ParameterError) as exc:
        reduced_state(case, crankgen.InitialState(**fields))
    assert words in str(exc.value)
    assert str(exc.value).startswith("initial state")


def test_a_state_within_the_tolerance_is_accepted():
    case = crankgen.Case(n_elements=4, omega=0.8)
    tiny = 1e-3 * 0.01**2 * 1e-6                                     # 1e-3 of the threshold
    reduced_state(case, crankgen.InitialState(u=lambda x: tiny + 0 * x))
    with pytest.raises(crankgen.ParameterError):
        reduced_state(case, crankgen.InitialState(u=lambda x: tiny + 0 * x, tol=1e-12))


def test_the_end_on_a_rocker_circle_is_found_and_checked():
    """Four-bar (circle guide) at theta0 = 0.6: an end displacement and velocity made from the
    guide's end map at s = 2e-4, s_t = 1e-3 give back those s and s_t; a point off the circle is
    refused."""
    from crankgen.discrete import kinematics as K
    from crankgen.declaration import schema
    mech = crankgen.Mechanism(guide=crankgen.Circle(center=(1.0, 0.0), radius=0.8))
    case = crankgen.Case(**mech.values(), omega=0.8, n_elements=4, theta0=0.6)
    E = K.end_map(case, K.case_state(case, 0.0).vector, 2e-4, 1e-3)
    (ue, ve), (ute, vte) = E[schema.END_MAP_ROWS["q"]], E[schema.END_MAP_ROWS["qd"]]
    ini = crankgen.InitialState(u=lambda x: ue * x, v=lambda x: ve * x + 1e-3 * x * (1 - x),
                                u_t=lambda x: ute * x, v_t=lambda x: vte * x)
    d0, v0 = reduced_state(case, ini)
    assert d0[-2] == pytest.approx(2e-4, rel=1e-12) and v0[-2] == pytest.approx(1e-3, rel=1e-12)
    with pytest.raises(crankgen.ParameterError, match="off the guide"):
        reduced_state(case, crankgen.InitialState(u=lambda x: ue * x, v=lambda x: 1.01 * ve * x))
