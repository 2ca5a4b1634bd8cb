"""The declared co-ordinates of the state in the compiled engine: a driven motion's crank angle (and
any other co-ordinate it declares, a rotor's angle), stepped with the rods' nodal co-ordinates.

The state x (N numbers) is the DOF map's: the n_rod nodal co-ordinates (the band), then the m
declared co-ordinates z (records.MeshData; none for a prescribed crank).  Their equations g(z, zd,
zdd, F_pin, kin) = 0 are the generated `coordinates_<motion>` (derive/motions.py): each row g_i and
its derivatives in every z_j, zd_j, zdd_j and the crank pin's force F_pin, the residual of the pin's
eliminated rows of the first element (the reaction the rod needs there).  The crank co-ordinate
sets the kinematics of the rods (the guide's closure at its angle, speed and acceleration).

Newton's iteration matrix of the step is bordered,

    [ S    B ] [ dqdd ]     [ R ]     S = dR/dqdd + cv dR/dv + cd dR/dd   (the band, exact)
    [ C^T  E ] [ dzdd ] = - [ g ]     C_i = dg_i/dF_pin . (the pin's rows of the first element's S)

B, the rod's residual against the co-ordinates, has one column, the crank's, which acts through
the kinematics: it and the crank's column of E are differenced (zdd_c + h, z_c and zd_c following
through cd and cv; one more residual per fresh matrix).  Another co-ordinate j enters g alone:
E[:, j] = dg/dzdd_j + cv dg/dzd_j + cd dg/dz_j, from the kernel.  Only the iteration matrix is
approximate; the residual is exact.  The system is solved by its Schur complement
Sm = E - C^T S^-1 B (m x m), with S's factors: S^-1 B once per fresh matrix, S^-1 R per iteration.

A motor's per-unit torque curve enters the equation of the co-ordinate it drives (records.
Coordinate.motor) as its departure from the linear law of the derivation: cubic Hermite pieces of
the rows Cases.curve (`hermite`; crankgen.declaration.torque_curve.departure_table).
"""

import numpy as np

from .banded import band_lu_solve, solve_fixed
from .calls import call
from .compiled import jit

COLUMN_STEP = 1e-7       # the crank's column is differenced with this step relative to max(1, |zdd_c|)


@jit                                # with a Python wrapper: tests call it against scipy
def hermite(tab, n, x):
    """(y(x), y'(x)) of the cubic Hermite pieces through the rows tab[:n] = (x_k, y_k, y'_k), x_k
    increasing, continued linearly with the end slopes beyond them: a torque curve's departure from
    the derivation's linear law (crankgen.declaration.torque_curve.departure_table)."""
    if x <= tab[0, 0]:
        return tab[0, 1] + tab[0, 2] * (x - tab[0, 0]), tab[0, 2]
    if x >= tab[n - 1, 0]:
        return tab[n - 1, 1] + tab[n - 1, 2] * (x - tab[n - 1, 0]), tab[n - 1, 2]
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tab[mid, 0] <= x:
            lo = mid
        else:
            hi = mid
    h = tab[hi, 0] - tab[lo, 0]
    t = (x - tab[lo, 0]) / h
    y = ((2 * t - 3) * t * t + 1) * tab[lo, 1] + ((t - 2) * t + 1) * t * h * tab[lo, 2] \
        + (3 - 2 * t) * t * t * tab[hi, 1] + (t - 1) * t * t * h * tab[hi, 2]
    dy = 6 * t * (t - 1) / h * (tab[lo, 1] - tab[hi, 1]) + ((3 * t - 4) * t + 1) * tab[lo, 2] \
        + (3 * t - 2) * t * tab[hi, 2]
    return y, dy


@jit(python=False)
def crank_kinematics(kern, params, theta, thetad, thetadd, w):
    """w.kin of the guide with the crank at (theta, thetad, thetadd)."""
    w.crank[0] = theta
    w.crank[1] = thetad
    w.crank[2] = thetadd
    call(kern.guide, 0, (w.crank, params, w.kin))


@jit(python=False)
def state_kinematics(kern, params, mesh, t, x, v, a, w):
    """w.kin of a state: at time t from the prescribed motion, or from the state's crank
    co-ordinate (a driven motion)."""
    if mesh.crank_index < 0:
        call(kern.motion, 0, (t, params, w.crank))
        call(kern.guide, 0, (w.crank, params, w.kin))
    else:
        c = mesh.n_rod + mesh.crank_index
        crank_kinematics(kern, params, x[c], v[c], a[c], w)


@jit(python=False)
def equations(kern, cases, b, mesh, x, v, a, w, out):
    """out (m, 3 m + 3) = the co-ordinates' equations and their derivatives (module docstring) at
    the state (x, v, a), the pin's force read from w.rE (the element loop's residual at that state)
    and the kinematics from w.kin; a torque curve's departure added on the motor's row."""
    n_rod = mesh.n_rod
    m = x.shape[0] - n_rod
    for j in range(m):
        w.zin[j] = x[n_rod + j]
        w.zin[m + j] = v[n_rod + j]
        w.zin[2 * m + j] = a[n_rod + j]
    for k in range(mesh.pin_slots.shape[0]):
        w.pin[k] = w.rE[0, mesh.pin_slots[k]]
    call(kern.coords, 0, (w.kin, w.zin, w.pin, cases.params[b], out))
    n = cases.curve_n[b]
    if n > 0 and mesh.motor_index >= 0:
        i = mesh.motor_index
        extra, slope = hermite(cases.curve[b], n, v[n_rod + i])
        out[i, 0] -= extra
        out[i, 1 + m + i] -= slope


@jit(python=False)
def solve_band(fixed, n_rod, kb, w, col):
    """col (n_rod,) <- S^-1 col with the factors of the step's iteration matrix (fixed: the
    fixed-bandwidth ones), through w.rhs (the same calls as the step's own solve)."""
    rhs = w.rhs
    for i in range(n_rod):
        rhs[i, 0] = col[i]
    if fixed:
        solve_fixed(w.F, n_rod, rhs[:, 0])
    else:
        band_lu_solve(w.W, kb, w.piv, w.ext, rhs)
    for i in range(n_rod):
        col[i] = rhs[i, 0]


@jit(python=False)
def border_rows(mesh, geq, S0, m, Cb):
    """Cb[i] = dg_i/dF_pin . (the pin's rows of the first element's matrix S0), on the nodal
    co-ordinates (row i of C^T)."""
    n_rod = mesh.n_rod
    for i in range(m):
        for k in range(n_rod):
            Cb[i, k] = 0.0
    for k in range(S0.shape[1]):
        idx = mesh.dofs[0, k]
        if idx < n_rod:
            for i in range(m):
                for p in range(mesh.pin_slots.shape[0]):
                    Cb[i, idx] += geq[i, 1 + 3 * m + p] * S0[mesh.pin_slots[p], k]


@jit(python=False)
def schur(fixed, mesh, kb, geq, geq1, R0, R1, h, cv, cd, w):
    """The bordered system's Schur complement w.Sm = E - C^T S^-1 B and w.Yb = S^-1 B (module
    docstring), from the rows at the state (geq, the residual R0) and, for the crank's column, at
    the state bumped by h (geq1, R1); w.Cb already holds C^T.  Returns False if Sm is singular."""
    n_rod = mesh.n_rod
    m = geq.shape[0]
    for j in range(m):
        if j == mesh.crank_index:
            for i in range(n_rod):
                w.Yb[j, i] = (R1[i] - R0[i]) / h
            solve_band(fixed, n_rod, kb, w, w.Yb[j])
            for i in range(m):
                w.Sm[i, j] = (geq1[i, 0] - geq[i, 0]) / h
        else:
            for i in range(n_rod):
                w.Yb[j, i] = 0.0
            for i in range(m):
                w.Sm[i, j] = geq[i, 1 + 2 * m + j] + cv * geq[i, 1 + m + j] + cd * geq[i, 1 + j]
    for i in range(m):
        for j in range(m):
            s = 0.0
            for k in range(n_rod):
                s += w.Cb[i, k] * w.Yb[j, k]
            w.Sm[i, j] -= s
    return _lu_small(w.Sm, m)


@jit(python=False)
def _lu_small(A, m):
    """In-place LU without pivoting of the small Schur complement (the co-ordinates' own inertia
    dominates its diagonal).  False if a pivot vanishes."""
    for k in range(m):
        if not (A[k, k] != 0.0 and np.isfinite(A[k, k])):
            return False
        for i in range(k + 1, m):
            A[i, k] /= A[k, k]
            for j in range(k + 1, m):
                A[i, j] -= A[i, k] * A[k, j]
    return True


@jit(python=False)
def bordered_solve(m, n_rod, w, g):
    """Given w.rhs[:n_rod, 0] = S^-1 (-R) and g (m, ...) the co-ordinates' rows: w.gz <- dzdd and
    w.rhs[:n_rod, 0] <- dqdd = S^-1 (-R) - (S^-1 B) dzdd (the Schur complement's solve)."""
    gz = w.gz
    rhs = w.rhs
    for i in range(m):
        s = -g[i, 0]
        for k in range(n_rod):
            s -= w.Cb[i, k] * rhs[k, 0]
        gz[i] = s
    for i in range(m):                  # L y = rhs
        for k in range(i):
            gz[i] -= w.Sm[i, k] * gz[k]
    for i in range(m - 1, -1, -1):      # U x = y
        for k in range(i + 1, m):
            gz[i] -= w.Sm[i, k] * gz[k]
        gz[i] /= w.Sm[i, i]
    for j in range(m):
        dz = gz[j]
        if dz != 0.0:
            for k in range(n_rod):
                rhs[k, 0] -= w.Yb[j, k] * dz
