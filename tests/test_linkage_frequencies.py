"""tests/linkage_frequencies.py, the exact (dynamic stiffness + Wittrick-Williams) natural
frequencies of the four-bar frozen with its crank locked, checked against closed forms and against
a second, independent route written here: a fine plain finite-element model of the same frame
(linear bar + cubic Hermite beam elements, consistent mass, scipy.linalg.eigh).

Units as crankgen's: L = 1, rhoA = 1, EI = 1/pi^4 (the coupler's first pinned-pinned bending
frequency is 1), EA = EI / eps^2 with eps the slenderness (radius of gyration / L).
"""

import numpy as np
import pytest
from scipy.linalg import eigh
from scipy.optimize import brentq

import linkage_frequencies as lf

PI = np.pi
EI0 = 1.0 / PI ** 4


def section(eps):
    """(rhoA, EA, EI) of crankgen's unit coupler with slenderness eps."""
    return 1.0, EI0 / eps ** 2, EI0


def default_args(eps=0.02, c=0.5, gamma_deg=60.0, m_B=0.0):
    """The intended case: same section for coupler and rocker."""
    r, ea, ei = section(eps)
    return dict(L=1.0, rhoA=r, EA=ea, EI=ei, c=c, rhoA_r=r, EA_r=ea, EI_r=ei,
                gamma=np.radians(gamma_deg), m_B=m_B)


# ----------------------------------------------------------------------------------------------
# The second route: a plain finite-element frame
# ----------------------------------------------------------------------------------------------

def _element(h, rhoA, EA, EI, cx, cy):
    """Global 6 x 6 stiffness and consistent mass of a plane frame element (u1, v1, th1, u2, v2,
    th2): linear bar axially, cubic Hermite beam transversely."""
    k = np.zeros((6, 6))
    m = np.zeros((6, 6))
    ax, tr = [0, 3], [1, 2, 4, 5]
    k[np.ix_(ax, ax)] = EA / h * np.array([[1, -1], [-1, 1]])
    m[np.ix_(ax, ax)] = rhoA * h / 6 * np.array([[2, 1], [1, 2]])
    k[np.ix_(tr, tr)] = EI / h ** 3 * np.array([[12, 6 * h, -12, 6 * h],
                                                [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                                                [-12, -6 * h, 12, -6 * h],
                                                [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    m[np.ix_(tr, tr)] = rhoA * h / 420 * np.array([[156, 22 * h, 54, -13 * h],
                                                   [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                                   [54, 13 * h, 156, -22 * h],
                                                   [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    R = np.array([[cx, cy, 0], [-cy, cx, 0], [0, 0, 1]])
    T = np.kron(np.eye(2), R)
    return T.T @ k @ T, T.T @ m @ T


def fe_frequencies(L, rhoA, EA, EI, c, rhoA_r, EA_r, EI_r, gamma, m_B=0.0, n=3,
                   elements_per_length=40):
    """The n lowest frequencies of a finite-element model of the frame: A = (-L, 0), B = (0, 0),
    D = c (-cos gamma, sin gamma) (so the angle between B -> A and B -> D is gamma); each member
    meshed from its fixed end to B; A and D pinned (translations fixed, rotation free); at B the
    members share the translations only (a pin: each keeps its own end rotation); m_B lumped on
    B's translations."""
    B = np.zeros(2)
    members = [(np.array([-L, 0.0]), L, rhoA, EA, EI),
               (c * np.array([-np.cos(gamma), np.sin(gamma)]), c, rhoA_r, EA_r, EI_r)]
    ndof = 2                                   # B's (X, Y) are dofs 0, 1
    blocks = []
    for P, l, r, ea, ei in members:
        ne = max(8, int(round(elements_per_length * l)))
        # node j's dofs: (u, v, theta); node 0 (the fixed pin) has no translation dofs, node ne
        # (B) has B's; every node has its own rotation
        nodes = []
        for j in range(ne + 1):
            if j == 0:
                trans = [-1, -1]
            elif j == ne:
                trans = [0, 1]
            else:
                trans = [ndof, ndof + 1]
                ndof += 2
            nodes.append(trans + [ndof])
            ndof += 1
        d = (B - P) / l
        blocks.append((nodes, l / ne, r, ea, ei, d))
    K = np.zeros((ndof, ndof))
    M = np.zeros((ndof, ndof))
    for nodes, h, r, ea, ei, d in blocks:
        ke, me = _element(h, r, ea, ei, d[0], d[1])
        for j in range(len(nodes) - 1):
            idx = np.array(nodes[j] + nodes[j + 1])
            keep = idx >= 0
            sub = np.ix_(idx[keep], idx[keep])
            K[sub] += ke[np.ix_(keep, keep)]
            M[sub] += me[np.ix_(keep, keep)]
    M[0, 0] += m_B
    M[1, 1] += m_B
    lam = eigh(K, M, eigvals_only=True, subset_by_index=[0, n - 1])
    return np.sqrt(np.abs(lam))


# ----------------------------------------------------------------------------------------------
# Closed forms
# ----------------------------------------------------------------------------------------------

def pinned_free_roots(k):
    """The first k positive roots z of tan z = tanh z (a pinned-free beam: omega = z^2 / L^2
    sqrt(EI / rhoA)); the j-th lies in (j pi, (j + 1/2) pi)."""
    f = lambda z: np.sin(z) * np.cosh(z) - np.cos(z) * np.sinh(z)
    return np.array([brentq(f, j * PI + 1e-6, (j + 0.5) * PI - 1e-6, xtol=1e-15)
                     for j in range(1, k + 1)])


def rod_end_mass_roots(ratio, k):
    """The first k positive roots y of y tan y = ratio (a fixed rod of mass rhoA L carrying m_B at
    its free end, ratio = rhoA L / m_B; omega = y / L sqrt(EA / rhoA)); ratio = inf gives the
    fixed-free rod, y = (j - 1/2) pi."""
    if np.isinf(ratio):
        return (np.arange(1, k + 1) - 0.5) * PI
    f = lambda y: y * np.sin(y) - ratio * np.cos(y)
    return np.array([brentq(f, j * PI + 1e-12, (j + 0.5) * PI - 1e-12, xtol=1e-15)
                     for j in range(k)])


def test_closed_form_helpers_are_what_they_say():
    """The closed-form roots used below (so that a wrong root finder here cannot hide)."""
    z = pinned_free_roots(3)
    assert np.allclose(z, [3.926602312047919, 7.068582745628732, 10.210176122813031], rtol=1e-12)
    assert np.allclose(np.tan(z), np.tanh(z), rtol=1e-9)
    y = rod_end_mass_roots(2.0, 2)
    assert np.allclose(y * np.tan(y), 2.0, rtol=1e-10) and 0 < y[0] < PI / 2


# ----------------------------------------------------------------------------------------------
# The member stiffnesses
# ----------------------------------------------------------------------------------------------

def test_member_stiffness_limits_and_series_switch():
    """Static limits (EA / l axially, none transversely), the rigid-body mass rhoA l / 3 in both
    directions at low frequency (with the first correction, 2 (beta l)^4 / 315, transversely),
    agreement of the series and the closed forms where the code switches between them, and the
    closed forms typed in again at a general frequency."""
    r, ea, ei = section(0.02)
    l = 0.7
    assert lf.member_stiffness(0.0, l, r, ea, ei) == (ea / l, 0.0)
    w = 1e-3
    k_ax, k_tr = lf.member_stiffness(w, l, r, ea, ei)
    assert k_ax == pytest.approx(ea / l - r * l * w * w / 3, rel=1e-12, abs=0)
    z4 = r * w * w / ei * l ** 4                     # (beta l)^4
    assert k_tr == pytest.approx(-r * l * w * w / 3 * (1 + 2 * z4 / 315), rel=1e-12, abs=0)
    # just below the switch to the series (argument 0.05), the series equal the closed forms
    # (which lose only ~1e-13 to cancellation there)
    for which in (0, 1):
        if which == 1:
            w_s = (lf._SMALL / l) ** 2 * np.sqrt(ei / r) * (1 - 1e-6)
        else:
            w_s = lf._SMALL / l * np.sqrt(ea / r) * (1 - 1e-6)
        alpha, beta = w_s * np.sqrt(r / ea), (r * w_s * w_s / ei) ** 0.25
        closed = (ea * alpha / np.tan(alpha * l),
                  ei * beta ** 3 / 2 * (1 / np.tan(beta * l) - 1 / np.tanh(beta * l)))[which]
        assert lf.member_stiffness(w_s, l, r, ea, ei)[which] == pytest.approx(closed, rel=1e-11,
                                                                               abs=0)
    # closed forms at a general frequency, typed in again
    w = 2.3
    alpha, beta = w * np.sqrt(r / ea), (r * w * w / ei) ** 0.25
    k_ax, k_tr = lf.member_stiffness(w, l, r, ea, ei)
    assert k_ax == pytest.approx(ea * alpha / np.tan(alpha * l), rel=1e-12)
    assert k_tr == pytest.approx(
        ei * beta ** 3 / 2 * (1 / np.tan(beta * l) - 1 / np.tanh(beta * l)), rel=1e-12)


def test_transverse_stiffness_vanishes_at_pinned_free_frequencies_and_poles_at_pinned_pinned():
    """k_tr = 0 is the pinned-free beam (tan z = tanh z); k_tr changes from -inf to +inf across
    each pinned-pinned frequency, where the member's count J steps by one."""
    r, ea, ei = section(0.02)
    l = 1.0
    for z in pinned_free_roots(3):
        w = z ** 2 * np.sqrt(ei / r)
        k_tr = lf.member_stiffness(w, l, r, ea, ei)[1]
        assert abs(k_tr) < 1e-10 * ei * (z / l) ** 3
    for j in (1, 2, 3):
        w = lf.pinned_pinned_bending(l, r, ei, j)
        below = lf.member_stiffness(w * (1 - 1e-7), l, r, ea, ei)[1]
        above = lf.member_stiffness(w * (1 + 1e-7), l, r, ea, ei)[1]
        assert below < -1e3 and above > 1e3
        assert lf.member_count(w * (1 + 1e-7), l, r, ea, ei) \
            - lf.member_count(w * (1 - 1e-7), l, r, ea, ei) == 1


def test_count_is_consistent_on_a_pole_to_the_last_bit():
    """At and within a few ulps of a pinned-pinned pole (where sin(beta l) is round-off and the
    computed beta l may fall on either side of j pi) the member's transverse share of the count,
    J_tr + [k_tr < 0], is j: the count follows the side that the computed sine (and so k_tr)
    says, and never counts the pole twice or not at all."""
    r, _, ei = section(0.02)
    ea = 1e8
    for l in (1.0, 0.5, 0.7, 1.2):
        for j in (1, 2, 3, 5):
            w = lf.pinned_pinned_bending(l, r, ei, j)
            assert w * np.sqrt(r / ea) * l < PI        # below the first axial pole
            shares = set()
            for k in range(-6, 7):
                om = w + k * np.spacing(w)
                k_tr = lf.member_stiffness(om, l, r, ea, ei)[1]
                shares.add(lf.member_count(om, l, r, ea, ei) + int(k_tr < 0))
            assert shares == {j}, (l, j, shares)


# ----------------------------------------------------------------------------------------------
# (a) Limits with closed forms
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("m_B", [0.0, 0.5])
def test_rigid_massless_rocker_at_right_angle(m_B):
    """A massless rocker, axially rigid (EA_r = 1e12), at gamma = 90 deg holds B against the
    coupler's transverse motion and leaves its axial motion free (a roller along the coupler's
    axis).  The frame's spectrum is then the union of the coupler's pinned-pinned bending
    frequencies (j pi)^2 sqrt(EI / rhoA) / L^2 (B does not move: m_B plays no part) and its axial
    frequencies as a fixed rod with m_B at the free end (y tan y = rhoA L / m_B, or fixed-free).
    The bending ones sit within 1e-12 of the coupler's poles: the count must still find them."""
    r, ea, ei = section(0.02)
    w = lf.frequencies(1.0, r, ea, ei, 0.5, 0.0, 1e12, ei, np.radians(90.0), m_B, n=5)
    ratio = np.inf if m_B == 0 else r * 1.0 / m_B
    axial = rod_end_mass_roots(ratio, 2) * np.sqrt(ea / r)
    bending = [lf.pinned_pinned_bending(1.0, r, ei, j) for j in (1, 2, 3, 4, 5)]
    expected = np.sort(np.concatenate([axial, bending]))[:5]
    assert np.allclose(w, expected, rtol=1e-9), (w, expected)
    # the axial ones do move into the lowest five (7.96 fixed-free, 5.46 with m_B = 0.5)
    assert np.any(np.isclose(w, axial[0], rtol=1e-9))


@pytest.mark.parametrize("m_B", [0.0, 0.5])
def test_axially_rigid_members_fix_B(m_B):
    """Both members axially rigid (EA = 1e12) at gamma = 60 deg fix B; the spectrum is the union
    of both members' pinned-pinned bending frequencies.  With c = L/2 and one section the
    rocker's (4, 16, ...) coincide with the coupler's second and fourth: double frequencies, on
    top of each other's poles."""
    r, _, ei = section(0.02)
    w = lf.frequencies(1.0, r, 1e12, ei, 0.5, r, 1e12, ei, np.radians(60.0), m_B, n=6)
    expected = [1.0, 4.0, 4.0, 9.0, 16.0, 16.0]
    assert np.allclose(w, expected, rtol=1e-9), w


def test_free_coupler_end_is_a_pinned_free_beam():
    """A massless, all but limp rocker (EA_r = EI_r = 1e-12, rhoA_r = 0) leaves B free: the
    coupler is a pinned-free beam, a rigid swing about A (frequency ~ 1e-6) and then
    tan(beta L) = tanh(beta L) in bending, the fixed-free rod axially (7.96 at eps = 0.02)."""
    r, ea, ei = section(0.02)
    w = lf.frequencies(1.0, r, ea, ei, 0.5, 0.0, 1e-12, 1e-12, np.radians(60.0), 0.0, n=4)
    assert w[0] < 1e-5
    bending = pinned_free_roots(3) ** 2 * np.sqrt(ei / r)
    axial = 0.5 * PI * np.sqrt(ea / r)
    expected = np.sort(np.concatenate([bending, [axial]]))[:3]
    assert np.allclose(w[1:], expected, rtol=1e-9), (w, expected)


def test_heavy_end_mass_on_the_members_static_springs():
    """A heavy m_B (1e4) vibrates on the members' static stiffness EA / l e e^T, carrying a third
    of each member's mass in every direction (rhoA l / 3 axially and transversely alike):
    omega^2 = eig(K_static) / (m_B + (rhoA L + rhoA_r c) / 3), to O(member mass / m_B)^2."""
    a = default_args(eps=0.02, c=0.8, gamma_deg=70.0, m_B=1e4)
    a["rhoA_r"], a["EA_r"] = 0.6, 3.0 * a["EA"]
    e_c, e_r = lf.directions(a["gamma"])
    K_s = a["EA"] / a["L"] * np.outer(e_c, e_c) + a["EA_r"] / a["c"] * np.outer(e_r, e_r)
    m = a["m_B"] + (a["rhoA"] * a["L"] + a["rhoA_r"] * a["c"]) / 3
    expected = np.sqrt(np.linalg.eigvalsh(K_s) / m)
    w = lf.frequencies(**a, n=2)
    assert np.allclose(w, expected, rtol=1e-6), (w, expected)
    assert not np.allclose(w, np.sqrt(np.linalg.eigvalsh(K_s) / a["m_B"]), rtol=1e-6)


def test_toggle_position_is_a_mechanism():
    """gamma = 0 (coupler and rocker collinear): B moves across the common line with no static
    stiffness, a zero frequency.  The axial motion is then that of one fixed-fixed rod of length
    L + c (same section, m_B = 0): omega = j pi / (L + c) sqrt(EA / rhoA); and the coupler's
    second pinned-pinned mode and the rocker's first (both 4, c = L/2) combine into a frame mode
    with B at rest, exactly on the two members' coincident poles.  Near the toggle the lowest
    frequency is B's mass and the members' thirds on the two axial springs in series:
    omega^2 = sin^2(gamma) k_c k_r / (k_c + k_r) / (m_B + (rhoA L + rhoA_r c) / 3),
    k_c = EA / L, k_r = EA_r / c; the others tend to their gamma = 0 values."""
    a = default_args(gamma_deg=0.0)
    w0 = lf.frequencies(**a, n=6)
    assert w0[0] < 1e-12
    assert w0[2] == pytest.approx(4.0, rel=1e-12)
    assert w0[5] == pytest.approx(PI / 1.5 * np.sqrt(a["EA"] / a["rhoA"]), rel=1e-12)
    for m_B in (0.0, 0.5):
        b = dict(a, m_B=m_B)
        w0 = lf.frequencies(**b, n=4)
        b["gamma"] = np.radians(1e-3)
        w = lf.frequencies(**b, n=4)
        k_c, k_r = b["EA"] / b["L"], b["EA_r"] / b["c"]
        m = m_B + (b["rhoA"] * b["L"] + b["rhoA_r"] * b["c"]) / 3
        assert w[0] == pytest.approx(np.sin(b["gamma"]) * np.sqrt(k_c * k_r / (k_c + k_r) / m),
                                     rel=1e-6)
        assert np.allclose(w0[1:], w[1:], rtol=1e-8)


# ----------------------------------------------------------------------------------------------
# (b) Against the finite-element frame
# ----------------------------------------------------------------------------------------------

GENERAL = [
    # the intended case
    default_args(eps=0.02, c=0.5, gamma_deg=60.0, m_B=0.0),
    default_args(eps=0.02, c=0.5, gamma_deg=60.0, m_B=0.5),
    # the slenderest, and a long rocker
    default_args(eps=0.01, c=1.2, gamma_deg=110.0, m_B=0.2),
    # different sections for the rocker
    dict(L=1.0, rhoA=1.0, EA=EI0 / 0.03 ** 2, EI=EI0, c=0.5, rhoA_r=1.7, EA_r=2.5 * EI0 / 0.03 ** 2,
         EI_r=0.4 * EI0, gamma=np.radians(60.0), m_B=0.3),
    # a stocky one: axial frequencies among the lowest
    default_args(eps=0.05, c=0.9, gamma_deg=35.0, m_B=0.5),
]


@pytest.mark.parametrize("a", GENERAL, ids=range(len(GENERAL)))
def test_dynamic_stiffness_equals_fine_finite_elements(a):
    """The first six exact frequencies equal a 40-elements-per-unit-length FE model's to 1e-4
    (the consistent-mass FE converges from above: its frequencies are not below the exact ones,
    but for eigh's round-off)."""
    w = lf.frequencies(**a, n=6)
    w_fe = fe_frequencies(**a, n=6)
    assert np.allclose(w, w_fe, rtol=1e-4), (w, w_fe)
    assert np.all(w_fe >= w * (1 - 1e-7))    # (eigh's round-off: ~1e-8 here)


def test_count_equals_finite_element_count():
    """The Wittrick-Williams count N(omega) equals the number of FE frequencies below omega midway
    between the first twelve frequencies and on either side (1e-9) of the members' poles
    (coupler pinned-pinned 1, 4, 9, 16; rocker 4, 16: coincident poles), and steps by one across
    each computed frequency.  (The FE's axial-dominated modes 9, 11, 12 converge only as h^2 with
    linear bar elements: 1e-3 there.)"""
    a = default_args(eps=0.02, c=0.5, gamma_deg=60.0, m_B=0.5)
    w_fe = fe_frequencies(**a, n=12)
    w = lf.frequencies(**a, n=12)
    assert np.allclose(w, w_fe, rtol=2e-3)
    assert np.all(np.diff(w) > 1e-3)            # simple frequencies (used just below)
    probes = np.concatenate([0.5 * (w[1:] + w[:-1]),
                             [lf.pinned_pinned_bending(1.0, 1.0, EI0, j) * (1 + s)
                              for j in (1, 2, 3, 4) for s in (-1e-9, 1e-9)]])
    for om in probes:
        assert lf.count_below(om, **a) == np.sum(w_fe < om), om
    for i, om in enumerate(w):
        assert lf.count_below(om * (1 - 1e-9), **a) == i
        assert lf.count_below(om * (1 + 1e-9), **a) == i + 1


# ----------------------------------------------------------------------------------------------
# (c) The angle gamma
# ----------------------------------------------------------------------------------------------

def test_supplementary_angles_are_the_same_frame():
    """Only the members' lines matter: gamma and pi - gamma give the same frequencies (and the
    FE frame, whose geometry does differ, agrees)."""
    a = default_args(gamma_deg=60.0, m_B=0.5)
    b = dict(a, gamma=np.radians(120.0))
    assert np.allclose(lf.frequencies(**a, n=4), lf.frequencies(**b, n=4), rtol=1e-13)
    assert np.allclose(fe_frequencies(**b, n=4), lf.frequencies(**a, n=4), rtol=1e-4)


@pytest.mark.parametrize("eps,m_B", [(0.02, 0.0), (0.01, 0.5)])
def test_continuous_in_gamma(eps, m_B):
    """Along gamma = 20 .. 160 deg in 1-deg steps each of the first three frequencies moves
    smoothly: no step larger than 5 % and every second difference below 5e-3 (relative; the
    largest true ones are about 3.3 % and 2.4e-3, near 20 deg, where the lowest modes fall
    towards the toggle position's zero).  A missed root would shift the later frequencies down
    one place, a jump by the gap between modes: the second is over twice the first here, but the
    second and third come within 1 % of each other near 90 deg, where the FE spot check (and the
    count, at every angle) is the guard.  Spot checks against the FE frame at three angles; at
    every angle, N(omega) steps from i to i + 1 across the i-th computed frequency."""
    g = np.arange(20.0, 160.5, 1.0)
    W = np.array([lf.frequencies(**default_args(eps=eps, gamma_deg=x, m_B=m_B), n=3) for x in g])
    assert np.all(np.diff(W, axis=1) > 0)
    assert np.min(W[:, 1] / W[:, 0]) > 2.0
    for x, w in zip(g, W):
        a = default_args(eps=eps, gamma_deg=x, m_B=m_B)
        assert [lf.count_below(om * s, **a) for om in w for s in (1 - 1e-9, 1 + 1e-9)] \
            == [0, 1, 1, 2, 2, 3]
    step = np.abs(np.diff(W, axis=0)) / W[:-1]
    assert step.max() < 0.05, step.max()
    second = np.abs(np.diff(W, 2, axis=0)) / W[1:-1]
    assert second.max() < 5e-3, second.max()
    for x in (25.0, 90.0, 155.0):
        i = int(np.argmin(np.abs(g - x)))
        w_fe = fe_frequencies(**default_args(eps=eps, gamma_deg=x, m_B=m_B), n=3)
        assert np.allclose(W[i], w_fe, rtol=1e-4)
