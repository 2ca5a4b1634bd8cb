"""Mesh of the connecting rod and the map from element DOFs to the reduced (free) DOFs.

Full nodal vector: 3 DOFs per node, (u, v, psi) (eq. 14), nodes 0..n along the rod.  The pin
removes u_0 = v_0 = 0; the end constraint replaces (u_n, v_n) by the single reduced co-ordinate s
of the guide's end map, (u_n, v_n) = g(s, t) (a slider: s (cos phi, sin phi), eq. 26; see
constraints.py).  The reduced vector is

    [psi_0,  u_1, v_1, psi_1,  ...,  u_{n-1}, v_{n-1}, psi_{n-1},  s, psi_n]     (3 n entries).
"""

from dataclasses import dataclass, field

import numpy as np

from .schema import ELEMENT_DOFS as NDOF
from .validation import integer

U, V, PSI = 0, 1, 2
NODE_DOFS = NDOF // 2            # (u, v, psi) at each of an element's two nodes


@dataclass(frozen=True)
class Mesh:
    """n equal elements of length l = 1/n on 0 <= x <= 1 (units of L)."""

    n_elements: int
    element_dofs: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        n = integer("n_elements", self.n_elements, 1)
        object.__setattr__(self, "n_elements", n)
        object.__setattr__(self, "element_dofs", self._element_dofs())

    @property
    def n_dofs(self):
        """Number of reduced DOFs, 3 n."""
        return 3 * self.n_elements

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
    def slider_dof(self):
        return self.n_dofs - 2

    def reduced_index(self, node, component):
        """Reduced index of (node, component), or None if pinned / replaced by the constraint."""
        n = self.n_elements
        if node == 0:
            return 0 if component == PSI else None
        if node == n:
            return {U: self.n_dofs - 2, V: None, PSI: self.n_dofs - 1}[component]
        return 1 + 3 * (node - 1) + component

    def _element_dofs(self):
        """(n, NDOF) reduced index of each element DOF; the last element's u_n slot holds s."""
        dofs = np.empty((self.n_elements, NDOF), dtype=np.intp)
        for e in range(self.n_elements):
            for k in range(NDOF):
                idx = self.reduced_index(e + k // NODE_DOFS, k % NODE_DOFS)
                dofs[e, k] = self.dummy if idx is None else idx
        return dofs

    def gather(self, reduced):
        """Element view (..., n, NDOF) of reduced vectors (..., N); constrained slots are 0 (the last
        element's u slot holds s, mapped to (u, v) by constraints.py)."""
        reduced = np.asarray(reduced)
        padded = np.concatenate([reduced, np.zeros(reduced.shape[:-1] + (1,))], axis=-1)
        return padded[..., self.element_dofs]

    def dof_scales(self, eps, end=None):
        """Natural size of each reduced DOF in units of L: eps^2 for axial (u* = u / eps^2),
        eps for transverse deflection and slope (v* = v / eps); the end's reduced co-ordinate
        (slider_dof) takes `end` (its guide's natural size; default eps^2, a slider)."""
        scales = np.full(self.n_dofs, eps)
        for node in range(1, self.n_elements + 1):
            idx = self.reduced_index(node, U)
            scales[idx] = eps**2
        if end is not None:
            scales[self.slider_dof] = end
        return scales

    def locate(self, x):
        """(element index, zeta) of the point x in [0, 1]."""
        e = min(int(np.floor(x * self.n_elements)), self.n_elements - 1)
        return e, (x - e * self.length) / self.length
