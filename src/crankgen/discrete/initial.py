"""An initial elastic state of the rod, projected onto the mesh and checked against the pin and the
guide.

The state is given in the moving frame of the RIGID mechanism at the start angle theta0 (e_i along
the rigid chord from the crank pin to the rigid end point, e_j a quarter turn counter-clockwise
of it, both turning with the rigid rod; derive/guides.py), as the rod's displacement fields and
their time derivatives in that frame, functions of the material position x along the rod
(0 <= x <= L):

    u(x)    axial displacement (along e_i),          u_t(x)   its rate d u / dt,
    v(x)    transverse displacement (along e_j),     v_t(x)   its rate d v / dt,
    v_x(x)  the slope d v / dx,                      v_xt(x)  its rate,
    u_x(x)  the slope d u / dx (the exact rod only), u_xt(x)  its rate.

The default, every field zero, is the rigid mechanism at theta0 with the rod undeformed and at rest
in the moving frame (the paper's start).  A field is None (zero), a callable of x (called with the
array of the n + 1 node positions; a function of a scalar only is called node by node), or the
array of its n + 1 nodal values (nodes x_k = k L / n).  The slopes v_x and v_xt (u_x and u_xt)
default to the derivatives of v and v_t (u and u_t): a callable is differentiated by the complex
step, v'(x) = Im v(x + i h) / h with h = 1e-20 L (exact to rounding for any analytic function that
accepts complex arguments); nodal arrays of v or v_t need their slopes given (of u or u_t, on the
exact rod).

Projection: nodal interpolation.  The element interpolates u linearly (the exact rod: cubic Hermite
in u and chi = u_x) and v with cubic Hermite polynomials (Appendix A), from the nodal values of u,
v and psi = v_x; crankgen takes those values from the fields at the nodes, so that a field in the
element space (u piecewise linear, v piecewise cubic with continuous slope, on the mesh) is
reproduced exactly, and any other field with the interpolation error of the element (O(h^2) in u,
O(h^4) in v).  The same holds for the rates.

Checks: the rod is pinned to the crank, so u, v, u_t, v_t vanish at x = 0; its end lies on the
guide and moves along it, so (u, v)(L) = g(s) and (u_t, v_t)(L) = g_s s_t + dg/dt for some s and
s_t (the guide's end map, derive/guides.py: for the slider g = s (cos phi, sin phi)).  A state that
violates either by more than `tol` times the natural size of the co-ordinate (eps^2 L axially and
for the end's guide co-ordinate, eps L transversely; the same per unit time 1/omega_b for the
rates) is refused with a ParameterError naming the field.  s and s_t are found by Gauss-Newton on
the end map.
"""

import math
from dataclasses import dataclass

import numpy as np

from . import kinematics as _kinematics
from ..declaration import schema
from ..errors import ParameterError
from .mesh import CHI, PSI, U, V, Mesh, components_of, nodal_mesh

COMPLEX_STEP = 1e-20
# the unit of each field (derive/declaration.py's units strings; crankgen.declaration.units)
FIELD_UNITS = {"u": "L", "v": "L", "v_x": "1", "u_t": "L omega_b", "v_t": "L omega_b", "v_xt": "omega_b",
               "u_x": "1", "u_xt": "omega_b"}
_SLOPE_OF = {"v_x": "v", "v_xt": "v_t", "u_x": "u", "u_xt": "u_t"}


@dataclass(frozen=True)
class InitialState:
    """The rod's elastic state at t = 0 in the rigid moving frame at theta0 (module docstring): each
    field None (zero), a callable of x or its nodal values; `tol`: the refusal threshold of the pin
    and guide checks, relative to the natural sizes."""

    u: object = None
    v: object = None
    u_t: object = None
    v_t: object = None
    v_x: object = None
    v_xt: object = None
    u_x: object = None
    u_xt: object = None
    tol: float = 1e-6

    def __post_init__(self):
        for name in FIELD_UNITS:
            value = getattr(self, name)
            if value is not None and not callable(value):
                arr = np.asarray(value)
                if arr.ndim != 1 or not np.issubdtype(arr.dtype, np.number) or np.iscomplexobj(arr):
                    raise ParameterError(f"initial state: {name} must be None, a callable of x or a "
                                         f"1-d array of its nodal values, got {value!r}")
        for slope, field in _SLOPE_OF.items():
            if getattr(self, slope) is not None and getattr(self, field) is None:
                raise ParameterError(f"initial state: {slope} is given without {field}")
        if isinstance(self.tol, (bool, np.bool_)) or not isinstance(self.tol, (int, float, np.integer, np.floating)) \
                or not 0 < self.tol < math.inf:
            raise ParameterError(f"initial state: tol must be a finite number > 0 (a fraction of the "
                                 f"natural sizes, default 1e-6), got {self.tol!r}")

    @property
    def is_rest(self):
        """True when every field is None: the rigid mechanism with the rod undeformed and at rest."""
        return all(getattr(self, name) is None for name in FIELD_UNITS)


def _numeric(values):
    """values as an array of numbers, or None when they are not numbers (text, a dict, booleans)."""
    try:
        arr = np.asarray(values)
    except Exception:
        return None
    return arr if arr.dtype.kind in "iufc" else None


def _evaluate(name, fn, x, complex_ok=False):
    """fn at the node positions x: vectorized, else node by node; one real number per node
    (crankgen.callables' rule, which names the field and what the callable returned).  complex_ok:
    the complex step's call (complex values kept, a failure raised as it is)."""
    from ..declaration.callables import check_values
    who = f"initial state: {name}(x)"
    values = None
    try:
        values = _numeric(fn(x))
        if values is not None and values.shape not in ((), x.shape):
            values = None
    except Exception:
        values = None
    if values is None:
        try:
            one = [fn(xk) for xk in x]
        except Exception as exc:
            if complex_ok:
                raise
            raise ParameterError(f"initial state: calling {name}(x) failed: {exc}") from None
        values = _numeric(one)
        if values is None or values.shape != x.shape:
            values = one                                # check_values says what is wrong with it
    if complex_ok:
        return np.broadcast_to(np.asarray(values), x.shape)
    return check_values(who, values, x)


def _nodal(name, value, x_user, n):
    """Nodal values (user units) of one field."""
    if value is None:
        return np.zeros(n + 1)
    if callable(value):
        out = _evaluate(name, value, x_user)
    else:
        out = np.asarray(value, dtype=float)
        if out.shape != (n + 1,):
            raise ParameterError(f"initial state: {name} as nodal values needs {n + 1} values (n_elements "
                                 f"+ 1, at x_k = k L / n), got {out.shape[0]}")
    out = np.asarray(out, dtype=float)
    if not np.all(np.isfinite(out)):
        raise ParameterError(f"initial state: {name} is not finite at every node")
    return out


def _slope(name, initial, x_user, n, length):
    """Nodal values of v_x or v_xt: given, or the complex-step derivative of the callable field."""
    given = getattr(initial, name)
    if given is not None:
        return _nodal(name, given, x_user, n)
    field = getattr(initial, _SLOPE_OF[name])
    if field is None:
        return np.zeros(n + 1)
    if not callable(field):
        raise ParameterError(f"initial state: {_SLOPE_OF[name]} is given as nodal values: give "
                             f"{name} too (its slopes at the nodes)")
    h = COMPLEX_STEP * length
    try:
        values = _evaluate(_SLOPE_OF[name], field, x_user + 1j * h, complex_ok=True)
    except Exception:
        values = None
    if values is None or not np.iscomplexobj(values):
        raise ParameterError(f"initial state: {_SLOPE_OF[name]} is a callable that does not take "
                             f"complex arguments, so its slope cannot be taken by the complex step: "
                             f"give {name}")
    out = np.imag(values) / h
    if not np.all(np.isfinite(out)):
        raise ParameterError(f"initial state: the slope {name} of {_SLOPE_OF[name]} is not finite at every node")
    return out


def _end_coordinate(case, kin, target, rate_target):
    """(s, sd, position misfit, rate misfit) of the end map closest to the end node's (u, v) and
    (u_t, v_t) (Gauss-Newton on g(s) = target; the rate is linear in sd)."""
    R = schema.END_MAP_ROWS
    s = 0.0
    for _ in range(60):
        E = _kinematics.end_map(case, kin, s)
        g, gs = E[R["q"]], E[R["g_s"]]
        step = float(gs @ (target - g) / (gs @ gs))
        s += step
        if abs(step) <= 1e-16 * (1.0 + abs(s)):
            break
    E = _kinematics.end_map(case, kin, s)
    misfit = float(np.linalg.norm(target - E[R["q"]]))
    gs, qd0 = E[R["g_s"]], E[R["qd"]]                    # rates at sd = 0
    sd = float(gs @ (rate_target - qd0) / (gs @ gs))
    E = _kinematics.end_map(case, kin, s, sd)
    rate_misfit = float(np.linalg.norm(rate_target - E[R["qd"]]))
    return s, sd, misfit, rate_misfit


def reduced_state(case, initial, scales=None):
    """(d0, v0): the reduced displacements and velocities (mesh.py's layout) of an InitialState for
    a case, projected by nodal interpolation and checked against the pin and the guide.  scales: a
    crankgen.declaration.units.Scales when the fields are in SI (x in m, u and v in m, u_t and v_t in m/s, v_x
    dimensionless, v_xt in 1/s); None: crankgen's units."""
    mesh = nodal_mesh(case)
    if mesh.rocker_elements:
        raise ParameterError("initial state: an InitialState gives the rod's fields alone; with a flexible rocker "
                             "give the reduced vectors (d0, v0) of the whole DOF map instead")
    n = mesh.n_elements
    x = np.arange(n + 1) / n
    length = 1.0 if scales is None else scales.L
    x_user = x * length

    def factor(name):
        return 1.0 if scales is None else scales.factor(FIELD_UNITS[name])

    values = {}
    for name in ("u", "v", "u_t", "v_t"):
        values[name] = _nodal(name, getattr(initial, name), x_user, n) / factor(name)
    slopes = ("v_x", "v_xt") + (("u_x", "u_xt") if "chi" in mesh.components else ())
    for name in slopes:
        values[name] = _slope(name, initial, x_user, n, length) / factor(name)

    tol = float(initial.tol)
    sizes = dict(zip(schema.NODE, case.natural_sizes))    # u: eps^2, v: eps
    natural = {"u": sizes["u"], "u_t": sizes["u"], "v": sizes["v"], "v_t": sizes["v"]}
    for name in ("u", "v", "u_t", "v_t"):
        at_pin = values[name][0]
        if abs(at_pin) > tol * natural[name]:
            unit = "crankgen units" if scales is None else scales.si_name(FIELD_UNITS[name])
            raise ParameterError(
                f"initial state: {name}(0) = {at_pin * factor(name):.6g} {unit}, but the rod is pinned to "
                f"the crank at x = 0, so {name}(0) must be 0 (tolerance {tol:g} of its natural size "
                f"{natural[name]:.3g} in crankgen's units)")

    kin = _kinematics.case_state(case, 0.0).vector
    s, sd, misfit, rate_misfit = _end_coordinate(
        case, kin, np.array([values["u"][n], values["v"][n]]), np.array([values["u_t"][n], values["v_t"][n]]))
    guide_scale = _kinematics.end_scale(case)
    for fields, off in (("u, v", misfit), ("u_t, v_t", rate_misfit)):
        if not off <= tol * guide_scale:
            what = ("is off the guide" if fields == "u, v" else
                    "has a velocity off the guide's (the end's velocity g_s s_t + dg/dt for any s_t)")
            raise ParameterError(
                f"initial state: the rod's end ({fields} at x = L) {what} by {off:.3g} (crankgen's "
                f"units; tolerance {tol:g} of the guide co-ordinate's natural size {guide_scale:.3g}): "
                f"the end must stay on the {case.guide_record.name} guide of the rigid mechanism at theta0 = "
                f"{case.theta0:g}")

    d0, v0 = np.zeros(mesh.n_dofs), np.zeros(mesh.n_dofs)
    for k in range(n + 1):
        for component, (disp, rate) in ((U, ("u", "u_t")), (V, ("v", "v_t")), (PSI, ("v_x", "v_xt")),
                                        (CHI, ("u_x", "u_xt"))):
            idx = mesh.reduced_index(k, component)
            if idx is not None:
                d0[idx] = values[disp][k]
                v0[idx] = values[rate][k]
    d0[mesh.reduced_coordinates()[0]], v0[mesh.reduced_coordinates()[0]] = s, sd
    return d0, v0


def initial_state(case, initial, scales=None):
    """(d0, v0, g0) of simulate's `initial`: None (zero: the rigid mechanism at rest), an InitialState
    (or a dict of its fields), a pair (d0, v0) of reduced vectors, or a triple (d0, v0, g0) with
    generalized-alpha's algorithmic accelerations (the three thirds of a SteadyState.state); g0 is
    None unless given (the run then starts from g0 = the accelerations of eq. 34).  The vectors are
    the rod's nodal ones (3 n_elements), or, for a driven motion, the DOF map's whole state (its
    co-ordinates after them)."""
    mesh = nodal_mesh(case)
    N = mesh.n_dofs
    if initial is None:
        return np.zeros(N), np.zeros(N), None
    if isinstance(initial, dict):
        try:
            initial = InitialState(**initial)
        except TypeError as exc:
            raise ParameterError(f"initial state: {exc}; the fields are {', '.join(FIELD_UNITS)} and tol") from None
    if isinstance(initial, InitialState):
        if initial.is_rest:
            return np.zeros(N), np.zeros(N), None
        return reduced_state(case, initial, scales) + (None,)
    if scales is not None:
        raise ParameterError("initial as reduced vectors (d0, v0) is in crankgen's units; with units='si' "
                             "give a crankgen.InitialState")
    try:
        vectors = [np.asarray(x, dtype=float) for x in initial]
    except (TypeError, ValueError):
        raise ParameterError("initial must be None, a crankgen.InitialState (or a dict of its fields), "
                             f"two reduced vectors (d0, v0) or three (d0, v0, a0), got {initial!r}") from None
    full = Mesh.of_case(case).n_dofs            # with a driven motion's co-ordinates: the DOF map's whole state
    lengths = {N} | {full}
    if len(vectors) not in (2, 3) or any(x.shape[0] not in lengths or x.ndim != 1 or not np.all(np.isfinite(x))
                                         for x in vectors) or len({x.shape for x in vectors}) > 1:
        also = f" (or {full}, with the motion's co-ordinates)" if full != N else ""
        raise ParameterError(f"initial must be two (d0, v0) or three (d0, v0, a0) finite vectors of "
                             f"length {N} (the rod's nodal unknowns){also}")
    if len(vectors) == 3 and case.rho_inf == 1.0:
        raise ParameterError("initial's third vector, algorithmic accelerations, belongs to generalized-alpha "
                             "(rho_inf < 1); Newmark (rho_inf = 1) starts from (d0, v0)")
    return vectors[0], vectors[1], (vectors[2] if len(vectors) == 3 else None)
