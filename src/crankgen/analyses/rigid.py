"""The rigid mechanism beside the flexible one: how much the rod's flexibility changes the crank
torque, the pin forces and the stress (a designer's first question).

**Rigid** is the kineto-static analysis a designer would otherwise do by hand: the rigid
mechanism's motion, and the rod's quasi-static deformation under its loads.  At each crank angle of
the revolution the model's own equations (eq. 30) are solved with the rod at rest in the moving
frame of the rigid mechanism, R(t, d, 0, 0) = 0, every row (Newton's method on the model's tangent,
crankgen.model.Model: the elastic and geometric stiffness, the end constraint): the rigid motion's
inertia and gravity loads, carried statically.  Its torque and joint forces are the rigid inverse
dynamics (plus the deformation's small effect on the geometry, of the order of the deflection over
L); its axial force and bending moment are the rigid rod's internal forces (with the P-delta
effect of the axial force), from which the rigid stresses follow.  **Flexible** is the steady
periodic state of the same mechanism (crankgen.steady_state): the rod's vibration included.

`compare` gives both, on the same crank angles, and the table of the quantities a designer sizes
by: the peak crank torque, the RMS torque, the peak pin forces at A and B (magnitudes), the peak
axial compression and bending moment and, with a crankgen.sections.Section, the peak outer-fibre
stress; each with flexible over rigid.  A crank that turns at a constant speed only (the rigid
motion of a run-up or a motor has no revolution to repeat).
"""

from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from ..declaration import schema
from ..errors import ConvergenceError, ParameterError
from ..results.outputs import DeclaredOutputs
from ..declaration.units import Scales
from .blas import single_thread

NEWTON_TOL = 1e-12
NEWTON_ITERATIONS = 40


@dataclass(frozen=True)
class RigidResult(DeclaredOutputs):
    """The kineto-static states of a revolution (module docstring): every declared output by name
    (torque, joint forces, axial_force(x), bending_moment(x), ...), in SI through `si` when made
    from a crankgen.SIMechanism."""

    case: object
    t: np.ndarray
    theta: np.ndarray
    states: np.ndarray = field(repr=False)
    rates: np.ndarray = field(repr=False)
    accelerations: np.ndarray = field(repr=False)
    outputs: dict = field(default=None, repr=False)
    scales: Optional[Scales] = field(default=None, repr=False)


def kineto_static(case, t):
    """The RigidResult of a case at times t (its crank at the prescribed motion's angles): the
    reduced states with R(t, d, 0, 0) = 0, by Newton's method from the straight rod."""
    from ..discrete import kinematics as _kinematics
    from .model_error import _dense
    from ..discrete.system import Model
    if case.motion_record.driven:
        raise ParameterError("the rigid mechanism needs a prescribed crank motion; this case's crank is "
                             "motor-driven (its speed is an unknown of the flexible model)")
    t = np.asarray(t, dtype=float)
    model = Model(case)
    kin = model.kinematics(t)
    N = model.mesh.n_dofs
    scales = model.mesh.dof_scales(case.natural_sizes, _kinematics.end_scale(case))
    d = np.zeros((t.size, N))
    zero = np.zeros_like(d)
    with single_thread():               # the Newton iterations' small dense solves
        for _ in range(NEWTON_ITERATIONS):
            r, K, _, _ = _dense(model, kin, d, zero, zero)
            step = -np.linalg.solve(K, r[..., None])[..., 0]
            d += step
            if not np.all(np.isfinite(d)):
                break
            size = np.max(np.abs(d) / scales, axis=1)
            if np.all(np.max(np.abs(step) / scales, axis=1) <= NEWTON_TOL * (1 + size)):
                return RigidResult(case, t, np.asarray(kin.theta, dtype=float), d, zero, zero.copy())
    raise ConvergenceError(f"the rigid mechanism's quasi-static rod did not converge at Omega* = "
                           f"{case.omega:g} (its compression beyond the rod's buckling load?)")


@dataclass(frozen=True)
class Comparison:
    """The rigid (kineto-static) and flexible (steady) mechanism on the same crank angles: `rows`,
    one per quantity {quantity, units, rigid, flexible, ratio}; `rigid` (RigidResult), `flexible`
    (SteadyState); `si` whether the numbers are in SI."""

    rows: list
    rigid: RigidResult = field(repr=False)
    flexible: object = field(repr=False)
    si: bool = False

    def row(self, quantity):
        return next(r for r in self.rows if r["quantity"] == quantity)

    def summary(self):
        """The table as lines of text."""
        width = max(len(r["quantity"]) for r in self.rows)
        lines = [f"{'':{width}}  {'rigid':>11}  {'flexible':>11}  flexible/rigid"]
        for r in self.rows:
            ratio = "—" if r["ratio"] is None else f"{r['ratio']:.4g}"
            scale, units = (1e6, "MPa") if r["units"] == "Pa" else (1.0, r["units"])
            lines.append(f"{r['quantity']:{width}}  {r['rigid'] / scale:11.4g}  {r['flexible'] / scale:11.4g}  "
                         f"{ratio:>8}  {units}")
        return lines

    def to_csv(self, path):
        from ..results.io import write_csv
        return write_csv(path, ["quantity", "units", "rigid", "flexible", "ratio"], self.rows)

    def plot(self, path):
        """The torque and the pin forces over the revolution, rigid (dashed) and flexible."""
        from ..plots.rigid import plot_comparison
        return plot_comparison(self, path)


def _views(result, scales):
    from ..results.outputs import SIView
    return result if scales is None else SIView(result, scales)


def _quantities(result, scales, section, si):
    """{quantity: (units, peak value)} of one result."""
    from .rod_loads import joints
    from .stresses import stress
    view = _views(result, scales)
    n = result.case.n_elements
    xs = np.arange(2 * n + 1) / (2 * n)
    length = 1.0 if scales is None else scales.L
    torque = np.asarray(view.quantity("torque"), dtype=float)

    def unit(name):
        declared = schema.OUTPUTS[name].units
        return declared if scales is None else Scales.si_name(declared)
    out = {"peak torque": (unit("torque"), float(np.max(np.abs(torque)))),
           "RMS torque": (unit("torque"), float(np.sqrt(np.mean(torque[:-1] ** 2 if len(torque) > 1 else torque ** 2))))}
    for base, x, y in joints(result.case.guide_record.name)[:2]:          # the pins at A and B
        f = np.hypot(np.asarray(view.quantity(x), dtype=float), np.asarray(view.quantity(y), dtype=float))
        out[f"peak {base.replace('_', ' ')} force"] = (unit(x), float(np.max(f)))
    N = np.asarray(view.quantity("axial_force", xs * length), dtype=float)
    M = np.asarray(view.quantity("bending_moment", xs * length), dtype=float)
    out["peak compression"] = (unit("axial_force"), float(max(0.0, -np.min(N))))
    out["peak tension"] = (unit("axial_force"), float(max(0.0, np.max(N))))
    out["peak bending moment"] = (unit("bending_moment"), float(np.max(np.abs(M))))
    if section is not None:
        history = stress(result, section, si=si) if si is not None else stress(result, section)
        peak = max(abs(history.maximum.value), abs(history.minimum.value))
        out["peak stress"] = ("Pa" if si is not None else "E", float(peak))
    return out


def compare(mech=None, omega=None, *, section=None, model=None, case=None, units="crankgen", **fields):
    """The rigid and the flexible mechanism side by side (module docstring): a Mechanism and its
    crank speed omega (Omega*) with the run's settings, or case=; units="si": a crankgen.SIMechanism
    (its crank speed; the table in N, N m, Pa).  section: a crankgen.sections.Section for the peak
    stress (in SI the rod's section).  Returns a Comparison."""
    from ..declaration.cases import run_case
    from ..declaration.si import si_input
    from .steady import steady_states
    from .stresses import check_section
    from ..declaration.sections import Section
    si = mech if units == "si" else None
    mech, crank, scales = si_input(mech, units, fields, omega=omega, case=case, what="compare")
    c = run_case(mech, case, model=model, omega=omega, crank=crank, **fields)
    if c.motion_record.name != schema.PARAMETERS[schema.SELECTOR["motion"]].default:
        raise ParameterError(f"the comparison needs a crank at a constant speed (its rigid motion repeats "
                             f"every revolution); the crank motion is {c.motion_record.name!r}")
    if section is not None:
        if not isinstance(section, Section):
            raise ParameterError(f"section must be a crankgen.sections.Section, got {type(section).__name__}")
        check_section(section, si)
    flexible = steady_states([c])[0]
    if flexible.states is None:
        raise ConvergenceError(f"the flexible mechanism has no periodic orbit here ({flexible.status}: "
                               f"{flexible.message})")
    rigid = kineto_static(c, flexible.t)
    if scales is not None:
        flexible, rigid = replace(flexible, scales=scales), replace(rigid, scales=scales)
    a, b = _quantities(rigid, scales, section, si), _quantities(flexible, scales, section, si)
    rows = [{"quantity": q, "units": a[q][0], "rigid": a[q][1], "flexible": b[q][1],
             "ratio": (b[q][1] / a[q][1]) if a[q][1] > 0 else None} for q in a]
    return Comparison(rows, rigid, flexible, scales is not None)
