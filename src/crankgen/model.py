"""The discrete model: mesh + generated element kernels + slider constraint + assembly.

For reduced displacements d, velocities v and accelerations a at time t the model gives the
reduced residual R(t, d, v, a) of eq. (30) (exact Lagrange or printed form) and the Newmark
iteration matrix  S = dR/da + c_v dR/dv + c_d dR/dd  in band storage.
"""

from dataclasses import dataclass, field

import numpy as np

from ._generated import energy as _energy
from .assembly import BandedAssembler
from .constraints import S_SLOT, expand, project, slider_map
from .kernels import ElementKernels, select_kernels
from .kinematics import crank_state
from .mesh import Mesh
from .parameters import Mechanism

SLIDER = slice(3, 5)   # (u, v) of the last node in the last element's nodal vector


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
    kernels: ElementKernels
    assembler: BandedAssembler = field(init=False, repr=False)

    def __post_init__(self):
        object.__setattr__(self, "assembler", BandedAssembler(self.mesh))

    @classmethod
    def build(cls, mechanism, omega, n_elements, formulation, approach, damping, membrane="pointwise"):
        return cls(mechanism, float(omega), Mesh(n_elements),
                   select_kernels(formulation, approach, damping, membrane))

    @property
    def n_dofs(self):
        return self.mesh.n_dofs

    def kinematics(self, t):
        return crank_state(self.mechanism.a, self.omega, t)

    def nodal_state(self, kin, d, v, a):
        """Element nodal vectors q, qd, qdd (n, 6) and the slider map of the last element."""
        p, pd, pdd = self.mesh.gather(d), self.mesh.gather(v), self.mesh.gather(a)
        tmaps = slider_map(kin.phi, kin.phid, kin.phidd)
        q_end, qd_end, qdd_end = expand(*tmaps, p[-1], pd[-1], pdd[-1])
        p[-1], pd[-1], pdd[-1] = q_end, qd_end, qdd_end
        return p, pd, pdd, tmaps

    def element_terms(self, kin, d, v, a, secant=False):
        """Residual and tangents per element.  secant=True gives the printed iteration matrices
        of eq. (37) (K_lin + K_non, C) instead of the exact tangent (paper formulation only)."""
        m, mesh, k = self.mechanism, self.mesh, self.kernels
        q, qd, qdd, tmaps = self.nodal_state(kin, d, v, a)
        kin_args = (m.a,) + kin.as_args()
        l, x0 = mesh.length, mesh.x0

        r, K, C, M = k.rod_inertia(q, qd, qdd, l, x0, m.rhoA, m.rhoI, *kin_args)
        elastic = k.rod_elastic(q, l, m.EA, m.EI)
        if k.damping == "paper":
            r_d, K_d, C_d = k.rod_damping(q, qd, l, m.EA, m.EI, m.rhoA, m.rhoI, kin.phid, m.mu)
        else:
            r_d, K_d, C_d = k.rod_damping(q, qd, l, m.EA, m.EI, m.mu)
        r = r + elastic[0] + r_d
        C = C + C_d
        if secant:
            K = K + elastic[2]            # printed K_lin + K_non; C(q) qd taken as given
        else:
            K = K + elastic[1] + K_d

        rs, Ks, Cs, Ms = k.slider_inertia(q[-1, SLIDER], qd[-1, SLIDER], qdd[-1, SLIDER],
                                          m.ms, 1.0, *kin_args)
        if k.slider_damping is not None:
            r_sd, K_sd, C_sd = k.slider_damping(qd[-1, SLIDER], m.ms, kin.phid, m.mu)
            rs, Cs = rs + r_sd, Cs + C_sd
        r[-1, SLIDER] += rs
        K[-1, SLIDER, SLIDER] += Ks
        C[-1, SLIDER, SLIDER] += Cs
        M[-1, SLIDER, SLIDER] += Ms

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

    def energies(self, t, d, v):
        """(kinetic T_c + T_s, strain U_c) of the approach at time t for reduced d, v."""
        m, mesh = self.mechanism, self.mesh
        kin = self.kinematics(t)
        q, qd, _, _ = self.nodal_state(kin, d, v, np.zeros_like(d))
        kin_args = (m.a, kin.theta, kin.thetad, kin.phi, kin.phid)
        T_rod = _energy.rod_kinetic_energy(q, qd, mesh.length, mesh.x0, m.rhoA, m.rhoI, *kin_args)
        T_slider = _energy.slider_kinetic_energy(q[-1, SLIDER], qd[-1, SLIDER], m.ms, 1.0, *kin_args)
        k = self.kernels
        averaged = k.membrane == "averaged" and k.approach != "C" and k.formulation == "lagrange"
        strain = getattr(_energy, f"strain_energy_{k.approach}" + ("_averaged" if averaged else ""))
        U = strain(q, mesh.length, m.EA, m.EI)
        return float(np.sum(T_rod) + T_slider), float(np.sum(U))

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
