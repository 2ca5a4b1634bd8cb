"""Batches of cases marched in lock step on the crank angle (compiled).

A batch holds cases that share a mesh and steps per revolution (theta_m = 2 pi m / steps_per_rev
for every case); each case keeps its own Newton iteration and status, so a failing case stops
alone.  The cases' model travels as named records (records.RUN) and the arrays of the declared
model (family variants, coefficients): see records.py.
"""

import math

import numpy as np
from numba import prange

from .. import newton
from .._generated import shape as _shape
from .compiled import call, jit, mark_warm
from .elements import step_outputs
from .records import RUN, make_work
from .step import NOT_FINITE, OK, SINGULAR, initial_acceleration, kinematics, newmark_step

HISTORY = newton.HISTORY


class Batch:
    """Cases that share a mesh and steps per revolution, packed for the compiled engine."""

    def __init__(self, cases, dt=None):
        """dt overrides the time step 2 pi / (omega steps_per_rev) (free vibration, omega ~ 0)."""
        from ..assembly import BandedAssembler
        from ..mesh import Mesh

        cases = list(cases)
        if not cases:
            raise ValueError("a batch needs at least one case")
        n, spr = cases[0].n_elements, cases[0].steps_per_rev
        if any(c.n_elements != n or c.steps_per_rev != spr for c in cases):
            raise ValueError("all cases of a batch must share n_elements and steps_per_rev")
        self.cases, self.n_elements, self.steps_per_rev = cases, n, spr
        self.mesh = Mesh(n)
        self.N = self.mesh.n_dofs
        self.dofs = np.ascontiguousarray(self.mesh.element_dofs, dtype=np.int64)
        self.kb = BandedAssembler(self.mesh).bandwidth
        self.l = self.mesh.length
        self.mid_element, zeta = self.mesh.locate(0.5)
        self.Nv_mid = np.ascontiguousarray(_shape.shape_functions(zeta, self.l)[1], dtype=float)
        self.G = np.ascontiguousarray(_shape.slope_gram(self.l), dtype=float)
        self.families = np.array([c.selection.families for c in cases], dtype=np.int64)
        self.coef = np.array([c.coefficients for c in cases], dtype=float)
        self.runs = np.zeros(len(cases), dtype=RUN)
        for b, c in enumerate(cases):
            run = self.runs[b]
            run["a"], run["offset"], run["omega"], run["eps"] = c.a, c.offset, c.omega, c.eps
            run["dt"] = dt if dt is not None else 2 * math.pi / c.omega / spr
            run["scheme"] = newton.SCHEMES.index(c.integrator)
            run["printed"] = c.selection.printed_iteration
        self.scales = np.array([self.mesh.dof_scales(c.eps) for c in cases])

    @property
    def dt(self):
        """Time step of each case (B,)."""
        return self.runs["dt"]

    def __len__(self):
        return len(self.cases)


class MarchResult:
    """Outputs of march: y[b, m] = (v*, u*(1), delta*) at step m, final states, statuses."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


def _march_impl(families, coef, runs, dofs, kb, l, scales, mid_e, Nv_mid, G, beta, gamma, tol,
                max_iter, step0, n_steps, D0, V0, A0, P, n_prev, keep_history, keep_rates,
                out_y, out_iter, status, fail_step, fail_res, Dh, Vh, Ah, D1, V1, A1):
    """Advance every case of the batch n_steps in lock step (see march)."""
    B = D0.shape[0]
    n = dofs.shape[0]
    N = D0.shape[1]
    for b in prange(B):
        w = make_work(n, N, kb)
        run = runs[b]
        d, v, acc = D0[b].copy(), V0[b].copy(), A0[b].copy()
        dn, vn, an = np.zeros(N), np.zeros(N), np.zeros(N)
        y = np.zeros(3)
        kinematics(run, step0 * run.dt, w.kin)
        step_outputs(dofs, mid_e, Nv_mid, G, run.eps, w.kin[3], d, w.q, y)
        out_y[b, 0, :] = y
        if keep_history:
            Dh[b, 0, :] = d
        if keep_rates:
            Vh[b, 0, :] = v
            Ah[b, 0, :] = acc
        for m in range(n_steps):
            if status[b] != OK:
                break
            t_new = (step0 + m + 1) * run.dt
            st, it, rn = newmark_step(families[b], coef[b], run, dofs, kb, l, scales[b], beta, gamma,
                                      tol, max_iter, t_new, d, v, acc, P[b], n_prev[b], dn, vn, an, w)
            out_iter[b, m] = it
            if st == OK:
                for i in range(N):
                    if not (np.isfinite(dn[i]) and np.isfinite(vn[i])):
                        st = NOT_FINITE
                        break
            if st != OK:
                status[b] = st
                fail_step[b] = step0 + m + 1
                fail_res[b] = rn
                break
            for k in range(HISTORY - 1, 0, -1):
                P[b, k, :] = P[b, k - 1]
            P[b, 0, :] = d
            n_prev[b] = min(n_prev[b] + 1, HISTORY)
            d[:] = dn
            v[:] = vn
            acc[:] = an
            step_outputs(dofs, mid_e, Nv_mid, G, run.eps, w.kin[3], d, w.q, y)
            out_y[b, m + 1, :] = y
            if keep_history:
                Dh[b, m + 1, :] = d
            if keep_rates:
                Vh[b, m + 1, :] = v
                Ah[b, m + 1, :] = acc
        D1[b, :] = d
        V1[b, :] = v
        A1[b, :] = acc


_march_serial = jit(_march_impl, name="_march_serial")
_march_parallel = jit(_march_impl, parallel=True, name="_march_parallel")


@jit
def _initial_accelerations(families, coef, runs, dofs, kb, l, step0, D0, V0, A0, status):
    n, N = dofs.shape[0], D0.shape[1]
    w = make_work(n, N, kb)
    for b in range(D0.shape[0]):
        if not initial_acceleration(families[b], coef[b], runs[b], dofs, kb, l, step0 * runs[b].dt,
                                    D0[b], V0[b], A0[b], w):
            status[b] = SINGULAR


def march(batch, n_steps, D0=None, V0=None, A0=None, step0=0, keep_history=False, parallel=None,
          beta=0.25, gamma=0.5, tol=1e-10, max_iter=30, status=None, previous=None):
    """Advance all cases of the batch from step index step0 (t = step0 dt) by n_steps Newmark steps.

    D0, V0: (B, N) initial reduced states (zero by default); A0 the accelerations, by default
    solved from eq. (34).  previous: the `previous` of the MarchResult this run continues (the
    displacements of the steps before D0, for the Newton starting guess; none by default).
    keep_history: True stores the displacements, velocities and accelerations of every step
    (D_history, V_history, A_history), "displacements" the displacements only.
    Cases whose status is not OK on entry are not advanced."""
    B, N = len(batch), batch.N
    D0 = np.zeros((B, N)) if D0 is None else np.ascontiguousarray(D0, dtype=float)
    V0 = np.zeros((B, N)) if V0 is None else np.ascontiguousarray(V0, dtype=float)
    status = np.zeros(B, dtype=np.int64) if status is None else np.array(status, dtype=np.int64)
    if A0 is None:
        A0 = np.zeros((B, N))
        call(_initial_accelerations, batch.families, batch.coef, batch.runs, batch.dofs, batch.kb,
             batch.l, step0, D0, V0, A0, status)
    else:
        A0 = np.ascontiguousarray(A0, dtype=float)
    if previous is None:
        P, n_prev = np.zeros((B, HISTORY, N)), np.zeros(B, dtype=np.int64)
    else:
        P, n_prev = np.array(previous[0], dtype=float), np.array(previous[1], dtype=np.int64)
    out_y = np.full((B, n_steps + 1, 3), np.nan)
    out_iter = np.zeros((B, n_steps), dtype=np.int64)
    fail_step = np.zeros(B, dtype=np.int64)
    fail_res = np.zeros(B)
    keep_rates = keep_history is True
    keep_history = bool(keep_history)
    hist_shape = (B, n_steps + 1, N) if keep_history else (1, 1, 1)
    rate_shape = hist_shape if keep_rates else (1, 1, 1)
    Dh, Vh, Ah = np.zeros(hist_shape), np.zeros(rate_shape), np.zeros(rate_shape)
    D1, V1, A1 = np.zeros((B, N)), np.zeros((B, N)), np.zeros((B, N))
    if parallel is None:
        parallel = B > 1
    fn = _march_parallel if parallel else _march_serial
    call(fn, batch.families, batch.coef, batch.runs, batch.dofs, batch.kb, batch.l, batch.scales,
         batch.mid_element, batch.Nv_mid, batch.G, beta, gamma, tol, max_iter, step0, n_steps,
         D0, V0, A0, P, n_prev, keep_history, keep_rates, out_y, out_iter, status, fail_step, fail_res, Dh, Vh, Ah,
         D1, V1, A1)
    mark_warm()
    return MarchResult(y=out_y, iterations=out_iter, status=status, fail_step=fail_step,
                       fail_residual=fail_res, D=D1, V=V1, A=A1, previous=(P, n_prev),
                       D_history=Dh if keep_history else None, V_history=Vh if keep_rates else None,
                       A_history=Ah if keep_rates else None)
