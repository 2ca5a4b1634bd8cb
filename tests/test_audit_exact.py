"""The audit's comparison of approach A with the exact strain (section 7, issue 26 item 5): the
series of what A drops, checked against the exact measures evaluated directly; the weights along a
real revolution, checked against the leading dropped term computed here from the nodal values and
against the order the series predicts along a sequence of amplitudes."""

import math

import numpy as np
import pytest
import sympy as sp

import crankgen
from crankgen._derive.audit import exact_strain as X
from crankgen.audit import exact_weights as W
from crankgen.audit.term_weights import consistent_case
from crankgen.discrete.mesh import NODE_DOFS, PSI, U, V

VALUES = {X.u_x: sp.Rational(37, 100), X.v_x: sp.Rational(-81, 100), X.v_xx: sp.Rational(64, 100),
          X.u_xx: sp.Rational(-29, 100), X.m2: sp.Rational(93, 100), X.var: sp.Rational(41, 100)}


@pytest.mark.parametrize("name", list(X.MEASURES))
def test_the_dropped_terms_are_the_series_of_the_exact_measures(name):
    """exact - A - (leading dropped term) evaluated at values scaled by the ordering, delta = 1e-2
    and 1e-3: what is left falls by delta^(k + 2) (the next term), k the leading term's order."""
    exact, approx, _ = X.MEASURES[name]
    (k, lead), (k_next, _) = X.dropped(name)
    assert k == X.a_order(name) + 2 and k_next == k + 2

    def rest(delta):                       # exact rationals, evaluated to 50 digits
        at = {sym: value * delta ** X.ORDER[sym] for sym, value in VALUES.items()}
        return float(((exact - approx).subs(at) - lead.subs(VALUES) * delta ** k).evalf(50))
    r1, r2 = rest(sp.Rational(1, 100)), rest(sp.Rational(1, 1000))
    assert abs(r1) < 1e-2 ** (k + 1)
    assert math.log10(abs(r1 / r2)) == pytest.approx(k + 2, abs=0.05)


def test_the_energy_difference_starts_two_orders_above_as_bending_energy():
    energy = X.energy_difference()
    assert min(energy) == 4 and set(energy[4].free_symbols) >= {X.v_xx, X.u_x}
    assert X.s.EA not in energy[4].free_symbols           # the membrane part enters at delta^6


def _hermite_slopes(q, l, zeta):
    """v_x of cubic Hermite elements (nodal v, psi at both ends) at the abscissae zeta in [0, 1]."""
    v1, p1, v2, p2 = q[..., V], q[..., PSI], q[..., NODE_DOFS + V], q[..., NODE_DOFS + PSI]
    z = np.asarray(zeta)[:, None, None]
    dn = [(-6 * z + 6 * z ** 2) / l, 1 - 4 * z + 3 * z ** 2, (6 * z - 6 * z ** 2) / l, -2 * z + 3 * z ** 2]
    return dn[0] * v1 + dn[1] * p1 + dn[2] * v2 + dn[3] * p2


@pytest.fixture(scope="module")
def orbit():
    case = consistent_case(0.01, 0.8, 4, steps_per_rev=50)
    return case, crankgen.steady_state(case=case)


def test_the_membrane_difference_is_the_leading_dropped_term_at_small_amplitude(orbit):
    """The exact stretch |r'| - 1 of A's own deformation field less A's strain u_x + v_x^2/2, at the
    element midpoints of the revolution scaled in the ordering, is the leading dropped term
    -(4 u_x v_x^2 + v_x^4) / 8 (7.1) to relative order delta^2: both evaluated here from the nodal
    values (u linear, v the Hermite cubic, numpy.hypot); and the audit's membrane weight is the
    RMS of that difference over the RMS of A's strain."""
    from crankgen.results.outputs import StateHistory
    case, st = orbit
    n, l = case.n_elements, 1.0 / case.n_elements
    for s, tol in ((0.25, 0.05), (0.0625, 0.004)):
        states = W.scaled_states(case, st.states, s)
        q = StateHistory(case, st.t, states).element_vectors()
        u_x = (q[..., NODE_DOFS + U] - q[..., U]) / l
        v_x = _hermite_slopes(q, l, [0.5])[0]
        e_a = u_x + v_x**2 / 2
        measured = np.hypot(1 + u_x, v_x) - 1 - e_a
        predicted = -(4 * u_x * v_x**2 + v_x**4) / 8
        assert np.max(np.abs(measured - predicted)) < tol * np.max(np.abs(predicted))
        rms = lambda x: np.sqrt(np.mean(np.square(x)))          # noqa: E731
        # |r'| - 1 less e_a cancels most digits (the difference is ~1e-3 of e_a at s = 0.0625): the
        # audit's sqrt and hypot here agree to 1.6e-9 of the weight (measured)
        assert W.weigh(case, st.t, states).membrane == pytest.approx(rms(measured) / rms(e_a), rel=1e-7)


def test_the_weights_fall_with_the_amplitude_as_the_series_order(orbit):
    """Along the revolution scaled in the ordering, each relative weight ~ delta^2: halving the
    amplitude divides it by 4 once the amplitude is small (slope 2 in log-log)."""
    case, st = orbit
    rows = W.scaled(case, st, (0.125, 0.0625, 0.03125))
    for key, tol in (("membrane", 0.1), ("curvature", 0.05), ("transverse", 0.15)):
        values = [getattr(r, key) for r in rows]
        slopes = np.log2(np.array(values[:-1]) / np.array(values[1:]))
        assert np.all(np.abs(slopes - 2.0) < tol), (key, slopes)
    assert rows[0].slope == pytest.approx(0.125 * W.weigh(case, st.t, st.states).slope, rel=1e-12)


def test_the_weights_of_a_real_revolution_are_large_where_the_slopes_are(orbit):
    case, st = orbit
    w = W.weigh(case, st.t, st.states, st.amplitude)
    assert 0.25 < w.slope < 0.4                     # max |v_x| ~ pi |v|/L, |v|/L ~ 0.09
    # measured: membrane 0.22, curvature 0.013, transverse 0.067 (the exact rod read with its own
    # axial unknowns settled to A's axial forces, the audit's definition since the exact rod's u is
    # cubic; the former element, read on A's nodal u, gave above 0.1)
    assert w.membrane > 0.1 and 1e-3 < w.curvature < 0.05 and 0.03 < w.transverse < 0.15

