"""Assembly of element arrays into reduced global arrays and banded LU solvers (compiled).

Row band storage W[i, j - i + kb] of a matrix of bandwidth kb.  band_factor / band_lu_solve: LU with
partial pivoting (like LAPACK gbtrf/gbtrs; width 3 kb + 1 for the fill of row interchanges).
factor_fixed / solve_fixed: a padded, fixed-bandwidth LU without pivoting for the Newton-Newmark
iteration matrices (see the note before KB_FIXED).
"""

import numpy as np

from ..declaration.schema import ELEMENT_DOFS as NDOF
from .compiled import jit


@jit
def assemble_vector(dofs, rE, out):
    out[:] = 0.0
    N = out.shape[0]
    for e in range(dofs.shape[0]):
        for i in range(NDOF):
            gi = dofs[e, i]
            if gi < N:
                out[gi] += rE[e, i]

@jit
def assemble_band(dofs, kb, ME, CE, KE, cm, cv, cd, W):
    """W[i, j - i + kb] += cm M + cv C + cd K (row band storage, width 3 kb + 1 for pivoting fill)."""
    W[:, :] = 0.0
    N = W.shape[0]
    for e in range(dofs.shape[0]):
        for i in range(NDOF):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(NDOF):
                gj = dofs[e, j]
                if gj >= N:
                    continue
                W[gi, gj - gi + kb] += cm * ME[e, i, j] + cv * CE[e, i, j] + cd * KE[e, i, j]

@jit
def assemble_band_newmark(dofs, kb, SE, W):
    """W[i, j - i + kb] += S_e[i, j]: the iteration matrix from element matrices SE (row band storage)."""
    W[:, :] = 0.0
    N = W.shape[0]
    for e in range(dofs.shape[0]):
        for i in range(NDOF):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(NDOF):
                gj = dofs[e, j]
                if gj < N:
                    W[gi, gj - gi + kb] += SE[e, i, j]

@jit
def band_factor(W, kb, piv, ext):
    """LU factorization with partial pivoting of the band matrix in row band storage W (N, 3 kb + 1),
    in place, like LAPACK gbtrf: U on and above the diagonal (upper bandwidth up to 2 kb after row
    interchanges), the multipliers of column k below it, piv[k] the row swapped with row k, ext[i]
    the last column of row i of U that can be non-zero.  Returns False if a pivot is zero."""
    N = W.shape[0]
    for i in range(N):
        ext[i] = min(N - 1, i + kb)
    for k in range(N):
        imax = min(N - 1, k + kb)
        p = k
        best = abs(W[k, kb])
        for i in range(k + 1, imax + 1):
            val = abs(W[i, k - i + kb])
            if val > best:
                best = val
                p = i
        if best == 0.0 or not np.isfinite(best):
            return False
        piv[k] = p
        if p != k:
            jmax = max(ext[k], ext[p])
            for j in range(k, jmax + 1):
                tmp = W[k, j - k + kb]
                W[k, j - k + kb] = W[p, j - p + kb]
                W[p, j - p + kb] = tmp
            ext[k], ext[p] = jmax, jmax
        jmax = ext[k]
        inv = 1.0 / W[k, kb]
        for i in range(k + 1, imax + 1):
            f = W[i, k - i + kb] * inv
            W[i, k - i + kb] = f
            if f == 0.0:
                continue
            oi = kb - i
            ok = kb - k
            for j in range(k + 1, jmax + 1):
                W[i, j + oi] -= f * W[k, j + ok]
            if jmax > ext[i]:
                ext[i] = jmax
    return True

@jit
def band_lu_solve(W, kb, piv, ext, B):
    """Solve A X = B in place (B: (N, m)) with the factors of band_factor."""
    N = W.shape[0]
    m = B.shape[1]
    for k in range(N):
        p = piv[k]
        if p != k:
            for c in range(m):
                tmp = B[k, c]
                B[k, c] = B[p, c]
                B[p, c] = tmp
        for i in range(k + 1, min(N - 1, k + kb) + 1):
            f = W[i, k - i + kb]
            if f != 0.0:
                for c in range(m):
                    B[i, c] -= f * B[k, c]
    for i in range(N - 1, -1, -1):
        inv = 1.0 / W[i, kb]
        for c in range(m):
            s = B[i, c]
            for j in range(i + 1, ext[i] + 1):
                s -= W[i, j - i + kb] * B[j, c]
            B[i, c] = s * inv

@jit
def band_solve(W, kb, B):
    """Solve A X = B in place (B: (N, m)); A in row band storage W (N, 3 kb + 1), overwritten by its
    LU factors.  Returns False if a pivot is zero."""
    N = W.shape[0]
    piv = np.empty(N, dtype=np.int64)
    ext = np.empty(N, dtype=np.int64)
    if not band_factor(W, kb, piv, ext):
        return False
    band_lu_solve(W, kb, piv, ext, B)
    return True


# Iteration matrices have a positive definite symmetric part (mass + beta dt^2 stiffness +
# gamma dt damping, with skew gyroscopic terms), for which LU without pivoting is stable.  With the
# element DOFs on consecutive indices the bandwidth is 5 (n_elements >= 2), and a fixed-width,
# padded LU without pivoting is several times faster than the general pivoted one.  It is used
# when every pivot keeps at least PIVOT_RATIO of its (non-zero) original diagonal entry and no
# multiplier exceeds MAX_MULTIPLIER (no large element growth); otherwise the step falls back to
# band_factor (partial pivoting).  The converged state does not depend on it: the residual is exact,
# the factorization only steers the iteration.
KB_FIXED = 5
PIVOT_RATIO = 1e-6
MAX_MULTIPLIER = 1e3


@jit
def assemble_fixed(dofs, SE, F, N):
    """F[i, j - i + 5] = A[i, j] (F: (N + 5, 11)); rows N.. are identity padding."""
    F[:, :] = 0.0
    for i in range(N, F.shape[0]):
        F[i, KB_FIXED] = 1.0
    for e in range(dofs.shape[0]):
        for i in range(NDOF):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(NDOF):
                gj = dofs[e, j]
                if gj < N:
                    F[gi, gj - gi + KB_FIXED] += SE[e, i, j]


@jit
def factor_fixed(F, N, diag):
    """In-place LU without pivoting of the padded bandwidth-5 matrix F (assemble_fixed).  Returns
    False (F then unusable) if a diagonal entry is zero, a pivot falls below PIVOT_RATIO times its
    diagonal entry or a multiplier exceeds MAX_MULTIPLIER."""
    for k in range(N):
        diag[k] = abs(F[k, KB_FIXED])
    for k in range(N):
        pivot = F[k, KB_FIXED]
        if not (abs(pivot) > PIVOT_RATIO * diag[k] and diag[k] > 0.0) or not np.isfinite(pivot):
            return False
        inv = 1.0 / pivot
        for ii in range(1, KB_FIXED + 1):
            i = k + ii
            o = KB_FIXED - ii
            f = F[i, o] * inv
            if abs(f) > MAX_MULTIPLIER:
                return False
            F[i, o] = f
            for j in range(1, KB_FIXED + 1):
                F[i, o + j] -= f * F[k, KB_FIXED + j]
    return True


@jit
def solve_fixed(F, N, b):
    """Solve with the factors of factor_fixed; b: (N + 5,) right-hand side, overwritten."""
    for i in range(N, b.shape[0]):
        b[i] = 0.0
    for k in range(N):
        bk = b[k]
        for ii in range(1, KB_FIXED + 1):
            b[k + ii] -= F[k + ii, KB_FIXED - ii] * bk
    for i in range(N - 1, -1, -1):
        s = b[i]
        for j in range(1, KB_FIXED + 1):
            s -= F[i, KB_FIXED + j] * b[i + j]
        b[i] = s / F[i, KB_FIXED]


@jit(python=False)
def band_matmul(dofs, kb, XE, X, out):
    """out = A X for A assembled from element matrices XE (no band storage needed), X: (N, m)."""
    out[:, :] = 0.0
    N = X.shape[0]
    m = X.shape[1]
    for e in range(dofs.shape[0]):
        for i in range(NDOF):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(NDOF):
                gj = dofs[e, j]
                if gj >= N:
                    continue
                aij = XE[e, i, j]
                if aij != 0.0:
                    for c in range(m):
                        out[gi, c] += aij * X[gj, c]
