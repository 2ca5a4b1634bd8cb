"""`crankgen audit`: the symbolic audit report, audit/report.md (Markdown with LaTeX).

SymPy and the derivation (crankgen._derive) are loaded inside `write_report` only, so importing
crankgen never imports SymPy.  The computations live in crankgen._derive.audit; this module only
lays them out: a summary computed from the sections run, then numbered sections (1 energies by
order, 2 Euler-Lagrange terms by kind, 3 printed form against the derivation, with the transcription
problems of the printed equations checked one by one); sections 4-6 are computed from runs of the
compiled engine by audit_numbers.py (4 weights of the groups along steady trajectories, 5 the
quartic term, 6 element convergence and membrane locking).
"""

from pathlib import Path

from ..errors import ParameterError

SECTIONS = (1, 2, 3, 4, 5, 6, 7)
TITLES = {
    1: "Energies and dissipation functions by order",
    2: "Element Euler-Lagrange equations by kind",
    3: "The printed matrix form against the derivation",
    4: "Weights of the groups along steady trajectories",
    5: "Effect of the quartic term",
    6: "Element convergence and membrane locking",
    7: "Approach A against the exact strain",
}

GROUP_TITLES = {
    "inertia": "inertia",
    "gyroscopic": "velocity-dependent (gyroscopic / Coriolis)",
    "phidd": r"terms in $\ddot\phi$",
    "centrifugal": "centrifugal",
    "forcing": r"kinematic forcing (independent of $\{q\}$)",
    "stiffness": "linear stiffness",
    "cubic_axial": r"cubic coupling $u_{,x}v_{,x}^2$, axial equation",
    "cubic_transverse": r"cubic coupling $u_{,x}v_{,x}^2$, transverse equation",
    "quartic": r"quartic term $v_{,x}^4$",
    "damping_linear": "damping, linear",
    "damping_centrifugal": r"damping, centrifugal part ($\propto\dot\phi^2$)",
    "damping_q1": "damping, displacement x rate",
    "damping_q2": "damping, displacement$^2$ x rate",
}
GROUP_RULES = {
    "inertia": "contains an acceleration",
    "gyroscopic": r"contains a displacement rate (no $\mu$)",
    "phidd": r"linear in the displacements, factor $\ddot\phi$",
    "centrifugal": r"linear in the displacements, factor $\dot\phi^2$",
    "forcing": "no displacement, rate or acceleration",
    "stiffness": r"$EA$ or $EI$, linear in the displacements",
    "cubic_axial": r"$EA$, quadratic in the displacements, axial ($\delta u$) equation",
    "cubic_transverse": r"$EA$, quadratic in the displacements, transverse ($\delta v$, $\delta\psi$) equation",
    "quartic": r"$EA$, cubic in the displacements",
    "damping_linear": r"$\mu$, independent of the displacements, no $\dot\phi$",
    "damping_centrifugal": r"$\mu$, independent of the displacements, factor $\dot\phi^2$",
    "damping_q1": r"$\mu$, linear in the displacements",
    "damping_q2": r"$\mu$, quadratic in the displacements",
}
SLOT_TITLES = {"u": r"$\delta u$", "v": r"$\delta v$", "psi": r"$\delta\psi$",
               "u_x": r"$\delta u_{,x}$", "v_x": r"$\delta v_{,x}$", "v_xx": r"$\delta v_{,xx}$"}
STATUS = {"kept": "✓", "dropped": "—", "differs": "≠", "present": "✓", "": ""}
FORMULATION_TITLES = {"lagrange": "exact Lagrange", "paper": "printed, corrected",
                      "printed": "as printed"}
DAMPING_TITLES = {"eq24": "eq. (24)", "kelvin-voigt": "Kelvin-Voigt"}

EXPLANATIONS = {
    ("rod inertia", "gyroscopic"): (
        r"The rod's kinetic energy contains $\rho A\,\dot\phi\,(\dot u v - u\dot v)$, bilinear in the "
        r"displacements and their rates. Eq. (17) has only quadratic forms in $\{\dot q\}$ and in "
        r"$\{q\}$ and linear terms, so this term and its Lagrange forces are absent from eq. (20): "
        r"the Coriolis force $2\dot\phi$ couples axial and transverse rates."),
    ("rod inertia", "phidd"): (
        r"Same source: $\frac{d}{dt}$ of $\partial T/\partial\dot u = \dots + \rho A\dot\phi v$ gives "
        r"$\rho A\ddot\phi v$ (and $-\rho A\ddot\phi u$ in the transverse equation), the Euler force "
        r"of the angular acceleration of the rod frame acting on the displaced centre line."),
    ("rod elastic", "cubic_axial"): (
        r"Eq. (18) is eq. (2) as an energy, but (B7) uses $P_i = EA\{B_u\}^T\{q\}$ 'as given': the "
        r"variation of $\frac12\int P v_{,x}^2\,dx$ then omits $\partial P/\partial\{q\}$. The "
        r"missing force is the axial force $\frac12 EA v_{,x}^2$ of the transverse deflection in the "
        r"axial equation; the transverse side ($EA u_{,x}v_{,x}$, i.e. $[k_{pvv}]\{q\}$) is kept."),
    ("slider inertia", "gyroscopic"): (
        r"The slider's kinetic energy (eqs. 6-7) contains $m_s\dot\phi\,(\dot u v - u\dot v)$ at "
        r"$x = L$; (B13)-(B16) have no term bilinear in the slider's displacements and rates."),
    ("slider inertia", "phidd"): (
        r"Same source as the slider's Coriolis terms: $m_s\ddot\phi v$ and $-m_s\ddot\phi u$."),
    ("rod inertia", "forcing"): (
        r"(B3) as printed has $-\rho I\dot\phi^2\{N_\psi\}$; its time derivative in eq. (25) gives "
        r"$2\rho I\dot\phi\ddot\phi$ where the Lagrange equations have $\rho I\ddot\phi$ (item B3 below)."),
    ("slider inertia", "forcing"): (
        r"Eq. (29) as printed subtracts $\{m_{s4}\}$ (a momentum) instead of its time derivative "
        r"(item eq. 29 below)."),
}

# The transcription problems of the printed equations that the audit checks (section 3.5;
# docs/errata.md states them for readers): as printed, what the derivation requires, how it is checked.
TRANSCRIPTION_TEXT = {
    "eq1": (r"bending part $-y\,v_{,xxx}$", r"$-y\,v_{,xx}$",
            "integrate $E e_{xx}^2/2$ over the section for both bending terms and compare with eq. (2); "
            "dimension of the bending term"),
    "B3": (r"last term $-\rho I\dot\phi^2\{N_\psi\}$", r"$-\rho I\dot\phi\{N_\psi\}$",
           r"the part of $T_i$ linear in $\{\dot q\}$ is exactly $\{\dot q\}^T\{m_3\}$; dimensions of the rows"),
    "eq29": (r"$-\{m_{s4}\}$", r"$-\{\dot m_{s4}\}$",
             "subtract eqs. (27)-(29) from the exact slider Lagrange equations; dimensions of the rows"),
    "eq37": ("a stray brace", "typesetting only",
             "solve the equation of motion at $t_{m+1}$ under (38), (39) and compare with (37)"),
    "eq39": (r"$\{v\}_{m+1} = \{\tilde v\}_m + \gamma\Delta t\{\hat a\}_{m+1}$",
             r"$\{\hat v\}_{m+1} = \{\tilde v\}_{m+1} + \gamma\Delta t\{\hat a\}_{m+1}$",
             "consistency with (37) and local truncation error (Taylor series of a smooth motion)"),
    "B15/B16": (r"evaluated at $\xi = 1$", r"$\zeta = 1$ (node $i+1$, $x = l$)",
                r"where the shape functions pick the end node; abscissa of that point in element $n$"),
}
# The same items in words: what is wrong in print and what it changes.
TRANSCRIPTION_WORDS = {
    "eq1": "The bending part of the axial strain carries a third derivative where the curvature (a "
           "second derivative) belongs; only the curvature gives the strain energy of eq. (2), and the "
           "printed term is not even dimensionless. Eq. (2) itself is right, so nothing downstream changes.",
    "B3": "The rotary-inertia entry of the vector linear in the rates carries the crank-frame angular "
          "speed squared instead of to the first power. Used as printed, eq. (25) turns it into a "
          "forcing twice the angular speed times the angular acceleration instead of the angular "
          "acceleration: a wrong force, and rows of mixed dimensions. Changes numbers; corrected in "
          "crankgen's `paper` formulation.",
    "eq29": "The slider's forcing subtracts the vector of its kinetic energy linear in the rates (a "
            "momentum) where its time derivative (a force) is required. Changes numbers; corrected in "
            "crankgen's `paper` formulation.",
    "eq37": "A brace without its partner; read without it, eq. (37) is exactly the equation of motion "
            "at the new time under eqs. (38)-(39). Typesetting only.",
    "eq39": "The velocity corrector starts from the previous step's velocity predictor instead of the "
            "current one: inconsistent with eq. (37), and its local error is of first order in the time "
            "step instead of third. crankgen's one-pass scheme uses the current predictor.",
    "B15/B16": "The slider terms are said to be evaluated at xi = 1, but xi is the moving-frame "
               "co-ordinate; the element's end node is at the local co-ordinate zeta = 1 (x = l of the "
               "last element, the rod end x = L). A wrong symbol; the terms are meant at the end node.",
}


def write_report(out_dir="audit", sections=None, progress=None):
    """Write out_dir/report.md with the chosen sections (default: all of SECTIONS); return its path.
    progress(section number) is called as each section starts."""
    chosen = SECTIONS if sections is None else tuple(sorted(set(sections)))
    unknown = [k for k in chosen if k not in SECTIONS]
    if unknown:
        raise ParameterError(f"sections must be among {SECTIONS}, got {unknown}")
    from .._derive import audit as derived     # lazy: SymPy is loaded here, not at import time
    report = _Report(derived)
    text = report.document(chosen, progress)
    from ..results.io import atomic_write
    path = Path(out_dir) / "report.md"
    return atomic_write(path, lambda fh: fh.write(text.encode("utf-8")), mode="wb")


class _Report:
    """Markdown rendering of the records of crankgen._derive.audit."""

    def __init__(self, derived):
        import sympy
        self.sp, self.d = sympy, derived

    # ---- formatting helpers ---------------------------------------------------------------
    def tex(self, expr, factor=True):
        sp = self.sp
        expr = sp.sympify(expr)
        if factor and not isinstance(expr, sp.MatrixBase):
            expr = sp.factor_terms(expr)
        return sp.latex(expr, symbol_names=self.d.LATEX_NAMES)

    def inline(self, expr, factor=True):
        return f"${self.tex(expr, factor)}$"

    def display(self, tex):
        return f"$$\n{tex}\n$$\n"

    def column(self, matrix):
        """A column vector written as a transposed row."""
        return self.tex(matrix.T) + "^T"

    @staticmethod
    def dim(dims):
        names = ("M", "L", "T")
        parts = [n if e == 1 else f"{n}^{{{e}}}" for n, e in zip(names, dims) if e != 0]
        return r"\,".join(parts) if parts else "1"

    def value(self, value):
        """LaTeX of an evidence value: expression, matrix, tuple of dimensions or of pairs."""
        sp = self.sp
        if isinstance(value, sp.MatrixBase):
            if value.shape[1] == 1 and value.shape[0] > 1:
                return f"${self.column(value)}$"
            return f"${self.tex(value)}$"
        if isinstance(value, tuple):
            if value and all(isinstance(v, tuple) and all(isinstance(e, int) for e in v) for v in value):
                return ", ".join(f"${self.dim(v)}$" for v in value)           # a set of dimensions
            if value and all(isinstance(v, tuple) and len(v) == 2 and isinstance(v[0], str) for v in value):
                return "; ".join(f"{k}: {v}" for k, v in value)              # (name, number) pairs
            if value and all(isinstance(v, tuple) for v in value):
                return "; ".join("(" + ", ".join(f"${self.dim(e)}$" for e in v) + ")" for v in value)
            if value and all(isinstance(v, str) for v in value):
                return ", ".join(GROUP_TITLES.get(v, v) for v in value)
            return ", ".join(self.inline(v) for v in value)
        return self.inline(value)

    @staticmethod
    def table(header, rows):
        lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
        lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
        return "\n" + "\n".join(lines) + "\n"

    def weak_table(self, grouped, first="group"):
        """Table of a {row label: weak form} mapping, one column per slot that occurs."""
        slots = [sl.name for sl in self.d.SLOTS if any(sl.name in form for form in grouped.values())]
        rows = [[label] + [self.inline(form[k]) if k in form else "" for k in slots]
                for label, form in grouped.items()]
        return self.table([first] + [SLOT_TITLES[k] for k in slots], rows)

    # ---- document -------------------------------------------------------------------------
    def document(self, sections, progress=None):
        from . import numbers as audit_numbers
        self.facts = {}
        parts = []
        builders = {1: self.section1, 2: self.section2, 3: self.section3, 4: self.section4,
                    5: self.section5, 6: self.section6, 7: self.section7}
        for k in sections:
            if progress is not None:
                progress(k)
            parts.append(f"## {k}. {TITLES[k]}\n\n" + builders[k]())
        differences = self.d.differences() if 3 in sections else None
        summary = audit_numbers.summary(self.facts, GROUP_TITLES, differences)
        return "\n".join([self.preamble(sections), summary] + parts)

    def preamble(self, sections):
        weak = (r"\{r\}_i = \int_0^l \Big(\{N_u\} f_u + \{N_v\} f_v + \{N_\psi\} f_\psi"
                r" + \{B_u\} f_{u,x} + \{B_v\} f_{v,x} + \{B_\psi\} f_{v,xx}\Big)\,dx")
        contents = "\n".join(f"{k}. {TITLES[k]}" for k in sections)
        return (
            "# Symbolic audit of the flexible slider-crank formulation\n\n"
            f"Generated by `crankgen audit` from the SymPy derivation (`crankgen._derive`, SymPy "
            f"{self.sp.__version__}). Equation numbers are the paper's.\n\n"
            "Formulations compared:\n\n"
            "- **exact Lagrange**: the Euler-Lagrange equations of $T_c + T_s - U_c$ (eq. 19), energies "
            "from eqs. (2)-(7);\n"
            "- **printed, corrected**: the matrix form of eqs. (17)-(29) and Appendix B with the "
            "two transcription problems that change numbers, (B3) and eq. (29), corrected (crankgen's "
            "`paper` formulation; every transcription problem is checked in 3.5);\n"
            "- **as printed**: the same without those corrections.\n\n"
            "Approaches: A keeps eq. (2) whole, B drops the quartic term, C uses the linear strain.\n\n"
            "Field-level equations are written as weak forms, one density per virtual quantity "
            "($\\delta u$, $\\delta v$, $\\delta\\psi$, $\\delta u_{,x}$, $\\delta v_{,x}$, "
            "$\\delta v_{,xx}$); the element vector is\n\n"
            + self.display(weak)
            + "\nEvery field-level statement below is also checked on the element vectors in "
            "$\\{q\\}_i = \\{u_i, v_i, \\psi_i, u_{i+1}, v_{i+1}, \\psi_{i+1}\\}$ (eq. 14), where the "
            "printed matrices live (tests/test_audit.py).\n\n"
            "Contents\n\nSummary\n" + contents + "\n"
        )

    # ---- section 1 ------------------------------------------------------------------------
    def section1(self):
        d, sp = self.d, self.sp
        out = ["### 1.1 Strain energy, eq. (2)\n",
               "Integrating $E e_{xx}^2/2$ of eq. (1) over the cross-section (centroidal axes: "
               "$\\int y\\,dA = 0$, $\\int y^2 dA = I$) with the bending term $-y\\,v_{,xx}$ gives\n",
               self.display(r"\frac{E}{2}\int_A e_{xx}^2\,dA = " + self.tex(d.section_strain_energy(d.v_xx), False)),
               f"which minus eq. (2) as printed is {self.inline(d.section_strain_energy(d.v_xx) - d.eq2_density())} "
               "(see item eq. (1) in 3.5 for the printed $v_{,xxx}$). By order in the displacement "
               "gradients $u_{,x}, v_{,x}, v_{,xx}$:\n"]
        rows = []
        for order, part in d.strain_orders().items():
            kept = ["✓" if order in d.STRAIN_ORDERS[ap] else "—" for ap in d.APPROACHES]
            rows.append([str(order), self.inline(part)] + kept)
        out.append(self.table(["order", "terms of eq. (2) per unit length", "A", "B", "C"], rows))
        square, minimum = d.membrane_square_check()
        linear = d.section_strain_energy(d.v_xx, nonlinear=False)
        out.append(
            "\n- A: the membrane part is a square, eq. (2) minus "
            r"$\frac{EA}{2}(u_{,x} + \frac12 v_{,x}^2)^2 + \frac{EI}{2}v_{,xx}^2$ = "
            f"{self.inline(square)}, so $U_A \\ge 0$.\n"
            "- B: dropping the quartic term leaves $\\frac{EA}{2}(u_{,x}^2 + u_{,x}v_{,x}^2)$, whose "
            f"minimum over $u_{{,x}}$ is {self.inline(minimum)}: not bounded below in $v_{{,x}}$.\n"
            "- C: the linear strain $e_{xx} = u_{,x} - y v_{,xx}$ gives "
            f"{self.inline(linear)}, the order-2 part.\n")

        out.append("\n### 1.2 Kinetic energy, eqs. (4)-(7)\n\n"
                   "Rod, per unit length, with $x$ the abscissa of the undeformed rod and "
                   "$\\psi = v_{,x}$ (rotary inertia of the section $y(-\\psi e_i + e_j)$). Terms by "
                   "order in $(u, v, \\psi)$ and their rates, and the quantity of eq. (17) that "
                   "holds them:\n")
        out.append(self.kinetic_table(d.kinetic_parts()))
        slider_T = d.slider_kinetic_energy(sp.Matrix([d.u, d.v]), sp.Matrix([d.ud, d.vd]))
        out.append("\nSlider (eqs. 6-7, $u$, $v$ the rod end displacements at $x = L$), same split; "
                   "(B13)-(B16) stand for $m_1$-$m_4$:\n")
        out.append(self.kinetic_table(d.kinetic_parts(slider_T), slider=True))
        out.append("\nAll approaches share the kinetic energy. The exact Lagrange equations keep every "
                   "term; eq. (17) has no place for the bilinear (gyroscopic) term. The constant term "
                   "does not depend on the displacements and has no effect on the equations of motion.\n")

        out.append("\n### 1.3 Dissipation functions\n\n"
                   "Kelvin-Voigt: $D = \\frac{\\mu}{2}\\int [EA\\,\\dot e^2 + EI\\,\\dot v_{,xx}^2]\\,dx$, "
                   "with $\\dot e = \\dot u_{,x} + v_{,x}\\dot v_{,x}$ (A and B, the rate of eq. (1)'s "
                   "strain) or $\\dot e = \\dot u_{,x}$ (C). Eq. (24): $[c] = \\mu([K_{lin}] + [K_{non}])$ "
                   "does not depend on $\\{\\dot q\\}$, so its force is $\\partial D/\\partial\\{\\dot q\\}$ "
                   "of $D = \\frac12\\{\\dot q\\}^T[c]\\{\\dot q\\}$; per unit length (with "
                   "$P = EA u_{,x}$ of (B9) and the $-[m_2]$ of eq. 22):\n")
        variables = "the displacements, their gradients and the rates"
        for model in d.DAMPING_MODELS:
            orders = {ap: d.dissipation_orders(model, ap) for ap in d.APPROACHES}
            all_orders = sorted({k for o in orders.values() for k in o})
            rows = [[str(k)] + [self.inline(orders[ap].get(k, 0)) if orders[ap].get(k, 0) != 0 else "—"
                                for ap in d.APPROACHES] for k in all_orders]
            out.append(f"\n{DAMPING_TITLES[model]}, by total order in {variables}:\n\n")
            out.append(self.table(["order", "A", "B", "C"], rows))
        rigid = d.eq24_rigid_dissipation("A")
        out.append("\nFor a velocity field without strain rate (rigid motion in the rod frame) eq. (24)'s "
                   f"function is {self.inline(rigid)} $\\le 0$: the $-\\mu[m_2]$ part supplies energy; "
                   "the slider part of eq. (24) (with eq. 28's $-[m_{s2}]$) gives "
                   f"{self.inline(d.slider_eq24_dissipation())}.\n")
        return "".join(out)

    def kinetic_table(self, parts, slider=False):
        d = self.d
        order = {"constant": 0, "m3": 1, "m4": 1, "m1": 2, "m2": 2, "bilinear": 2}
        matrix_names = {"m1": "[m_1]", "m2": "[m_2]", "m3": "\\{m_3\\}", "m4": "\\{m_4\\}"}
        slider_names = {"m1": "[m_{s1}]", "m2": "[m_{s2}]", "m3": "\\{m_{s4}\\}", "m4": "\\{m_{s3}\\}"}
        names = slider_names if slider else matrix_names
        kinds = {"constant": "constant", "m1": "quadratic in rates", "m2": "quadratic in displacements",
                 "m3": "linear in rates", "m4": "linear in displacements",
                 "bilinear": "displacement x rate"}
        rows = []
        for key in ("constant", "m3", "m4", "m1", "m2", "bilinear"):
            part = self.sp.trigsimp(parts[key])
            if part == 0:
                continue
            printed = f"${names[key]}$" if key in names else ("none (dropped)" if key == "constant" else "**missing**")
            rows.append([str(order[key]), kinds[key], self.inline(part), printed, "✓"])
        return self.table(["order", "kind", "terms", "eq. (17)" if not slider else "(B13)-(B16)",
                           "exact Lagrange (A, B, C)"], rows)

    # ---- section 2 ------------------------------------------------------------------------
    def section2(self):
        d = self.d
        out = ["Each term of the expanded equations falls in exactly one group: a term with $\\mu$ is "
               "damping, otherwise the first matching rule of the table decides (the elastic rules "
               "are tested after inertia and before the kinetic ones).\n"]
        out.append(self.table(["group", "rule"], [[GROUP_TITLES[g], GROUP_RULES[g]] for g in d.GROUPS]))

        exact = d.add_weak(d.rod_inertia_weak("lagrange"), d.rod_elastic_weak("lagrange", "A"))
        grouped = {GROUP_TITLES[g]: form for g, form in d.group_weak_form(exact).items()}
        out.append("\n### 2.1 Rod element, exact Lagrange equations, approach A\n\n"
                   "Densities $f_k$ of the weak form (the $\\delta u_{,x}$ column enters the axial "
                   "equation, $\\delta v_{,x}$ and $\\delta v_{,xx}$ the transverse one):\n\n")
        out.append(self.weak_table(grouped))

        slider = d.group_vector(d.slider_inertia("lagrange"), d.SLIDER_VARS, d.SLIDER_AXIAL_ROWS)
        rows = [[GROUP_TITLES[g], self.inline(vec[0]), self.inline(vec[1])] for g, vec in slider.items()]
        out.append("\n### 2.2 Slider, exact Lagrange equations\n\n"
                   "Forces on the rod end node $(u_{n+1}, v_{n+1})$ (before the constraint of eq. 26):\n\n")
        out.append(self.table(["group", "$u_{n+1}$ equation", "$v_{n+1}$ equation"], rows))

        out.append("\n### 2.3 Which formulation and approach keeps each group\n\n"
                   "✓ identical to the exact approach-A equations, — absent, ≠ present but different.\n\n")
        header = ["group"] + [f"{FORMULATION_TITLES[f]}, {ap}" for f, ap in d.ROD_COLUMNS]
        out.append("Rod element:\n\n")
        out.append(self.table(header, [[GROUP_TITLES[r.group]] + [STATUS[x] for x in r.status]
                                       for r in d.rod_keep_table()]))
        out.append("\nSlider:\n\n")
        out.append(self.table(["group"] + [FORMULATION_TITLES[f] for f in d.FORMULATIONS],
                              [[GROUP_TITLES[r.group]] + [STATUS[x] for x in r.status]
                               for r in d.slider_keep_table()]))

        out.append("\n### 2.4 Damping forces\n\n"
                   "The damping model is chosen independently of the formulation. Weak-form densities "
                   "of the damping force ($\\partial D/\\partial$ rate, section 1.3):\n\n")
        forms = {f"{DAMPING_TITLES[m]}, {ap}": d.rod_damping_weak(m, ap) for m, ap in d.DAMPING_COLUMNS}
        out.append(self.weak_table(forms, first="model, approach"))
        out.append("\nGroups present:\n\n")
        header = ["group"] + [f"{DAMPING_TITLES[m]}, {ap}" for m, ap in d.DAMPING_COLUMNS]
        out.append(self.table(header, [[GROUP_TITLES[r.group]] + [STATUS[x] or "—" for x in r.status]
                                       for r in d.damping_keep_table()]))
        out.append("\nThe printed slider damping is $-\\mu[m_{s2}]\\{\\dot q\\}$ (eqs. 24, 28), "
                   "a centrifugal-type term; Kelvin-Voigt damping acts on the rod's strain rates only.\n")
        return "".join(out)

    # ---- section 3 ------------------------------------------------------------------------
    def section3(self):
        d, sp = self.d, self.sp
        out = ["### 3.1 Eq. (17) against the rod's kinetic energy\n\n"
               "Element integral of the kinetic-energy terms each printed quantity stands for (section "
               "1.2), minus the printed quadratic or linear form:\n\n"]
        labels = {"m1": r"$\frac12\{\dot q\}^T[m_1]\{\dot q\}$ (B1)",
                  "m2": r"$\frac12\{q\}^T[m_2]\{q\}$ (B2)",
                  "m3": r"$\{\dot q\}^T\{m_3\}$ (B3, corrected)",
                  "m3 as printed": r"$\{\dot q\}^T\{m_3\}$ (B3, as printed)",
                  "m4": r"$\{q\}^T\{m_4\}$ (B4)",
                  "bilinear": "bilinear terms (no printed counterpart)"}
        checks = d.eq17_checks()
        W = d.bilinear_matrix()
        W_ok = sp.expand((d.s.qd.T * W * d.s.q)[0, 0] - checks["bilinear"]) == 0
        rows = [[labels[k], self.inline(v) if k != "bilinear" else
                 r"$\{\dot q\}^T[W]\{q\}$" + (" (checked)" if W_ok else " (CHECK FAILED)")]
                for k, v in checks.items()]
        out.append(self.table(["printed quantity", "exact minus printed"], rows))
        factor = d.common_factor(W)
        out.append("\nwith the antisymmetric matrix\n\n" + self.display(
            f"[W] = {self.tex(factor)}" + self.tex(W.applyfunc(lambda e: sp.simplify(e / factor)))))

        out.append("\n### 3.2 Eq. (18) against eq. (2)\n\n"
                   "With $P_i = EA\\{B_u\\}^T\\{q\\}$ (B9) (exact: $u_{,x}$ is constant in an element) "
                   "and $[k_{vvv}]$ of (B8) read as $\\frac14\\int EA\\,v_{,x}^2\\{B_v\\}\\{B_v\\}^T dx$, "
                   "$U_i$ of eq. (18) minus the element integral of the approach's strain energy is: "
                   + ", ".join(f"{ap}: {self.inline(v)}" for ap, v in d.eq18_checks().items())
                   + ". As energies eqs. (18) and (2) agree; the differences below come from how "
                   "eq. (20) is obtained from eq. (18).\n")

        out.append("\n### 3.3 Terms of the Lagrange equations that the printed form does not contain\n\n"
                   "Exact Lagrange equations minus the printed form (corrected), group by group, "
                   "for the rod's inertia and elastic forces and the slider's forces; no other group "
                   "differs. Items marked *as printed* are the additional differences of the uncorrected "
                   "text. (Damping is a modelling choice, compared in 3.4.)\n")
        for k, item in enumerate(d.differences(), 1):
            out.append(self.difference(k, item))

        out.append("\n### 3.4 Further findings\n\n")
        out.append(self.further_findings())

        out.append("\n### 3.5 Transcription problems of the printed equations, item by item\n\n"
                   "Places where the printed equations cannot be what the derivation gives (a wrong "
                   "derivative order, a missing time derivative, a wrong predictor, a wrong symbol), "
                   "each checked symbolically; docs/errata.md states them in words.\n\n")
        rows = []
        for verdict in d.errata_verdicts():
            printed, required, check = TRANSCRIPTION_TEXT[verdict.key]
            rows.append([verdict.item, printed, required, check, f"**{verdict.verdict}**"])
        out.append(self.table(["item", "as printed", "required", "symbolic check", "verdict"], rows))
        for verdict in d.errata_verdicts():
            out.append(f"\n**{verdict.item}** ({verdict.verdict}). {TRANSCRIPTION_WORDS[verdict.key]}\n\n")
            for ev in verdict.evidence:
                out.append(f"- {ev.label}: {self.value(ev.value)}\n")
        out.append("\n### 3.6 Conventions the derivation relies on (checked)\n\n"
                   "$e_r = (\\cos\\theta, \\sin\\theta)$, $e_i = (\\cos\\phi, -\\sin\\phi)$, "
                   "$e_j = (\\sin\\phi, \\cos\\phi)$ in $X, Y$:\n\n")
        for ev in d.convention_checks():
            out.append(f"- {ev.label}: {self.value(ev.value)}\n")
        out.append("\nThe pinned crank end ($u_1 = v_1 = 0$) and free end slopes are modelling choices, "
                   "not symbolic claims.\n")
        return "".join(out)

    def difference(self, k, item):
        d, sp = self.d, self.sp
        tag = " (*as printed*)" if item.formulation == "printed" else ""
        approaches = ", ".join(item.approaches)
        head = (f"\n**{k}. {item.component}: {GROUP_TITLES[item.group]}**{tag} "
                f"(approaches {approaches})\n\n")
        text = EXPLANATIONS.get((item.component, item.group), "") + "\n\n"
        body = []
        if item.weak is not None:
            body.append("Missing weak-form densities: " + ", ".join(
                f"{SLOT_TITLES[name]}: {self.inline(density)}" for name, density in item.weak.items()) + ".\n\n")
        if item.component == "slider inertia":
            body.append("Missing slider forces $(u_{n+1}, v_{n+1})$: "
                        f"${self.column(item.element.applyfunc(sp.factor_terms))}$.\n\n")
        rates, coords = ((d.s.qsd, d.s.qs) if item.component == "slider inertia" else (d.s.qd, d.s.q))
        C, K = d.linear_parts(item.element, rates, coords)
        linear = sp.expand(C * sp.Matrix(rates) + K * sp.Matrix(coords) - item.element) == sp.zeros(*item.element.shape)
        if item.component != "slider inertia" and linear and (C != sp.zeros(*C.shape) or K != sp.zeros(*K.shape)):
            for name, matrix, vector in (("C", C, r"\{\dot q\}"), ("K", K, r"\{q\}")):
                if matrix == sp.zeros(*matrix.shape):
                    continue
                factor = d.common_factor(matrix)
                scaled = matrix.applyfunc(lambda e: sp.simplify(e / factor))
                W = d.bilinear_matrix()
                relation = {"C": (2 * W, "2[W]"), "K": (W * d.s.phidd / d.s.phid, r"(\ddot\phi/\dot\phi)[W]")}[name]
                same = sp.expand(matrix - relation[0]) == sp.zeros(*matrix.shape)
                note = f" $= {relation[1]}$ of 3.1" if same else ""
                body.append(f"Element level: $[{name}]{vector}${note}, with\n\n"
                            + self.display(f"[{name}] = {self.tex(factor)}" + self.tex(scaled)))
        elif item.group == "cubic_axial" and item.element == d.axial_force_vector():
            body.append("Element level: $\\frac{EA}{2}\\,(\\{q\\}^T[S]\\{q\\})\\,\\{B_u\\}$ with "
                        "$[S] = \\int_0^l\\{B_v\\}\\{B_v\\}^T dx$ and "
                        f"$\\{{B_u\\}} = {self.column(d.SLOT['u_x'].shape)}$ (checked).\n\n")
        elif item.component != "slider inertia":
            body.append(f"Element level: ${self.column(item.element)}$.\n\n")
        return head + text + "".join(body)

    def further_findings(self):
        d, sp = self.d, self.sp
        asym = {(f, ap): d.elastic_asymmetry(f, ap) for f in ("lagrange", "paper") for ap in d.APPROACHES}
        nonsym = [ap for ap in d.APPROACHES if asym[("paper", ap)] != sp.zeros(6, 6)]
        exact_sym = all(asym[("lagrange", ap)] == sp.zeros(6, 6) for ap in d.APPROACHES)
        out = [
            "**Non-conservative printed elastic force.** The Jacobian of eq. (20)'s elastic force "
            f"is {'symmetric' if exact_sym else 'NOT symmetric'} for the exact equations (a gradient) and "
            f"non-symmetric for the printed form in approaches {', '.join(nonsym) or 'none'}: with "
            "$P_i$ taken as given the force is not the gradient of eq. (18), and it does work around "
            "closed deformation cycles. "
            + ("For A and B, $[K] - [K]^T = EA\\int_0^l v_{,x}\\,(\\{B_v\\}\\{B_u\\}^T - "
               "\\{B_u\\}\\{B_v\\}^T)\\,dx$ (checked), the $\\partial P/\\partial\\{q\\}$ "
               "coupling present on one side of the diagonal only.\n\n"
               if all(asym[("paper", ap)] == d.frozen_force_asymmetry() for ap in ("A", "B"))
               else "$[K] - [K]^T$ for A:" + self.display(self.tex(asym[("paper", "A")])) + "\n")]
        tangent = {ap: d.tangent_minus_secant(ap) for ap in d.APPROACHES}
        out.append(
            "**Iteration matrix of eq. (37).** $[K_{lin}] + [K_{non}]$ with $[K_{non}]$ frozen is a "
            "secant, not the tangent of eq. (20)'s force; the weak form of "
            "$([K_{tan}] - [K_{sec}])\\{\\dot q\\}$ is "
            + "; ".join(f"{ap}: " + (", ".join(f"{SLOT_TITLES[n]} {self.inline(v)}" for n, v in form.items())
                                      if form else "0") for ap, form in tangent.items())
            + ". The one-pass scheme of eqs. (34)-(39) is therefore not a Newton step for "
            + (", ".join(ap for ap, form in tangent.items() if form) or "no approach")
            + " (crankgen's `newton` integrator uses the exact tangent).\n\n")
        guide, s_g, sd_g = d.slider_eq24_guide_force()
        names = {**d.LATEX_NAMES, s_g: "s", sd_g: r"\dot{s}"}
        out.append(
            "**Centrifugal part of eq. (24).** $[K_{lin}]$ of eqs. (22)/(28) contains $-[m_2]$ "
            "($-[m_{s2}]$ at the slider), so eq. (24) damps with $-\\mu\\dot\\phi^2$ times a mass "
            "matrix: the dissipation function is indefinite (section 1.3), and the slider's "
            "printed damping is pure negative damping, with dissipation function "
            f"{self.inline(d.slider_eq24_dissipation())} $\\le 0$; constrained to the guide by eq. (26), "
            "$(u, v)_{n+1} = s(\\cos\\phi, \\sin\\phi)$, the force on the slider displacement $s$ is "
            f"${sp.latex(guide, symbol_names=names)}$. This is a property of the "
            "printed model, kept by crankgen's `paper` damping.\n\n")
        out.append(
            "**Eq. (24) versus strain-rate damping.** Besides that term, eq. (24) damps the "
            "non-linear terms with the secant coefficients ($\\mu P\\dot v_{,x}$, "
            "$\\frac{\\mu}{2}EA v_{,x}^2\\dot v_{,x}$) where the Kelvin-Voigt function of the strain "
            "of eq. (1) gives $\\mu EA\\,v_{,x}(\\dot u_{,x} + v_{,x}\\dot v_{,x})$ and adds "
            "$\\mu EA\\,v_{,x}\\dot v_{,x}$ to the axial equation (section 2.4).\n")
        return "".join(out)

    # ---- sections 4-6: numbers from runs --------------------------------------------------
    def section4(self):
        from . import numbers as audit_numbers
        return audit_numbers.section4(GROUP_TITLES, self.facts)

    def section5(self):
        from . import numbers as audit_numbers
        return audit_numbers.section5(GROUP_TITLES, self.facts)

    def section6(self):
        from . import numbers as audit_numbers
        return audit_numbers.section6()

    # ---- section 7: A against the exact strain ----------------------------------------------
    def section7(self):
        from .._derive.audit import exact_strain as X
        from . import exact_weights
        from .numbers import EPS, N_AUDIT, OMEGAS
        names = {**self.d.LATEX_NAMES, **X.LATEX_NAMES}

        def tex(expr):
            return self.sp.latex(self.sp.sympify(expr), symbol_names=names)
        out = ["### 7.1 What A drops: the series of the exact strain\n\n"
               "The geometrically exact rod (`model=\"exact\"`, README) measures the stretch and the "
               "curvature of the centre line without approximation; approach A keeps $u_{,x} + "
               "v_{,x}^2/2$ and $v_{,xx}$. In the ordering of eq. (1) ($v_{,x}, v_{,xx} \\sim \\delta$; "
               "$u_{,x}, u_{,xx}, \\langle v_{,x}^2\\rangle \\sim \\delta^2$; "
               "$\\operatorname{var}(v_{,x}^2) \\sim \\delta^4$, over an element) the exact measure less A's "
               "is, by order in $\\delta$ (SymPy series of `crankgen._derive.audit.exact_strain`):\n"]
        rows = []
        for name, (exact, approx, words) in X.MEASURES.items():
            terms = X.dropped(name)
            rows.append([words, f"${tex(exact)}$", f"$\\delta^{X.a_order(name)}$"]
                        + [f"$\\delta^{k}$: ${tex(part)}$" for k, part in terms])
        out.append(self.table(["measure", "exact", "A's order", "leading dropped term", "next"], rows))
        energy = X.energy_difference()
        out.append("\nEvery dropped term is two orders in $\\delta$ above A's own measure: relative to it, "
                   "of order $\\delta^2$, the square of the slopes. With the element's stretch and "
                   "crankgen's curvature, the exact strain energy density "
                   "$\\frac{EA}{2}e^2 + \\frac{EI}{2}\\kappa^2$ less A's is\n\n"
                   + "".join(self.display(f"\\delta^{k}:\\quad " + tex(part)) for k, part in energy.items())
                   + "\nThe bending part leads (a factor $1 - u_{,x} + (v_{,x}^2 - \\langle v_{,x}^2\\rangle)/2$ "
                   "on the curvature); the membrane part enters at $\\delta^6$, through $EA$ times A's strain. "
                   "Approach A is the exact rod's first term: the two agree to relative order $\\delta^2$ "
                   "(tests/test_exact_rod.py checks it on the element's strain energy).\n")
        out.append(exact_weights.section_numbers(EPS, OMEGAS, N_AUDIT, self.facts))
        return "".join(out)
