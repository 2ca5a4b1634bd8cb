"""The outputs a result can give, declared in derive/model.py (OUTPUTS) and read from the generated
table: step quantities (one value per stored step: v_mid, u_end, extension, slider_position) and
fields (per step, at any x* in [0, 1]: axial_force, bending_moment, surface_strain, ...).

Fields are evaluated from the stored reduced states with the generated field kernels.  Quantities
made of element-wise derivatives (u_x is constant in an element, v_xx linear) jump at the nodes;
at an interior node crankgen returns the mean of the two elements' values (the average of the
one-sided limits), inside an element the element's own value.
"""

import numpy as np

from . import ingredients
from ._generated.shape import shape_functions, slope_gram
from .errors import ParameterError
from .kinematics import crank_state, slider_position as rigid_slider_position
from .mesh import Mesh
from .validation import finite_number, in_range

NODE_TOLERANCE = 1e-12      # x* closer than this (relative to an element) to a node is at the node


def element_history(mesh, d, phi):
    """Element nodal vectors (steps, n, 6) with the slider constraint applied."""
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


class StateHistory:
    """What the declared outputs need of a run: its case and the reduced states at the stored times."""

    def __init__(self, case, t, states):
        self.case, self.t, self.states = case, np.asarray(t, dtype=float), states
        self.mesh = Mesh(case.n_elements)

    def element_vectors(self):
        phi = crank_state(self.case.a, self.case.omega, self.t, self.case.offset).phi
        return element_history(self.mesh, self.states, phi)

    def field(self, name, x, **arguments):
        """Values of the field output `name` at x* (scalar: (steps,); array: (steps, len(x)))."""
        spec = ingredients.OUTPUTS.get(name)
        kernel = ingredients.field_kernel(name, self.case.options)
        extra = []
        for arg in spec["arguments"]:
            if arg not in arguments:
                raise ParameterError(f"{name} needs the argument {arg!r}")
            extra.append(finite_number(arg, arguments.pop(arg)))
        if arguments:
            raise ParameterError(f"{name} takes no argument {next(iter(arguments))!r}")
        xs = np.atleast_1d(np.asarray(x, dtype=float))
        q = self.element_vectors()
        coef, l = self.case.coefficients, self.mesh.length
        out = np.empty((q.shape[0], xs.size))
        for j, xj in enumerate(xs):
            in_range("x (position x* along the rod)", xj, 0.0, 1.0)
            values = [kernel(q[:, e, :], zeta, np.array([l, e * l]), coef, *extra)
                      for e, zeta in _sides(self.mesh, float(xj))]
            out[:, j] = np.mean(values, axis=0)
        return out[:, 0] if np.ndim(x) == 0 else out

    def slider_position(self):
        """X / L of the slider per stored step: the rigid position plus s, its displacement along
        the guide."""
        c = self.case
        theta = c.omega * self.t
        return rigid_slider_position(c.a, theta, c.offset) + self.states[:, self.mesh.slider_dof]


class DeclaredOutputs:
    """Mixin of results that store their states: every declared output by name.

    `result.quantity(name, x=None, **arguments)` gives any declared output; each field output is
    also a method of its name (`result.axial_force(0.5)`, `result.surface_strain(0.5, fiber=3**0.5)`),
    and `result.slider_position` the slider's X / L per stored step."""

    def _history(self):
        if getattr(self, "states", None) is None:
            raise ParameterError("this result holds no states (a failed or state-less result)")
        return StateHistory(self.case, self.t, self.states)

    def quantity(self, name, x=None, **arguments):
        spec = ingredients.OUTPUTS.get(name)
        if spec is None:
            raise ParameterError(f"no output {name!r}; the outputs are {', '.join(ingredients.OUTPUTS)}")
        if spec["kind"] == "field":
            if x is None:
                raise ParameterError(f"{name} is a field: give x (x* in [0, 1])")
            return self._history().field(name, x, **arguments)
        if name == "slider_position":
            return self._history().slider_position()
        return getattr(self, name)

    @property
    def slider_position(self):
        return self.quantity("slider_position")

    def __getattr__(self, name):
        spec = ingredients.OUTPUTS.get(name)
        if spec is not None and spec["kind"] == "field":
            return lambda x, **arguments: self.quantity(name, x, **arguments)
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r}")
