"""The range of the theory, and the approach whose strain energy has no lower bound.

**The paper's range** (approaches A, B and C: the paper's model, the consistent model).  The
element is built for moderate deflections and small strains (eq. 1, the von Karman strain of a
slender rod).  A result is **beyond the theory** when

- its largest transverse deflection |v| / L = eps |v*| exceeds DEFLECTION_LIMIT (0.1), or
- its largest axial strain exceeds STRAIN_LIMIT (0.01): the approach's own membrane strain of the
  neutral axis (u_x + v_x^2 / 2 for A and B, its element mean with membrane="averaged", u_x for
  C), at the nodes and element midpoints, over the stored steps (fiber = 0 of the declared
  output surface_strain).

Such numbers are outputs of the equations, not predictions of a real rod; the geometrically exact
rod (model="exact", REMEDY) drops none of the terms these limits guard, and the flag says so.

**The exact rod's own limits** (approach "exact").  Its kinematics are exact; what remains
approximated is the rod theory and the material, and the element's representation:
- SLENDERNESS_LIMIT (eps = r/L <= 0.05): Euler-Bernoulli, no shear deformation.  Shear lowers a
  pinned rod's first bending frequency by the factor 1/sqrt(1 + (pi eps)^2 E/(k G)) (Timoshenko;
  rotary inertia is already in the model): about 3.6 % at eps = 0.05 for a steel-like rectangle
  (E/(k G) = 2 (1 + nu)/k = 3.12, nu = 0.3, k = 5/6), 0.15 % at eps = 0.01;
- FIBRE_STRAIN_LIMIT (0.005): a linear elastic law, N = EA e and M = EI kappa, holds while the
  material is elastic.  The largest |axial strain| at the outer fibres of a rectangular section
  (fiber = +-sqrt(3) radii of gyration: e - y kappa), nodes and element midpoints over the stored
  steps, must stay below 0.5 %, the yield strain of high-strength steels and aluminium alloys
  (structural steel yields near 0.15 %: compare the measure's value with your material's);
- the section rotation is not limited: the element's tangent (1 + u_x, v_x) turns through any angle
  (a section may turn past 90 degrees from the chord).  Its largest value (degrees, from the
  chord, atan2(|v_x|, 1 + u_x) at the nodes) is reported beside the limits, as information.
An exact-model result is flagged when one of these is exceeded (EXACT_CRITERION), and the flag names
which; crankgen has no model beyond them.

Every command that writes a response flags it the same way: columns deflection_over_L,
axial_strain, beyond_theory ("yes" / "no", empty when the response does not exist) and range_note
(the tripped limits and what to use, empty when within); an exact-model row also fibre_strain and
section_rotation (degrees), and its beyond_theory is by its own limits.  In the API the flag is
data: `result.beyond_theory` of a SimulationResult or SteadyState is a RangeFlag (true when
beyond), with every Measure (name, value, limit) and those that tripped it; a continuation's
branches carry theirs point by point; simulate, steady_state(s) and continuation warn once
(BeyondTheoryWarning) when a response is beyond.

**Ill-posed is not unstable.**  Approach B drops the quartic term (EA/8) v_x^4 from the full square
(EA/2) (u_x + v_x^2/2)^2 of eq. (2).  What remains, (EA/2) (u_x^2 + u_x v_x^2), has its minimum
over u_x at u_x = -v_x^2/2, where it is -(EA/8) v_x^4: the strain energy is unbounded below in v_x
(the audit, section 1.1, derives it).  The equations of B are therefore ill-posed: a motion can
run off to ever larger deflections with ever lower energy.  A B run that diverges is that, not an
instability of a periodic state, and its numbers before it stopped are not an amplitude.
Approaches A (a full square) and C (quadratic) have energies bounded below by zero.
"""

import math
from dataclasses import dataclass

import numpy as np

from .. import notices
from ..notices import BeyondTheoryWarning  # noqa: F401  (re-exported)

DEFLECTION_LIMIT = 0.1
STRAIN_LIMIT = 0.01

EXACT = "exact"                    # the approach that has its own limits
SLENDERNESS_LIMIT = 0.05           # eps = r/L: no shear (module docstring)
FIBRE_STRAIN_LIMIT = 0.005         # outer-fibre strain: a linear elastic material
OUTER_FIBRE = math.sqrt(3.0)       # a rectangle's outer fibres, in radii of gyration
ROTATION_LIMIT = math.inf          # the section rotation is reported, not limited (module docstring)

# approach -> why its strain energy is unbounded below (approaches not listed: bounded below by 0)
UNBOUNDED_BELOW = {
    "B": "approach B drops the quartic term of eq. (2): its strain energy (EA/2)(u_x^2 + u_x v_x^2) "
         "falls to -(EA/8) v_x^4 at u_x = -v_x^2/2, so it is unbounded below",
}
ILL_POSED = "ill-posed: strain energy unbounded below"
CRITERION = (f"|v|/L = eps max|v*| > {DEFLECTION_LIMIT:g} or axial strain of the neutral axis "
             f"> {STRAIN_LIMIT:g}")
EXACT_CRITERION = (f"the exact rod's limits: slenderness eps > {SLENDERNESS_LIMIT:g} (no shear), outer-fibre "
                   f"strain > {FIBRE_STRAIN_LIMIT:g} (a linear elastic material)")

# what to use beyond the range (a model whose range covers it), shown by the flag and the warning
REMEDY = ('use model="exact": the geometrically exact rod drops none of the terms these limits guard '
          '(it has its own limits: slenderness, outer-fibre strain)')
# what each of the exact rod's limits leaves out: crankgen has no model beyond them
EXACT_BEYOND = {"slenderness": "shear deformation (a Timoshenko rod)",
                "fibre_strain": "plasticity (a material beyond its elastic range)"}


@dataclass(frozen=True)
class Measure:
    """One measure of the range of the theory: its name (a CSV column: deflection_over_L,
    axial_strain), its largest value over the response (nan when unknown) and its limit."""

    name: str
    value: float
    limit: float

    @property
    def exceeded(self):
        return math.isfinite(self.value) and self.value > self.limit

    @property
    def known(self):
        return math.isfinite(self.value)

    def __str__(self):
        label = {"deflection_over_L": "|v|/L", "axial_strain": "axial strain",
                 "slenderness": "slenderness r/L", "fibre_strain": "outer-fibre strain",
                 "section_rotation": "section rotation (deg)"}.get(self.name, self.name)
        if not self.known:
            return f"{label} unknown"
        if not math.isfinite(self.limit):                  # reported, not limited
            return f"{label} = {self.value:.3g}"
        return f"{label} = {self.value:.3g} {'>' if self.exceeded else '<='} {self.limit:g}"


@dataclass(frozen=True)
class RangeFlag:
    """Whether a response leaves the range of the theory, as data: true (bool) when a measure
    exceeds its limit; `measures` all of them, `tripped` those over their limit, `known` whether
    any was computed, `label` the CSV word ("yes", "no", "" when nothing is known), `remedy` what
    to use beyond it (REMEDY for the paper's range; for the exact rod what its limits leave out),
    `criterion` the limits in words (CRITERION or EXACT_CRITERION)."""

    measures: tuple
    remedy: str = ""
    criterion: str = CRITERION

    @property
    def beyond(self):
        return any(m.exceeded for m in self.measures)

    def __bool__(self):
        return self.beyond

    @property
    def tripped(self):
        return tuple(m for m in self.measures if m.exceeded)

    @property
    def known(self):
        return any(m.known for m in self.measures)

    def measure(self, name):
        return next(m for m in self.measures if m.name == name)

    @property
    def label(self):
        return "" if not self.known else ("yes" if self.beyond else "no")

    @property
    def reason(self):
        """The tripped measures in words ('' when none), e.g. '|v|/L = 0.54 > 0.1'."""
        return "; ".join(str(m) for m in self.tripped)

    @property
    def exact(self):
        """Whether these are the exact rod's own limits (EXACT_CRITERION)."""
        return self.criterion == EXACT_CRITERION

    @property
    def note(self):
        """The range_note column: the tripped limits and what to use (or what is left out), '' when
        within or unknown."""
        if not self.beyond:
            return ""
        if self.exact:
            return f"beyond the exact rod's limits ({self.reason}): {self.remedy}"
        return f"beyond the paper's range ({self.reason}): {self.remedy}"

    def __str__(self):
        if not self.known:
            return "range of the theory unknown (no response)"
        if not self.beyond:
            return "within the range of the theory (" + "; ".join(str(m) for m in self.measures if m.known) + ")"
        return (f"BEYOND THE THEORY ({self.reason}; criterion {self.criterion})"
                + (f"; {self.remedy}" if self.remedy else ""))


def range_flag(deflection=math.nan, strain=math.nan):
    """The RangeFlag of a response's largest deflection |v|/L and axial strain (nan: unknown)."""
    def value(x):
        try:
            x = float(x)
        except (TypeError, ValueError):
            return math.nan
        return x if math.isfinite(x) else math.nan
    return RangeFlag((Measure("deflection_over_L", value(deflection), DEFLECTION_LIMIT),
                      Measure("axial_strain", value(strain), STRAIN_LIMIT)), REMEDY)


def _finite(x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        return math.nan
    return x if math.isfinite(x) else math.nan


def exact_range_flag(slenderness=math.nan, fibre_strain=math.nan, rotation=math.nan):
    """The RangeFlag of an exact-model response by the exact rod's own limits: its slenderness eps,
    largest outer-fibre strain and largest section rotation (degrees; nan: unknown; reported, not
    limited)."""
    tripped = [name for name, x, lim in (("slenderness", slenderness, SLENDERNESS_LIMIT),
                                         ("fibre_strain", fibre_strain, FIBRE_STRAIN_LIMIT))
               if math.isfinite(_finite(x)) and _finite(x) > lim]
    remedy = ("crankgen has no model of " + " nor of ".join(EXACT_BEYOND[n] for n in tripped)) if tripped else ""
    return RangeFlag((Measure("slenderness", _finite(slenderness), SLENDERNESS_LIMIT),
                      Measure("fibre_strain", _finite(fibre_strain), FIBRE_STRAIN_LIMIT),
                      Measure("section_rotation", _finite(rotation), ROTATION_LIMIT)), remedy, EXACT_CRITERION)


def is_exact(case):
    """Whether a case (or a model's options) is the exact rod's (its own limits)."""
    approach = case.get("approach") if isinstance(case, dict) else getattr(case, "approach", None)
    return approach == EXACT


def flag_of(result):
    """The RangeFlag of a result that stores its per-step v* (SimulationResult, SteadyState): its
    largest |v|/L = eps max|v*| and largest axial strain (axial_strain) over its steps; for the
    exact rod its own measures (exact_measures)."""
    v = getattr(result, "v_mid", None)
    case = getattr(result, "case", None)
    if case is not None and is_exact(case):
        if v is None or not np.size(v):
            return exact_range_flag(case.eps)
        fibre, rotation = exact_measures(result)
        return exact_range_flag(case.eps, fibre, rotation)
    if v is None or case is None or not np.size(v):
        return range_flag()
    v = np.abs(np.asarray(v, dtype=float))
    with np.errstate(invalid="ignore"):
        deflection = float(case.eps * np.nanmax(v)) if np.isfinite(v).any() else math.nan
    return range_flag(deflection, axial_strain(result))


def warn_beyond(results, what="response", stacklevel=3):
    """Warn once (BeyondTheoryWarning) when any of the results is beyond the theory: the first,
    and how many more.  Silent inside crankgen.notices.quiet()."""
    if notices.silenced(BeyondTheoryWarning):
        return
    flags = [r.beyond_theory for r in results if r is not None and getattr(r, "case", None) is not None]
    beyond = [f for f in flags if f]
    if beyond:
        more = f" (and {len(beyond) - 1} more of {len(flags)})" if len(beyond) > 1 else ""
        first = beyond[0]
        notices.warn(BeyondTheoryWarning, f"the {what} is beyond the theory ({first.reason}){more}: its "
                     f"numbers are the equations' output, not a prediction of the rod (criterion "
                     f"{first.criterion}); result.beyond_theory holds the measures"
                     + (f"; {first.remedy}" if first.remedy else ""), stacklevel=stacklevel)


def ill_posed(approach):
    """Whether an approach's strain energy is unbounded below (its equations are ill-posed)."""
    return approach in UNBOUNDED_BELOW


def strain_energy(approach):
    """'bounded below' or 'unbounded below (ill-posed)': the words the CSV files carry."""
    return "unbounded below (ill-posed)" if ill_posed(approach) else "bounded below"


def deflection_over_L(eps, v_star):
    """|v| / L of a deflection v* (scaled by r) at slenderness eps (nan when unknown)."""
    try:
        x = abs(float(eps) * float(v_star))
    except (TypeError, ValueError):
        return math.nan
    return x if math.isfinite(x) else math.nan


def axial_strain(result, per_step=False):
    """Largest |axial strain of the neutral axis| of a result that stores its states
    (SimulationResult, SteadyState), over the nodes and element midpoints: one value per stored
    step (per_step) or the largest over them; nan when the result holds no states."""
    if getattr(result, "states", None) is None or getattr(result, "case", None) is None:
        t = getattr(result, "t", None)
        return np.full(0 if t is None else len(t), math.nan) if per_step else math.nan
    values = None
    for x in np.linspace(0.0, 1.0, 2 * result.case.n_elements + 1):      # one point at a time:
        with np.errstate(over="ignore", invalid="ignore"):              # memory of one step array
            e = np.abs(np.asarray(result.quantity("surface_strain", float(x), fiber=0.0), dtype=float))
        e = np.where(np.isnan(e), np.inf, e)           # the history of a run that diverged
        values = e if values is None else np.maximum(values, e)
    return values if per_step else (float(values.max()) if values.size else math.nan)


def exact_measures(result, per_step=False):
    """(largest |outer-fibre strain|, largest section rotation in degrees) of an exact-model result
    that stores its states: the strain e - y kappa at fiber = +-OUTER_FIBRE over the nodes and
    element midpoints; the rotation |atan2(v_x, 1 + u_x)| from the chord at the nodes (0 to 180).
    One value per stored step (per_step) or the largest over them; nan when the result holds no
    states."""
    case = getattr(result, "case", None)
    if getattr(result, "states", None) is None or case is None:
        t = getattr(result, "t", None)
        empty = np.full(0 if t is None else len(t), math.nan)
        return (empty, empty.copy()) if per_step else (math.nan, math.nan)
    from ..discrete.mesh import CHI, NODE_DOFS, PSI
    n = case.n_elements
    fibre = None
    with np.errstate(over="ignore", invalid="ignore"):
        for x in np.linspace(0.0, 1.0, 2 * n + 1):
            for y in (OUTER_FIBRE, -OUTER_FIBRE):
                e = np.abs(np.asarray(result.quantity("surface_strain", float(x), fiber=y), dtype=float))
                e = np.where(np.isnan(e), np.inf, e)
                fibre = e if fibre is None else np.maximum(fibre, e)
        q = result._history().element_vectors()
        angles = [np.abs(np.arctan2(q[..., node * NODE_DOFS + PSI], 1.0 + q[..., node * NODE_DOFS + CHI]))
                  for node in (0, 1)]
        rotation = np.degrees(np.maximum(*angles))
        rotation = np.where(np.isfinite(rotation), rotation, 180.0).max(axis=-1)
    if per_step:
        return fibre, rotation
    return ((float(fibre.max()) if fibre.size else math.nan),
            (float(rotation.max()) if rotation.size else math.nan))


def beyond(deflection=math.nan, strain=math.nan):
    """"yes" when either measure exceeds its limit, "no" when the known ones do not, "" when
    neither is known."""
    known = [(x, lim) for x, lim in ((deflection, DEFLECTION_LIMIT), (strain, STRAIN_LIMIT))
             if x is not None and math.isfinite(x)]
    if not known:
        return ""
    return "yes" if any(x > lim for x, lim in known) else "no"


def reasons(deflection=math.nan, strain=math.nan):
    """The exceeded limits in words ('' when none)."""
    out = []
    if deflection is not None and math.isfinite(deflection) and deflection > DEFLECTION_LIMIT:
        out.append(f"|v|/L = {deflection:.3g} > {DEFLECTION_LIMIT:g}")
    if strain is not None and math.isfinite(strain) and strain > STRAIN_LIMIT:
        out.append(f"axial strain {strain:.3g} > {STRAIN_LIMIT:g}")
    return "; ".join(out)
