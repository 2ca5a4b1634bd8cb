"""Assembly of element vectors and matrices into reduced global arrays (banded storage).

Scatter indices are computed once per mesh; each assembly is one np.bincount over the element
entries (COO triplets summed in place), giving the residual vector and the LAPACK band storage
used by dgbsv.  The band holds the rod's nodal DOFs (mesh.n_rod); the declared co-ordinates of a
driven motion, which follow them in the state, border it (crankgen.discrete.newmark).
"""

from dataclasses import dataclass, field

import numpy as np

from .mesh import Mesh
from ..declaration.schema import ELEMENT_DOFS as NDOF


@dataclass(frozen=True)
class BandedAssembler:
    mesh: Mesh
    bandwidth: int = field(init=False)
    _vec_index: np.ndarray = field(init=False, repr=False)
    _vec_valid: np.ndarray = field(init=False, repr=False)
    _mat_index: np.ndarray = field(init=False, repr=False)
    _mat_valid: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        dofs = self.mesh.element_dofs
        valid = dofs < self.mesh.n_rod
        rows = np.broadcast_to(dofs[:, :, None], dofs.shape + (NDOF,))
        cols = np.broadcast_to(dofs[:, None, :], dofs.shape + (NDOF,))
        mvalid = valid[:, :, None] & valid[:, None, :]
        kb = int(np.max(np.abs(rows[mvalid] - cols[mvalid])))
        n = self.mesh.n_rod
        # LAPACK gbsv band storage: ab[2 kb + i - j, j] = A[i, j], shape (3 kb + 1, n).
        flat = (2 * kb + rows - cols) * n + cols
        object.__setattr__(self, "bandwidth", kb)
        object.__setattr__(self, "_vec_valid", valid.ravel())
        object.__setattr__(self, "_vec_index", dofs.ravel()[valid.ravel()])
        object.__setattr__(self, "_mat_valid", mvalid.ravel())
        object.__setattr__(self, "_mat_index", flat.ravel()[mvalid.ravel()])

    @property
    def band_shape(self):
        return (3 * self.bandwidth + 1, self.mesh.n_rod)

    def vector(self, element_vectors):
        """Sum (n, NDOF) element vectors into the reduced nodal vector (n_rod,)."""
        w = element_vectors.reshape(-1)[self._vec_valid]
        return np.bincount(self._vec_index, weights=w, minlength=self.mesh.n_rod)

    def banded(self, element_matrices):
        """Sum (n, NDOF, NDOF) element matrices into LAPACK band storage."""
        w = element_matrices.reshape(-1)[self._mat_valid]
        size = self.band_shape[0] * self.band_shape[1]
        return np.bincount(self._mat_index, weights=w, minlength=size).reshape(self.band_shape)

    def dense(self, element_matrices):
        """The same matrix as a dense (N, N) array (tests and diagnostics)."""
        ab = self.banded(element_matrices)
        kb, n = self.bandwidth, self.mesh.n_rod
        A = np.zeros((n, n))
        for j in range(n):
            for i in range(max(0, j - kb), min(n, j + kb + 1)):
                A[i, j] = ab[2 * kb + i - j, j]
        return A

    def factorize(self, ab):
        """LU factors (LAPACK gbtrf, partial pivoting) of the band matrix ab; None if singular."""
        from scipy.linalg import lapack          # the NumPy reference only: not on the engine's start-up
        kb = self.bandwidth
        lu, ipiv, info = lapack.dgbtrf(ab, kb, kb)
        if info != 0:
            return None
        return lu, ipiv

    def solve_factorized(self, factors, rhs):
        """x with A x = rhs from the factors of factorize (LAPACK gbtrs)."""
        from scipy.linalg import lapack
        kb = self.bandwidth
        lu, ipiv = factors
        rhs = np.asarray(rhs, dtype=float)
        x, info = lapack.dgbtrs(lu, kb, kb, rhs.reshape(rhs.shape[0], -1), ipiv)
        if info != 0:
            raise ValueError(f"dgbtrs: illegal argument {-info}")
        return x.reshape(rhs.shape)

    def solve(self, ab, rhs):
        """Solve A x = rhs with A in band storage (LU with partial pivoting); None if singular."""
        from scipy.linalg import lapack
        kb = self.bandwidth
        _, _, x, info = lapack.dgbsv(kb, kb, ab, rhs, overwrite_ab=1, overwrite_b=0)
        if info != 0:
            return None
        return x
