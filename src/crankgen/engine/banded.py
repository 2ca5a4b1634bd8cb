"""Assembly of element arrays into reduced global arrays and banded LU solvers (compiled).

Row band storage W[i, j - i + kb] of a matrix of bandwidth kb.  band_factor / band_lu_solve: LU with
partial pivoting (like LAPACK gbtrf/gbtrs; width 3 kb + 1 for the fill of row interchanges).
factor_fixed / solve_fixed: a padded, fixed-bandwidth LU without pivoting for the Newton-Newmark
iteration matrices, compiled for each bandwidth of FIXED_WIDTHS (see the note before KB_FIXED).
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
# element DOFs on consecutive indices the bandwidth is 5 for nodes (u, v, psi) and 7 for the exact
# rod's (u, v, psi, chi) (n_elements >= 2), and a padded LU without pivoting, compiled for each of
# these widths (the width a constant: numba unrolls its loops), is several times faster than the
# general pivoted one.  It is used when every pivot keeps at least PIVOT_RATIO of its (non-zero)
# original diagonal entry and no multiplier exceeds MAX_MULTIPLIER (no large element growth);
# otherwise the step falls back to band_factor (partial pivoting).  The converged state does not
# depend on it: the residual is exact, the factorization only steers the iteration.
KB_FIXED = 5                    # the default models' bandwidth
FIXED_WIDTHS = (5, 7)           # the bandwidths with a fixed-width LU (5, and 7: the exact rod's)
PIVOT_RATIO = 1e-6
MAX_MULTIPLIER = 1e3
KB = KB_FIXED                   # the width of the functions below; each compiled copy binds its own


def _assemble_fixed(dofs, SE, F, N):
    """F[i, j - i + KB] = A[i, j] (F: (N + KB, 2 KB + 1)); rows N.. are identity padding."""
    F[:, :] = 0.0
    for i in range(N, F.shape[0]):
        F[i, KB] = 1.0
    for e in range(dofs.shape[0]):
        for i in range(NDOF):
            gi = dofs[e, i]
            if gi >= N:
                continue
            for j in range(NDOF):
                gj = dofs[e, j]
                if gj < N:
                    F[gi, gj - gi + KB] += SE[e, i, j]


def _factor_fixed(F, N, diag):
    """In-place LU without pivoting of the padded bandwidth-KB matrix F (assemble_fixed)."""
    for k in range(N):
        diag[k] = abs(F[k, KB])
    for k in range(N):
        pivot = F[k, KB]
        if not (abs(pivot) > PIVOT_RATIO * diag[k] and diag[k] > 0.0) or not np.isfinite(pivot):
            return False
        inv = 1.0 / pivot
        for ii in range(1, KB + 1):
            i = k + ii
            o = KB - ii
            f = F[i, o] * inv
            if abs(f) > MAX_MULTIPLIER:
                return False
            F[i, o] = f
            for j in range(1, KB + 1):
                F[i, o + j] -= f * F[k, KB + j]
    return True


def _solve_fixed(F, N, b):
    """Solve with the factors of factor_fixed; b: (N + KB,), overwritten."""
    for i in range(N, b.shape[0]):
        b[i] = 0.0
    for k in range(N):
        bk = b[k]
        for ii in range(1, KB + 1):
            b[k + ii] -= F[k + ii, KB - ii] * bk
    for i in range(N - 1, -1, -1):
        s = b[i]
        for j in range(1, KB + 1):
            s -= F[i, KB + j] * b[i + j]
        b[i] = s / F[i, KB]


def _solve_fixed_columns(F, B):
    """Solve with the factors of factor_fixed for B (N, m), in place."""
    N, m = B.shape
    for k in range(N):
        for ii in range(1, min(KB, N - 1 - k) + 1):
            f = F[k + ii, KB - ii]
            for c in range(m):
                B[k + ii, c] -= f * B[k, c]
    for i in range(N - 1, -1, -1):
        for j in range(1, min(KB, N - 1 - i) + 1):
            u = F[i, KB + j]
            for c in range(m):
                B[i, c] -= u * B[i + j, c]
        piv = F[i, KB]
        for c in range(m):
            B[i, c] /= piv


def _width_copies(fn):
    """fn compiled once per width of FIXED_WIDTHS, KB bound to it (named fn_5, fn_7)."""
    return tuple(jit(fn, name=f"{fn.__name__[1:]}_{kb}", namespace={"KB": kb}, python=False)
                 for kb in FIXED_WIDTHS)


_assemble_5, _assemble_7 = _width_copies(_assemble_fixed)
_factor_5, _factor_7 = _width_copies(_factor_fixed)
_solve_5, _solve_7 = _width_copies(_solve_fixed)
_columns_5, _columns_7 = _width_copies(_solve_fixed_columns)
_WIDE = 2 * FIXED_WIDTHS[1] + 1         # the columns of F for the wider width


@jit
def fixed_width(kb):
    """Whether bandwidth kb has a fixed-width LU (one of FIXED_WIDTHS)."""
    return kb == FIXED_WIDTHS[0] or kb == FIXED_WIDTHS[1]


@jit
def assemble_fixed(dofs, SE, F, N):
    """F[i, j - i + kb] = A[i, j] (F: (N + kb, 2 kb + 1), kb of FIXED_WIDTHS); rows N.. are identity padding."""
    if F.shape[1] == _WIDE:
        _assemble_7(dofs, SE, F, N)
    else:
        _assemble_5(dofs, SE, F, N)


@jit
def factor_fixed(F, N, diag):
    """In-place LU without pivoting of the padded band matrix F (assemble_fixed; its bandwidth kb of
    FIXED_WIDTHS from its shape).  Returns False (F then unusable) if a diagonal entry is zero, a
    pivot falls below PIVOT_RATIO times its diagonal entry or a multiplier exceeds MAX_MULTIPLIER."""
    if F.shape[1] == _WIDE:
        return _factor_7(F, N, diag)
    return _factor_5(F, N, diag)


@jit
def solve_fixed(F, N, b):
    """Solve with the factors of factor_fixed; b: (N + kb,) right-hand side, overwritten."""
    if F.shape[1] == _WIDE:
        _solve_7(F, N, b)
    else:
        _solve_5(F, N, b)


@jit
def solve_fixed_columns(F, B):
    """Solve with the factors of factor_fixed for B (N, m), in place."""
    if F.shape[1] == _WIDE:
        _columns_7(F, B)
    else:
        _columns_5(F, B)


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
