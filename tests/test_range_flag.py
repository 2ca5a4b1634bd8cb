"""The range of the theory as data in the API (result.beyond_theory: a RangeFlag with its measures),
one warning per call, the command line's own report; and the joint forces' old names."""

import warnings

import numpy as np
import pytest

import crankgen
from crankgen.analyses import theory
from crankgen.declaration.cases import Case
from crankgen.errors import ParameterError
from crankgen.notices import BeyondTheoryWarning

SMALL = dict(n_elements=4, steps_per_rev=50)


def _run(fn, *args, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = fn(*args, **kw)
    return out, [w for w in caught if issubclass(w.category, BeyondTheoryWarning)]


def test_a_periodic_state_beyond_the_theory_says_so_as_data_and_warns_once():
    """Omega* = 1.0, eps = 0.01: max |v*| about 14, |v|/L = eps max|v*| = 0.14 > 0.1."""
    st, caught = _run(crankgen.steady_state, omega=1.0, **SMALL)
    assert st.status == "periodic"
    flag = st.beyond_theory
    assert flag and flag.beyond and flag.label == "yes"
    assert [m.name for m in flag.tripped] == ["deflection_over_L"]
    d = flag.measure("deflection_over_L")
    assert d.value == pytest.approx(0.01 * st.amplitude, rel=1e-12) and d.limit == theory.DEFLECTION_LIMIT
    s = flag.measure("axial_strain")
    assert s.value == pytest.approx(theory.axial_strain(st), rel=1e-12) and not s.exceeded
    assert len(caught) == 1
    text = str(caught[0].message)
    assert "\n" not in text and "|v|/L = " in text and "> 0.1" in text


def test_within_the_range_the_flag_is_false_and_silent():
    st, caught = _run(crankgen.steady_state, omega=0.5, **SMALL)
    assert not st.beyond_theory and st.beyond_theory.label == "no" and st.beyond_theory.known
    assert st.beyond_theory.tripped == () and caught == []


def test_many_states_warn_once_and_a_failure_is_unknown():
    cases = [Case(omega=w, **SMALL) for w in (0.5, 1.0, 1.02)]
    states, caught = _run(crankgen.steady_states, cases)
    assert [bool(s.beyond_theory) for s in states] == [False, True, True]
    assert len(caught) == 1 and "(and 1 more of 3)" in str(caught[0].message)
    failed = crankgen.steady_state(case=Case(formulation="lagrange", approach="B", omega=0.8, n_elements=4))
    assert failed.status == "failed" and not failed.beyond_theory.known and failed.beyond_theory.label == ""


def test_a_run_carries_its_flag_over_every_stored_step():
    r, caught = _run(crankgen.simulate, omega=1.4, revolutions=8, **SMALL)
    flag = r.beyond_theory
    assert flag and len(caught) == 1
    assert flag.measure("deflection_over_L").value == pytest.approx(0.01 * np.max(np.abs(r.v_mid)), rel=1e-12)
    assert flag.measure("axial_strain").value == pytest.approx(np.max(theory.axial_strain(r, per_step=True)))


def test_continuation_branches_carry_the_flag_point_by_point():
    d, caught = _run(crankgen.continuation, crankgen.Mechanism(eps=0.01), "omega", 0.9, 1.2, max_period=2,
                     **SMALL)
    assert len(caught) == 1
    for br in d.branches:
        np.testing.assert_allclose(br.deflection_over_L, 0.01 * np.abs(br.amplitude), rtol=1e-12)
        assert np.array_equal(br.beyond_theory, br.deflection_over_L > 0.1)
    assert d.beyond_theory and any(br.beyond_theory.any() for br in d.branches)


def test_the_command_line_reports_it_in_its_own_line_without_the_warning(tmp_path, capsys):
    from crankgen.cli.main import main
    rc = main(["steady", "--omega", "1.0", "--elements", "4", "--steps-per-rev", "50", "--out", str(tmp_path),
               "--quiet"])
    out, err = capsys.readouterr()
    assert rc == 0 and "BEYOND THE THEORY" in out and "BeyondTheoryWarning" not in err
    import csv
    row = next(csv.DictReader(open(tmp_path / "steady.csv")))
    assert row["beyond_theory"] == "yes"


def test_the_joint_forces_old_names_say_their_new_ones():
    r = crankgen.simulate(omega=0.5, revolutions=0.1, **SMALL)
    with pytest.raises(AttributeError, match="pin_force_x was renamed crank_on_rod_x"):
        r.pin_force_x
    with pytest.raises(ParameterError, match="end_force_y was renamed guide_on_slider_y"):
        r.quantity("end_force_y")
    assert not hasattr(r, "end_force_x")
    with pytest.raises(ParameterError, match="exists for the circle guide only"):
        r.rod_on_tip_x
