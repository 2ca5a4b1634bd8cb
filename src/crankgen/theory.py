"""The range of the theory, and the approach whose strain energy has no lower bound.

The element is built for moderate deflections and small strains (eq. 1, the von Karman strain of
a slender rod).  A result is **beyond the theory** when

- its largest transverse deflection |v| / L = eps |v*| exceeds DEFLECTION_LIMIT (0.1), or
- its largest axial strain exceeds STRAIN_LIMIT (0.01): the approach's own membrane strain of the
  neutral axis (u_x + v_x^2 / 2 for A and B, its element mean with membrane="averaged", u_x for
  C), at the nodes and element midpoints, over the stored steps (fiber = 0 of the declared
  output surface_strain).

Such numbers are outputs of the equations, not predictions of a real rod.  Every command that
writes a response flags them the same way: columns deflection_over_L, axial_strain and
beyond_theory ("yes" / "no", empty when the response does not exist).  In the API the flag is
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

from . import notices
from .notices import BeyondTheoryWarning  # noqa: F401  (re-exported)

DEFLECTION_LIMIT = 0.1
STRAIN_LIMIT = 0.01

# approach -> why its strain energy is unbounded below (approaches not listed: bounded below by 0)
UNBOUNDED_BELOW = {
    "B": "approach B drops the quartic term of eq. (2): its strain energy (EA/2)(u_x^2 + u_x v_x^2) "
         "falls to -(EA/8) v_x^4 at u_x = -v_x^2/2, so it is unbounded below",
}
ILL_POSED = "ill-posed: strain energy unbounded below"
CRITERION = (f"|v|/L = eps max|v*| > {DEFLECTION_LIMIT:g} or axial strain of the neutral axis "
             f"> {STRAIN_LIMIT:g}")


# what to use beyond the range (a model whose range covers it), shown by the flag and the warning;
# empty while crankgen has none
REMEDY = ""


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
        label = {"deflection_over_L": "|v|/L", "axial_strain": "axial strain"}.get(self.name, self.name)
        if not self.known:
            return f"{label} unknown"
        return f"{label} = {self.value:.3g} {'>' if self.exceeded else '<='} {self.limit:g}"


@dataclass(frozen=True)
class RangeFlag:
    """Whether a response leaves the range of the theory, as data: true (bool) when a measure
    exceeds its limit; `measures` all of them, `tripped` those over their limit, `known` whether
    any was computed, `label` the CSV word ("yes", "no", "" when nothing is known), `remedy` what
    to use beyond it (REMEDY)."""

    measures: tuple
    remedy: str = ""

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

    def __str__(self):
        if not self.known:
            return "range of the theory unknown (no response)"
        if not self.beyond:
            return "within the range of the theory (" + "; ".join(str(m) for m in self.measures if m.known) + ")"
        return (f"BEYOND THE THEORY ({self.reason}; criterion {CRITERION})"
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


def flag_of(result):
    """The RangeFlag of a result that stores its per-step v* (SimulationResult, SteadyState): its
    largest |v|/L = eps max|v*| and largest axial strain (axial_strain) over its steps."""
    v = getattr(result, "v_mid", None)
    case = getattr(result, "case", None)
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
        notices.warn(BeyondTheoryWarning, f"the {what} is beyond the theory ({beyond[0].reason}){more}: its "
                     f"numbers are the equations' output, not a prediction of the rod (criterion {CRITERION}); "
                     f"result.beyond_theory holds the measures" + (f"; {REMEDY}" if REMEDY else ""),
                     stacklevel=stacklevel)


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
