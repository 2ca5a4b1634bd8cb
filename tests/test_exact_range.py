"""The range of the theory revisited (issue 26 item 6): a result of the paper's or the consistent
model beyond the paper's range points to model="exact"; the exact rod is judged by its own limits
(slenderness: no shear; outer-fibre strain: a linear elastic material; section rotation: its
element), and says which it left."""

import csv
import math
import warnings

import numpy as np
import pytest

import crankgen
from crankgen.analyses import theory
from crankgen.notices import BeyondTheoryWarning

SMALL = dict(n_elements=4, steps_per_rev=50)


def _run(fn, *args, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = fn(*args, **kw)
    return out, [str(w.message) for w in caught if issubclass(w.category, BeyondTheoryWarning)]


@pytest.mark.parametrize("model, eps, omega, tripped", [
    ("consistent", 0.01, 1.0, ["deflection_over_L"]),     # |v|/L about 0.14 > 0.1
    ("paper", 0.1, 0.8, ["axial_strain"])])               # a thick rod: u_x + v_x^2/2 about 0.14 > 0.01
def test_beyond_the_papers_range_points_to_the_exact_model(model, eps, omega, tripped):
    st, caught = _run(crankgen.steady_state, crankgen.Mechanism(eps=eps), omega=omega, model=model, **SMALL)
    flag = st.beyond_theory
    assert flag and [m.name for m in flag.tripped] == tripped
    assert flag.criterion == theory.CRITERION and not flag.exact
    assert 'model="exact"' in flag.remedy and 'model="exact"' in str(flag) and 'model="exact"' in flag.note
    assert len(caught) == 1 and 'model="exact"' in caught[0]


def test_the_exact_rod_within_its_limits_where_the_consistent_flag_fires_is_silent():
    """A rod ten times as slender (eps = 0.001) at Omega* = 1.0: the same |v|/L about 0.15 (v* scales
    as 1/eps), beyond the paper's range, but its outer fibres strain about eps / 0.01 less (0.26 %)
    and its sections turn about 28 degrees: within the exact rod's limits."""
    mech = crankgen.Mechanism(eps=0.001)
    cons, caught = _run(crankgen.steady_state, mech, omega=1.0, model="consistent", **SMALL)
    assert cons.beyond_theory and len(caught) == 1
    ex, caught = _run(crankgen.steady_state, mech, omega=1.0, model="exact", **SMALL)
    assert ex.status == "periodic" and caught == []
    assert 0.001 * ex.amplitude > theory.DEFLECTION_LIMIT            # where the paper's flag fires
    flag = ex.beyond_theory
    assert flag.exact and flag.known and not flag and flag.label == "no" and flag.note == ""
    names = [m.name for m in flag.measures]
    assert names == ["slenderness", "fibre_strain", "section_rotation"]
    assert flag.measure("slenderness").value == 0.001
    # the measures against the rod's other outputs: the outer-fibre strain is e -+ sqrt(3) eps M*
    # (M* = kappa L), so it lies between the bending part alone less the membrane strain and their sum
    x = np.linspace(0.0, 1.0, 9)
    bending = math.sqrt(3.0) * 0.001 * np.max(np.abs(ex.bending_moment(x)))
    membrane = np.max(np.abs(ex.axial_force(x))) * 0.001 ** 2        # N* = e EA L^2 / EI = e / eps^2
    fibre = flag.measure("fibre_strain").value
    assert bending - membrane - 1e-12 <= fibre <= bending + membrane + 1e-12 and 0.001 < fibre < 0.005
    # the sections' rotation: the slope of the deflected centre line, asin(v_x / lambda) ~ atan(v_x)
    # at this small stretch; the mid-span deflection |v| / L ~ 0.15 of a half sine gives ~ pi 0.15
    rotation = flag.measure("section_rotation").value
    assert 15.0 < rotation < 45.0


def test_an_exact_result_beyond_its_own_limits_warns_and_says_which():
    # the outer-fibre strain: eps = 0.01, Omega* = 1.0 bends the fibres by about 2.6 %
    st, caught = _run(crankgen.steady_state, crankgen.Mechanism(eps=0.01), omega=1.0, model="exact", **SMALL)
    flag = st.beyond_theory
    assert flag and [m.name for m in flag.tripped] == ["fibre_strain"]
    assert flag.measure("fibre_strain").value > 0.02
    assert len(caught) == 1 and "outer-fibre strain" in caught[0] and "plasticity" in caught[0]
    assert 'model="exact"' not in caught[0] and "|v|/L" not in flag.reason
    # the slenderness: a thick rod (eps = 0.08) slowly (Omega* = 0.1), small strains, but no shear in the model
    st, caught = _run(crankgen.steady_state, crankgen.Mechanism(eps=0.08), omega=0.1, model="exact", **SMALL)
    flag = st.beyond_theory
    assert [m.name for m in flag.tripped] == ["slenderness"]
    assert len(caught) == 1 and "slenderness r/L = 0.08 > 0.05" in caught[0] and "shear" in caught[0]


def test_the_exact_limits_as_data_name_what_they_leave_out():
    """The section rotation is reported, not limited (the element turns through any angle): a
    rotation past 90 degrees trips nothing; the limits that remain name what they leave out."""
    for rotation in (59.0, 75.0, 170.0):
        flag = theory.exact_range_flag(0.01, 0.001, rotation)
        assert not flag and flag.known and not flag.tripped
        assert f"section rotation (deg) = {rotation:.3g}" in str(flag) and ">" not in str(flag)
        assert flag.measure("section_rotation").value == rotation
    flag = theory.exact_range_flag(0.08, 0.001, 170.0)
    assert [m.name for m in flag.tripped] == ["slenderness"] and "shear" in flag.remedy
    flag = theory.exact_range_flag(0.01, 0.02, 10.0)
    assert [m.name for m in flag.tripped] == ["fibre_strain"] and "plasticity" in flag.remedy
    assert not theory.exact_range_flag().known and theory.exact_range_flag().label == ""


def test_steady_csv_carries_the_exact_rods_measures_and_the_notes(tmp_path, capsys):
    from crankgen.cli.main import main
    for model, eps, out in (("exact", "0.001", tmp_path / "exact"), ("consistent", "0.001", tmp_path / "cons")):
        rc = main(["steady", "--model", model, "--eps", eps, "--omega", "1.0", "--elements", "4",
                   "--steps-per-rev", "50", "--out", str(out), "--quiet"])
        assert rc == 0
    text = capsys.readouterr().out
    exact = next(csv.DictReader(open(tmp_path / "exact" / "steady.csv")))
    cons = next(csv.DictReader(open(tmp_path / "cons" / "steady.csv")))
    assert exact["beyond_theory"] == "no" and exact["range_note"] == ""
    assert 0.001 < float(exact["fibre_strain"]) < 0.005 and 15 < float(exact["section_rotation_deg"]) < 45
    assert float(exact["deflection_over_L"]) > 0.1                       # measured, not its limit
    assert cons["beyond_theory"] == "yes" and 'model="exact"' in cons["range_note"]
    assert cons["fibre_strain"] == "" and cons["section_rotation_deg"] == ""
    assert text.count("BEYOND THE THEORY") == 1 and 'model="exact"' in text


def test_an_exact_continuation_flags_its_points_by_the_outer_fibre_strain(tmp_path):
    d, caught = _run(crankgen.continuation, crankgen.Mechanism(eps=0.01), "omega", 0.5, 0.9, max_period=1,
                     model="exact", **SMALL)
    br = d.branches[0]
    strain = br.quantities["peak_strain"]
    assert np.array_equal(br.beyond_theory, strain > theory.FIBRE_STRAIN_LIMIT)
    assert not br.beyond_theory[0] and br.beyond_theory[-1]          # 0.4 % at 0.5, 2.7 % at 0.9
    assert d.beyond_theory.exact and [m.name for m in d.beyond_theory.tripped] == ["fibre_strain"]
    assert len(caught) == 1 and "outer-fibre strain" in caught[0] and "|v|/L" not in caught[0]
    d.to_csv(tmp_path)
    rows = list(csv.DictReader(open(tmp_path / "branches.csv")))
    assert [r["beyond_theory"] for r in rows if r["branch"] == "0"] == ["yes" if b else "no" for b in br.beyond_theory]
