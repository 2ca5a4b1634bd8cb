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

Checkpoint format (one strict JSON document per line; missing numbers are null):

    {"format": "crankgen-sweep-checkpoint", "version": 1}                      <- header
    {"key": Case.key(), "settings": {"tol": ..., "max_revolutions": ...},
     "code": provenance.code_version(), "row": {...}}

Lines are only ever appended, a whole chunk in one write followed by flush and fsync, so a crash
can tear at most the last line; on resume a torn last line is dropped (with a warning) and the
file is truncated back to its last complete line before anything is appended.  The last record of
a key wins.  Records made with other settings (tol, max_revolutions) are not reused; records made
by other code (another crankgen version or other generated kernels, or records without "code")
are recomputed with a warning unless sweep(keep_other_versions=True).  One sweep at a time may
write a given checkpoint.
"""

import concurrent.futures as cf
import csv
import json
import math
import os
import warnings
from collections import Counter
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from .cases import Case
from .errors import ParameterError
from .io import atomic_file, fsync_dir
from .provenance import code_version
from .steady import SteadyState, _check_resolved, steady_states
from .validation import in_range, integer

__all__ = ["SweepTable", "sweep"]

_HEADER = json.dumps({"format": "crankgen-sweep-checkpoint", "version": 1}) + "\n"
# Fields that fix the shape of a case's equations; chunks group cases alike in these so that a
# lock-step batch engine gets compatible cases together (the order of the table is unaffected).
_STRUCTURE = ("formulation", "approach", "damping", "integrator", "n_elements", "steps_per_rev")


def _failed_row(case, error):
    """Row of a case whose computation raised instead of returning a SteadyState."""
    message = error if isinstance(error, str) else f"{type(error).__name__}: {error}"
    return SteadyState(case, "failed", None, None, 0, 0, None, message, 0.0).row()


def _plain(value):
    """numpy scalars -> Python scalars, a non-finite float -> None (rows must be strict JSON and
    CSV friendly; a missing number is None)."""
    value = value.item() if isinstance(value, np.generic) else value
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _run_chunk(cases, tol=1e-8, max_revolutions=400, parallel=None):
    """Rows of one chunk of cases (module level, so executors pickle it by reference).

    The whole chunk goes to `steady_states` at once; if that raises, the cases are run one by one
    so that only the case at fault is recorded as failed.  In an executor's worker the engine runs
    serially (parallel=False): the executor is the parallelism, and a worker forked from a process
    whose OpenMP threads are running must not start OpenMP threads of its own."""
    try:
        states = steady_states(cases, tol=tol, max_revolutions=max_revolutions, parallel=parallel)
        if len(states) != len(cases):
            raise RuntimeError(f"steady_states returned {len(states)} results for {len(cases)} cases")
        return [{k: _plain(v) for k, v in s.row().items()} for s in states]
    except Exception as exc:
        if len(cases) == 1:
            return [_failed_row(cases[0], exc)]
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


class _Checkpoint:
    """Append-only JSON Lines record of finished cases (see the module docstring)."""

    def __init__(self, path, settings, keep_other_versions=False):
        self.path = Path(path)
        self.settings = settings
        self.code = code_version()
        self.keep_other_versions = keep_other_versions

    def open(self):
        """Create the file or repair its tail; return {key: row} of reusable records."""
        try:
            data = self.path.read_bytes()
        except FileNotFoundError:
            data = b""
        header = _HEADER.encode()
        if not data.startswith(header):
            if not header.startswith(data):
                raise ValueError(f"{self.path} exists and is not a crankgen sweep checkpoint")
            if data:
                warnings.warn(f"checkpoint {self.path}: torn header ignored, starting afresh",
                              RuntimeWarning, stacklevel=3)
            self._rewrite(header)
            return {}
        end = data.rfind(b"\n") + 1
        if end < len(data):
            warnings.warn(f"checkpoint {self.path}: ignoring a torn last line "
                          f"({len(data) - end} bytes, an interrupted write); its case is recomputed",
                          RuntimeWarning, stacklevel=3)
            with open(self.path, "r+b") as fh:
                fh.truncate(end)
                fh.flush()
                os.fsync(fh.fileno())
        rows, bad, stale, other = {}, 0, 0, {}
        for line in data[len(header):end].splitlines():
            try:          # NaN / Infinity written by older versions are read as missing (None)
                record = json.loads(line, parse_constant=lambda name: None)
                key, settings, row = record["key"], record["settings"], record["row"]
                if not isinstance(key, str) or not isinstance(row, dict):
                    raise TypeError
            except (ValueError, KeyError, TypeError):
                bad += 1
                continue
            if settings != self.settings:
                stale += 1
                continue
            code = record.get("code")
            if code != self.code and not self.keep_other_versions:
                other[key] = code
                continue
            rows[key] = row
        other = {key: code for key, code in other.items() if key not in rows}
        if other:
            made_by = sorted({json.dumps(code, sort_keys=True) for code in other.values()})
            warnings.warn(f"checkpoint {self.path}: {len(other)} record(s) made by other code "
                          f"({'; '.join(made_by)}, this is {json.dumps(self.code, sort_keys=True)}) "
                          "are recomputed; pass keep_other_versions=True to reuse them",
                          RuntimeWarning, stacklevel=3)
        if bad:
            warnings.warn(f"checkpoint {self.path}: {bad} unreadable line(s) ignored; "
                          "their cases are recomputed", RuntimeWarning, stacklevel=3)
        if stale:
            warnings.warn(f"checkpoint {self.path}: {stale} record(s) made with other settings "
                          f"than {self.settings} are not reused", RuntimeWarning, stacklevel=3)
        return rows

    def _rewrite(self, content):
        with open(self.path, "wb") as fh:
            fh.write(content)
            fh.flush()
            os.fsync(fh.fileno())
        fsync_dir(self.path.parent)

    def append(self, pairs):
        """Append (key, row) records in one write, then flush and fsync."""
        payload = "".join(json.dumps({"key": key, "settings": self.settings, "code": self.code,
                                      "row": row}, allow_nan=False) + "\n"
                          for key, row in pairs)
        with open(self.path, "ab") as fh:
            fh.write(payload.encode())
            fh.flush()
            os.fsync(fh.fileno())


def sweep(cases, executor=None, checkpoint=None, batch_size=64, tol=1e-8, progress=None, *,
          max_revolutions=400, retry_failed=False, keep_other_versions=False):
    """Periodic steady states of many cases, as a SweepTable (one row per case, input order).

    cases: iterable of `Case` or mappings (`Case.from_dict`); all are validated before any work
        (a bad one raises ParameterError naming its index).  Duplicates are computed once.
    executor: None runs in this process; otherwise any `concurrent.futures.Executor`, e.g.
        `ProcessPoolExecutor()` or `distributed.Client(...).get_executor()`.  The executor is
        the caller's: it is used, not shut down.  Chunks it does not finish (a worker died, the
        pool broke) are never recorded as results; they are run again in this process after the
        others, with a RuntimeWarning.
    checkpoint: path of a JSON Lines file; finished cases are appended after every chunk and, on
        a later call, cases already in it (same `Case.key()`, tol and max_revolutions, same
        `provenance.code_version()`) are taken from it instead of being recomputed.  Failed
        cases are recorded too and are not retried unless retry_failed=True.  Records made by
        other code are recomputed, with a warning, unless keep_other_versions=True.
    batch_size: cases per call of `steady_states` (per task with an executor).
    tol, max_revolutions: passed to `steady_states`.
    progress: progress(done, total) after each finished chunk, counting cases in the input
        (cases taken from the checkpoint count as done from the start).
    """
    cases = _as_cases(cases)
    batch_size = integer("batch_size", batch_size, 1)
    tol = in_range("tol", tol, 0, None, low_open=True)
    max_revolutions = integer("max_revolutions", max_revolutions, 1)

    keys = [case.key() for case in cases]
    multiplicity = Counter(keys)
    total = len(cases)
    results = {}
    store = None
    if checkpoint is not None:
        store = _Checkpoint(checkpoint, {"tol": tol, "max_revolutions": max_revolutions},
                            keep_other_versions)
        results = {key: row for key, row in store.open().items()
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
            except cf.BrokenExecutor as exc:      # broken before every chunk was sent
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
                      RuntimeWarning, stacklevel=3)
    return left


def _standard_columns():
    return list(_failed_row(Case(), "").keys())


class SweepTable:
    """Rows of a sweep (dicts: the case's parameters, then status, amplitude, half_peak_to_peak,
    periods, iterations, residual, wall_time, message), in the order of the input cases."""

    def __init__(self, rows):
        self.rows = [dict(row) for row in rows]

    @property
    def columns(self):
        """Column names: those of the rows in order of first appearance."""
        if not self.rows:
            return _standard_columns()
        names = {}
        for row in self.rows:
            names.update(dict.fromkeys(row))
        return list(names)

    def column(self, name):
        """One column as a NumPy array (float for numbers, str for text).  A numeric column with
        missing values (None) is a masked array (numpy.ma), masked where the value is missing."""
        if name not in self.columns:
            raise KeyError(f"no column {name!r}; columns are {', '.join(self.columns)}")
        values = [row.get(name) for row in self.rows]
        present = [v for v in values if v is not None]
        if len(present) < len(values) and present and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
            return np.ma.masked_array([0.0 if v is None else float(v) for v in values],
                                      mask=[v is None for v in values])
        return np.array(values)

    @property
    def failed(self):
        """Rows whose status is not "periodic" (failed, not periodic or unstable)."""
        return [row for row in self.rows if row.get("status") != "periodic"]

    @property
    def cases(self):
        """The rows' cases, as Case objects."""
        return [Case.from_dict(row) for row in self.rows]

    def __len__(self):
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def __getitem__(self, index):
        return self.rows[index]

    def __repr__(self):
        return f"SweepTable({len(self)} rows, {len(self.failed)} not periodic)"

    def to_csv(self, path):
        """Write the table as CSV (floats in full precision; a missing number, None, is an empty
        field), atomically (crankgen.io.atomic_file): path holds either the old or the complete new
        table, never a partial one."""
        with atomic_file(path) as fh:
            writer = csv.DictWriter(fh, fieldnames=self.columns)
            writer.writeheader()
            writer.writerows({k: _plain(v) for k, v in row.items()} for row in self.rows)
        return Path(path)

    def to_pandas(self):
        """The table as a pandas DataFrame (needs pandas, which crankgen does not require)."""
        import pandas as pd
        return pd.DataFrame(self.rows, columns=self.columns)
