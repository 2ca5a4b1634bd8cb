"""The discrete model in plain NumPy (the reference the compiled engine is tested against): mesh +
the generated element kernels of the selected term families + slider constraint + assembly.

For reduced displacements d, velocities v and accelerations a at time t the model gives the
reduced residual R(t, d, v, a) of eq. (30) (exact Lagrange or printed form) and the Newmark
iteration matrix  S = dR/da + c_v dR/dv + c_d dR/dd  in band storage.  The families, their kernels
and the coefficient vector come from the declared model (crankgen.ingredients); this module loops
over them and never names one.
"""

from dataclasses import dataclass, field

import numpy as np

from . import ingredients
from .assembly import BandedAssembler
from .constraints import expand, project, slider_map
from .kinematics import crank_state
from .mesh import Mesh
from .parameters import Mechanism


@dataclass(frozen=True)
class ElementTerms:
    """Element residuals and tangents (n, 6) / (n, 6, 6), constraint already applied."""

    r: np.ndarray
    K: np.ndarray
    C: np.ndarray
    M: np.ndarray


@dataclass(frozen=True)
class Model:
    mechanism: Mechanism
    omega: float
    mesh: Mesh
    selection: ingredients.Selection
    coefficients: np.ndarray
    assembler: BandedAssembler = field(init=False, repr=False)

    def __post_init__(self):
        object.__setattr__(self, "assembler", BandedAssembler(self.mesh))

    @classmethod
    def build(cls, mechanism, omega, n_elements, formulation="lagrange", approach="A", damping="paper",
              membrane="pointwise", rotary_inertia=True, groups_off=()):
        options = ingredients.check_options(dict(formulation=formulation, approach=approach,
                                                 damping=damping, membrane=membrane,
                                                 rotary_inertia=rotary_inertia))
        off = ingredients.check_switched_off(groups_off, ingredients.select(options))
        coefficients = ingredients.coefficients(mechanism, options, off)
        return cls(mechanism, float(omega), Mesh(n_elements), ingredients.select(options, coefficients),
                   coefficients)

    @classmethod
    def from_case(cls, case):
        return cls(case.mechanism, case.omega, Mesh(case.n_elements), case.selection, case.coefficients)

    @property
    def options(self):
        return self.selection.options

    @property
    def n_dofs(self):
        return self.mesh.n_dofs

    def kinematics(self, t):
        return crank_state(self.mechanism.a, self.omega, t, self.mechanism.offset)

    @property
    def geometry(self):
        """(n, 2): (l, x0) of every element, the kernels' geo."""
        mesh = self.mesh
        return np.stack([np.full(mesh.n_elements, mesh.length), mesh.x0], axis=-1)

    def nodal_state(self, kin, d, v, a):
        """Element nodal vectors q, qd, qdd (n, 6) and the slider map of the last element."""
        p, pd, pdd = self.mesh.gather(d), self.mesh.gather(v), self.mesh.gather(a)
        tmaps = slider_map(kin.phi, kin.phid, kin.phidd)
        q_end, qd_end, qdd_end = expand(*tmaps, p[-1], pd[-1], pdd[-1])
        p[-1], pd[-1], pdd[-1] = q_end, qd_end, qdd_end
        return p, pd, pdd, tmaps

    def element_terms(self, kin, d, v, a, secant=False):
        """Residual and tangents per element.  secant=True gives the printed iteration matrices of
        eq. (37) where the selected variants declare one (K_printed), for the one-pass scheme."""
        q, qd, qdd, tmaps = self.nodal_state(kin, d, v, a)
        geo, coef, kv = self.geometry, self.coefficients, kin.vector
        n = self.mesh.n_elements
        r, K, C, M = np.zeros((n, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6))
        parts = [("rod", slice(None), (q, qd, qdd, geo)),
                 ("end", n - 1, (q[-1], qd[-1], qdd[-1], geo[-1]))]
        for part, where, args in parts:
            for _name, kernel in self.selection.vectorized(part):
                out = kernel(*args, coef, kv)
                r[where] += out[0]
                K[where] += out[4] if secant and len(out) > 4 else out[1]
                C[where] += out[2]
                M[where] += out[3]
        r[-1], K[-1], C[-1], M[-1] = project(*tmaps, r[-1], K[-1], C[-1], M[-1])
        return ElementTerms(r, K, C, M)

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

    def full_nodal(self, d, phi):
        """Full nodal vectors (..., 3 (n+1)) [u_0, v_0, psi_0, ...] from reduced d (..., N)."""
        d = np.asarray(d)
        n = self.mesh.n_elements
        out = np.zeros(d.shape[:-1] + (3 * (n + 1),))
        out[..., 2] = d[..., 0]
        out[..., 3:3 * n] = d[..., 1:3 * n - 2]
        s = d[..., self.mesh.slider_dof]
        out[..., 3 * n] = s * np.cos(phi)
        out[..., 3 * n + 1] = s * np.sin(phi)
        out[..., 3 * n + 2] = d[..., -1]
        return out
