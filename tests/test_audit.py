"""Checks of the symbolic audit (crankgen._derive.audit) and of its report (crankgen.audit).

Expected terms are built here independently (from the shape functions, the energies of eqs. 2-7,
or a concrete cross-section) rather than copied from the audit's output.
"""

import subprocess
import sys
from functools import lru_cache

import pytest
import sympy as sp

from crankgen import audit as report
from crankgen._derive import audit as A
from crankgen._derive import printed
from crankgen._derive import symbols as s
from crankgen._derive.energies import (
    kelvin_voigt_dissipation, rod_kinetic_energy, slider_kinetic_energy, strain_energy,
)
from crankgen._derive.euler_lagrange import gradient, jacobian, kinetic_residual
from crankgen._derive.shape_functions import B_U, B_V, N_U, N_V
from crankgen.errors import ParameterError

APPROACHES = ("A", "B", "C")


def integral(matrix):
    """int_0^l matrix dx via the antiderivative in zeta (independent of integrate_element)."""
    def one(entry):
        antiderivative = sp.Poly(sp.expand(entry * s.l), s.zeta).integrate()
        return sp.expand(antiderivative.eval(1) - antiderivative.eval(0))
    return sp.Matrix(matrix).applyfunc(one)


def is_zero(matrix):
    m = sp.Matrix(matrix).applyfunc(sp.expand)
    return m == sp.zeros(*m.shape)


def slope():
    return (B_V.T * s.q)[0, 0]


@lru_cache(maxsize=None)
def rod_T():
    return rod_kinetic_energy()


@lru_cache(maxsize=None)
def rod_U(approach):
    return strain_energy(approach)


@lru_cache(maxsize=None)
def elastic_force(approach):
    return gradient(rod_U(approach), s.q)


@lru_cache(maxsize=None)
def kelvin_voigt_force(approach):
    return gradient(kelvin_voigt_dissipation(approach), s.qd)


@lru_cache(maxsize=None)
def eq24_force(approach):
    return printed.rod_damping_residual(approach, A.printed_set(True))


@lru_cache(maxsize=None)
def exact_rod_inertia():
    return kinetic_residual(rod_T(), s.q, s.qd, s.qdd)


def time_powers(expr):
    """Powers of lam in expr after the change of time unit t -> t / lam (rates scale by lam)."""
    lam = sp.Symbol("lam", positive=True)
    scale = {s.thetad: lam * s.thetad, s.phid: lam * s.phid, s.phidd: lam**2 * s.phidd,
             s.thetadd: lam**2 * s.thetadd}
    scale.update({r: lam * r for r in tuple(s.qd) + tuple(s.qsd)})
    scale.update({r: lam**2 * r for r in tuple(s.qdd) + tuple(s.qsdd)})
    scaled = sp.expand(sp.sympify(expr).xreplace(scale))
    return {m[0] for m in sp.Poly(scaled, lam).monoms()}


# ---- import hygiene ---------------------------------------------------------------------------
def test_importing_crankgen_audit_does_not_import_sympy():
    code = "import sys, crankgen, crankgen.audit; sys.exit(1 if 'sympy' in sys.modules else 0)"
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


# ---- section 1 -------------------------------------------------------------------------------
def test_strain_energy_orders_sum_back_to_eq2():
    u_x, v_x, v_xx = A.u_x, A.v_x, A.v_xx
    eq2 = (s.EA * (u_x**2 + u_x * v_x**2 + v_x**4 / 4) + s.EI * v_xx**2) / 2
    parts = A.strain_orders()
    assert sorted(parts) == [2, 3, 4]
    assert sp.expand(sum(parts.values()) - eq2) == 0
    assert sp.expand(parts[3] - s.EA * u_x * v_x**2 / 2) == 0
    assert sp.expand(parts[4] - s.EA * v_x**4 / 8) == 0


@pytest.mark.parametrize("approach", APPROACHES)
def test_approach_strain_density_is_the_element_strain_energy(approach):
    assert sp.expand(A.element_integral(A.strain_density(approach)) - rod_U(approach)) == 0


def test_eq2_follows_from_vxx_on_a_rectangular_section():
    E, b, h, y = sp.symbols("E b h y", positive=True)
    u_x, v_x = A.u_x, A.v_x

    def section_energy(bending):
        strain = u_x + v_x**2 / 2 - y * bending
        return sp.expand(sp.integrate(E * strain**2 / 2 * b, (y, -h / 2, h / 2)))

    eq2 = (E * b * h * (u_x**2 + u_x * v_x**2 + v_x**4 / 4) + E * b * h**3 / 12 * A.v_xx**2) / 2
    assert sp.expand(section_energy(A.v_xx) - eq2) == 0
    assert sp.expand(section_energy(A.v_xxx) - eq2) != 0
    assert A.erratum_eq1().verdict == "confirmed"


def test_kinetic_density_integrates_to_the_element_kinetic_energy():
    assert sp.expand(A.element_integral(A.kinetic_density()) - rod_T()) == 0


def test_bilinear_kinetic_term_is_the_gyroscopic_form():
    W = integral(s.rhoA * s.phid * (N_U * N_V.T - N_V * N_U.T))
    assert is_zero(A.bilinear_matrix() - W)
    assert sp.expand(A.element_integral(A.kinetic_parts()["bilinear"]) - (s.qd.T * W * s.q)[0, 0]) == 0


def test_eq24_dissipation_is_negative_for_a_rigid_axial_translation():
    translation = sp.Matrix([1, 0, 0, 0, 1, 0, 0, 0])           # u of both nodes (u, v, psi, chi)
    for ap in APPROACHES:
        c = jacobian(eq24_force(ap), s.qd)
        D = sp.expand((translation.T * c * translation)[0, 0] / 2)
        assert sp.expand(D + s.mu * s.phid**2 * s.rhoA * s.l / 2) == 0
        rigid = A.eq24_rigid_dissipation(ap).subs({A.ud: 1, A.vd: 0, A.psid: 0})
        assert sp.expand(rigid + s.mu * s.phid**2 * s.rhoA / 2) == 0
    guide_force, _, s_rate = A.slider_eq24_guide_force()
    assert sp.simplify(guide_force + s.mu * s.ms * s.phid**2 * s_rate) == 0


# ---- weak forms equal the element residuals ------------------------------------------------
@pytest.mark.parametrize("formulation", ("lagrange", "paper", "printed"))
def test_inertia_weak_form_matches_element_residual(formulation):
    reference = exact_rod_inertia() if formulation == "lagrange" else printed.rod_kinetic_residual(
        A.printed_set(formulation == "paper"))
    assert is_zero(A.element_vector(A.rod_inertia_weak(formulation)) - reference)


@pytest.mark.parametrize("formulation", ("lagrange", "paper"))
@pytest.mark.parametrize("approach", APPROACHES)
def test_elastic_weak_form_matches_element_residual(formulation, approach):
    if formulation == "lagrange":
        reference = elastic_force(approach)
    else:
        reference = printed.rod_elastic_residual(approach, A.printed_set(True))[0]
    assert is_zero(A.element_vector(A.rod_elastic_weak(formulation, approach)) - reference)


@pytest.mark.parametrize("model", ("eq24", "kelvin-voigt"))
@pytest.mark.parametrize("approach", APPROACHES)
def test_damping_weak_form_matches_element_force(model, approach):
    if model == "eq24":
        reference = eq24_force(approach)
    else:
        reference = kelvin_voigt_force(approach)
    assert is_zero(A.element_vector(A.rod_damping_weak(model, approach)) - reference)


# ---- section 2: groups ---------------------------------------------------------------------
def test_classification_of_sample_terms():
    field = A.FIELD_VARS
    assert A.classify(s.EA * A.u_x * A.v_x, field, axial=False) == "cubic_transverse"
    assert A.classify(s.EA * A.v_x**2 / 2, field, axial=True) == "cubic_axial"
    assert A.classify(s.EA * A.v_x**3, field, axial=False) == "quartic"
    assert A.classify(2 * s.rhoA * s.phid * A.vd, field, axial=True) == "gyroscopic"
    assert A.classify(s.rhoA * s.phidd * A.v, field, axial=True) == "phidd"
    assert A.classify(s.rhoA * s.phidd * A.x, field, axial=False) == "forcing"
    assert A.classify(-s.mu * s.phid**2 * s.rhoA * A.ud, field, axial=True) == "damping_centrifugal"
    with pytest.raises(ValueError):
        A.classify(s.a * A.u, field, axial=True)


def test_groups_add_back_to_the_residual():
    total = exact_rod_inertia() + elastic_force("A")
    groups = A.group_vector(sp.ImmutableMatrix(total))
    assert is_zero(sum(groups.values(), sp.zeros(s.ELEMENT_DOFS, 1)) - total)
    assert set(groups) == {"inertia", "gyroscopic", "phidd", "centrifugal", "forcing", "stiffness",
                           "cubic_axial", "cubic_transverse", "quartic"}


def test_keep_table_matches_the_approaches():
    columns = A.ROD_COLUMNS
    table = {row.group: dict(zip(columns, row.status)) for row in A.rod_keep_table()}
    for ap in APPROACHES:
        assert table["gyroscopic"][("paper", ap)] == "dropped"
        assert table["phidd"][("paper", ap)] == "dropped"
        assert table["gyroscopic"][("lagrange", ap)] == "kept"
        assert table["cubic_axial"][("paper", ap)] == "dropped"
    assert table["cubic_transverse"][("paper", "A")] == "kept"
    assert table["cubic_axial"][("lagrange", "B")] == "kept"
    assert table["quartic"][("lagrange", "B")] == "dropped"
    assert table["quartic"][("paper", "A")] == "kept"
    assert table["cubic_transverse"][("lagrange", "C")] == "dropped"
    assert table["forcing"][("printed", "A")] == "differs"
    assert table["forcing"][("paper", "A")] == "kept"


# ---- section 3: printed form against the derivation ----------------------------------------
def test_rod_inertia_difference_is_the_gyroscopic_and_phidd_coupling():
    G = integral(s.rhoA * (N_U * N_V.T - N_V * N_U.T))
    expected = 2 * s.phid * G * s.qd + s.phidd * G * s.q
    paper = printed.rod_kinetic_residual(A.printed_set(True))
    assert is_zero(exact_rod_inertia() - paper - expected)
    items = [d for d in A.differences() if d.component == "rod inertia" and d.formulation == "paper"]
    assert sorted(d.group for d in items) == ["gyroscopic", "phidd"]
    assert is_zero(sum((d.element for d in items), sp.zeros(s.ELEMENT_DOFS, 1)) - expected)


@pytest.mark.parametrize("approach", APPROACHES)
def test_rod_elastic_difference_is_the_axial_force_of_the_deflection(approach):
    expected = integral(s.EA / 2 * slope()**2 * B_U) if approach != "C" else sp.zeros(s.ELEMENT_DOFS, 1)
    paper = printed.rod_elastic_residual(approach, A.printed_set(True))[0]
    assert is_zero(elastic_force(approach) - paper - expected)
    items = [d for d in A.differences() if d.component == "rod elastic" and approach in d.approaches]
    assert is_zero(sum((d.element for d in items), sp.zeros(s.ELEMENT_DOFS, 1)) - expected)
    if approach != "C":
        assert [d.group for d in items] == ["cubic_axial"]
        assert dict(items[0].weak) == {"u_x": s.EA * A.v_x**2 / 2}


def test_slider_difference_is_the_slider_gyroscopic_coupling():
    u, v, ud, vd = s.qs[0], s.qs[1], s.qsd[0], s.qsd[1]
    expected = s.ms * sp.Matrix([2 * s.phid * vd + s.phidd * v, -2 * s.phid * ud - s.phidd * u])
    exact = kinetic_residual(slider_kinetic_energy(), s.qs, s.qsd, s.qsdd)
    paper = printed.slider_kinetic_residual(A.printed_set(True), corrected=True)
    assert is_zero(exact - paper - expected)
    items = [d for d in A.differences() if d.component == "slider inertia" and d.formulation == "paper"]
    assert is_zero(sum((d.element for d in items), sp.zeros(2, 1)) - expected)


def test_only_the_errata_items_are_added_by_the_text_as_printed():
    extra = [(d.component, d.group) for d in A.differences() if d.formulation == "printed"]
    assert extra == [("rod inertia", "forcing"), ("slider inertia", "forcing")]


def test_eq17_and_eq18_reproduce_the_energies():
    checks = A.eq17_checks()
    for key in ("m1", "m2", "m3", "m4"):
        assert checks[key] == 0
    assert checks["m3 as printed"] != 0 and checks["bilinear"] != 0
    assert all(v == 0 for v in A.eq18_checks().values())


def test_printed_elastic_force_is_not_conservative():
    expected = integral(s.EA * slope() * (B_V * B_U.T - B_U * B_V.T))
    for ap in ("A", "B"):
        K = jacobian(printed.rod_elastic_residual(ap, A.printed_set(True))[0], s.q)
        assert is_zero(K - K.T - expected)
        assert is_zero(A.elastic_asymmetry("paper", ap) - expected)
        assert is_zero(A.elastic_asymmetry("lagrange", ap))
    assert is_zero(A.elastic_asymmetry("paper", "C"))


@pytest.mark.parametrize("approach", APPROACHES)
def test_tangent_minus_secant(approach):
    residual, secant = printed.rod_elastic_residual(approach, A.printed_set(True))
    defect = (jacobian(residual, s.q) - secant) * s.qd
    assert is_zero(A.element_vector(A.tangent_minus_secant(approach)) - defect)


# ---- transcription problems of the printed equations (docs/errata.md): verdicts ------------
def test_every_errata_item_has_a_verdict():
    verdicts = {v.key: v.verdict for v in A.errata_verdicts()}
    assert list(verdicts) == ["eq1", "B3", "eq29", "eq37", "eq39", "B15/B16"]
    assert all(v.startswith("confirmed") for v in verdicts.values())


def test_b3_as_printed_mixes_time_units_and_is_not_the_lagrange_term():
    exact_m3 = gradient(rod_T(), s.qd).xreplace({c: 0 for c in tuple(s.q) + tuple(s.qd)})
    as_printed, corrected = A.printed_set(False)["m3"], A.printed_set(True)["m3"]
    assert is_zero(exact_m3 - corrected)
    assert not is_zero(exact_m3 - as_printed)
    # a momentum: every term scales as 1/time; the printed rotary term scales as 1/time^2
    assert all(time_powers(e) == {1} for e in corrected if e != 0)
    assert any(time_powers(e) == {1, 2} for e in as_printed)
    assert A.erratum_b3().verdict == "confirmed"


def test_eq29_as_printed_mixes_momentum_and_force():
    as_printed = printed.slider_kinetic_residual(A.printed_set(False), corrected=False)
    corrected = printed.slider_kinetic_residual(A.printed_set(True), corrected=True)
    assert all(time_powers(e) == {2} for e in corrected)
    assert all(time_powers(e) == {1, 2} for e in as_printed)
    assert A.erratum_eq29().verdict == "confirmed"


def _newmark_velocity(printed_corrector, g=2.0, dt=0.1, steps=10, gamma=0.5):
    """Velocity after `steps` steps of the corrector for the motion ddot d = g (v(0) = 0)."""
    v, a = 0.0, g
    v_pred_prev = v
    for _ in range(steps):
        v_pred = v + dt * (1 - gamma) * a
        v = (v_pred_prev if printed_corrector else v_pred) + gamma * dt * g
        v_pred_prev = v_pred
    return v


def test_eq39_corrector():
    assert _newmark_velocity(False) == pytest.approx(2.0 * 0.1 * 10)
    assert abs(_newmark_velocity(True) - 2.0) > 0.5
    assert A.erratum_eq39().verdict == "confirmed"
    assert A.newmark_eq37_residual("corrected") == 0
    assert A.erratum_eq37().verdict == "confirmed (typesetting only)"


def test_b15_b16_evaluation_point():
    assert list(N_U.subs(s.zeta, 1)) == [0, 0, 0, 0, 1, 0, 0, 0]          # (u, v, psi, chi) of each node
    assert list(N_V.subs(s.zeta, 1)) == [0, 0, 0, 0, 0, 1, 0, 0]
    assert list(N_V.subs(s.zeta, 0)) != [0, 0, 0, 0, 0, 1, 0, 0]
    assert A.erratum_b15_b16().verdict == "confirmed"


def test_conventions_of_the_errata_hold():
    for evidence in A.convention_checks()[:4]:
        values = evidence.value if isinstance(evidence.value, tuple) else tuple(evidence.value)
        assert all(sp.simplify(v) == 0 for v in values)
    rigid, flexible = A.convention_checks()[4:]
    assert sp.simplify(rigid.value[0] - s.a * sp.sin(s.theta) / s.L) == 0
    assert sp.simplify(flexible.value[0] - s.qs[0] * sp.tan(s.phi)) == 0


def test_exact_residual_rows_are_dimensionally_homogeneous():
    total = exact_rod_inertia() + elastic_force("A") + kelvin_voigt_force("A")
    psi_rows, chi_rows = s.element_slots(0, ("psi",)) + s.element_slots(1, ("psi",)), \
        s.element_slots(0, ("chi",)) + s.element_slots(1, ("chi",))
    for i, entry in enumerate(total):
        if i in chi_rows:                     # approach A has no chi: its rows are empty
            assert entry == 0
            continue
        assert A.dimensions(entry) == ((A.MOMENT,) if i in psi_rows else (A.FORCE,))


# ---- the report ---------------------------------------------------------------------------------
def test_write_report_has_every_section_and_is_deterministic(tmp_path):
    path = report.write_report(tmp_path / "one")
    text = path.read_text(encoding="utf-8")
    assert path.name == "report.md"
    for k, title in report.TITLES.items():
        assert f"## {k}. {title}" in text
    assert "Not yet computed" not in text
    assert "$$" in text and "nan" not in text.lower().replace("nanc", "")
    assert "CHECK FAILED" not in text
    # section 7: A's leading dropped term of the pointwise stretch, -v_x^2 (4 u_x + v_x^2)/8, and the
    # weights against the amplitude (tests/test_audit_exact.py checks their numbers)
    assert "v_{,x}^{2} \\left(4 u_{,x} + v_{,x}^{2}\\right)" in text and "### 7.3" in text
    # the symbolic sections are reproduced exactly (the numeric ones are checked in test_term_groups)
    again = report.write_report(tmp_path / "two", sections=[1, 2, 3]).read_text(encoding="utf-8")
    body = text[text.index("## 1."):text.index("## 4.")]
    assert again[again.index("## 1."):].rstrip() == body.rstrip()
    _check_summary_and_tables(text)


def _check_summary_and_tables(text):
    """The summary opens the report, and its numbers are those of the tables below it; no table
    is wider than 12 columns; no file outside the repository is cited."""
    import re
    assert text.index("## Summary") < text.index("## 1.")
    summary = text[text.index("## Summary"):text.index("## 1.")]
    assert "ERRATA" not in text and "shared/" not in text
    widths = [line.count("|") - 1 for line in text.splitlines() if line.startswith("|---")]
    assert widths and max(widths) <= 12
    table = text[text.index("### 5.1"):text.index("### 5.2")]
    rows = [[c.strip() for c in line.strip("|").split("|")] for line in table.splitlines()
            if line.startswith("| paper") or line.startswith("| consistent")]
    assert len(rows) == 24
    for model in ("paper", "consistent"):
        ratios = [float(r[5]) for r in rows if r[0] == model and r[1] == "0.01" and r[4] != "failed"]
        n_ok = sum(1 for r in rows if r[0] == model and re.fullmatch(r"[0-9.]+", r[5]))
        line = next(l for l in summary.splitlines() if l.startswith(f"- Steady amplitude, {model} model"))
        assert f"B periodic in {n_ok} of 12 cases" in line
        assert f"to {max(ratios):.3f}" in line.split("eps = 0.1:")[0]
    where = next(l for l in summary.splitlines() if l.startswith("- Where (3.3)"))
    assert "5 groups" in where and "cubic coupling" in where
    switch = text[text.index("### 4.3"):text.index("## 5.")]
    changes = [float(c.strip().rstrip("%")) for line in switch.splitlines() if line.startswith("| 0.")
               for c in [line.strip("|").split("|")[6]] if c.strip().endswith("%")]
    much = next(l for l in summary.splitlines() if l.startswith("- How much (4.3)"))
    assert f"axial equation: at most {max(changes, key=abs):+.1f}%" in much


def test_write_report_sections_subset_and_validation(tmp_path):
    text = report.write_report(tmp_path, sections=[1]).read_text(encoding="utf-8")
    assert "## 1." in text and "## 2." not in text
    with pytest.raises(ParameterError):
        report.write_report(tmp_path, sections=[8])
