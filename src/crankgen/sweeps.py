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

Checkpoint format (one strict JSON document per line; missing numbers are null; CRLF line
endings are read as well):

    {"format": "crankgen-sweep-checkpoint", "version": 1}                      <- header
    {"key": Case.key(), "settings": {"tol": ..., "max_revolutions": ...},
     "code": provenance.code_version(), "row": {...}}

A file whose first line is not this header is refused (CheckpointError), as is a header of another
format version.  Lines are only ever appended, a whole chunk in one write followed by fsync, so a
crash can tear at most the last line; on opening, a torn last line is dropped (with a warning) and
the file is truncated back to its last complete line before anything is appended.  The last record
of a key wins.  Records made with other settings (tol, max_revolutions) are not reused; records
made by other code (another crankgen version or other generated kernels, or records without
"code") are recomputed with a warning unless sweep(keep_other_versions=True).

One sweep at a time uses a checkpoint: it holds an exclusive lock (flock) on the sidecar file
`CHECKPOINT.lock`, which holds its process id, from opening (and repairing) the checkpoint to its
last append; another sweep on the same checkpoint is refused at once, naming that process.  The
lock file is removed at the end (a killed sweep leaves it behind, unlocked: the next sweep takes
it over).  The checkpoint must be a regular file (or absent): a folder, a device, a FIFO or a
socket is refused, and so is a symbolic link out of the checkpoint's folder.  If the checkpoint is
removed while the sweep runs, the next append creates it again, header first, with every record of
this sweep.
"""

import concurrent.futures as cf
import csv
import errno
import json
import math
import os
import stat
import threading
import warnings
from collections import Counter
from collections.abc import Mapping
from pathlib import Path

try:
    import fcntl
except ImportError:           # not on Windows: checkpoints are used unlocked there
    fcntl = None

import numpy as np

from .cases import Case
from .errors import CrankgenError, ParameterError
from .io import NotRegularFileError, OutputWriteError, atomic_file, check_target, kind_of
from .limits import check_run_size
from .provenance import code_version
from . import notices, time_scheme
from .steady import SteadyState, _check_resolved, steady_states
from .validation import in_range, integer

__all__ = ["CheckpointError", "SweepTable", "sweep"]

FORMAT, VERSION = "crankgen-sweep-checkpoint", 1
_HEADER = json.dumps({"format": FORMAT, "version": VERSION}) + "\n"
BATCH_SIZE = 8           # default cases per batch: each finished batch is checkpointed and reported
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
        with notices.quiet():                # the sweep warned once for all its cases
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


class CheckpointError(CrankgenError, ValueError):
    """A checkpoint that cannot be used: not a crankgen sweep checkpoint, another format version,
    or in use by another sweep.  The message names the file."""


def checkpoint_header(first_line):
    """The format version of a checkpoint whose first line (bytes, CRLF or LF) is first_line, or
    None when it is not the header of a crankgen sweep checkpoint."""
    try:
        header = json.loads(first_line.decode("utf-8").strip())
    except (UnicodeDecodeError, ValueError):
        return None
    if not isinstance(header, dict) or header.get("format") != FORMAT:
        return None
    return header.get("version")


def check_checkpoint_file(path, data=None):
    """Refuse (CheckpointError) a file that is not a crankgen sweep checkpoint of this format
    version, from its first bytes (`data`, default: read from path, which must be a regular file);
    an empty file or a torn header is accepted (it is started afresh)."""
    if data is None:
        data = _read_regular(path, 4096)            # path: a regular file, not a link
    first, newline, _ = data.partition(b"\n")
    if not newline:
        if _HEADER.encode().startswith(first.rstrip(b"\r")):
            return                                          # empty, or a torn header
        raise CheckpointError(f"{path} exists and is not a crankgen sweep checkpoint; choose "
                              "another checkpoint")
    version = checkpoint_header(first)
    if version is None:
        raise CheckpointError(f"{path} exists and is not a crankgen sweep checkpoint; choose "
                              "another checkpoint")
    if version != VERSION:
        raise CheckpointError(f"{path} is a crankgen sweep checkpoint of format version "
                              f"{version!r}; this crankgen reads version {VERSION} only (use "
                              "another checkpoint, or the crankgen that wrote it)")


def _open_regular(path, flags):
    """os.open of a regular file only (never blocks on a FIFO, never follows a last symlink);
    NotRegularFileError otherwise."""
    for name in ("O_NONBLOCK", "O_NOCTTY", "O_NOFOLLOW", "O_CLOEXEC"):
        flags |= getattr(os, name, 0)
    fd = os.open(path, flags, 0o666)
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        raise NotRegularFileError(errno.EINVAL, f"is {kind_of(mode)}, not a regular file",
                                  str(path))
    return fd


def _read_regular(path, limit=None):
    fd = _open_regular(path, os.O_RDONLY)
    try:
        with os.fdopen(fd, "rb") as fh:
            fd = None
            return fh.read() if limit is None else fh.read(limit)
    finally:
        if fd is not None:
            os.close(fd)


# file descriptors of the checkpoints and locks this process holds; a forked pool worker closes
# its copies (sweeps.worker_init), so that no worker keeps a lock alive
_HELD = set()


class _Lock:
    """Exclusive flock on the sidecar file PATH.lock holding the owner's pid."""

    def __init__(self, checkpoint):
        self.checkpoint = checkpoint
        self.path = checkpoint.with_name(checkpoint.name + ".lock")
        self.fd = None

    def acquire(self):
        for _ in range(20):
            fd = _open_regular(check_target(self.path), os.O_RDWR | os.O_CREAT)
            try:
                if fcntl is None:
                    raise OSError(errno.ENOTSUP, "no flock")
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                try:
                    owner = os.pread(fd, 64, 0).decode(errors="replace").strip() or "unknown"
                finally:
                    os.close(fd)
                raise CheckpointError(
                    f"checkpoint {self.checkpoint} is in use by another sweep (process {owner}, "
                    f"lock {self.path}); wait for it to finish, or choose another checkpoint"
                ) from None
            except OSError:                     # a file system without flock: run unlocked
                pass
            try:
                same = os.path.samestat(os.stat(self.path), os.fstat(fd))
            except FileNotFoundError:
                same = False
            if not same:                        # removed by its owner as we locked it: again
                os.close(fd)
                continue
            os.ftruncate(fd, 0)
            os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
            self.fd = fd
            _HELD.add(fd)
            return self
        raise CheckpointError(f"could not lock checkpoint {self.checkpoint} ({self.path} keeps "
                              "changing)")

    def release(self):
        if self.fd is None:
            return
        try:
            if os.path.samestat(os.stat(self.path), os.fstat(self.fd)):
                os.unlink(self.path)
        except OSError:
            pass
        _HELD.discard(self.fd)
        os.close(self.fd)
        self.fd = None


class _Checkpoint:
    """Append-only JSON Lines record of finished cases (see the module docstring).  open() takes
    the lock and returns the reusable records; close() releases it."""

    def __init__(self, path, settings, keep_other_versions=False):
        if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
            raise ParameterError(f"checkpoint must be the path of a file, got {path!r}")
        self.given = Path(path)
        try:
            self.path = check_target(self.given)
        except NotRegularFileError as exc:
            raise ParameterError(f"checkpoint {exc}") from None
        if not self.path.parent.is_dir():
            raise ParameterError(f"checkpoint {self.given}: its folder {self.path.parent} does not "
                                 "exist" + (" (it is a file)" if self.path.parent.exists() else ""))
        self.settings = settings
        self.code = code_version()
        self.keep_other_versions = keep_other_versions
        self.lock = _Lock(self.path)
        self.fd = None
        self.kept = []               # records of this sweep: written again if the file disappears
        self.recreated = False

    def open(self, keys=(), fresh=False):
        """Lock, create the file or repair its tail; return {key: row} of reusable records (of
        the given keys).  fresh=True discards every record (the file restarts with its header)."""
        self.lock.acquire()
        try:
            return self._open(set(keys), fresh)
        except BaseException:
            self.close()
            raise

    def _open(self, keys, fresh):
        try:
            data = _read_regular(self.path)
        except FileNotFoundError:
            data = b""
        except NotRegularFileError as exc:
            raise ParameterError(f"checkpoint {exc}") from None
        if data:
            check_checkpoint_file(self.given, data)
        first, newline, _ = data.partition(b"\n")
        if fresh or not newline:
            if data and not fresh:
                warnings.warn(f"checkpoint {self.given}: torn header ignored, starting afresh",
                              RuntimeWarning, stacklevel=4)
            self._create()
            return {}
        header_end = len(first) + 1
        end = data.rfind(b"\n") + 1
        self._attach()
        if end < len(data):
            warnings.warn(f"checkpoint {self.given}: ignoring a torn last line "
                          f"({len(data) - end} bytes, an interrupted write); its case is recomputed",
                          RuntimeWarning, stacklevel=4)
            os.ftruncate(self.fd, end)
            os.fsync(self.fd)
        rows, lines, bad, stale, other = {}, {}, 0, 0, {}
        for line in data[header_end:end].splitlines():
            if not line.strip():
                continue
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
            if key in keys:
                lines[key] = line.rstrip(b"\r") + b"\n"
        self.kept = list(lines.values())
        other = {key: code for key, code in other.items() if key not in rows}
        if other:
            made_by = sorted({json.dumps(code, sort_keys=True) for code in other.values()})
            warnings.warn(f"checkpoint {self.given}: {len(other)} record(s) made by other code "
                          f"({'; '.join(made_by)}, this is {json.dumps(self.code, sort_keys=True)}) "
                          "are recomputed; pass keep_other_versions=True to reuse them",
                          RuntimeWarning, stacklevel=4)
        if bad:
            warnings.warn(f"checkpoint {self.given}: {bad} unreadable line(s) ignored; "
                          "their cases are recomputed", RuntimeWarning, stacklevel=4)
        if stale:
            warnings.warn(f"checkpoint {self.given}: {stale} record(s) made with other settings "
                          f"than {self.settings} are not reused", RuntimeWarning, stacklevel=4)
        return rows

    def _create(self):
        """(Re)write the file atomically: the header and the records kept so far."""
        content = _HEADER.encode() + b"".join(self.kept)
        if self.fd is not None:
            self._detach()
        atomic_file_write(self.path, content)
        self._attach()

    def _attach(self):
        self.fd = _open_regular(self.path, os.O_WRONLY | os.O_APPEND)
        self.identity = os.fstat(self.fd)
        _HELD.add(self.fd)

    def _detach(self):
        _HELD.discard(self.fd)
        os.close(self.fd)
        self.fd = None

    def append(self, pairs):
        """Append (key, row) records in one write, then fsync; a checkpoint removed meanwhile is
        created again (header and every record of this sweep)."""
        payload = "".join(json.dumps({"key": key, "settings": self.settings, "code": self.code,
                                      "row": row}, allow_nan=False) + "\n"
                          for key, row in pairs).encode()
        if self.fd is None:
            return
        try:
            current = os.stat(self.path)
        except FileNotFoundError:
            current = None
        try:
            if current is None:
                warnings.warn(f"checkpoint {self.given} was removed during the sweep; it is "
                              f"created again with the {len(self.kept)} record(s) of this sweep "
                              "so far", RuntimeWarning, stacklevel=3)
                self._create()
            elif not os.path.samestat(current, self.identity):
                warnings.warn(f"checkpoint {self.given} was replaced by another file during the "
                              "sweep; this sweep no longer records to it", RuntimeWarning,
                              stacklevel=3)
                self._detach()
                return
            view = memoryview(payload)
            while view:
                view = view[os.write(self.fd, view):]
            os.fsync(self.fd)
        except NotRegularFileError as exc:
            raise ParameterError(f"checkpoint {exc}") from None
        except OSError as exc:
            raise OutputWriteError(exc.errno, f"cannot append to the checkpoint: "
                                   f"{exc.strerror or exc}", str(self.given)) from None
        self.kept.append(payload)

    def close(self):
        if self.fd is not None:
            self._detach()
        self.lock.release()


def atomic_file_write(path, content):
    """Write bytes to path atomically (crankgen.io.atomic_file)."""
    with atomic_file(path, "wb") as fh:
        fh.write(content)


def sweep(cases, executor=None, checkpoint=None, batch_size=BATCH_SIZE, tol=1e-8, progress=None, *,
          max_revolutions=400, retry_failed=False, keep_other_versions=False, fresh=False):
    """Periodic steady states of many cases, as a SweepTable (one row per case, input order).

    cases: iterable of `Case` or mappings (`Case.from_dict`); all are validated before any work
        (a bad one raises ParameterError naming its index).  Duplicates are computed once.  A
        sweep whose memory (crankgen.limits) would exceed the machine's is refused before any work.
    executor: None runs in this process; otherwise any `concurrent.futures.Executor`, e.g.
        `ProcessPoolExecutor()` or `distributed.Client(...).get_executor()`.  The executor is
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
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ParameterError("executor must be None or a concurrent.futures.Executor (e.g. "
                             "ProcessPoolExecutor() or a Dask client's get_executor()), got "
                             f"{executor!r}")
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
        store = _Checkpoint(checkpoint, {"tol": tol, "max_revolutions": max_revolutions},
                            keep_other_versions)
        recorded = store.open(multiplicity, fresh=fresh)
    try:
        return _sweep(cases, keys, multiplicity, store, recorded if store else {}, executor,
                      batch_size, tol, max_revolutions, retry_failed, progress)
    finally:
        if store is not None:
            store.close()


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


# ---- process pools whose workers die with the sweep -------------------------------------------

PR_SET_PDEATHSIG = 1


def worker_init(parent, interval=0.5):
    """Initializer of the command line's pool workers: the worker dies with the process that
    made the pool (`parent`, its pid), even if that one is killed with SIGKILL.  On Linux the
    kernel sends the worker SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG); everywhere, a
    watchdog thread checks every `interval` seconds that the parent is still there and ends the
    worker when it is not.  Ctrl-C is left to the parent (which shuts the pool down), and the
    checkpoint and lock files the parent held when it forked the worker are closed in it."""
    import signal

    for fd in list(_HELD):
        try:
            os.close(fd)
        except OSError:
            pass
    _HELD.clear()
    try:                                    # Ctrl-C is the parent's; SIGTERM kills (a forked
        signal.signal(signal.SIGINT, signal.SIG_IGN)        # worker inherits the command
        signal.signal(signal.SIGTERM, signal.SIG_DFL)       # line's SIGTERM handler)
    except ValueError:                      # not the main thread of the worker
        pass
    _set_parent_death_signal(signal.SIGKILL)
    if not _alive(parent):                  # the parent died before the worker could ask
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent, interval), daemon=True,
                     name="crankgen-parent-watchdog").start()


def _set_parent_death_signal(signum):
    """prctl(PR_SET_PDEATHSIG, signum) on Linux; False where it is not available."""
    import sys
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(PR_SET_PDEATHSIG, int(signum), 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _alive(pid):
    if os.getppid() == 1 and pid != 1:      # re-parented to init: the parent is gone
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _watch_parent(parent, interval):
    import time
    first = os.getppid()
    while True:
        time.sleep(interval)
        if os.getppid() != first or not _alive(parent):
            os._exit(1)


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
