"""Mesh of the connecting rod and its DOF map: from element DOFs to the reduced (free) DOFs.

Full nodal vector: the components of each node (schema.NODE: u, v, psi, eq. 14, and chi = u_x,
which only the exact rod's nodes have: the DOF map of the other models leaves it out), nodes 0..n
along the rod.  Each constraint of the DOF map (schema.CONSTRAINTS, declared in derive/declaration.py)
eliminates components of its node; its reduced co-ordinates take the places of the first of them,
in order.  The crank pin eliminates u_0, v_0; the guide replaces (u_n, v_n) by the reduced
co-ordinate s of its end map, (u_n, v_n) = g(s, t) (a slider: s (cos phi, sin phi), eq. 26; see
constraints.py).  The reduced vector is

    [psi_0,  u_1, v_1, psi_1,  ...,  u_{n-1}, v_{n-1}, psi_{n-1},  s, psi_n]     (3 n entries),

with chi after each psi on the exact rod (4 n + 1 entries),

With a flexible rocker (`rocker_elements` n_r > 0: the body "rocker", its constraints "ground" and
"tip" in place of the guide's "end") the rod's end node is held by the rocker's tip, (u_n, v_n) =
R(t) (u_r, v_r): the rocker tip's (u, v) are the reduced co-ordinates.  The rocker's nodes follow
the rod's, from its tip to its pivot, so that the band stays narrow:

    [..., u_{n-1}, v_{n-1}, psi_{n-1},  psi_n,  u_r, v_r,  psi_r,  (the rocker's nodes n_r - 1 .. 1),  psi_r0]

(chi after each psi on the exact rod), the rocker's elements after the rod's (element n + k joins
its nodes k and k + 1, from the pivot D, x = 0, to the tip B, x = c);

followed by the co-ordinates the case's motion declares (records.Coordinate: a driven crank's
angle, a motor rotor's angle; none for a prescribed crank), each with its own equation: the DOF
map owns the whole state, `n_dofs` of them, the first `n_rod` the nodal ones (the band).
"""

from dataclasses import dataclass, field

import numpy as np

from ..declaration import schema
from ..declaration.ingredients import flexible_bodies
from ..declaration.validation import integer

NDOF = schema.ELEMENT_DOFS
# the flexible body (schema.BODIES: the rod; one runs today) and its node's components (u, v, psi,
# chi; chi only where the case's model has it: records.Body.components)
BODY = next(b for b in schema.BODIES.values() if b.kind == "flexible")
COMPONENTS = BODY.node
NODE_DOFS = len(COMPONENTS)                   # per node; an element holds two nodes' (NDOF)
U, V, PSI, CHI = range(NODE_DOFS)
MAPPED = next(c for c in schema.CONSTRAINTS if c.body == BODY.name and c.map is not None)   # reduced co-ordinates


def components_of(options):
    """The rod's node components under a case's model options (records.Body.components: chi only
    on the exact rod); {} gives the default model's."""
    return BODY.components(dict(options) or schema.resolve_options())


ROCKER = next((b for b in schema.BODIES.values() if b.kind == "flexible" and b.name != BODY.name), None)


def rocker_of(case):
    """(element count, length) of a case's flexible rocker: (0, 1.0) when it has none (a rigid
    rocker, or a guide without one)."""
    if ROCKER is None or ROCKER.name not in flexible_bodies(case):
        return 0, 1.0
    return int(getattr(case, ROCKER.elements)), float(getattr(case, ROCKER.length))


def nodal_mesh(case):
    """The DOF map of a case's flexible bodies without its motion's co-ordinates (the nodal state)."""
    return Mesh(case.n_elements, (), components_of(case.options), *rocker_of(case))


def joints(body=BODY, present=()):
    """The constraints of the body's nodes: the joints that hold them (schema.CONSTRAINTS), those of
    a case whose optional flexible bodies are `present` (names)."""
    return tuple(c for c in schema.CONSTRAINTS if c.body == body.name and c.applies(present))


def mapped_constraint(present=()):
    """The DOF map's mapped constraint (the one with reduced co-ordinates through a map) of a case
    whose optional flexible bodies are `present`: the guide's end, or a flexible rocker's tip."""
    return next(c for c in schema.CONSTRAINTS if c.map is not None and c.applies(present))


def element_slots(node_in_element, components):
    """The places in an element's nodal vector of components of its node 0 (first) or 1 (second)."""
    return tuple(node_in_element * NODE_DOFS + COMPONENTS.index(c) for c in components)


@dataclass(frozen=True)
class Mesh:
    """n equal elements of length l = 1/n on 0 <= x <= 1 (units of L), with the DOF map of the
    schema's constraints, and the declared co-ordinates after the nodal ones (`coordinates`:
    records.Coordinate, a driven motion's)."""

    n_elements: int
    coordinates: tuple = ()
    components: tuple = None
    rocker_elements: int = 0                     # a flexible rocker's (0: none)
    rocker_length: float = 1.0                   # its length c (units of L)
    element_dofs: np.ndarray = field(init=False, repr=False)

    @classmethod
    def of_case(cls, case):
        """The DOF map of a case: its rod's mesh with the node components of its model, a flexible
        rocker's elements, and its motion's co-ordinates."""
        n_r, c = rocker_of(case)
        return cls(case.n_elements, tuple(case.motion_record.coordinates), components_of(case.options), n_r, c)

    def __post_init__(self):
        n = integer("n_elements", self.n_elements, 1)
        object.__setattr__(self, "n_elements", n)
        object.__setattr__(self, "rocker_elements", integer("rocker_elements", self.rocker_elements, 0))
        object.__setattr__(self, "rocker_length", float(self.rocker_length))
        object.__setattr__(self, "present", (ROCKER.name,) if self.rocker_elements else ())
        object.__setattr__(self, "coordinates", tuple(self.coordinates))
        present = components_of({}) if self.components is None else tuple(self.components)
        if not set(present) <= set(COMPONENTS) or not present:
            raise ValueError(f"components must be some of {COMPONENTS}, got {present!r}")
        object.__setattr__(self, "components", tuple(c for c in COMPONENTS if c in present))
        object.__setattr__(self, "_index", self._numbering())
        object.__setattr__(self, "element_dofs", self._element_dofs())

    @property
    def mapped(self):
        """The mapped constraint of this DOF map (the guide's end, or a flexible rocker's tip)."""
        return mapped_constraint(self.present)

    @property
    def n_all(self):
        """Number of elements of every flexible body: the rod's, then a flexible rocker's."""
        return self.n_elements + self.rocker_elements

    def node_of(self, constraint):
        """The node (0 .. n) of its body a constraint holds."""
        count = self.rocker_elements if ROCKER is not None and constraint.body == ROCKER.name else self.n_elements
        return constraint.node % (count + 1)

    def _numbering(self):
        """{(node, component): reduced index or None} of the rod, {(rocker, node, component): ...} of
        a flexible rocker, and {(constraint, j): reduced index} of the DOF map: nodes in order (the
        rocker's from its tip), components in order; an eliminated component gives its place to the
        constraint's j-th reduced co-ordinate (j its rank among the eliminated), or none.  A
        flexible rocker's tip: the rod's end node's own components first, then the tip constraint's
        reduced co-ordinates (the rocker tip's u, v), then the rocker tip's other components."""
        index, k = {}, 0
        order = [((node,), node, joints(BODY, self.present)) for node in range(self.n_elements + 1)]
        if self.rocker_elements:
            n_r = self.rocker_elements
            order += [((ROCKER.name, node), node, joints(ROCKER, self.present)) for node in range(n_r, -1, -1)]
        shared = None
        for key, node, held in order:
            c = next((c for c in held if self.node_of(c) == node), None)
            later = []
            for comp in range(NODE_DOFS):
                name = COMPONENTS[comp]
                if name not in self.components:         # not a component of this model's node
                    index[key + (comp,)] = None
                    continue
                if shared is not None and key[0] == ROCKER.name and node == self.rocker_elements \
                        and name in shared.reduced:     # the rocker tip's (u, v): the tip's reduced co-ordinates
                    index[key + (comp,)] = index[(shared.name, shared.reduced.index(name))]
                    continue
                if c is not None and name in c.eliminated:
                    j = c.eliminated.index(name)
                    if j < len(c.reduced):
                        if self.rocker_elements and c is self.mapped:
                            later.append((c, j, key + (comp,)))
                            continue
                        index[(c.name, j)] = k
                    else:
                        index[key + (comp,)] = None
                        continue
                index[key + (comp,)] = k
                k += 1
            for c, j, at in later:                      # after the node's own components
                index[(c.name, j)] = index[at] = k
                k += 1
                shared = c
        index["size"] = k
        return index

    @property
    def n_rod(self):
        """Number of the rod's reduced nodal DOFs (3 n, 4 n + 1 with chi, with the pin and the guide):
        the band."""
        return self._index["size"]

    @property
    def n_dofs(self):
        """Number of unknowns of the state: the nodal ones, then the declared co-ordinates."""
        return self._index["size"] + len(self.coordinates)

    def coordinate_index(self, name):
        """The state's index of a declared co-ordinate."""
        return self.n_rod + [c.name for c in self.coordinates].index(name)

    @property
    def crank_coordinate(self):
        """The index among the declared co-ordinates of the crank angle, -1 if none is."""
        return next((j for j, c in enumerate(self.coordinates) if c.crank), -1)

    @property
    def motor_coordinate(self):
        """The index among the declared co-ordinates of the one a motor's torque curve drives, -1."""
        return next((j for j, c in enumerate(self.coordinates) if c.motor), -1)

    @property
    def dummy(self):
        """Index standing for 'no reduced DOF' (pinned or constrained-away); gathers a zero."""
        return self.n_dofs

    @property
    def length(self):
        return 1.0 / self.n_elements

    @property
    def x0(self):
        """x co-ordinate of the first node of each element."""
        return np.arange(self.n_elements) * self.length

    @property
    def rocker_element_length(self):
        return self.rocker_length / self.rocker_elements if self.rocker_elements else 0.0

    def reduced_coordinates(self, constraint=None):
        """The reduced indices of a constraint's reduced co-ordinates (default: the mapped one's)."""
        constraint = self.mapped if constraint is None else constraint
        return tuple(self._index[(constraint.name, j)] for j in range(len(constraint.reduced)))

    def mapped_values(self, x):
        """The mapped constraint's reduced co-ordinates in vectors x (..., N), as its map takes them
        (crankgen.discrete.kinematics.end_map): (...) for the guide's one, (..., 2) for a flexible
        rocker tip's (u_r, v_r)."""
        S = self.reduced_coordinates()
        return np.asarray(x)[..., list(S) if self.rocker_elements else S[0]]

    def holders(self, constraint=None):
        """[(element, slots of the eliminated components there, slots of the reduced co-ordinates)]
        of the elements holding a constraint's node (one at the first or last node, two inside;
        default: the mapped constraint's); a rocker's elements are numbered after the rod's."""
        constraint = self.mapped if constraint is None else constraint
        node = self.node_of(constraint)
        rocker = ROCKER is not None and constraint.body == ROCKER.name
        count, first = (self.rocker_elements, self.n_elements) if rocker else (self.n_elements, 0)
        out = []
        for e, at in ((node - 1, 1), (node, 0)):
            if 0 <= e < count:
                slots = element_slots(at, constraint.eliminated)
                out.append((first + e, slots, slots[:len(constraint.reduced)]))
        return out

    def reduced_index(self, node, component):
        """Reduced index of (node, component) of the rod (node a number) or of a flexible rocker
        (node = (body name, number)), or None if constrained away (or holding a reduced co-ordinate
        of its constraint: reduced_coordinates)."""
        key = node + (component,) if isinstance(node, tuple) else (node, component)
        return self._index.get(key)

    def _element_dofs(self):
        """(n_all, NDOF) reduced index of each element DOF, the rod's elements then a flexible
        rocker's; an eliminated slot holding a reduced co-ordinate holds its index (the end element's
        u_n slot holds s)."""
        bodies = [(BODY, (), self.n_elements)]
        if self.rocker_elements:
            bodies.append((ROCKER, (ROCKER.name,), self.rocker_elements))
        rows = []
        for body, key, count in bodies:
            held = {self.node_of(c): c for c in joints(body, self.present)}
            for e in range(count):
                row = []
                for k in range(NDOF):
                    node, comp = e + k // NODE_DOFS, k % NODE_DOFS
                    c = held.get(node)
                    idx = self._index.get(key + (node, comp))
                    if c is not None and COMPONENTS[comp] in c.eliminated and COMPONENTS[comp] in self.components:
                        j = c.eliminated.index(COMPONENTS[comp])
                        idx = self._index[(c.name, j)] if j < len(c.reduced) else None
                    row.append(self.dummy if idx is None else idx)
                rows.append(row)
        return np.array(rows, dtype=np.intp).reshape(-1, NDOF)

    def gather(self, reduced):
        """The rod's element view (..., n, NDOF) of reduced vectors (..., N; or their nodal part,
        n_rod); constrained slots are 0 (a slot holding a reduced co-ordinate holds it, mapped by
        constraints.py).  gather_all: every flexible body's elements."""
        return self.gather_all(reduced)[..., :self.n_elements, :]

    def gather_all(self, reduced):
        """Element view (..., n_all, NDOF) of reduced vectors: the rod's elements, then a flexible
        rocker's."""
        reduced = np.asarray(reduced)[..., :self.n_rod]
        padded = np.concatenate([reduced, np.zeros(reduced.shape[:-1] + (self.n_dofs + 1 - self.n_rod,))], axis=-1)
        return padded[..., self.element_dofs]

    def dof_scales(self, sizes, end=None):
        """Natural size of each reduced DOF in units of L: the size of its component (sizes: one per
        component of a node, schema.NODE order, from schema.natural_sizes; a number: the slenderness
        eps, whose declared sizes are taken: u* = u / eps^2, v* = v / eps), and `end` for the end
        map's reduced co-ordinate (its guide's natural size; default: the axial size, a slider); a
        declared co-ordinate's is 1 of its unit (an angle: 1 rad)."""
        if np.ndim(sizes) == 0:
            sizes = schema.natural_sizes({schema.UNIT_PARAMETERS["r"]: float(sizes)})
        scales = np.empty(self.n_dofs)
        keys = [k for k in self._index if isinstance(k, tuple) and self._index[k] is not None]
        for node, comp in (k for k in keys if not isinstance(k[0], str)):
            scales[self._index[(node, comp)]] = sizes[comp]
        for key in (k for k in keys if isinstance(k[0], str) and len(k) == 3):     # a flexible rocker's nodes
            scales[self._index[key]] = sizes[key[2]]
        for key in (k for k in keys if isinstance(k[0], str) and len(k) == 2):     # the reduced co-ordinates
            c = next(c for c in schema.CONSTRAINTS if c.name == key[0])
            name = c.reduced[key[1]]
            scales[self._index[key]] = (sizes[COMPONENTS.index(name)] if name in COMPONENTS    # a node's own (u, v)
                                        else sizes[U] if end is None else end)
        scales[self.n_rod:] = 1.0
        return scales

    def locate(self, x):
        """(element index, zeta) of the point x in [0, 1]."""
        e = min(int(np.floor(x * self.n_elements)), self.n_elements - 1)
        return e, (x - e * self.length) / self.length


def transfer(values, source, target):
    """Reduced vectors (..., source.n_dofs) of one DOF map in the layout of another on the same
    elements and co-ordinates (a consistent model's states read by the exact rod, whose nodes add
    chi): every (node, component) both have is copied, and the reduced and declared co-ordinates;
    a chi that the source lacks is the slope of its u at the node (the mean of the two elements'
    slopes u_x, the one element's at an end; the end node's u through the reduced co-ordinate is
    not at hand there, so the last element's slope is its neighbour's).  Returns (..., target.n_dofs)."""
    values = np.asarray(values, dtype=float)
    if (source.n_elements != target.n_elements or source.coordinates != target.coordinates
            or (source.rocker_elements, source.rocker_length) != (target.rocker_elements, target.rocker_length)):
        raise ValueError("transfer needs two DOF maps of the same elements and co-ordinates")
    out = np.zeros(values.shape[:-1] + (target.n_dofs,))
    n = source.n_elements
    u = np.zeros(values.shape[:-1] + (n + 1,))
    known = np.zeros(n + 1, dtype=bool)
    for node in range(n + 1):
        for comp in range(NODE_DOFS):
            i, j = source.reduced_index(node, comp), target.reduced_index(node, comp)
            if comp == U and i is not None and i not in set(source.reduced_coordinates()):
                u[..., node], known[node] = values[..., i], True
            if i is not None and j is not None:
                out[..., j] = values[..., i]
    known[0] = True                                  # the pin: u_0 = 0
    for a, b in zip(source.reduced_coordinates(), target.reduced_coordinates()):
        out[..., b] = values[..., a]
    out[..., target.n_rod:] = values[..., source.n_rod:]
    if "chi" in target.components and "chi" not in source.components:
        h = source.length
        slopes = np.full(values.shape[:-1] + (n,), np.nan)
        for e in range(n):
            if known[e] and known[e + 1]:
                slopes[..., e] = (u[..., e + 1] - u[..., e]) / h
        for e in range(n):                           # an element without both ends: its neighbour's slope
            if not (known[e] and known[e + 1]):
                slopes[..., e] = slopes[..., e - 1] if e > 0 else 0.0
        for node in range(n + 1):
            j = target.reduced_index(node, CHI)
            if j is None:
                continue
            around = [e for e in (node - 1, node) if 0 <= e < n]
            out[..., j] = np.mean([slopes[..., e] for e in around], axis=0)
    if source.rocker_elements:                       # a flexible rocker's nodes: its own u at every node
        n_r = source.rocker_elements
        u_r = np.zeros(values.shape[:-1] + (n_r + 1,))
        for node in range(n_r + 1):
            for comp in range(NODE_DOFS):
                i, j = source.reduced_index((ROCKER.name, node), comp), target.reduced_index((ROCKER.name, node), comp)
                if comp == U and i is not None:
                    u_r[..., node] = values[..., i]
                if i is not None and j is not None:
                    out[..., j] = values[..., i]
        if "chi" in target.components and "chi" not in source.components:
            slopes = np.diff(u_r, axis=-1) / source.rocker_element_length
            for node in range(n_r + 1):
                j = target.reduced_index((ROCKER.name, node), CHI)
                around = [e for e in (node - 1, node) if 0 <= e < n_r]
                out[..., j] = np.mean([slopes[..., e] for e in around], axis=0)
    return out
