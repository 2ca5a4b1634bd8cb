"""The outputs a result can give, declared in derive/declaration.py (OUTPUTS) and read from the schema:
quantities the engine computes at every step (v_mid, u_end, extension), step quantities (one value
per stored step: the crank speed, the end's position, the chord angle, the driving torque, the pin
and end reactions, ...) and fields (per step, at any x* in [0, 1]: axial_force, bending_moment,
surface_strain, chord_deflection, ...).

Each step or field output is a generated kernel whose inputs the schema names; StateHistory
supplies them from the stored reduced states: the kinematics, the nodal vector of the element
holding x*, the end node's (u, v), their rates and the reduced co-ordinate, and the reactions at the pin and the
end (the residual rows of the constrained DOFs, which need the stored velocities and
accelerations).  Quantities made of element-wise derivatives (u_x is constant in an element, v_xx
linear) jump at the nodes; at an interior node crankgen returns the mean of the two elements'
values (the average of the one-sided limits), inside an element the element's own value.
"""

import numpy as np

from . import ingredients, schema
from . import kinematics as _kinematics
from ._generated.shape import shape_functions, slope_gram
from .errors import ParameterError
from .mesh import Mesh
from .validation import finite_number, in_range

NODE_TOLERANCE = 1e-12      # x* closer than this (relative to an element) to a node is at the node


def element_history(mesh, d, phi):
    """Element nodal vectors (steps, n, 6) of a slider on a straight guide, (u, v) = s (cos phi,
    sin phi) at the end (a case's own end map: StateHistory.element_vectors)."""
    q = mesh.gather(d)
    s = q[..., -1, 3].copy()
    q[..., -1, 3] = s * np.cos(phi)
    q[..., -1, 4] = s * np.sin(phi)
    return q


def deflection_at(mesh, q, x):
    """v(x) in units of L, interpolated with the element's shape functions (any element count)."""
    e, zeta = mesh.locate(x)
    _, N_v, _ = shape_functions(zeta, mesh.length)
    return q[..., e, :] @ N_v


def mid_deflection(mesh, q, eps):
    """v* = v / r at x* = 1/2."""
    return deflection_at(mesh, q, 0.5) / eps


def end_axial(q, eps):
    """u*(1) = L u(L) / r^2."""
    return q[..., -1, 3] / eps**2


def extension(mesh, q):
    """delta* = u(L)/L + (1/2) int_0^1 (dv/dx)^2 dx  (eq. 40, in units of L)."""
    G = slope_gram(mesh.length)
    slope_sq = np.einsum("...ei,ij,...ej->...", q, G, q)
    return q[..., -1, 3] + 0.5 * slope_sq


def _sides(mesh, x):
    """[(element, zeta)] of the element(s) a point x* belongs to: two at an interior node."""
    n, l = mesh.n_elements, mesh.length
    k = round(x / l)
    if abs(x / l - k) < NODE_TOLERANCE and 0 < k < n:
        return [(k - 1, 1.0), (k, 0.0)]
    e, zeta = mesh.locate(x)
    return [(e, min(max(zeta, 0.0), 1.0))]


# the kinematic parameters an output kernel reads beside kin (those kin does not carry already)
_PARAMS_BESIDE_KIN = [k for k, n in enumerate(schema.KINEMATIC_PARAMETERS) if n not in schema.KINEMATICS]


class StateHistory:
    """What the declared outputs need of a run: its case and the reduced states at the stored times
    (velocities and accelerations too for the reactions)."""

    def __init__(self, case, t, states, rates=None, accelerations=None):
        self.case, self.t, self.states = case, np.asarray(t, dtype=float), np.asarray(states)
        self.rates, self.accelerations = rates, accelerations
        self.mesh = Mesh(case.n_elements)
        self._kin = None
        self._pin_end = None

    def kinematics(self):
        if self._kin is None:
            self._kin = _kinematics.case_state(self.case, self.t)
        return self._kin

    def element_vectors(self):
        """(steps, n, 6) nodal vectors, the end node through the guide's end map."""
        q = self.mesh.gather(self.states)
        E = _kinematics.end_map(self.case, self.kinematics().vector, self.states[:, self.mesh.slider_dof])
        q[..., -1, 3] = E[..., 0, 0]
        q[..., -1, 4] = E[..., 0, 1]
        return q

    def _reactions(self):
        if self.rates is None or self.accelerations is None:
            raise ParameterError("the reactions need the stored velocities and accelerations, which "
                                 "this result does not hold")
        if self._pin_end is None:            # torque, pin and end forces all read them
            from .model import Model
            self._pin_end = Model(self.case).reactions(self.t, self.states, self.rates, self.accelerations)
        return self._pin_end

    def _inputs(self, spec, element=None):
        """{input name: array} for an output kernel (element: (q, zeta, geo) of a field)."""
        out = {}
        q_all = None
        for name in spec.inputs:
            if name in ("q", "zeta", "geo", "fiber"):
                continue
            if name == "coef":
                out[name] = self.case.coefficients
            elif name == "kin":
                out[name] = self.kinematics().vector
            elif name == "params":
                out[name] = self.case.kinematic_parameters[_PARAMS_BESIDE_KIN]
            elif name == "q_end":
                q_all = self.element_vectors() if q_all is None else q_all
                out[name] = q_all[:, -1, 3:5]
            elif name == "qd_end":
                if self.rates is None:
                    raise ParameterError(f"{spec.name} needs the stored velocities, which this result "
                                         "does not hold")
                E = _kinematics.end_map(self.case, self.kinematics().vector,
                                        self.states[:, self.mesh.slider_dof], self.rates[:, self.mesh.slider_dof])
                out[name] = E[..., schema.END_MAP_ROWS["qd"], :]
            elif name == "s":
                out[name] = self.states[:, self.mesh.slider_dof]
            elif name in ("pin", "end"):
                pin, end = self._reactions()
                out["pin"], out["end"] = pin, end
        return out

    def _call(self, kernel, spec, values, element=None, extra=()):
        args = []
        for name in spec.inputs:
            if name in ("q", "zeta", "geo"):
                args.append(element[("q", "zeta", "geo").index(name)])
            elif name == "fiber":
                args.append(extra[0])
            else:
                args.append(values[name])
        return kernel(*args)

    def step(self, name):
        """Values of the step output `name` per stored step."""
        spec = schema.OUTPUTS[name]
        kernel = ingredients.output_kernel(name, self.case.options)
        return np.broadcast_to(self._call(kernel, spec, self._inputs(spec)), self.t.shape).copy()

    def field(self, name, x, **arguments):
        """Values of the field output `name` at x* (scalar: (steps,); array: (steps, len(x)))."""
        spec = schema.OUTPUTS.get(name)
        kernel = ingredients.field_kernel(name, self.case.options)
        extra = []
        for arg in spec.arguments:
            if arg not in arguments:
                raise ParameterError(f"{name} needs the argument {arg!r}")
            extra.append(finite_number(arg, arguments.pop(arg)))
        if arguments:
            raise ParameterError(f"{name} takes no argument {next(iter(arguments))!r}")
        xs = np.atleast_1d(np.asarray(x, dtype=float))
        for xj in xs:
            in_range("x (position x* along the rod)", xj, 0.0, 1.0)
        q = self.element_vectors()
        values = self._inputs(spec)
        l = self.mesh.length
        out = np.empty((q.shape[0], xs.size))
        for j, xj in enumerate(xs):
            parts = [self._call(kernel, spec, values, (q[:, e, :], zeta, np.array([l, e * l])), extra)
                     for e, zeta in _sides(self.mesh, float(xj))]
            out[:, j] = np.mean(np.broadcast_arrays(*parts), axis=0)
        return out[:, 0] if np.ndim(x) == 0 else out


class DeclaredOutputs:
    """Mixin of results that store their states: every declared output by name.

    `result.quantity(name, x=None, **arguments)` gives any declared output; each step output is also
    an attribute of its name (`result.torque`, `result.slider_position`, `result.chord_angle`) and
    each field output a method (`result.axial_force(0.5)`, `result.surface_strain(0.5, fiber=3**0.5)`)."""

    def _history(self):
        """The result's StateHistory, made once: its kinematics and reactions serve every output
        asked of the result (kept beside the frozen dataclass's fields, never pickled)."""
        if getattr(self, "states", None) is None:
            raise ParameterError("this result holds no states (a failed or state-less result)")
        history = self.__dict__.get("_state_history")
        if history is None:
            history = StateHistory(self.case, self.t, self.states, getattr(self, "rates", None),
                                   getattr(self, "accelerations", None))
            object.__setattr__(self, "_state_history", history)
        return history

    def __getstate__(self):
        state = dict(self.__dict__)
        state.pop("_state_history", None)
        return state

    def quantity(self, name, x=None, **arguments):
        spec = schema.OUTPUTS.get(name)
        if spec is None:
            raise ParameterError(f"no output {name!r}; the outputs are {', '.join(schema.OUTPUTS)}")
        if self.case.guide_record.name not in spec.guides:
            raise ParameterError(f"{name} exists for the {' and '.join(spec.guides)} guide only "
                                 f"(this case's guide is {self.case.guide_record.name!r})")
        if spec.kind == "field":
            if x is None:
                raise ParameterError(f"{name} is a field: give x (x* in [0, 1])")
            return self._history().field(name, x, **arguments)
        if x is not None or arguments:
            raise ParameterError(f"{name} is a step output (one value per stored step): it takes no "
                                 f"position or argument")
        if spec.kind == "step":
            return self._history().step(name)
        return getattr(self, name)

    @property
    def slider_position(self):
        return self.quantity("slider_position")

    def __getattr__(self, name):
        spec = schema.OUTPUTS.get(name)
        if spec is not None and spec.kind == "field":
            return lambda x, **arguments: self.quantity(name, x, **arguments)
        if spec is not None and spec.kind == "step":
            return self.quantity(name)
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r}")


class SIView:
    """A result's quantities in SI: t in s, theta in rad, and every declared output converted with
    the units it declares in derive/declaration.py (crankgen.units: "L" -> m, "rad", "omega_b" -> rad/s,
    "rhoA L^2 omega_b^2" -> N, "rhoA L^3 omega_b^2" -> N m, "EI/L^2" -> N, "EI/L" -> N m, ...).

    Fields take the position x along the rod in metres (0 <= x <= L); their other arguments keep
    their own meaning (surface_strain's fiber: the distance from the neutral axis in units of the
    radius of gyration).  `units(name)` names the SI unit of a quantity; `nodes` gives the nodal
    history with u, v in m (psi, a slope, is dimensionless); `at_times` the SI view of the result at
    the requested times."""

    # the result's own per-step arrays beside the declared outputs, and their units
    BASE = {"t": "1/omega_b", "theta": "rad"}

    def __init__(self, result, scales):
        self.result, self.scales = result, scales

    def units(self, name):
        """Name of the SI unit of t, theta or a declared output."""
        if name in self.BASE:
            return self.scales.si_name(self.BASE[name])
        spec = schema.OUTPUTS.get(name)
        if spec is None:
            raise ParameterError(f"no output {name!r}; the outputs are {', '.join(schema.OUTPUTS)}")
        return self.scales.si_name(spec.units)

    def quantity(self, name, x=None, **arguments):
        """The declared output `name` in SI (a field at x in metres)."""
        spec = schema.OUTPUTS.get(name)
        if spec is None:
            raise ParameterError(f"no output {name!r}; the outputs are {', '.join(schema.OUTPUTS)}")
        if x is not None:
            for xj in np.atleast_1d(np.asarray(x, dtype=float)):
                in_range(f"x (position along the rod, m; the rod is {self.scales.L:g} m long)", xj, 0.0,
                         self.scales.L)
            x = np.asarray(x, dtype=float) / self.scales.L if np.ndim(x) else float(x) / self.scales.L
        return self.result.quantity(name, x, **arguments) * self.scales.factor(spec.units)

    @property
    def nodes(self):
        nodes = self.result.nodes
        if nodes is None:
            return None
        out = np.array(nodes, dtype=float)
        out[..., 0::3] *= self.scales.L
        out[..., 1::3] *= self.scales.L
        return out

    @property
    def at_times(self):
        inner = self.result.at_times
        return None if inner is None else SIView(inner, self.scales)

    def __getattr__(self, name):
        if name in ("result", "scales"):
            raise AttributeError(name)
        if name in self.BASE:
            return getattr(self.result, name) * self.scales.factor(self.BASE[name])
        spec = schema.OUTPUTS.get(name)
        if spec is not None and spec.kind == "field":
            return lambda x, **arguments: self.quantity(name, x, **arguments)
        if spec is not None:
            return self.quantity(name)
        raise AttributeError(f"SIView has no attribute {name!r}")

    def __repr__(self):
        return (f"SIView({type(self.result).__name__}, L = {self.scales.L:g} m, "
                f"omega_b = {self.scales.omega_b:g} rad/s)")
