"""The discrete model in plain NumPy (the reference the compiled engine is tested against): mesh +
the generated element kernels of the selected term families + the guide's end map + assembly.

For reduced displacements d, velocities v and accelerations a at time t the model gives the
reduced residual R(t, d, v, a) of eq. (30) (exact Lagrange or printed form) and the Newmark
iteration matrix  S = dR/da + c_v dR/dv + c_d dR/dd  in band storage.  Everything that depends on
the case (families, kernels, coefficients, guide, crank motion) comes from the Case and the
declared model (crankgen.ingredients, crankgen.kinematics); this module loops over them and never
names one.
"""

from dataclasses import dataclass, field

import numpy as np

from . import kinematics as _kinematics
from .assembly import BandedAssembler
from .cases import Case
from .constraints import expand, project
from .mesh import Mesh
from .schema import ELEMENT_DOFS as NDOF

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
        mesh = Mesh(self.case.n_elements)
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
        return self.mesh.n_dofs

    def kinematics(self, t):
        return _kinematics.case_state(self.case, t)

    @property
    def geometry(self):
        """(n, 2): (l, x0) of every element, the kernels' geo."""
        mesh = self.mesh
        return np.stack([np.full(mesh.n_elements, mesh.length), mesh.x0], axis=-1)

    def nodal_state(self, kin, d, v, a):
        """Element nodal vectors q, qd, qdd (..., n, 6) with the end node mapped by the guide's end
        map, and the end map's values E (..., 8, 2)."""
        p, pd, pdd = self.mesh.gather(d), self.mesh.gather(v), self.mesh.gather(a)
        S = self.mesh.slider_dof
        E = _kinematics.end_map(self.case, kin.vector, np.asarray(d)[..., S], np.asarray(v)[..., S],
                                np.asarray(a)[..., S])
        p[..., -1, :], pd[..., -1, :], pdd[..., -1, :] = expand(E, p[..., -1, :], pd[..., -1, :], pdd[..., -1, :])
        return p, pd, pdd, E

    def unprojected_terms(self, kin, d, v, a, secant=False, rod_end=None):
        """(q, E, r, K, C, M): the element terms before the end map's projection (the last
        element's end node rows are the force the guide must apply, the end mass included).
        rod_end: an array (..., 2) that receives those rows of the rod's own families (before the
        end mass's are added)."""
        q, qd, qdd, E = self.nodal_state(kin, d, v, a)
        geo, coef, kv = self.geometry, self.coefficients, kin.vector
        shape = q.shape[:-1]
        n = NDOF
        r, K, C, M = np.zeros(shape + (n,)), np.zeros(shape + (n, n)), np.zeros(shape + (n, n)), np.zeros(shape + (n, n))
        lead = (slice(None),) * (q.ndim - 2)
        kb = kv[..., None, :] if kv.ndim > 1 else kv
        parts = [("rod", lead + (slice(None),), (q, qd, qdd, geo), kb),
                 ("end", lead + (-1,), (q[..., -1, :], qd[..., -1, :], qdd[..., -1, :], geo[-1]), kv)]
        for part, where, args, kin_arg in parts:
            if part == "end" and rod_end is not None:
                rod_end[...] = r[..., -1, 3:5]
            for _name, kernel in self.selection.vectorized(part):
                out = kernel(*args, coef, kin_arg)
                r[where] += out[0]
                K[where] += out[4] if secant and len(out) > 4 else out[1]
                C[where] += out[2]
                M[where] += out[3]
        return q, E, r, K, C, M

    def element_terms(self, kin, d, v, a, secant=False):
        """Residual and tangents per element.  secant=True gives the printed iteration matrices of
        eq. (37) where the selected variants declare one (K_printed), for the one-pass scheme."""
        _, E, r, K, C, M = self.unprojected_terms(kin, d, v, a, secant)
        r[..., -1, :], K[..., -1, :, :], C[..., -1, :, :], M[..., -1, :, :] = project(
            E, r[..., -1, :], K[..., -1, :, :], C[..., -1, :, :], M[..., -1, :, :])
        return ElementTerms(r, K, C, M)

    def reactions(self, t, d, v, a):
        """(pin, end, rod_end), each (..., 2), in the moving frame (e_i, e_j), at time(s) t for
        reduced states d, v, a (..., N): the residual rows of the constrained DOFs.  pin: the force
        the crank pin applies to the rod (rows u_0, v_0); end: the force the guide applies to the
        end mass (rows u_n, v_n of every family: the rod's end with the end mass; normal to the
        guide, g_s . end = 0 at a solution); rod_end: the force the end mass applies to the rod at
        B (the same rows of the rod's own families; the rod applies -rod_end to the end mass)."""
        rod_end = np.zeros(np.shape(d)[:-1] + (2,))
        _, _, r, _, _, _ = self.unprojected_terms(self.kinematics(t), d, v, a, rod_end=rod_end)
        return r[..., 0, 0:2].copy(), r[..., -1, 3:5].copy(), rod_end

    def residual(self, t, d, v, a):
        """Reduced residual R(t, d, v, a)."""
        terms = self.element_terms(self.kinematics(t), d, v, a)
        return self.assembler.vector(terms.r)

    def linearize(self, kin, d, v, a, c_v, c_d, secant=False):
        """(R, S) with S = dR/da + c_v dR/dv + c_d dR/dd in band storage."""
        terms = self.element_terms(kin, d, v, a, secant=secant)
        S = terms.M + c_v * terms.C + c_d * terms.K
        return self.assembler.vector(terms.r), self.assembler.banded(S)

    def energy(self, kind, t, d, v):
        """Sum of the selected families' energies of one kind ('kinetic': T_c + T_s, 'potential':
        U_c plus gravity's V, 'dissipation': the Rayleigh function D) at time t for reduced d, v."""
        kin = self.kinematics(t)
        q, qd, _, _ = self.nodal_state(kin, d, v, np.zeros_like(d))
        geo, coef = self.geometry, self.coefficients
        total = 0.0
        for _name, part, kernel in self.selection.energy_kernels(kind):
            if part == "rod":
                total += float(np.sum(kernel(q, qd, geo, coef, kin.vector)))
            else:
                total += float(kernel(q[-1], qd[-1], geo[-1], coef, kin.vector))
        return total

    def energies(self, t, d, v):
        """(kinetic T_c + T_s, potential U_c + V) of the model at time t for reduced d, v."""
        return self.energy("kinetic", t, d, v), self.energy("potential", t, d, v)

    def full_nodal(self, d, kin):
        """Full nodal vectors (..., 3 (n+1)) [u_0, v_0, psi_0, ...] from reduced d (..., N) at the
        kinematics kin (a CrankState of the same leading shape)."""
        d = np.asarray(d)
        n = self.mesh.n_elements
        k = NDOF // 2                                   # DOFs per node
        out = np.zeros(d.shape[:-1] + (k * (n + 1),))
        out[..., 2] = d[..., 0]
        out[..., k:k * n] = d[..., 1:k * n - 2]
        E = _kinematics.end_map(self.case, kin.vector, d[..., self.mesh.slider_dof])
        out[..., k * n] = E[..., 0, 0]
        out[..., k * n + 1] = E[..., 0, 1]
        out[..., k * n + 2] = d[..., -1]
        return out
