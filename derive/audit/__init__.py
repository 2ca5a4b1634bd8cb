"""Symbolic audit: energies by order, Euler-Lagrange terms by kind, the printed matrix form
(eqs. 17-29, Appendix B) against the derivation, and the transcription problems of the printed
equations (docs/errata.md).

Two levels are used throughout.
- Field level: densities in the field symbols (u, v, psi, their rates and x-derivatives, the
  abscissa x).  Readable; this is what the report prints.  An element equation is written as a
  weak form, one density per virtual quantity ("slot"): the element vector is
      r = int_0^l ( N_u f_u + N_v f_v + N_psi f_psi + B_u f_{u_x} + B_v f_{v_x} + B_psi f_{v_xx} ) dx.
- Element level: 6-vectors in {q}, {qd}, {qdd} of eq. (14), what the kernels and the printed
  matrices are.  `element_vector` maps a weak form to this level, so each field-level statement is
  checked where the printed matrices live.
Everything returns SymPy objects or frozen records; expensive results are cached (treat them as
read-only).  crankgen.audit turns them into the report.

Modules, by concern (this package re-exports their public names):
- field_symbols: the field symbols, their LaTeX names, the split of an expression by order;
- weak_forms: slots, weak forms, the exact map to the element level, the split by term group
  (the classification itself is the derive stage groups.py);
- densities: energies (eqs. 1-7) and dissipation functions by order (report section 1);
- residuals: element residuals of each formulation and which one keeps each group (section 2);
- printed_vs_exact: the printed matrix form against the exact Lagrange equations (section 3);
- units: (M, L, T) exponents for the units checks;
- newmark: the Newmark update on scalar stand-ins (eqs. 35-39);
- errata: one verdict per transcription problem, and the conventions that follow from eq. (7).
Code generation (kernels.py, model.py, dispatch.py) does not import this package.
"""

from .. import symbols as s  # noqa: F401  (re-exported: the report reads the element symbols here)
from ..energies import slider_kinetic_energy  # noqa: F401
from ..groups import (  # noqa: F401  (re-exported: the audit names them)
    ELEMENT_VARS, GROUPS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, Variables, classify, group_vector,
)
from .densities import (  # noqa: F401
    DAMPING_MODELS, EQ17_PART, STRAIN_ORDERS, dissipation_density, dissipation_orders, eq2_density,
    eq17_density, eq18_density, eq24_density, kelvin_voigt_density, kinetic_density, kinetic_parts,
    membrane_square_check, printed_elastic_weak_form, section_strain_energy, strain_density, strain_orders,
)
from .errata import (  # noqa: F401
    Evidence, Verdict, convention_checks, errata_verdicts, erratum_b3, erratum_b15_b16, erratum_eq1,
    erratum_eq29, erratum_eq37, erratum_eq39,
)
from .field_symbols import (  # noqa: F401
    ACCELS, APPROACHES, COORDS, FIELD_LATEX_NAMES, GRADIENT_RATES, GRADIENTS, P, RATE_OF, RATES,
    order_split, psi, psid, psidd, u, u_x, ud, ud_x, udd, v, v_x, v_xx, v_xxx, vd, vd_x, vd_xx, vdd, x, y,
)
from .newmark import (  # noqa: F401
    D_PRED, DERIVS, H, NEWMARK_LATEX_NAMES, NM_BETA, NM_C, NM_DT, NM_F, NM_GAMMA, NM_K, NM_M, V_PRED,
    V_PRED_PREV, leading_order, newmark_defects, newmark_eq37_residual,
)
from .printed_vs_exact import (  # noqa: F401
    Difference, axial_force_vector, bilinear_matrix, common_factor, differences, elastic_asymmetry,
    eq17_checks, eq18_checks, eq24_rigid_dissipation, frozen_force_asymmetry, linear_parts,
    slider_eq24_dissipation, slider_eq24_guide_force, slope_gram, tangent_minus_secant,
)
from .residuals import (  # noqa: F401
    DAMPING_COLUMNS, FORMULATIONS, ROD_COLUMNS, KeepRow, damping_keep_table, printed_set, rod_T, rod_U,
    rod_damping, rod_damping_weak, rod_elastic, rod_elastic_weak, rod_inertia, rod_inertia_weak,
    rod_keep_table, slider_inertia, slider_keep_table,
)
from .units import (  # noqa: F401
    ANGULAR_MOMENTUM, DIMENSIONS, ENERGY, FORCE, MOMENT, MOMENTUM, dimensions, monomial_dimension,
)
from .weak_forms import (  # noqa: F401
    FIELD_VARS, SLOT, SLOTS, Slot, add_weak, dissipation_weak_form, element_integral, element_interpolated,
    element_vector, group_weak_form, interpolation, kinetic_weak_form, potential_weak_form, weak_form,
)

# LaTeX names of every symbol the report prints: the fields, the nodal values, the Newmark stand-ins.
LATEX_NAMES = {**FIELD_LATEX_NAMES, **NEWMARK_LATEX_NAMES}
