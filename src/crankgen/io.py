"""Atomic output files: each file is written to a temporary file beside it, flushed, fsynced and
moved into place with os.replace, so an interrupted run never leaves a half-written CSV, PNG or
Markdown file under the final name.  Files get the mode of an ordinary new file (0666 less the
umask, 0644 by default), not mkstemp's 0600.

Also: the checks every command makes on its output folder before computing anything
(`prepare_folder`), so that a bad --out is reported at once, as one line, and leaves nothing behind.
"""

import csv
import io
import math
import contextlib
import os
import uuid
from pathlib import Path

import numpy as np

from .errors import CrankgenError

__all__ = ["OutputExistsError", "OutputPathError", "atomic_write", "atomic_write_text", "csv_text",
           "write_csv", "save_figure", "existing_outputs", "prepare_folder", "remove_if_empty",
           "remove_stale_temporaries", "fsync_dir"]


class OutputExistsError(CrankgenError):
    """The output folder already holds files that the run would overwrite (and no --force)."""


class OutputPathError(CrankgenError):
    """The output folder cannot be used: it is a file, lies under a file, or is not writable."""


def fsync_dir(folder):
    """Make directory entries durable (best effort: not every platform can open a folder)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _temporary(path):
    """(fd, name) of a new temporary file beside path, created with mode 0666 less the umask."""
    for _ in range(100):
        tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
        try:
            return os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"could not create a temporary file beside {path}")


def atomic_write(path, write, mode="w", overwrite=True):
    """Call write(fileobj) on a temporary file in path's folder, then move it to path.
    On any exception (KeyboardInterrupt included) the temporary file is removed and path is left
    as it was.  With overwrite=False an existing path raises OutputExistsError."""
    path = Path(path)
    if not overwrite and path.exists():
        raise OutputExistsError(f"{path} exists; use --force to overwrite it")
    with atomic_file(path, mode) as fh:
        write(fh)
    return path


@contextlib.contextmanager
def atomic_file(path, mode="w"):
    """`with atomic_file(path) as fh:` -- write fh, and path appears complete (atomic_write) or not
    at all; text mode uses newline="" (CSV)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = _temporary(path)
    try:
        kwargs = {"newline": ""} if "b" not in mode else {}
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    fsync_dir(path.parent)


def atomic_write_text(path, text, overwrite=True):
    return atomic_write(path, lambda fh: fh.write(text), overwrite=overwrite)


def _cell(value):
    """CSV cell: full precision floats, empty for a missing number (NaN / None)."""
    if value is None:
        return ""
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return "" if not math.isfinite(value) else repr(value)
    if isinstance(value, (np.integer,)):
        return str(int(value))
    return str(value)


def csv_text(columns, rows):
    """CSV text of rows (mappings) with the given column order."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(columns)
    for row in rows:
        w.writerow([_cell(row.get(c)) for c in columns])
    return buf.getvalue()


def write_csv(path, columns, rows, overwrite=True):
    text = csv_text(columns, rows)
    return atomic_write(path, lambda fh: fh.write(text), overwrite=overwrite)


def save_figure(fig, path, overwrite=True, dpi=120):
    """Save a matplotlib figure atomically as PNG (and close it)."""
    try:
        return atomic_write(path, lambda fh: fig.savefig(fh, format="png", dpi=dpi), mode="wb",
                            overwrite=overwrite)
    finally:
        import matplotlib.pyplot as plt
        plt.close(fig)


def existing_outputs(folder, names):
    """The names (in order) that already exist in folder."""
    folder = Path(folder)
    return [n for n in names if (folder / n).exists()]


def prepare_folder(folder, names=(), force=False):
    """Check, before any computing, that folder can receive the files `names`; create it if
    missing, and remove temporary files of those names left by a killed run.  Returns the list of folders created (for `remove_if_empty` if the run stops before
    writing anything).  Raises OutputPathError (a file, under a file, not creatable, not writable)
    or OutputExistsError (one of names is there and force is false)."""
    folder = Path(folder)
    try:
        return _prepare(folder, names, force)
    except OSError as exc:                          # e.g. a parent folder that cannot be read
        raise OutputPathError(f"cannot use {folder}: {exc.strerror or exc}") from None


def _prepare(folder, names, force):
    if folder.exists() and not folder.is_dir():
        raise OutputPathError(f"{folder} is a file, not a folder")
    if folder.is_dir():
        there = existing_outputs(folder, names)
        if there and not force:
            more = f" (and {len(there) - 1} more output(s) of this command)" if len(there) > 1 else ""
            raise OutputExistsError(f"{folder / there[0]} already exists{more}; use --force to "
                                    "overwrite, or choose another --out")
    created = []
    probe = folder
    while not probe.exists():
        created.append(probe)
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        raise OutputPathError(f"cannot create {folder}: {probe} is a file, not a folder")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        remove_if_empty(created)
        raise OutputPathError(f"cannot create {folder}: {exc.strerror or exc}") from None
    try:                                            # writable? (root ignores mode bits, so try)
        fd, tmp = _temporary(folder / "probe")
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        remove_if_empty(created)
        raise OutputPathError(f"cannot write to {folder}: {exc.strerror or exc}") from None
    remove_stale_temporaries(folder, names)
    return created


def remove_stale_temporaries(folder, names):
    """Remove temporary files that an earlier, killed run left beside the outputs `names`
    (`.NAME.PID.XXXXXXXX.tmp` whose process no longer exists); return how many were removed."""
    removed = 0
    for name in names:
        for tmp in Path(folder).glob(f".{name}.*.tmp"):
            parts = tmp.name[len(name) + 2:].split(".")
            if len(parts) != 3 or not parts[0].isdigit():
                continue
            pid = int(parts[0])
            if pid != os.getpid():
                try:
                    os.kill(pid, 0)
                    continue                        # still running: not ours to remove
                except ProcessLookupError:
                    pass
                except OSError:
                    continue
            try:
                tmp.unlink()
                removed += 1
            except OSError:
                pass
    return removed


def remove_if_empty(folders):
    """Remove the given folders (deepest first) where they are empty; ignore the others."""
    for folder in sorted((Path(f) for f in folders), key=lambda p: len(p.parts), reverse=True):
        try:
            folder.rmdir()
        except OSError:
            pass
