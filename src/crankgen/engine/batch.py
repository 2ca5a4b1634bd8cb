"""Batches of cases marched in lock step on the crank angle (compiled).

A batch holds cases that share a mesh and steps per revolution; each case keeps its own Newton
iteration and status, so a failing case stops alone.  The cases' model travels as named records
(records.py): the kernel tables of every model in the batch, one `Cases` row per case.  Batches of
more than one case run on every core: the compiled loop releases the GIL and threads take slices
of the batch (`parallel_slices`).
"""

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..discrete import kinematics as _kinematics
from ..discrete import newton, time_scheme
from ..discrete.mesh import ROCKER, components_of, rocker_of
from ..declaration import schema, torque_curve
from ..results.outputs import primitive_data
from .borrow import borrowed_cases, borrowed_kernels, borrowed_mesh, borrowed_work, keep
from .build import entry_point, prepare
from .compiled import call, jit
from .coordinates import state_kinematics
from .elements import step_outputs
from .kernels import build_items, noop_tables, select_rows, tables
from .records import N_KIN, N_OUTPUTS, NDOF, Cases, MeshData, Scheme, condensation, make_work
from .step import NOT_FINITE, OK, SINGULAR, initial_acceleration, newmark_step

HISTORY = newton.HISTORY
PIN = next(c for c in schema.CONSTRAINTS if c.map is None and c.node == 0)     # the crank pin (its reaction)


def body_data(mesh):
    """(bodies, lengths, frames) of the engine's mesh: per flexible body (the rod, then a flexible
    rocker) its elements' range [first, end), its element length and its frame map (kin_b = F kin;
    the rod's, unused, the identity)."""
    bodies, lengths, frames = [(0, mesh.n_elements)], [mesh.length], [np.eye(N_KIN)]
    if mesh.rocker_elements:
        bodies.append((mesh.n_elements, mesh.n_all))
        lengths.append(mesh.rocker_element_length)
        frames.append(np.array(ROCKER.frame_map, dtype=float))
    return (np.array(bodies, dtype=np.int64), np.array(lengths, dtype=float),
            np.ascontiguousarray(np.array(frames, dtype=float)))


def body_coefficients(case, mesh):
    """(bodies, n_coef): the coefficient vector of each flexible body's elements, the rod's first."""
    rows = [case.coefficients]
    if mesh.rocker_elements:
        rows.append(case.body_coefficients(ROCKER.name))
    return np.array(rows, dtype=float)


class Batch:
    """Cases that share a mesh and steps per revolution, packed for the compiled engine."""

    def __init__(self, cases, dt=None, entries=("march",), kernels_table=None, like=None):
        """dt overrides the time step: one for every case (free vibration, omega ~ 0) or one per case
        (the steps of simulate's `times` that land between the steps of a run).  entries: the
        engine's entry points the batch will use ("march", "revolution"), compiled ahead with its
        kernels when this machine has not compiled them yet (engine/build.py).  kernels_table: the
        kernel tables to use instead of the cases' own (engine/build.py compiles on no-op tables).
        like: a Batch of one model whose mesh, kernel tables and compiled entries these cases share
        when they have its mesh, steps per revolution and model (a continuation builds a batch per
        parameter value); otherwise ignored."""
        cases = list(cases)
        if not cases:
            raise ValueError("a batch needs at least one case")
        n, spr = cases[0].n_elements, cases[0].steps_per_rev
        if any(c.n_elements != n or c.steps_per_rev != spr for c in cases):
            raise ValueError("all cases of a batch must share n_elements and steps_per_rev")
        coordinates = tuple(cases[0].motion_record.coordinates)
        if any(tuple(c.motion_record.coordinates) != coordinates for c in cases):
            raise ValueError("all cases of a batch must share the co-ordinates of their motion (one state layout)")
        components = components_of(cases[0].options)
        if any(components_of(c.options) != components for c in cases):
            raise ValueError("all cases of a batch must share their rod's node components (one state layout): "
                             "the exact rod's nodes carry chi = u_x, the other models' do not")
        rocker = rocker_of(cases[0])
        if any(rocker_of(c) != rocker for c in cases):
            raise ValueError("all cases of a batch must share their flexible rocker's elements and length (one "
                             "state layout)")
        self.cases, self.n_elements, self.steps_per_rev = cases, n, spr
        select = select_rows(cases)
        self.entries = frozenset(entries)
        if (like is not None and kernels_table is None and like.n_elements == n and like.steps_per_rev == spr
                and len(like.runs) == 1 and (select == like.records.select[0]).all()
                and self.entries <= like.entries and like.mesh.coordinates == coordinates
                and like.mesh.components == components
                and (like.mesh.rocker_elements, like.mesh.rocker_length) == rocker):
            self.mesh, self.N, self.meshdata = like.mesh, like.N, like.meshdata
            self.runs = [(like.runs[0][0], 0, len(cases))]
        else:
            self._new_mesh(n, coordinates, components, rocker)
            if kernels_table is None:
                prepare([f"entry:{e}" for e in entries] + build_items(select))
            # runs of consecutive cases of one model, each with its model's kernel table
            starts = [0] + [b for b in range(1, len(cases)) if not np.array_equal(select[b], select[b - 1])]
            self.runs = [(kernels_table if kernels_table is not None else tables(select[lo]), lo, hi)
                         for lo, hi in zip(starts, starts[1:] + [len(cases)])]
        printed = np.array([c.integrator == "one-pass" and c.selection.printed_iteration for c in cases])
        self.kernels = self.runs[0][0]
        self.records = Cases(
            select, np.array([body_coefficients(c, self.mesh) for c in cases], dtype=float),
            np.array([c.kinematic_parameters for c in cases], dtype=float),
            (np.array([_kinematics.step_period(c) / spr for c in cases], dtype=float) if dt is None else
             np.array(np.broadcast_to(np.asarray(dt, dtype=float), (len(cases),)))),
            np.array([c.parameter_vector for c in cases], dtype=float),
            np.array([newton.SCHEMES.index(c.integrator) for c in cases], dtype=np.int64),
            printed.astype(np.bool_),
            np.array([self.mesh.dof_scales(c.natural_sizes, _kinematics.end_scale(c))
                      for c in cases]),
            np.array([time_scheme.coefficients(c.rho_inf).as_array() for c in cases], dtype=float),
            *torque_curve.batch_tables(cases))
        self.generalized = np.array([time_scheme.coefficients(c.rho_inf).generalized for c in cases])

    def _new_mesh(self, n, coordinates, components, rocker):
        from ..discrete.assembly import BandedAssembler
        from ..discrete.mesh import Mesh

        self.mesh = Mesh(n, coordinates, components, *rocker)
        self.N = self.mesh.n_dofs
        points, grams = primitive_data(self.mesh)
        self.meshdata = MeshData(
            np.ascontiguousarray(self.mesh.element_dofs, dtype=np.int64), BandedAssembler(self.mesh).bandwidth,
            self.mesh.length, np.array([k for k, _, _ in points], dtype=np.int64),
            np.array([e for _, e, _ in points], dtype=np.int64),
            np.ascontiguousarray(np.array([w for _, _, w in points], dtype=float).reshape(len(points), NDOF)),
            np.array([k for k, _ in grams], dtype=np.int64),
            np.ascontiguousarray(np.array([G for _, G in grams], dtype=float).reshape(len(grams), NDOF, NDOF)),
            self.mesh.n_rod, self.mesh.crank_coordinate, self.mesh.motor_coordinate,
            np.array(self.mesh.holders(PIN)[0][1], dtype=np.int64), *body_data(self.mesh),
            *condensation(self.mesh.n_all, self.mesh.holders(), len(self.mesh.mapped.reduced)))

    @property
    def dt(self):
        """Time step of each case (B,)."""
        return self.records.dt

    @property
    def scales(self):
        return self.records.scales

    @property
    def state_size(self):
        """Numbers in a state of the revolution map: (d, v), 2 N, for Newmark; (d, v, a), 3 N, for
        generalized-alpha (its algorithmic accelerations carry memory).  Every case of a batch
        that shoots has the same (steady.py groups them so)."""
        if self.generalized.all():
            return 3 * self.N
        if not self.generalized.any():
            return 2 * self.N
        raise ValueError("a batch that shoots must not mix Newmark and generalized-alpha cases")

    def __len__(self):
        return len(self.cases)


class MarchResult:
    """Outputs of march: y[b, m] = the engine's outputs (schema.ENGINE_OUTPUTS) at step m, Z[b, m] =
    the declared co-ordinates' values, rates and accelerations at step m (3 m numbers; none for a
    prescribed crank), final states, statuses."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


@jit(python=False)
def _coordinates_out(n_rod, d, v, acc, out):
    """out (3 m,) = the declared co-ordinates' values, rates and accelerations (m = N - n_rod)."""
    m = d.shape[0] - n_rod
    for j in range(m):
        out[j] = d[n_rod + j]
        out[m + j] = v[n_rod + j]
        out[2 * m + j] = acc[n_rod + j]


@jit
def _march_cases(kern, cases, mesh, scheme, lo, hi, t0, step0, n_steps, D0, V0, A0, G0, start, P, n_prev,
                 keep_history, keep_rates, keep_alg, out_y, out_z, out_iter, status, fail_step, fail_res, Dh, Vh, Ah,
                 Gh, D1, V1, A1, G1):
    """Advance cases lo..hi-1 of the batch n_steps in lock step (see march)."""
    n = mesh.dofs.shape[0]
    N = D0.shape[1]
    kern, cases, mesh = borrowed_kernels(kern), borrowed_cases(cases), borrowed_mesh(mesh)    # the caller's
    for b in range(lo, hi):
        owned = make_work(mesh, N)
        w = borrowed_work(owned)
        sel, params = cases.select[b], cases.params[b]
        dt = cases.dt[b]
        d, v, acc, alg = D0[b].copy(), V0[b].copy(), A0[b].copy(), G0[b].copy()
        dn, vn, an, gn = np.zeros(N), np.zeros(N), np.zeros(N), np.zeros(N)
        y = np.zeros(N_OUTPUTS)
        state_kinematics(kern, params, mesh, t0[b] + step0 * dt, d, v, acc, w)
        step_outputs(kern, sel, params, cases.p[b], mesh, d, w, y)
        for k in range(N_OUTPUTS):
            out_y[b, 0, k] = y[k]
        _coordinates_out(mesh.n_rod, d, v, acc, out_z[b, 0])
        if keep_history:
            for i in range(N):
                Dh[b, 0, i] = d[i]
        if keep_rates:
            for i in range(N):
                Vh[b, 0, i] = v[i]
                Ah[b, 0, i] = acc[i]
        if keep_alg:
            for i in range(N):
                Gh[b, 0, i] = alg[i]
        for m in range(n_steps):
            if status[b] != OK:
                break
            t_new = t0[b] + (step0 + m + 1) * dt
            st, it, rn = newmark_step(kern, cases, b, mesh, scheme, t_new, d, v, acc, alg, P[b], n_prev[b],
                                      dn, vn, an, gn, w, start and m == 0)
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
                for i in range(N):
                    P[b, k, i] = P[b, k - 1, i]
            for i in range(N):
                P[b, 0, i] = d[i]
                d[i] = dn[i]
                v[i] = vn[i]
                acc[i] = an[i]
                alg[i] = gn[i]
            n_prev[b] = min(n_prev[b] + 1, HISTORY)
            if mesh.crank_index >= 0:         # the kinematics of the converged state (the step's last is a trial's)
                state_kinematics(kern, params, mesh, t_new, d, v, acc, w)
            step_outputs(kern, sel, params, cases.p[b], mesh, d, w, y)
            for k in range(N_OUTPUTS):
                out_y[b, m + 1, k] = y[k]
            _coordinates_out(mesh.n_rod, d, v, acc, out_z[b, m + 1])
            if keep_history:
                for i in range(N):
                    Dh[b, m + 1, i] = d[i]
            if keep_rates:
                for i in range(N):
                    Vh[b, m + 1, i] = v[i]
                    Ah[b, m + 1, i] = acc[i]
            if keep_alg:
                for i in range(N):
                    Gh[b, m + 1, i] = alg[i]
        for i in range(N):
            D1[b, i] = d[i]
            V1[b, i] = v[i]
            A1[b, i] = acc[i]
            G1[b, i] = alg[i]
        keep(owned)


@jit
def _initial_accelerations(kern, cases, mesh, lo, hi, t0, step0, D0, V0, A0, status):
    n, N = mesh.dofs.shape[0], D0.shape[1]
    w = make_work(mesh, N)
    for b in range(lo, hi):
        if not initial_acceleration(kern, cases, b, mesh, t0[b] + step0 * cases.dt[b], D0[b], V0[b], A0[b], w):
            status[b] = SINGULAR


def threads():
    """Worker threads for a batch: the cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


CHUNKS_PER_WORKER = 4     # a parallel batch is cut into this many slices per worker thread


def balanced_bounds(lo, hi, active, parts):
    """Cut lo..hi into at most `parts` contiguous slices holding equal numbers of the cases marked in
    `active` (the others cost next to nothing: the compiled loops skip them) and covering every
    case of lo..hi; the bounds increase strictly (no slice is empty)."""
    idx = lo + np.flatnonzero(active[lo:hi])
    parts = max(1, min(parts, len(idx)))
    return [lo] + [int(idx[(k * len(idx)) // parts]) for k in range(1, parts)] + [hi]


def parallel_slices(fn, batch, parallel, leading, trailing, active=None):
    """fn(kernels, *leading, lo, hi, *trailing) over slices of the batch's cases, each run of one
    model with its kernel table: on threads when parallel (the compiled functions release the
    GIL), else one call per run.  active: the cases that will do work (default: all).  A parallel
    run is cut into CHUNKS_PER_WORKER slices per thread with equal numbers of active cases, taken by
    the threads as they come free: the work balances when the active cases cluster (the slow,
    non-periodic cases of a sweep sit side by side) or when some cases stop early."""
    B = len(batch)
    active = np.ones(B, dtype=bool) if active is None else np.asarray(active, dtype=bool)
    workers = min(threads(), B) if parallel else 1
    tasks = []
    for kern, lo, hi in batch.runs:
        bounds = balanced_bounds(lo, hi, active, workers * CHUNKS_PER_WORKER if workers > 1 else 1)
        tasks += [(kern, a, b) for a, b in zip(bounds[:-1], bounds[1:])]
    if workers <= 1 or len(tasks) <= 1:
        for kern, lo, hi in tasks:
            call(fn, kern, *leading, lo, hi, *trailing)
        return
    call(fn, tasks[0][0], *leading, 0, 0, *trailing)          # compile (or load) once, before threading
    with ThreadPoolExecutor(workers) as pool:
        futures = [pool.submit(fn, kern, *leading, lo, hi, *trailing) for kern, lo, hi in tasks]
        for f in futures:
            f.result()


def march(batch, n_steps, D0=None, V0=None, A0=None, step0=0, keep_history=False, parallel=None,
          tol=1e-10, max_iter=30, status=None, previous=None, t0=None, G0=None):
    """Advance all cases of the batch from step index step0 (t = t0 + step0 dt) by n_steps steps of
    each case's time scheme (Newmark or generalized-alpha: crankgen.discrete.time_scheme).  t0: (B,) time
    origins (default 0).

    D0, V0: (B, N) initial reduced states (zero by default); A0 the accelerations, by default
    solved from eq. (34); G0 the algorithmic accelerations of generalized-alpha (Newmark ignores
    them).  Without G0 the run starts: its first generalized-alpha step is the starter
    (time_scheme.STARTER), after which a = qdd.  The result's G: their final values (A for
    Newmark).  previous: the `previous` of the MarchResult this run continues (the
    displacements of the steps before D0, for the Newton starting guess; none by default).
    keep_history: True stores the displacements, velocities and accelerations of every step
    (D_history, V_history, A_history; and G_history, the algorithmic accelerations, when a case
    uses generalized-alpha), "displacements" the displacements only.
    Cases whose status is not OK on entry are not advanced.  parallel: slices of the batch on
    threads (default: when it holds more than one case)."""
    B, N = len(batch), batch.N
    D0 = np.zeros((B, N)) if D0 is None else np.ascontiguousarray(D0, dtype=float)
    V0 = np.zeros((B, N)) if V0 is None else np.ascontiguousarray(V0, dtype=float)
    status = np.zeros(B, dtype=np.int64) if status is None else np.array(status, dtype=np.int64)
    t0 = np.zeros(B) if t0 is None else np.array(np.broadcast_to(np.asarray(t0, dtype=float), (B,)))
    cases, mesh = batch.records, batch.meshdata
    if parallel is None:
        parallel = B > 1
    if A0 is None:
        A0 = np.zeros((B, N))
        parallel_slices(_initial_accelerations, batch, parallel, (cases, mesh), (t0, step0, D0, V0, A0, status))
    else:
        A0 = np.ascontiguousarray(A0, dtype=float)
    start = G0 is None
    G0 = A0 if G0 is None else np.ascontiguousarray(G0, dtype=float)
    if previous is None:
        P, n_prev = np.zeros((B, HISTORY, N)), np.zeros(B, dtype=np.int64)
    else:
        P, n_prev = np.array(previous[0], dtype=float), np.array(previous[1], dtype=np.int64)
    out_y = np.full((B, n_steps + 1, N_OUTPUTS), np.nan)
    out_z = np.full((B, n_steps + 1, 3 * (N - batch.mesh.n_rod)), np.nan)
    out_iter = np.zeros((B, n_steps), dtype=np.int64)
    fail_step = np.zeros(B, dtype=np.int64)
    fail_res = np.zeros(B)
    keep_rates = keep_history is True
    keep_history = bool(keep_history)
    hist_shape = (B, n_steps + 1, N) if keep_history else (1, 1, 1)
    rate_shape = hist_shape if keep_rates else (1, 1, 1)
    keep_alg = keep_rates and bool(batch.generalized.any())
    Dh, Vh, Ah = np.zeros(hist_shape), np.zeros(rate_shape), np.zeros(rate_shape)
    Gh = np.zeros(rate_shape if keep_alg else (1, 1, 1))
    D1, V1, A1, G1 = np.zeros((B, N)), np.zeros((B, N)), np.zeros((B, N)), np.zeros((B, N))
    scheme = Scheme(float(tol), int(max_iter))
    parallel_slices(_march_cases, batch, parallel, (cases, mesh, scheme),
                    (t0, step0, n_steps, D0, V0, A0, G0, start, P, n_prev, keep_history, keep_rates, keep_alg, out_y,
                     out_z, out_iter, status, fail_step, fail_res, Dh, Vh, Ah, Gh, D1, V1, A1, G1), active=status == OK)
    return MarchResult(y=out_y, Z=out_z, iterations=out_iter, status=status, fail_step=fail_step,
                       fail_residual=fail_res, D=D1, V=V1, A=A1, G=G1, previous=(P, n_prev),
                       D_history=Dh if keep_history else None, V_history=Vh if keep_rates else None,
                       A_history=Ah if keep_rates else None, G_history=Gh if keep_alg else None)


def split_state(X, N):
    """(D0, V0, G0) of states X (B, 2N or 3N) of the revolution map (Batch.state_size); G0 None for
    (d, v)."""
    X = np.asarray(X, dtype=float)
    return X[:, :N], X[:, N:2 * N], (X[:, 2 * N:3 * N] if X.shape[1] == 3 * N else None)


def join_state(res, generalized, steps=None):
    """The states (B, 2N or 3N) a march ended in: (D, V), with G for generalized-alpha; with
    steps (indices), the states of case 0 at those steps of its history (steps, 2N or 3N)."""
    if steps is not None:
        parts = [res.D_history[0, steps], res.V_history[0, steps]] + (
            [res.G_history[0, steps]] if generalized else [])
    else:
        parts = [res.D, res.V] + ([res.G] if generalized else [])
    return np.concatenate(parts, axis=1)


def march_state(batch, n_steps, X, **kw):
    """march from states X (B, batch.state_size) of the revolution map: (d, v), or (d, v, a) for
    generalized-alpha, whose algorithmic accelerations go on as G0."""
    D0, V0, G0 = split_state(X, batch.N)
    return march(batch, n_steps, D0=D0, V0=V0, G0=G0, **kw)


def compiling_batch():
    """A one-element batch on no-op kernels: running an entry point on it compiles the entry (the
    engine's types do not depend on which kernels it is given)."""
    from ..declaration.cases import Case
    return Batch([Case(omega=1.0, n_elements=1, steps_per_rev=4)], kernels_table=noop_tables())


@entry_point("march")
def _compile_march():
    march(compiling_batch(), 1, parallel=False)
