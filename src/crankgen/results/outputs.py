"""The outputs a result can give, declared in derive/outputs.py (OUTPUTS) and read from the
schema: step quantities (one value per stored step: the crank speed, the end's position, the chord
angle, the driving torque, the joint forces, ...), fields (per step, at any x* in [0, 1]:
axial_force, bending_moment, surface_strain, chord_deflection, ...) and reductions (per step, a sum
or integral over the rod).  The outputs flagged `engine` (v_mid, u_end, extension) the engine
computes at every step, so that every result has them, with or without stored states.

Each step, field or reduction output is a generated kernel whose inputs the schema names;
StateHistory supplies them from the stored reduced states: the kinematics, the nodal vector (and
rate) of the element holding x* or of every element, the end node's (u, v), their rates and the
reduced co-ordinate, the parameter vector, and the joint forces at the crank pin A and at B (the
residual rows of the constrained DOFs, which need the stored velocities and accelerations: the
crank's force on the rod, the guide's on the end mass and, from the rod's own families alone, the
end mass's on the rod).  The engine's
outputs are the generated per_step of what they accumulate (schema.PRIMITIVES: a field at a point,
an integral over the rod), evaluated here for stored states as the engine does at every step.
Quantities made of element-wise derivatives (u_x is constant in an element, v_xx linear) jump at the
nodes; at an interior node crankgen returns the mean of the two elements' values (the average of the
one-sided limits), inside an element the element's own value.
"""

import functools

import numpy as np

from ..declaration import ingredients, schema
from ..discrete import kinematics as _kinematics
from .._generated import per_step as _per_step
from .._generated.shape import shape_functions
from ..errors import ParameterError
from ..declaration.ingredients import available
from ..discrete.mesh import MAPPED, NODE_DOFS, U, V, Mesh, components_of, nodal_mesh, rocker_of
from ..declaration.validation import finite_number, in_range

NODE_TOLERANCE = 1e-12      # x* closer than this (relative to an element) to a node is at the node

# outputs renamed to say which body acts on which (crankgen 0.2): the old name -> the new one(s)
RENAMED = {"pin_force_x": "crank_on_rod_x", "pin_force_y": "crank_on_rod_y",
           "end_force_x": "guide_on_slider_x (rocker_on_tip_x on a four-bar)",
           "end_force_y": "guide_on_slider_y (rocker_on_tip_y on a four-bar)"}


def unknown_output(name):
    """The ParameterError of an output name that does not exist (naming the new name of a renamed
    one)."""
    if name in RENAMED:
        return ParameterError(f"{name} was renamed {RENAMED[name]}: the joint forces are named for who "
                              f"acts on whom (crank_on_rod, rod_on_slider, guide_on_slider; rod_on_tip, "
                              f"rocker_on_tip on a four-bar)")
    return ParameterError(f"no output {name!r}; the outputs are {', '.join(schema.OUTPUTS)}")
FIELDS = ("u", "v", "psi")  # the interpolated fields, in the order of the shape functions (eqs. 8-10)
# (shape_functions gives a fourth, the exact rod's cubic N_u in u and chi; no engine output reads u
# between the nodes)


def primitive_data(mesh):
    """What the engine's outputs accumulate (schema.PRIMITIVES) on this mesh: [(place in prims,
    element, the field's shape functions at x*)] of the points, [(place, Gram matrix)] of the
    integrals over the rod (the engine reads the same, engine/batch.py)."""
    points, grams = [], []
    for k, p in enumerate(schema.PRIMITIVES):
        if p.kind == "point":
            e, zeta = mesh.locate(p.at)
            points.append((k, e, shape_functions(zeta, mesh.length)[FIELDS.index(p.field)]))
        else:
            grams.append((k, getattr(_per_step, p.kernel)(mesh.length)))
    return points, grams


def engine_outputs(mesh, q, parameters):
    """The engine's outputs (..., len(schema.ENGINE_OUTPUTS)) of element nodal vectors q (..., n, 6)
    with their end node mapped, for the parameter vector: the engine's arithmetic in NumPy."""
    points, grams = primitive_data(mesh)
    prims = np.zeros(q.shape[:-2] + (len(schema.PRIMITIVES),))
    for k, e, weights in points:
        prims[..., k] = q[..., e, :] @ weights
    for k, G in grams:
        prims[..., k] = np.einsum("...ei,ij,...ej->...", q, G, q)
    e, slots, _ = mesh.holders()[0]
    return _per_step.per_step(prims, q[..., e, list(slots)], parameters)


def deflection_at(mesh, q, x):
    """v(x) in units of L, interpolated with the element's shape functions (any element count)."""
    e, zeta = mesh.locate(x)
    _, N_v, _, _ = shape_functions(zeta, mesh.length)
    return q[..., e, :] @ N_v


def mid_deflection(mesh, q, eps):
    """v* = v / r at x* = 1/2."""
    return deflection_at(mesh, q, 0.5) / eps


def takes_engine_outputs(cls):
    """A result class (a frozen dataclass whose field `outputs` holds the engine's outputs by name)
    whose constructor also takes each of them by name: Result(..., v_mid=..., u_end=...)."""
    init = cls.__init__

    @functools.wraps(init)
    def __init__(self, *args, **kwargs):
        given = {name: kwargs.pop(name) for name in schema.ENGINE_OUTPUTS if name in kwargs}
        init(self, *args, **kwargs)
        if given:
            object.__setattr__(self, "outputs", dict(self.outputs or {}, **given))
    cls.__init__ = __init__
    return cls


def engine_columns(y):
    """{name: per-step array} of the engine's outputs y (..., len(schema.ENGINE_OUTPUTS))."""
    return {name: y[..., k] for k, name in enumerate(schema.ENGINE_OUTPUTS)}


def _sides(mesh, x):
    """[(element, zeta)] of the element(s) a point x* belongs to: two at an interior node."""
    n, l = mesh.n_elements, mesh.length
    k = round(x / l)
    if abs(x / l - k) < NODE_TOLERANCE and 0 < k < n:
        return [(k - 1, 1.0), (k, 0.0)]
    e, zeta = mesh.locate(x)
    return [(e, min(max(zeta, 0.0), 1.0))]


class StateHistory:
    """What the declared outputs need of a run: its case and the reduced states at the stored times
    (velocities and accelerations too for the reactions and the rates)."""

    def __init__(self, case, t, states, rates=None, accelerations=None, crank=None):
        self.case, self.t = case, np.asarray(t, dtype=float)
        self.states = None if states is None else np.asarray(states)   # None: the kinematics' outputs alone
        self.crank = None if crank is None else np.asarray(crank, dtype=float)     # a driven crank's (theta, thetad, thetadd)
        self.rates, self.accelerations = rates, accelerations
        self.mesh = nodal_mesh(case)
        self._kin = None
        self._pin_end = None
        self._constraints = tuple(c.name for c in schema.CONSTRAINTS)

    def kinematics(self):
        if self._kin is None:
            if self.crank is not None:          # a driven crank: its kinematics from its states
                self._kin = _kinematics.crank_state(self.case, self.crank)
            else:
                self._kin = _kinematics.case_state(self.case, self.t)
        return self._kin

    def _need_states(self):
        if self.states is None:
            raise ParameterError("this result holds no states (a failed or state-less result): only the "
                                 "outputs of the crank's and the guide's kinematics are available")
        return self.states

    def _mapped(self, reduced, row, rates=None, accelerations=None):
        """(steps, n, 6) element vectors of reduced vectors, the end node's (u, v) from the end map's
        row ("q": positions; "qd": rates, from the states and `rates`; "qdd": accelerations, from
        those and `accelerations`)."""
        self._need_states()
        q = self.mesh.gather(reduced)
        mapped = self.mesh.mapped_values
        E = _kinematics.end_map(self.case, self.kinematics().vector, mapped(self.states),
                                0.0 if rates is None else mapped(rates),
                                0.0 if accelerations is None else mapped(accelerations))
        for e, slots, _ in self.mesh.holders():
            for a, slot in enumerate(slots):
                q[..., e, slot] = E[..., schema.END_MAP_ROWS[row], a]
        return q

    def element_vectors(self):
        """(steps, n, 6) nodal vectors, the end node through the guide's end map."""
        return self._mapped(self.states, "q")

    def element_rates(self):
        """(steps, n, 6) nodal velocities, the end node's through the guide's end map."""
        return self._mapped(self._need_rates("the rates of the nodes"), "qd", self.rates)

    def element_accelerations(self):
        """(steps, n, 6) nodal accelerations, the end node's through the guide's end map."""
        self._need_rates("the accelerations of the nodes")
        if self.accelerations is None:
            raise ParameterError("the accelerations of the nodes need the stored accelerations, which "
                                 "this result does not hold")
        return self._mapped(self.accelerations, "qdd", self.rates, self.accelerations)

    def rocker_deflection(self, x):
        """(steps,): a flexible rocker's deflection at x* = x from its chord, in units of r (Result)."""
        from .._generated.shape import shape_functions
        mesh = self.mesh
        if not mesh.rocker_elements:
            raise ParameterError("rocker_deflection: this case's rocker is rigid (it has no elements)")
        states = self._need_states()
        n_r, c, l = mesh.rocker_elements, mesh.rocker_length, mesh.rocker_element_length
        q = mesh.gather_all(states)[:, mesh.n_elements:, :]           # the rocker's nodes are its own
        e = min(int(np.floor(x * n_r)), n_r - 1)
        N_u, N_v, _, N_u_cubic = shape_functions((x * c - e * l) / l, l)
        u = q[:, e] @ (N_u_cubic if "chi" in mesh.components else N_u)
        v = q[:, e] @ N_v
        u_tip, v_tip = (states[:, i] for i in mesh.reduced_coordinates())
        chord_x, chord_y = c + u_tip, v_tip                               # pivot to tip, in the rocker's frame
        deflection = (chord_x * v - chord_y * (x * c + u)) / np.hypot(chord_x, chord_y)
        return deflection / self.case.natural_sizes[V]

    def _need_rates(self, what):
        if self.rates is None:
            raise ParameterError(f"{what} need the stored velocities, which this result does not hold")
        return self.rates

    def _reactions(self):
        self._need_states()
        if self.rates is None or self.accelerations is None:
            raise ParameterError("the reactions need the stored velocities and accelerations, which "
                                 "this result does not hold")
        if self._pin_end is None:            # torque and every joint force read them
            from ..discrete.system import Model
            self._pin_end = Model(self.case).joint_forces(self.t, self.states, self.rates, self.accelerations,
                                                          kin=self.kinematics())
        return self._pin_end

    def _inputs(self, spec):
        """{input name: array} of an output kernel's inputs that are the same for every element
        (those of an element, q, qd, zeta and geo, and a field's arguments: _call)."""
        out = {}
        for name in spec.inputs:
            if name in ("q", "qd", "zeta", "geo", "fiber") or name in out:
                continue
            if not available(spec.name, self.case):
                if not rocker_of(self.case)[0]:
                    raise ParameterError(f"{spec.name} is a flexible rocker's; this case's rocker is rigid (it has "
                                         f"no elements)")
                raise ParameterError(
                    f"{spec.name}: with a flexible rocker the rod's end is held by the rocker's tip, not by a "
                    f"rigid rocker on its circle, and this output reads the rigid rocker's angle or takes the "
                    f"rocker as rigid (a flexible rocker's pivot force: ground_on_flexible_rocker)")
            if name == "coef":
                out[name] = self.case.coefficients
            elif name == "kin":
                out[name] = self.kinematics().vector
            elif name == "parameters":
                out[name] = self.case.parameter_vector
            elif name in ("q_end", "qd_end", "qdd_end"):      # the mapped node's eliminated components
                e, slots, _ = self.mesh.holders()[0]
                values = {"q_end": self.element_vectors, "qd_end": self.element_rates,
                          "qdd_end": self.element_accelerations}[name]()
                out[name] = values[:, e, list(slots)]
            elif name == "s":
                out[name] = self._need_states()[:, self.mesh.reduced_coordinates()[0]]
            elif name in self._constraints:          # the force a constraint applies (pin, end)
                out.update(zip(self._constraints, self._reactions()[0]))
                if self.mesh.mapped is not MAPPED:   # a flexible rocker's tip holds the end: its force is the end's
                    out[MAPPED.name] = out[self.mesh.mapped.name]
            elif name == "rod_end":                  # the force the end mass applies to the rod at B
                out[name] = dict(zip(self._constraints, self._reactions()[1]))[self.mesh.mapped.name]
        return out

    def _call(self, kernel, spec, values, element=None, extra=()):
        """The kernel of `spec` with its inputs: values, element = {q, qd, zeta, geo} of an element
        (or of every element), extra: a field's arguments."""
        args = []
        for name in spec.inputs:
            if name in ("q", "qd", "zeta", "geo"):
                args.append(element[name])
            elif name == "fiber":
                args.append(extra[0])
            else:
                args.append(values[name])
        return kernel(*args)

    def engine_outputs(self):
        """(steps, len(schema.ENGINE_OUTPUTS)): the engine's outputs of the stored states."""
        return engine_outputs(self.mesh, self.element_vectors(), self.case.parameter_vector)

    def step(self, name):
        """Values of the step output `name` per stored step."""
        spec = schema.OUTPUTS[name]
        if spec.engine:
            return self.engine_outputs()[:, schema.ENGINE_OUTPUTS.index(name)].copy()
        kernel = ingredients.output_kernel(name, self.case.options)
        return np.broadcast_to(self._call(kernel, spec, self._inputs(spec)), self.t.shape).copy()

    def reduction(self, name):
        """Values of the reduction output `name` per stored step: its kernel on every element, summed."""
        spec = schema.OUTPUTS[name]
        kernel = ingredients.output_kernel(name, self.case.options)
        mesh = self.mesh
        element = {"q": self.element_vectors(),
                   "geo": np.stack([np.full(mesh.n_elements, mesh.length), mesh.x0], axis=-1)}
        if "qd" in spec.inputs:
            element["qd"] = self.element_rates()
        values = self._inputs(spec)
        if "kin" in values:
            values["kin"] = values["kin"][:, None, :]          # every element at its step's kinematics
        parts = np.broadcast_to(self._call(kernel, spec, values, element), self.t.shape + (mesh.n_elements,))
        return np.sum(parts, axis=-1)

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
        qd = self.element_rates() if "qd" in spec.inputs else None
        values = self._inputs(spec)
        l = self.mesh.length
        out = np.empty((q.shape[0], xs.size))
        for j, xj in enumerate(xs):
            parts = [self._call(kernel, spec, values, {"q": q[:, e, :], "qd": None if qd is None else qd[:, e, :],
                                                       "zeta": zeta, "geo": np.array([l, e * l])}, extra)
                     for e, zeta in _sides(self.mesh, float(xj))]
            out[:, j] = np.mean(np.broadcast_arrays(*parts), axis=0)
        return out[:, 0] if np.ndim(x) == 0 else out


class DeclaredOutputs:
    """Mixin of results: every declared output by name, and the range of the theory
    (`beyond_theory`).

    The engine's outputs (schema.ENGINE_OUTPUTS: v_mid, u_end, extension) are held by every result
    (its field `outputs`); the others need the stored states.  `result.quantity(name, x=None,
    **arguments)` gives any declared output; each step or reduction output is also an attribute of
    its name (`result.v_mid`, `result.torque`, `result.slider_position`, `result.chord_angle`) and
    each field output a method (`result.axial_force(0.5)`, `result.surface_strain(0.5, fiber=3**0.5)`)."""

    def _history(self):
        """The result's StateHistory, made once: its kinematics and reactions serve every output
        asked of the result (kept beside the frozen dataclass's fields, never pickled)."""
        history = self.__dict__.get("_state_history")
        if history is None:
            history = StateHistory(self.case, self.t, self.states, getattr(self, "rates", None),
                                   getattr(self, "accelerations", None), getattr(self, "crank", None))
            object.__setattr__(self, "_state_history", history)
        return history

    def __getstate__(self):
        state = dict(self.__dict__)
        state.pop("_state_history", None)
        state.pop("_beyond_theory", None)
        state.pop("_verdict", None)
        return state

    @property
    def beyond_theory(self):
        """Whether the response leaves the range of the theory, as data (crankgen.analyses.theory.RangeFlag:
        true when beyond; its measures deflection_over_L = eps max|v*| and the largest axial
        strain over the stored steps, each with its value and limit, and those that tripped it)."""
        flag = self.__dict__.get("_beyond_theory")
        if flag is None:
            from ..analyses.theory import flag_of
            flag = flag_of(self)
            object.__setattr__(self, "_beyond_theory", flag)
        return flag

    @property
    def verdict(self):
        """Which model to trust for this response (crankgen.analyses.model_error.Verdict: "trust this model
        here", "use the exact rod" or "beyond both", with the estimated relative difference from the
        exact rod's response behind it and the exact rod's limits on these states)."""
        value = self.__dict__.get("_verdict")
        if value is None:
            from ..analyses.model_error import verdict
            value = verdict(self)
            object.__setattr__(self, "_verdict", value)
        return value

    def quantity(self, name, x=None, **arguments):
        spec = schema.OUTPUTS.get(name)
        if spec is None:
            raise unknown_output(name)
        if getattr(self, "case", None) is not None and self.case.guide_record.name not in spec.guides:
            raise ParameterError(f"{name} exists for the {' and '.join(spec.guides)} guide only "
                                 f"(this case's guide is {self.case.guide_record.name!r})")
        if spec.kind == "field":
            if x is None:
                raise ParameterError(f"{name} is a field: give x (x* in [0, 1])")
            return self._history().field(name, x, **arguments)
        if x is not None or arguments:
            raise ParameterError(f"{name} is a {spec.kind} output (one value per stored step): it takes no "
                                 f"position or argument")
        if spec.engine and (self.__dict__.get("outputs") or {}).get(name) is not None:
            return self.outputs[name]
        if spec.kind == "reduction":
            return self._history().reduction(name)
        return self._history().step(name)

    def rocker_deflection(self, x=0.5):
        """A flexible rocker's deflection per stored step at x* = x (a fraction of its length c, from
        its ground pivot D, 0 <= x <= 1) from its chord (the line from D through its tip as they
        are), in units of the coupler's radius of gyration r = eps L (like v*)."""
        from ..declaration.validation import in_range
        return self._history().rocker_deflection(in_range("x (fraction of the rocker's length)", x, 0.0, 1.0))

    def output_names(self):
        """The declared outputs this result gives per step (the engine's; with stored states every
        step and reduction output of its guide), in the schema's order."""
        from .exports import output_names
        return output_names(self)

    def table(self, x=(0.5,), fiber=None, along=False, section=None):
        """(columns, arrays): t, the crank angle in degrees, every output of output_names, each joint
        force's magnitude and direction, the field outputs at x* in x (default the mid-span;
        surface_strain with `fiber`), with `along` the axial force at every node and with a
        crankgen.sections.Section (`section`) also the outer-fibre stresses there (units of E), the
        range of the theory per step; each column named with its unit (crankgen.exports)."""
        from .exports import per_step
        return per_step(self, None, x, fiber, along=along, section=section)

    def to_csv(self, path, x=(0.5,), fiber=None, along=False, section=None):
        """Write the table (crankgen's units, each column named with its unit: t_per_omega_b,
        theta_deg, v_mid_r, torque_rhoA_L3_omega_b2, ..., bending_moment_at_0.5_EI_per_L, ...,
        deflection_over_L, axial_strain, beyond_theory) as CSV in full precision, atomically;
        a number that does not exist is an empty field."""
        from .exports import write
        from .io import output_path
        path = output_path(path)                   # named before the table is computed
        return write(path, *self.table(x, fiber, along, section))

    @property
    def si(self):
        """The result in SI (crankgen.results.outputs.SIView) of a run given in SI (units="si")."""
        scales = self.__dict__.get("scales")
        if scales is None:
            raise ParameterError("this result was computed in crankgen's units: result.si needs a run made "
                                 "with units='si' from a crankgen.SIMechanism; result.si_view(si_mechanism) "
                                 "converts any result")
        return SIView(self, scales)

    def si_view(self, si_mechanism):
        """The result in SI for the SIMechanism whose dimensionless form it was computed for."""
        from ..declaration.si import scales_of
        return SIView(self, scales_of(si_mechanism))

    def __dir__(self):
        """The attributes, and every declared output this result gives by name."""
        names = set(super().__dir__())
        if getattr(self, "case", None) is not None:
            guide = self.case.guide_record.name
            names.update(n for n, spec in schema.OUTPUTS.items() if guide in spec.guides)
        return sorted(names)

    @property
    def slider_position(self):
        return self.quantity("slider_position")

    def animate(self, path, **options):
        """Write the deforming mechanism's motion to path (.gif, or .mp4 with ffmpeg): see
        crankgen.plots.animation.animate for the options (magnification, frames, fps, title)."""
        from ..plots.animation import animate
        return animate(self, path, **options)

    def __getattr__(self, name):
        spec = schema.OUTPUTS.get(name)
        if spec is not None and spec.engine:
            outputs = self.__dict__.get("outputs")
            return None if outputs is None else outputs.get(name)
        if spec is not None and spec.kind == "field":
            return lambda x, **arguments: self.quantity(name, x, **arguments)
        if spec is not None:
            return self.quantity(name)
        if name in RENAMED:
            raise AttributeError(str(unknown_output(name)))
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r}")


class SIView:
    """A result's quantities in SI: t in s, theta in rad, and every declared output converted with
    the units it declares in derive/outputs.py (crankgen.declaration.units: "L" -> m, "rad", "omega_b" -> rad/s,
    "rhoA L^2 omega_b^2" -> N, "rhoA L^3 omega_b^2" -> N m, "EI/L^2" -> N, "EI/L" -> N m, ...).

    Fields take the position x along the rod in metres (0 <= x <= L); their other arguments keep
    their own meaning (surface_strain's fiber: the distance from the neutral axis in units of the
    radius of gyration).  `units(name)` names the SI unit of a quantity; `nodes` gives the nodal
    history with u, v in m (psi, a slope, is dimensionless); `at_times` the SI view of the result at
    the requested times."""

    from .exports import BASE      # the result's own per-step arrays beside the outputs, and their units

    def __init__(self, result, scales):
        self.result, self.scales = result, scales

    def units(self, name):
        """Name of the SI unit of t, theta or a declared output."""
        if name in self.BASE:
            return self.scales.si_name(self.BASE[name])
        spec = schema.OUTPUTS.get(name)
        if spec is None:
            raise unknown_output(name)
        return self.scales.si_name(spec.units)

    def quantity(self, name, x=None, **arguments):
        """The declared output `name` in SI (a field at x in metres)."""
        spec = schema.OUTPUTS.get(name)
        if spec is None:
            raise unknown_output(name)
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
        for comp in (U, V):                      # u and v in m (psi, a slope, is dimensionless)
            out[..., comp::NODE_DOFS] *= self.scales.L
        return out

    @property
    def at_times(self):
        inner = getattr(self.result, "at_times", None)
        return None if inner is None else SIView(inner, self.scales)

    def table(self, x=None, fiber=None, along=False, section=None):
        """(columns, arrays) of the result's table in SI (crankgen.exports): t_s, theta_rad, every
        output of the result's output_names, each joint force's magnitude (N) and direction (rad),
        the fields at x in metres (default the mid-span; surface_strain with `fiber`), with `along`
        the axial force at every node and with a Section (`section`, in m) the outer-fibre stresses
        there (Pa), the range of the theory per step."""
        from .exports import per_step
        return per_step(self.result, self, (self.scales.L / 2,) if x is None else x, fiber, along=along,
                        section=section)

    def to_csv(self, path, x=None, fiber=None, along=False, section=None):
        """Write the table in SI (t_s, theta_rad, v_mid_m, ..., torque_N_m, crank_on_rod_x_N, ...) as
        CSV in full precision, atomically."""
        from .exports import write
        from .io import output_path
        path = output_path(path)                   # named before the table is computed
        return write(path, *self.table(x, fiber, along, section))

    def __dir__(self):
        names = set(super().__dir__()) | set(self.BASE)
        case = getattr(self.result, "case", None)
        if case is not None:
            names.update(n for n, spec in schema.OUTPUTS.items() if case.guide_record.name in spec.guides)
        return sorted(names)

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
        if name in RENAMED:
            raise AttributeError(str(unknown_output(name)))
        raise AttributeError(f"SIView has no attribute {name!r}")

    def __repr__(self):
        return (f"SIView({type(self.result).__name__}, L = {self.scales.L:g} m, "
                f"omega_b = {self.scales.omega_b:g} rad/s)")
