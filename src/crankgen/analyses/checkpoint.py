"""The sweep checkpoint: a JSON Lines file of finished cases, appended a batch at a time, from
which an interrupted or extended sweep resumes.

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

Why JSON Lines and not SQLite.  The checkpoint's faults found so far (a file deleted while a sweep
runs, a second opener repairing a torn line another sweep was writing, locking) were about who
may open the file and whether it is still the same file, which SQLite does not settle either: it
makes a second writer wait for the first's transaction and then interleaves their batches instead
of refusing it (the sidecar lock would stay), and a database deleted while open keeps taking
writes into the unlinked file (SQLite 3.40.1 in WAL mode, checked; the identity check would
stay).  What SQLite would remove is the torn-line repair, a dozen lines here: one writer appends
whole batches with one write and one fsync, so only the last line can tear, and it is dropped.
Against that, SQLite's write-ahead log (WAL) does not work on network file systems, where sweeps
on a cluster keep their checkpoints; WAL mode adds two sidecar files (-wal, -shm) that the
regular-file and symbolic-link rules would have to cover; and every existing checkpoint, which
users read with grep or pandas (`pd.read_json(path, lines=True)`), would need converting.  So the
store stays JSON Lines, with its guarantees stated here and tested (tests/test_faults.py,
tests/test_durability.py): whole-batch appends with fsync, a torn last line dropped on opening,
one sweep at a time (file_lock.py), regular files only (io.open_regular), re-creation when deleted.
"""

import json
import os
import warnings
from pathlib import Path

from ..errors import ParameterError
from .file_lock import HELD, CheckpointError, SidecarLock
from ..results.io import NotRegularFileError, OutputWriteError, atomic_file, check_target, open_regular, read_regular
from ..results.provenance import code_version

__all__ = ["CheckpointError", "Checkpoint", "check_checkpoint_file", "checkpoint_header", "FORMAT", "VERSION"]

FORMAT, VERSION = "crankgen-sweep-checkpoint", 1
_HEADER = json.dumps({"format": FORMAT, "version": VERSION}) + "\n"


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
        data = read_regular(path, 4096, follow=False)      # a regular file, not a link
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


class Checkpoint:
    """Append-only JSON Lines record of finished cases (see the module docstring).  open() takes
    the lock and returns the reusable records; append() records a finished batch; close()
    releases the lock.  code: the provenance stamp of this sweep's records."""

    def __init__(self, path, settings, keep_other_versions=False, code=None):
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
        self.code = code_version() if code is None else code
        self.keep_other_versions = keep_other_versions
        self.lock = SidecarLock(self.path)
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
            data = read_regular(self.path, follow=False)
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
        self.fd = open_regular(self.path, os.O_WRONLY | os.O_APPEND, follow=False)
        self.identity = os.fstat(self.fd)
        HELD.add(self.fd)

    def _detach(self):
        HELD.discard(self.fd)
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
    """Write bytes to path atomically (crankgen.results.io.atomic_file)."""
    with atomic_file(path, "wb") as fh:
        fh.write(content)
