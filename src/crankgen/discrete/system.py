"""The discrete model in plain NumPy (the reference the compiled engine is tested against): mesh +
the generated element kernels of the selected term families + the guide's end map + assembly.

For reduced displacements d, velocities v and accelerations a at time t the model gives the
reduced residual R(t, d, v, a) of eq. (30) (exact Lagrange or printed form) and the Newmark
iteration matrix  S = dR/da + c_v dR/dv + c_d dR/dd  in band storage.  The state is the DOF map's
(crankgen.discrete.mesh): the rod's nodal co-ordinates (the band), then the co-ordinates a driven
motion declares, whose equations (`coordinate_equations`) the integrator borders the band with
(crankgen.discrete.newmark); the crank's kinematics then follow from the state.  Everything that depends on
the case (families, kernels, coefficients, guide, crank motion) comes from the Case and the
declared model (crankgen.declaration.ingredients, crankgen.discrete.kinematics); this module loops over them and never
names one.
"""

from dataclasses import dataclass, field

import numpy as np

from . import kinematics as _kinematics
from .assembly import BandedAssembler
from ..declaration.cases import Case
from ..declaration import schema
from .constraints import ROWS, expand, project, tangents
from .mesh import COMPONENTS, MAPPED, NODE_DOFS, ROCKER, Mesh
from ..declaration.schema import ELEMENT_DOFS as NDOF
# the body that carries each family when it is not the one the family's part names (Family.body)
CARRIER = {f.name: f.body for f in schema.FAMILIES}

_PIN = next(c for c in schema.CONSTRAINTS if c.map is None and c.node == 0)     # the crank pin

def check_coordinates(case):
    """Refuse a case with declared co-ordinates (a driven crank) that the bordered step cannot take:
    one element (the crank pin's and the guide's rows in the same element), or the one-pass scheme
    (no bordered form)."""
    from ..errors import ParameterError
    if case.n_elements < 2:
        raise ParameterError("a driven crank needs n_elements >= 2 (the crank pin's element must not hold the "
                             "guide's node)")
    if case.integrator == "one-pass":
        raise ParameterError("a driven crank needs integrator 'newton' or 'full-newton' (the one-pass scheme has "
                             "no bordered form)")


# positional model options of Model.build, in the order its callers pass them
_BUILD_POSITIONAL = ("formulation", "approach", "damping", "membrane")


@dataclass(frozen=True)
class ElementTerms:
    """Element residuals and tangents (n, 6) / (n, 6, 6), constraint already applied."""

    r: np.ndarray
    K: np.ndarray
    C: np.ndarray
    M: np.ndarray


@dataclass(frozen=True)
class Model:
    case: Case
    assembler: BandedAssembler = field(init=False, repr=False)
    mesh: Mesh = field(init=False, repr=False)

    def __post_init__(self):
        mesh = Mesh.of_case(self.case)
        object.__setattr__(self, "mesh", mesh)
        object.__setattr__(self, "assembler", BandedAssembler(mesh))
        object.__setattr__(self, "_selection", self.case.selection)
        object.__setattr__(self, "_coefficients", self.case.coefficients)

    @classmethod
    def build(cls, mechanism, omega, n_elements, *options, **settings):
        """The model of a mechanism at crank speed omega with n_elements; options: formulation,
        approach, damping, membrane (positional, in this order) or any Case field by keyword
        (model= a preset; the default model is `consistent`)."""
        settings.update(zip(_BUILD_POSITIONAL, options))
        if "groups_off" in settings and not isinstance(settings["groups_off"], str):
            settings["groups_off"] = ",".join(settings["groups_off"])
        return cls(Case.from_mechanism(mechanism, omega=omega, n_elements=n_elements, **settings))

    @classmethod
    def from_case(cls, case):
        return cls(case)

    @property
    def mechanism(self):
        return self.case.mechanism

    @property
    def omega(self):
        return self.case.omega

    @property
    def selection(self):
        return self._selection

    @property
    def coefficients(self):
        return self._coefficients

    @property
    def options(self):
        return self.selection.options

    @property
    def n_dofs(self):
        """The unknowns of the state: the nodal ones, then the declared co-ordinates."""
        return self.mesh.n_dofs

    @property
    def n_rod(self):
        """The rod's nodal unknowns (the band)."""
        return self.mesh.n_rod

    def kinematics(self, t):
        """The prescribed crank motion's kinematics at time(s) t."""
        return _kinematics.case_state(self.case, t)

    def state_kinematics(self, t, d, v, a):
        """The kinematics of states (d, v, a) at time(s) t: the prescribed motion's, or a driven
        motion's from the state's crank co-ordinate."""
        if not self.mesh.coordinates:
            return self.kinematics(t)
        return _kinematics.crank_state(self.case, _kinematics.state_crank(self.case, d, v, a))

    def coordinate_equations(self, kin, d, v, a, r):
        """The declared co-ordinates' equations and derivatives (m, 3 m + 3) (generated
        coordinates_<motion>: row i (g_i, dg_i/dz, dg_i/dzd, dg_i/dzdd, dg_i/dpin)) at the state,
        the crank pin's force from the unprojected element residuals r (its eliminated rows of the
        first element), a motor's torque curve's departure from the linear law on the motor's row
        (crankgen.declaration.torque_curve)."""
        from .._generated import kinematics as _generated
        from ..declaration import torque_curve
        n_rod, coords = self.mesh.n_rod, self.mesh.coordinates
        m = len(coords)
        z = np.concatenate([np.asarray(x, dtype=float)[n_rod:] for x in (d, v, a)])
        pin = r[0, list(self.mesh.holders(_PIN)[0][1])]
        geq = np.array(getattr(_generated, f"coordinates_{self.case.motion_record.name}")(
            kin.vector, z, pin, self.case.kinematic_parameters), dtype=float).reshape(m, 3 * m + 3)
        motor = self.mesh.motor_coordinate
        law = torque_curve.of(self.case)
        if motor >= 0 and law is not None and tuple(law[0]) != torque_curve.LINEAR:
            curve, stall, no_load, _ = law
            extra, slope = torque_curve.departure(curve, float(np.asarray(v)[n_rod + motor]) / no_load)
            geq[motor, 0] -= stall * extra
            geq[motor, 1 + m + motor] -= stall / no_load * slope
        return geq

    @property
    def geometry(self):
        """(n_all, 2): (l, x0) of every element (the rod's, then a flexible rocker's), the kernels' geo."""
        mesh = self.mesh
        rod = np.stack([np.full(mesh.n_elements, mesh.length), mesh.x0], axis=-1)
        if not mesh.rocker_elements:
            return rod
        lr = mesh.rocker_element_length
        rocker = np.stack([np.full(mesh.rocker_elements, lr), np.arange(mesh.rocker_elements) * lr], axis=-1)
        return np.concatenate([rod, rocker])

    def bodies(self, kv):
        """[(elements slice, coefficients, kinematics vector)] of each flexible body at the mechanism's
        kinematics vector kv (..., N_KIN): the rod's, then a flexible rocker's (its frame's kinematics,
        schema Body.frame_map)."""
        mesh = self.mesh
        out = [(slice(0, mesh.n_elements), self.coefficients, kv)]
        if mesh.rocker_elements:
            F = np.array(ROCKER.frame_map, dtype=float)
            out.append((slice(mesh.n_elements, mesh.n_all), self.case.body_coefficients(ROCKER.name),
                        np.einsum("ij,...j->...i", F, kv)))
        return out

    def nodal_state(self, kin, d, v, a):
        """Element nodal vectors q, qd, qdd (..., n_all, NDOF) with the constrained node mapped by the
        constraint's map (the guide's end map) in every element holding it, and the map's values
        E (..., rows, k)."""
        mesh = self.mesh
        p, pd, pdd = mesh.gather_all(d), mesh.gather_all(v), mesh.gather_all(a)
        E = _kinematics.end_map(self.case, kin.vector, mesh.mapped_values(d), mesh.mapped_values(v),
                                mesh.mapped_values(a))
        for e, slots, _ in self.mesh.holders():
            p[..., e, :], pd[..., e, :], pdd[..., e, :] = expand(E, p[..., e, :], pd[..., e, :], pdd[..., e, :],
                                                                 slots)
        return p, pd, pdd, E

    def unprojected_terms(self, kin, d, v, a, secant=False, rod_only=None, carried=None):
        """(q, E, r, K, C, M): the element terms before the projection on the reduced co-ordinates
        (the eliminated rows of an element holding a constrained node are the force the constraint
        must apply: the guide's with the end mass included).  rod_only: a list that receives a copy
        of r with the rod's own families alone (before the constrained node's end mass's).
        carried: a list that receives the residual of the families another body than the end
        mass carries (Family.body: a four-bar's rocker's), when any is selected."""
        q, qd, qdd, E = self.nodal_state(kin, d, v, a)
        geo, coef, kv = self.geometry, self.coefficients, kin.vector
        shape = q.shape[:-1]
        n = NDOF
        r, K, C, M = np.zeros(shape + (n,)), np.zeros(shape + (n, n)), np.zeros(shape + (n, n)), np.zeros(shape + (n, n))
        lead = (slice(None),) * (q.ndim - 2)
        e = self.mesh.holders()[0][0]           # the element whose families the constrained node carries
        parts = [("rod", lead + (at,), (q[..., at, :], qd[..., at, :], qdd[..., at, :], geo[at]), cb,
                  kb[..., None, :] if kb.ndim > 1 else kb) for at, cb, kb in self.bodies(kv)]
        parts.append((MAPPED.name, lead + (e,), (q[..., e, :], qd[..., e, :], qdd[..., e, :], geo[e]), coef, kv))
        for part, where, args, cb, kin_arg in parts:
            if part != "rod" and rod_only is not None:
                rod_only.append(r.copy())
            for name, kernel in self.selection.vectorized(part):
                out = kernel(*args, cb, kin_arg)
                r[where] += out[0]
                if carried is not None and CARRIER[name] is not None:
                    if not carried:
                        carried.append(np.zeros_like(r))
                    carried[0][where] += out[0]
                K[where] += out[4] if secant and len(out) > 4 else out[1]
                C[where] += out[2]
                M[where] += out[3]
        return q, E, r, K, C, M

    def element_terms(self, kin, d, v, a, secant=False):
        """Residual and tangents per element.  secant=True gives the printed iteration matrices of
        eq. (37) where the selected variants declare one (K_printed), for the one-pass scheme."""
        _, E, r, K, C, M = self.unprojected_terms(kin, d, v, a, secant)
        for e, slots, reduced in self.mesh.holders():
            r[..., e, :], K[..., e, :, :], C[..., e, :, :], M[..., e, :, :] = project(
                E, r[..., e, :], K[..., e, :, :], C[..., e, :, :], M[..., e, :, :], slots, reduced)
        return ElementTerms(r, K, C, M)

    def reactions(self, t, d, v, a):
        """The force each constraint of the DOF map applies to the rod (schema.CONSTRAINTS order:
        the crank pin's, the guide's), each (..., k), in the moving frame (e_i, e_j), at time(s) t
        for reduced states d, v, a (..., N): the residual rows of its eliminated components (summed
        over the elements holding its node; the end node's reaction is normal to the guide:
        g_s . end = 0 at a solution)."""
        return self._constraint_forces(self.state_kinematics(t, d, v, a), d, v, a)[0]

    def _constraint_forces(self, kin, d, v, a):
        """(reactions, rod's, carried): the constraint rows of every family, of the rod's alone, and
        of the families another body carries (None: none selected), the latter's part along the
        guide's tangent only (below)."""
        rod, carried = [], []
        _, E, r, _, _, _ = self.unprojected_terms(kin, d, v, a, rod_only=rod, carried=carried)

        present = self.mesh.present

        def at_constraints(x):             # a constraint that is not the case's: zero
            return tuple(sum((x[..., e, list(slots)] for e, slots, _ in self.mesh.holders(c)),
                             np.zeros(x.shape[:-2] + (len(c.eliminated),))) if c.applies(present)
                         else np.zeros(x.shape[:-2] + (len(c.eliminated),)) for c in schema.CONSTRAINTS)
        if not carried:
            return at_constraints(r), at_constraints(rod[0] if rod else r), None
        own = list(at_constraints(carried[0]))
        # A rocker's families are written as those of a point mass at its tip (derive/declaration.py:
        # the same reduced equations, the tip held on the rocker's circle); what the rocker's inertia,
        # weight and spring demand of the force at its tip is their part along the circle's tangent
        # (its moment about the pivot), the part along the rocker being the pivot's to bear.
        k = schema.CONSTRAINTS.index(MAPPED)
        G = tangents(E)                                           # (..., m, k)
        coeffs = np.linalg.solve(G @ np.swapaxes(G, -1, -2), (G @ own[k][..., None]))
        own[k] = (np.swapaxes(G, -1, -2) @ coeffs)[..., 0]
        return at_constraints(r), at_constraints(rod[0] if rod else r), tuple(own)

    def joint_forces(self, t, d, v, a, kin=None):
        """(joints', rod's): the force each constraint's joint applies to what it holds, and the
        same rows of the rod's own families alone.  At the crank pin both are the reaction (no
        end mass there).  At the guide's node, the first is the force the guide's body applies to
        the end mass (the slider's guide; a four-bar's rocker, whose own spring, weight and
        inertia, written on the node, are left out: the rocker turns under them and the force at
        its tip); the second the force the end mass applies to the rod (the rod applies its
        opposite to the end mass, through the pin at B).  kin: the kinematics (a CrankState) in
        place of the prescribed motion's at t (a motor-driven crank's, crankgen.discrete.motor)."""
        kin = self.state_kinematics(t, d, v, a) if kin is None else kin
        reactions, rod, carried = self._constraint_forces(kin, d, v, a)
        if carried is not None:
            reactions = tuple(total - own for total, own in zip(reactions, carried))
        return reactions, rod

    def residual(self, t, d, v, a):
        """Reduced nodal residual R(t, d, v, a) (n_rod,)."""
        terms = self.element_terms(self.state_kinematics(t, d, v, a), d, v, a)
        return self.assembler.vector(terms.r)

    def linearize(self, kin, d, v, a, c_v, c_d, secant=False):
        """(R, S) with S = dR/da + c_v dR/dv + c_d dR/dd in band storage."""
        terms = self.element_terms(kin, d, v, a, secant=secant)
        S = terms.M + c_v * terms.C + c_d * terms.K
        return self.assembler.vector(terms.r), self.assembler.banded(S)

    def energy(self, kind, t, d, v, kin=None):
        """Sum of the selected families' energies of one kind ('kinetic': T_c + T_s, 'potential':
        U_c plus gravity's V, 'dissipation': the Rayleigh function D) at time t for reduced d, v
        (kin: the kinematics in place of the prescribed motion's at t)."""
        kin = self.kinematics(t) if kin is None else kin
        q, qd, _, _ = self.nodal_state(kin, d, v, np.zeros_like(d))
        geo, coef = self.geometry, self.coefficients
        end = self.mesh.n_elements - 1         # the rod's last element (the end mass's node)
        total = 0.0
        for _name, part, kernel in self.selection.energy_kernels(kind):
            if part == "rod":
                for at, cb, kb in self.bodies(kin.vector):
                    total += float(np.sum(kernel(q[..., at, :], qd[..., at, :], geo[at], cb, kb)))
            else:
                total += float(kernel(q[..., end, :], qd[..., end, :], geo[end], coef, kin.vector))
        return total

    def energies(self, t, d, v):
        """(kinetic T_c + T_s, potential U_c + V) of the model at time t for reduced d, v."""
        return self.energy("kinetic", t, d, v), self.energy("potential", t, d, v)

    def rocker_nodal(self, d):
        """A flexible rocker's full nodal vectors (..., NODE_DOFS (n_r + 1)), in its own frame, from
        reduced d (its pivot's u, v zero)."""
        d = np.asarray(d)
        mesh = self.mesh
        out = np.zeros(d.shape[:-1] + (NODE_DOFS * (mesh.rocker_elements + 1),))
        for node in range(mesh.rocker_elements + 1):
            for comp in range(NODE_DOFS):
                idx = mesh.reduced_index((ROCKER.name, node), comp)
                if idx is not None:
                    out[..., NODE_DOFS * node + comp] = d[..., idx]
        return out

    def full_nodal(self, d, kin):
        """Full nodal vectors (..., 3 (n+1)) [u_0, v_0, psi_0, ...] from reduced d (..., N) at the
        kinematics kin (a CrankState of the same leading shape)."""
        d = np.asarray(d)
        mesh = self.mesh
        out = np.zeros(d.shape[:-1] + (NODE_DOFS * (mesh.n_elements + 1),))
        for node in range(mesh.n_elements + 1):
            for comp in range(NODE_DOFS):
                idx = mesh.reduced_index(node, comp)
                if idx is not None:
                    out[..., NODE_DOFS * node + comp] = d[..., idx]
        E = _kinematics.end_map(self.case, kin.vector, mesh.mapped_values(d))
        node = mesh.node_of(mesh.mapped)
        for a, name in enumerate(mesh.mapped.eliminated):
            out[..., NODE_DOFS * node + COMPONENTS.index(name)] = E[..., ROWS["q"], a]
        return out
