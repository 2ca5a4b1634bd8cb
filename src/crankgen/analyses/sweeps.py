"""Parameter sweeps: many cases -> periodic steady states -> one tidy table.

`sweep` sends the cases to `steady_states` (the batched entry point) in chunks of `batch_size`,
either in this process or through any `concurrent.futures.Executor` (a process pool, or a Dask
cluster via `distributed.Client.get_executor()`).  Each finished chunk is appended to an optional
JSON Lines checkpoint, so an interrupted sweep resumes without recomputing what it finished.

Failure never sinks a sweep, and a case that failed is told from one that never ran: a case that
diverges or does not settle comes back from `steady_states` with its status and message (a
result, recorded); a chunk that raises is retried case by case in the worker, so only the case at
fault is recorded as "failed".  A chunk whose future raises did not run to its end (a worker
died, the executor broke, the task could not be sent or was cancelled): nothing is recorded for
it, and once the executor has returned every other chunk, such chunks are run again serially in
this process, with a RuntimeWarning.  (Serial, not a fresh pool: crankgen cannot rebuild an
arbitrary executor, e.g. a Dask client's, and the caller's executor may be broken for good.)

No row holds NaN or inf: a missing number is None in the table, an empty field in the CSV and
null in the checkpoint, with the row's status and message saying why.

The checkpoint (crankgen.analyses.checkpoint: format, resuming, repair, why JSON Lines) records every
finished batch; one sweep at a time uses it (crankgen.analyses.file_lock).  The table is a SweepTable
(crankgen.results.sweep_table); the command line's pool workers die with the sweep (crankgen.analyses.pool_workers).
"""

import concurrent.futures as cf
import warnings
from collections import Counter
from collections.abc import Mapping

from ..declaration.cases import Case
from .checkpoint import Checkpoint, CheckpointError, check_checkpoint_file  # noqa: F401 (public here too)
from ..errors import ParameterError
from .limits import check_run_size
from .pool_workers import worker_init  # noqa: F401 (the command line's pool initializer)
from ..results.provenance import code_version
from .. import notices
from ..discrete import time_scheme
from .steady import _check_resolved, steady_states
from ..results.sweep_table import SweepTable, failed_row, plain
from ..declaration.validation import in_range, integer

__all__ = ["CheckpointError", "SweepTable", "sweep"]

BATCH_SIZE = 8           # default cases per batch: each finished batch is checkpointed and reported
# Fields that fix the shape of a case's equations; chunks group cases alike in these so that a
# lock-step batch engine gets compatible cases together (the order of the table is unaffected).
_STRUCTURE = ("formulation", "approach", "damping", "integrator", "n_elements", "steps_per_rev")


def _run_chunk(cases, tol=1e-8, max_revolutions=400, parallel=None):
    """Rows of one chunk of cases (module level, so executors pickle it by reference).

    The whole chunk goes to `steady_states` at once; if that raises, the cases are run one by one
    so that only the case at fault is recorded as failed.  In an executor's worker the engine runs
    serially (parallel=False): the executor is the parallelism, and a worker forked from a process
    whose OpenMP threads are running must not start OpenMP threads of its own."""
    try:
        with notices.quiet():                # the sweep warned once for all its cases
            states = steady_states(cases, tol=tol, max_revolutions=max_revolutions, parallel=parallel)
        if len(states) != len(cases):
            raise RuntimeError(f"steady_states returned {len(states)} results for {len(cases)} cases")
        return [{k: plain(v) for k, v in s.row().items()} for s in states]
    except Exception as exc:
        if len(cases) == 1:
            return [failed_row(cases[0], exc)]
    return [row for case in cases for row in _run_chunk([case], tol, max_revolutions, parallel)]


def _as_cases(cases):
    """List of Case from Case objects or mappings; every case is validated before any work."""
    if isinstance(cases, (Case, Mapping)):
        raise TypeError("cases must be an iterable of Case objects or mappings "
                        "(wrap a single case in a list)")
    out = []
    for i, item in enumerate(cases):
        if isinstance(item, Case):
            out.append(item)
        elif isinstance(item, Mapping):
            try:
                out.append(Case.from_dict(item))
            except (ParameterError, TypeError, ValueError) as exc:
                raise ParameterError(f"cases[{i}]: {exc}") from exc
        else:
            raise TypeError(f"cases[{i}] must be a crankgen.Case or a mapping of its parameters, "
                            f"got {type(item).__name__}")
        _check_resolved(out[-1], f"cases[{i}]: ")
    return out


def sweep(cases, executor=None, checkpoint=None, batch_size=BATCH_SIZE, tol=1e-8, progress=None, *,
          max_revolutions=400, retry_failed=False, keep_other_versions=False, fresh=False):
    """Periodic steady states of many cases, as a SweepTable (one row per case, input order).

    cases: iterable of `Case` or mappings (`Case.from_dict`); all are validated before any work
        (a bad one raises ParameterError naming its index).  Duplicates are computed once.  A
        sweep whose memory (crankgen.analyses.limits) would exceed the machine's is refused before any work.
    executor: None runs in this process; otherwise any `concurrent.futures.Executor`, e.g.
        `ProcessPoolExecutor()` or `distributed.Client(...).get_executor()`; a Dask `Client`
        itself is accepted (its get_executor() is used), any other object refused at once.  The executor is
        the caller's: it is used, not shut down.  Chunks it does not finish (a worker died, the
        pool broke, or it refused the task: shut down, a closed Dask client) are never recorded
        as results; they are run again in this process after the others, with a RuntimeWarning.
    checkpoint: path of a JSON Lines file; finished cases are appended after every chunk and, on
        a later call, cases already in it (same `Case.key()`, tol and max_revolutions, same
        `provenance.code_version()`) are taken from it instead of being recomputed, so a sweep
        can be resumed, or extended with more cases.  Failed cases are recorded too and are not
        retried unless retry_failed=True.  Records made by other code are recomputed, with a
        warning, unless keep_other_versions=True.  fresh=True discards its records first.  The
        sweep holds a lock on it (CHECKPOINT.lock) while it runs: a second sweep on the same
        checkpoint raises CheckpointError at once.
    batch_size: cases per call of `steady_states` (per task with an executor); every finished
        batch is checkpointed and reported, so a small batch loses little to an interruption.
    tol, max_revolutions: passed to `steady_states`.
    progress: progress(done, total) after each finished chunk, counting cases in the input
        (cases taken from the checkpoint count as done from the start).
    """
    executor = _executor(executor)
    if progress is not None and not callable(progress):
        raise ParameterError(f"progress must be None or a function progress(done, total), got "
                             f"{progress!r}")
    cases = _as_cases(cases)
    time_scheme.warn_steps(cases)
    batch_size = integer("batch_size", batch_size, 1)
    tol = in_range("tol", tol, 0, None, low_open=True)
    max_revolutions = integer("max_revolutions", max_revolutions, 1)

    keys = [case.key() for case in cases]
    multiplicity = Counter(keys)
    if cases:
        heaviest = max(cases, key=lambda c: c.n_elements)
        check_run_size(heaviest.n_elements, heaviest.steps_per_rev, len(multiplicity), "steady",
                       batch=batch_size, names={"n_cases": "cases", "n_steps": "steps_per_rev",
                                                "n_elements": "n_elements (with batch_size)"})
    store = None
    if checkpoint is not None:
        store = Checkpoint(checkpoint, {"tol": tol, "max_revolutions": max_revolutions},
                           keep_other_versions, code=code_version())
        recorded = store.open(multiplicity, fresh=fresh)
    try:
        return _sweep(cases, keys, multiplicity, store, recorded if store else {}, executor,
                      batch_size, tol, max_revolutions, retry_failed, progress)
    finally:
        if store is not None:
            store.close()


def _executor(executor):
    """The executor a sweep submits to: None, or a concurrent.futures.Executor, whose futures
    concurrent.futures.as_completed can wait on.  A Dask client, which Dask's own API teaches to
    pass, submits Dask futures that as_completed cannot wait on: its get_executor() is used (a
    concurrent.futures.Executor on the same cluster).  Anything else is refused at once."""
    if executor is None or isinstance(executor, cf.Executor):
        return executor
    get = getattr(executor, "get_executor", None)
    if callable(get):
        inner = get()
        if isinstance(inner, cf.Executor):
            return inner
    raise ParameterError(f"executor must be None or a concurrent.futures.Executor (e.g. "
                         f"ProcessPoolExecutor(), or a Dask client's client.get_executor()), got "
                         f"{type(executor).__name__} {executor!r}"[:300])


def _sweep(cases, keys, multiplicity, store, recorded, executor, batch_size, tol, max_revolutions,
           retry_failed, progress):
    total = len(cases)
    results = {key: row for key, row in recorded.items()
               if key in multiplicity and not (retry_failed and row.get("status") == "failed")}
    todo, seen = [], set(results)
    for key, case in zip(keys, cases):
        if key not in seen:
            seen.add(key)
            todo.append(case)
    todo.sort(key=lambda c: tuple(getattr(c, name) for name in _STRUCTURE))   # stable
    chunks = [todo[i:i + batch_size] for i in range(0, len(todo), batch_size)]

    done = sum(multiplicity[key] for key in results)
    if progress is not None and done:
        progress(done, total)

    def finish(chunk, rows):
        nonlocal done
        pairs = [(case.key(), row) for case, row in zip(chunk, rows)]
        if store is not None:
            store.append(pairs)
        results.update(pairs)
        done += sum(multiplicity[key] for key, _ in pairs)
        if progress is not None:
            progress(done, total)

    if executor is not None:
        chunks = _run_on(executor, chunks, finish, tol, max_revolutions)
    for chunk in chunks:
        finish(chunk, _run_chunk(chunk, tol, max_revolutions))
    return SweepTable([results[key] for key in keys])


def _run_on(executor, chunks, finish, tol, max_revolutions):
    """Run the chunks through the executor, finish() each one that comes back, and return those
    it did not finish (in their original order), after warning about them."""
    futures, unfinished, reason = {}, set(), None
    try:
        for i, chunk in enumerate(chunks):
            try:
                futures[executor.submit(_run_chunk, chunk, tol, max_revolutions, False)] = i
            except Exception as exc:   # broken, shut down, closed (a Dask client): not sent
                unfinished.update(range(i, len(chunks)))
                reason = f"{type(exc).__name__}: {exc}"
                break
        for future in cf.as_completed(futures):
            i = futures[future]
            try:
                rows = future.result()
            except Exception as exc:   # _run_chunk itself never raises: the task did not complete
                unfinished.add(i)
                reason = reason or f"{type(exc).__name__}: {exc}"
                continue
            finish(chunks[i], rows)
    finally:
        for future in futures:
            future.cancel()
    left = [chunks[i] for i in sorted(unfinished)]
    if left:
        warnings.warn(f"{sum(map(len, left))} case(s) were not finished by the executor ({reason}); "
                      "nothing was recorded for them and they are run again in this process",
                      RuntimeWarning, stacklevel=4)
    return left
