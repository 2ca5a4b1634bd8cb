"""The compiled engine's runs of `simulate`: a march in chunks (progress between them, the states
at requested times picked from the chunks that hold them, every case of a batch stopping alone),
the start of a run on the DOF map (the rods at rest or in a given state, a driven motion's
co-ordinates at their start), and the kinematics of a run's steps (the prescribed motion's at
their times, or a driven crank's from its co-ordinate)."""

import numpy as np

from .. import engine as _engine
from ..discrete import kinematics as _kinematics


def start_state(case, d0, v0):
    """(d0, v0) of a run of the case on the DOF map: the rod's nodal (d0, v0), then the co-ordinates
    its motion declares at their start (their values and rates at t = 0; none for a prescribed
    crank); vectors of the whole state are taken as they are."""
    d0, v0 = np.asarray(d0, dtype=float), np.asarray(v0, dtype=float)
    z0, zd0 = _kinematics.coordinates_start(case)
    if d0.shape[-1] == 3 * case.n_elements and z0.size:
        return np.concatenate([d0, z0]), np.concatenate([v0, zd0])
    return d0, v0


def coordinate_histories(case, Z):
    """{name: (..., 3) value, rate and acceleration} of each declared co-ordinate from Z (..., 3 m)
    (MarchResult.Z; empty for a prescribed crank)."""
    coords = case.motion_record.coordinates
    m = len(coords)
    return {c.name: np.stack([Z[..., j], Z[..., m + j], Z[..., 2 * m + j]], axis=-1) for j, c in enumerate(coords)}


def crank_of(case, coordinates):
    """The crank co-ordinate's (..., 3) history (theta, thetad, thetadd) of a driven run, None for a
    prescribed crank."""
    crank = next((c.name for c in case.motion_record.coordinates if c.crank), None)
    return None if crank is None else coordinates[crank]


def run_kinematics(case, t, crank=None):
    """The kinematics (CrankState) of a run's steps: the prescribed motion's at the times t, or a
    driven crank's from its history (theta, thetad, thetadd)."""
    return _kinematics.case_state(case, t) if crank is None else _kinematics.crank_state(case, crank)


# the most memory a chunk's states may take while the states at requested times are picked from it
CHUNK_BYTES = 64 * 2**20


def march_in_chunks(batch, D0, V0, n_steps, tol=1e-10, keep_states=False, progress=None,
                    chunks=20, stops=(), captured=None, G0=None):
    """Run the compiled engine from (D0, V0) in a few chunks, so that progress(done_steps) can be
    shown; a case that fails stops alone.  Returns (y, iterations, status, fail_step,
    fail_residual, D, V, A, Z) with y (B, n_steps + 1, the engine's outputs), the histories of the
    reduced displacements, velocities and accelerations (None unless keep_states) and Z (B,
    n_steps + 1, 3 m), the declared co-ordinates' values, rates and accelerations at every step (a
    driven motion's: its crank's give the kinematics of every output; (B, n_steps + 1, 0) else).  stops: step indices
    whose states (D, V, A), each (B, N), are put in the dict `captured`: taken from the states of
    the chunk that holds them (a chunk with stops keeps its states, and is at most CHUNK_BYTES of
    them long), so the work grows linearly with the stops; the marching is the same as without
    them (chunks continue from the state and history where the last one ended).  G0: generalized-
    alpha's algorithmic accelerations (None: the run starts, its first step the starter); the
    captured states hold them as a fourth entry (None at step 0 of a start)."""
    B = len(batch)
    D, V, A, G, previous = np.array(D0, dtype=float), np.array(V0, dtype=float), None, G0, None
    status = np.zeros(B, dtype=np.int64)
    fail_step, fail_res = np.zeros(B, dtype=np.int64), np.zeros(B)
    ys, zs, its, hist = [], [], [], ([], [], [])
    size = max(1, -(-n_steps // chunks)) if progress is not None else n_steps
    stops = np.unique(np.asarray([k for k in stops if 0 <= k <= n_steps], dtype=np.int64))
    if not keep_states and stops.size:
        size = min(size, max(1, CHUNK_BYTES // (3 * 8 * B * max(1, batch.N))))
    if stops.size and stops[0] == 0:
        first = _engine.march(batch, 0, D0=D, V0=V, G0=G, tol=tol, status=status)
        A, status = first.A, first.status
        captured[0] = (D.copy(), V.copy(), A.copy(), None if G is None else G.copy())
    done, next_stop = 0, int(np.searchsorted(stops, 1))
    while done < n_steps:
        k = min(size, n_steps - done)
        last_stop = int(np.searchsorted(stops, done + k, side="right"))
        holds = last_stop > next_stop                          # stops in (done, done + k]
        res = _engine.march(batch, k, D0=D, V0=V, A0=A, G0=G, step0=done, keep_history=bool(keep_states or holds),
                            tol=tol, status=status, previous=previous)
        new_fail = (res.status != _engine.OK) & (status == _engine.OK)
        fail_step[new_fail], fail_res[new_fail] = res.fail_step[new_fail], res.fail_residual[new_fail]
        status = res.status
        ys.append(res.y if done == 0 else res.y[:, 1:])
        zs.append(res.Z if done == 0 else res.Z[:, 1:])
        its.append(res.iterations)
        for stop in stops[next_stop:last_stop]:
            j = int(stop) - done
            captured[int(stop)] = (res.D_history[:, j].copy(), res.V_history[:, j].copy(),
                                   res.A_history[:, j].copy(),
                                   (res.A_history if res.G_history is None else res.G_history)[:, j].copy())
        next_stop = last_stop
        if keep_states:
            for store, h in zip(hist, (res.D_history, res.V_history, res.A_history)):
                store.append(h if done == 0 else h[:, 1:])
        D, V, A, G, previous = res.D, res.V, res.A, res.G, res.previous
        done += k
        if not np.any(status == _engine.OK):
            # every case has stopped: the rest would be NaN rows (what the engine writes for a
            # case that does not advance), and progress must not count steps never computed
            if progress is not None:
                progress(int(np.max(fail_step)) - 1)
            rest = n_steps - done
            ys.append(np.full((B, rest, ys[-1].shape[2]), np.nan))
            zs.append(np.full((B, rest, zs[-1].shape[2]), np.nan))
            its.append(np.zeros((B, rest), dtype=its[-1].dtype))
            if keep_states:
                for store in hist:
                    store.append(np.full(store[-1].shape[:1] + (rest,) + store[-1].shape[2:], np.nan))
            break
        if progress is not None:
            progress(done)
    histories = tuple(np.concatenate(h, axis=1) if keep_states else None for h in hist)
    return ((np.concatenate(ys, axis=1), np.concatenate(its, axis=1), status, fail_step, fail_res) + histories
            + (np.concatenate(zs, axis=1),))
