"""simulate(times=...): the state and the outputs where the user asks; the frame-free outputs of the
rod's chord (chord_angle, chord_rate, chord_elongation, chord_deflection(x), slider_position,
slider_velocity) against a hand computation from the nodal states."""

import math

import numpy as np
import pytest

import crankgen

MECH = crankgen.Mechanism(mu=0.0)
RUN = dict(omega=0.8, n_elements=4, steps_per_rev=40, approach="C")
DT = 2 * math.pi / 0.8 / 40


def _bent():
    """A bent, moving initial state (first-mode shape and rate; the end at rest on the guide)."""
    return crankgen.InitialState(v=lambda x: 5e-3 * np.sin(math.pi * x), v_t=lambda x: -2e-2 * np.sin(math.pi * x))


def test_a_requested_time_between_steps_equals_a_run_whose_steps_land_on_it():
    """t = 7.5 dt: the run of 7 steps of dt, continued by one step of dt / 2 (a second run started
    from the first one's last state, at the crank angle it reached, with steps_per_rev doubled).
    Newmark: its state is (d, v) (generalized-alpha's also holds the algorithmic accelerations,
    which a restart does not see: next test)."""
    t_req = 7.5 * DT
    run = dict(RUN, rho_inf=1.0)
    asked = crankgen.simulate(MECH, times=[t_req], initial=_bent(), **run)
    assert len(asked.t) == 9                                # revolutions left out: up to step 8
    first = crankgen.simulate(MECH, revolutions=7 / 40, initial=_bent(), **run)
    landing = crankgen.simulate(MECH, initial=(first.states[-1], first.rates[-1]), theta0=float(first.theta[-1]),
                                revolutions=1 / 80, **dict(run, steps_per_rev=80))
    at = asked.at_times
    assert at.t[0] == t_req and at.theta[0] == pytest.approx(0.8 * t_req, rel=1e-15)
    for name in ("states", "rates", "accelerations"):
        mine, theirs = getattr(at, name)[0], getattr(landing, name)[-1]
        assert np.max(np.abs(mine - theirs)) <= 1e-9 * np.max(np.abs(theirs)), name
    for name in ("v_mid", "slider_position", "chord_angle", "chord_rate", "torque", "crank_on_rod_y"):
        assert getattr(at, name)[0] == pytest.approx(getattr(landing, name)[-1], rel=1e-8, abs=1e-12), name
    assert at.chord_deflection(0.3)[0] == pytest.approx(landing.chord_deflection(0.3)[-1], rel=1e-8)
    # the run's own steps are those of a run without times
    plain = crankgen.simulate(MECH, revolutions=8 / 40, initial=_bent(), **run)
    assert np.array_equal(asked.states, plain.states)


def test_generalized_alpha_reaches_a_time_between_steps_like_the_numpy_reference():
    """Generalized-alpha (rho_inf = 0.8): the step of the remaining length from step k carries the
    algorithmic accelerations of step k; the compiled engine and the NumPy reference (newmark.py,
    its own code) agree (and differ from Newmark's)."""
    t_req = 7.5 * DT
    runs = {e: crankgen.simulate(MECH, times=[t_req], initial=_bent(), engine=e, rho_inf=0.8, **RUN)
            for e in ("compiled", "numpy")}
    a, b = runs["compiled"].at_times, runs["numpy"].at_times
    for name in ("states", "rates", "accelerations"):
        assert np.max(np.abs(getattr(a, name) - getattr(b, name))) <= 1e-9 * np.max(np.abs(getattr(b, name))), name
    newmark = crankgen.simulate(MECH, times=[t_req], initial=_bent(), rho_inf=1.0, **RUN).at_times
    assert np.max(np.abs(a.states - newmark.states)) > 1e-6 * np.max(np.abs(newmark.states))


def test_times_on_steps_are_those_steps_and_keep_the_order_given():
    r = crankgen.simulate(MECH, revolutions=0.25, initial=_bent(), times=[5 * DT, 0.0, 10 * DT, 2.5 * DT], **RUN)
    at = r.at_times
    for j, k in ((0, 5), (1, 0), (2, 10)):
        for name in ("states", "rates", "accelerations", "v_mid", "u_end", "extension"):
            assert np.array_equal(getattr(at, name)[j], getattr(r, name)[k]), (name, k)
    assert np.all(at.iterations[:3] == 0) and at.iterations[3] > 0
    assert r.v_mid[2] != at.v_mid[3] != r.v_mid[3]


def test_numpy_reference_gives_the_same_states_at_requested_times():
    times = [2.5 * DT, 4 * DT + 0.3 * DT]
    c = crankgen.simulate(MECH, initial=_bent(), times=times, **RUN)
    n = crankgen.simulate(MECH, initial=_bent(), times=times, engine="numpy", **RUN)
    scale = np.max(np.abs(c.at_times.states))
    assert np.max(np.abs(c.at_times.states - n.at_times.states)) < 1e-9 * scale


@pytest.mark.parametrize("times, words", [([-1.0], ">= 0"), ([float("nan")], "finite"), ([], "one or more"),
                                          (["x"], "numbers"), ([100.0], "beyond the run's end")])
def test_bad_times_are_refused(times, words):
    with pytest.raises(crankgen.ParameterError) as exc:
        crankgen.simulate(MECH, revolutions=0.25, times=times, **RUN)
    assert words in str(exc.value)


# ---- the chord outputs by hand ---------------------------------------------------------------------
def _hand(r, k, x):
    """Chord quantities of stored step k from the nodal states, written out here: the pin
    A = a (cos theta, sin theta); the moving frame e_i = (cos phi, -sin phi), e_j = (sin phi,
    cos phi) with sin phi = a sin theta; the end B = A + (1 + u_n) e_i + v_n e_j; a rod point
    P(x) = A + (x + u(x)) e_i + v(x) e_j (u linear, v cubic Hermite in the element)."""
    a, omega = 0.1, 0.8
    n = r.case.n_elements
    th = r.theta[k]
    phi = math.asin(a * math.sin(th))
    phid = a * math.cos(th) * omega / math.cos(phi)
    ei, ej = np.array([math.cos(phi), -math.sin(phi)]), np.array([math.sin(phi), math.cos(phi)])
    A = a * np.array([math.cos(th), math.sin(th)])
    Ad = a * omega * np.array([-math.sin(th), math.cos(th)])
    nodes = r.nodes[k]
    u, v, psi = nodes[0::4], nodes[1::4], nodes[2::4]             # (u, v, psi, chi) a node
    B = A + (1 + u[n]) * ei + v[n] * ej
    # the end's rates: (u, v)_n = s (cos phi, sin phi), s the slider's reduced co-ordinate
    s, sd = r.states[k][-2], r.rates[k][-2]
    un_t = sd * math.cos(phi) - s * math.sin(phi) * phid
    vn_t = sd * math.sin(phi) + s * math.cos(phi) * phid
    Bd = Ad + un_t * ei + vn_t * ej + (1 + u[n]) * (-phid * ej) + v[n] * (phid * ei)
    chord = B - A
    length = math.hypot(*chord)
    e = min(int(x * n), n - 1)
    z, l = x * n - e, 1.0 / n
    ux = (1 - z) * u[e] + z * u[e + 1]
    vx = ((1 - 3 * z**2 + 2 * z**3) * v[e] + z * (z - 1) ** 2 * l * psi[e]
          + z**2 * (3 - 2 * z) * v[e + 1] + z**2 * (z - 1) * l * psi[e + 1])
    P = A + (x + ux) * ei + vx * ej
    cross = lambda p, q: p[0] * q[1] - p[1] * q[0]                          # noqa: E731
    return dict(chord_angle=math.atan2(chord[1], chord[0]), chord_elongation=length - 1,
                chord_rate=cross(chord, Bd - Ad) / length**2, slider_position=B[0], slider_velocity=Bd[0],
                chord_deflection=cross(chord, P - A) / length)


def test_chord_outputs_against_a_hand_computation_from_nodal_states():
    r = crankgen.simulate(crankgen.Mechanism(mu=0.0), omega=0.8, n_elements=5, steps_per_rev=40, approach="A",
                          revolutions=0.6, initial=_bent(), store_nodes=True)
    x = 0.37
    for k in (0, 7, 19, 24):
        hand = _hand(r, k, x)
        for name in ("chord_angle", "chord_elongation", "chord_rate", "slider_position", "slider_velocity"):
            assert getattr(r, name)[k] == pytest.approx(hand[name], rel=1e-10, abs=1e-15), (name, k)
        assert r.chord_deflection(x)[k] == pytest.approx(hand["chord_deflection"], rel=1e-10, abs=1e-15)
    # not trivially zero: the rod is bent and the chord turns off the rigid one
    assert abs(r.chord_deflection(x)[7]) > 1e-3 and abs(r.chord_elongation[19]) > 1e-7


def test_history_off_keeps_the_requested_states_bit_for_bit():
    times = [0.0, 3 * DT, 6.25 * DT, 6.75 * DT]
    full = crankgen.simulate(MECH, initial=_bent(), times=times, revolutions=0.2, **RUN)
    calls = []
    lean = crankgen.simulate(MECH, initial=_bent(), times=times, revolutions=0.2, history=False,
                             progress=lambda done, total: calls.append(done), **RUN)
    assert lean.states is None and lean.rates is None and calls[-1] == len(full.t) - 1
    assert np.array_equal(lean.v_mid, full.v_mid) and np.array_equal(lean.iterations, full.iterations)
    for name in ("states", "rates", "accelerations", "v_mid"):
        assert np.array_equal(getattr(lean.at_times, name), getattr(full.at_times, name)), name
    assert np.array_equal(lean.at_times.chord_angle, full.at_times.chord_angle)
    with pytest.raises(crankgen.ParameterError, match="holds no states"):
        lean.chord_angle
    with pytest.raises(crankgen.ParameterError, match="store_nodes"):
        crankgen.simulate(MECH, history=False, store_nodes=True, revolutions=0.1, **RUN)
