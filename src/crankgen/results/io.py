"""Atomic output files: each file is written to a temporary file beside it, flushed, fsynced and
moved into place with os.replace, so an interrupted run never leaves a half-written CSV, PNG or
Markdown file under the final name.  Files get the mode of an ordinary new file (0666 less the
umask, 0644 by default), not mkstemp's 0600.

crankgen writes, replaces or truncates only regular files: a path that is a folder, a device, a
FIFO or a socket is refused (`check_target`), and so is a symbolic link pointing out of the
folder it is in; a link to a regular file inside it is written through (the target is replaced).
An error while writing names the file the caller asked for, never the temporary file.

One check of an output path for every writer (`output_path`: CSV, JSON, PNG, GIF, MP4, from the
API and the command line alike), made before any work: the path is a file name (not None, not
empty, not a folder, a device, a FIFO, a socket or a link out of its folder), its folder exists or
can be created and is writable; temporary files an earlier, killed writer left beside it are
removed (`remove_stale_temporaries`: those of a process that no longer runs).  A writer that
writes by file name (Pillow, ffmpeg) writes a temporary path of its own (`atomic_path`), moved into
place the same way.

Also: the checks every command makes on its output folder before computing anything
(`prepare_folder`), so that a bad --out is reported at once, as one line, and leaves nothing behind.
"""

import csv
import errno
import io
import math
import contextlib
import os
import stat
import uuid
from pathlib import Path

import numpy as np

from ..errors import CrankgenError, ParameterError

__all__ = ["OutputExistsError", "OutputPathError", "output_path", "output_folder", "atomic_path", "atomic_write", "atomic_write_text", "csv_text",
           "write_csv", "save_figure", "existing_outputs", "prepare_folder", "remove_if_empty",
           "remove_stale_temporaries", "fsync_dir", "check_target", "kind_of", "open_regular", "read_regular"]


class OutputExistsError(CrankgenError):
    """The output folder already holds files that the run would overwrite (and no --force)."""


class OutputPathError(ParameterError):
    """An output path or folder cannot be used: not a path, a folder where a file goes, under a
    file, not writable, or a name taken by something that is not a regular file (a ParameterError:
    the path argument is wrong, named in the message)."""


def kind_of(mode):
    """What a file of this st_mode is, in words ("a folder", "a character device", ...)."""
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISLNK, "a symbolic link"),
                       (stat.S_ISREG, "a regular file")):
        if test(mode):
            return name
    return "a special file"


class OutputWriteError(OSError):
    """An output file could not be written; filename is the file the caller asked for (never a
    temporary file) and str() is "FILE: what went wrong"."""

    def __str__(self):
        return f"{self.filename}: {self.strerror}"


class NotRegularFileError(OutputWriteError):
    """An output path is taken by something crankgen does not write: a folder, a device, a FIFO,
    a socket, or a symbolic link out of its folder."""


def check_target(path, folder=None):
    """The path to write for `path`, after checking that crankgen may write it: absent or a
    regular file; a symbolic link only if it resolves into `folder` (default: the link's own
    folder) to an absent or regular file, and then the resolved path is returned (writing it keeps
    the link).  Raises NotRegularFileError (an OSError) naming the path and what it is."""
    path = Path(path)
    try:
        st = os.lstat(path)
    except (FileNotFoundError, NotADirectoryError):
        return path
    if stat.S_ISLNK(st.st_mode):
        target = Path(os.path.realpath(path))
        base = Path(os.path.realpath(folder if folder is not None else path.parent))
        if base != target.parent and base not in target.parents:
            raise NotRegularFileError(errno.EPERM, f"is a symbolic link to {target}, outside "
                                      f"{folder if folder is not None else path.parent}; crankgen "
                                      "does not write through it", str(path))
        try:
            st = os.stat(target)
        except (FileNotFoundError, NotADirectoryError):
            return target
        if not stat.S_ISREG(st.st_mode):
            raise NotRegularFileError(errno.EINVAL, f"is a symbolic link to {target}, "
                                      f"{kind_of(st.st_mode)}, not a regular file", str(path))
        return target
    if not stat.S_ISREG(st.st_mode):
        code = errno.EISDIR if stat.S_ISDIR(st.st_mode) else errno.EINVAL
        raise NotRegularFileError(code, f"is {kind_of(st.st_mode)}, not a regular file; crankgen "
                                  "writes only regular files (remove it or choose another name)",
                                  str(path))
    return path


def open_regular(path, flags=os.O_RDONLY, follow=True):
    """os.open of a regular file only: a FIFO, a device, a socket or a folder is refused
    (NotRegularFileError) without blocking (O_NONBLOCK: opening a FIFO with no writer would wait
    for one) and without reading from it; follow=False also refuses a symbolic link."""
    for name in ("O_NONBLOCK", "O_NOCTTY", "O_CLOEXEC") + (() if follow else ("O_NOFOLLOW",)):
        flags |= getattr(os, name, 0)
    try:
        fd = os.open(path, flags, 0o666)
    except IsADirectoryError:
        raise NotRegularFileError(errno.EISDIR, "is a folder, not a regular file", str(path)) from None
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        raise NotRegularFileError(errno.EINVAL, f"is {kind_of(mode)}, not a regular file",
                                  str(path))
    return fd


def read_regular(path, limit=None, follow=True):
    """The bytes of a regular file (its first `limit` bytes), refusing anything else as
    open_regular does: every file crankgen reads as input comes through here."""
    fd = open_regular(path, os.O_RDONLY, follow)
    with os.fdopen(fd, "rb") as fh:
        return fh.read() if limit is None else fh.read(limit)


def _named(exc, path, doing=None):
    """The OSError exc, re-raised under the name of the file the caller asked for (`path`) when
    it names no file or a temporary one; `doing` prefixes its text ("cannot create its folder")."""
    if isinstance(exc, NotRegularFileError) or (
            exc.filename is not None and not str(exc.filename).endswith(".tmp")):
        return exc
    text = exc.strerror or str(exc)
    return OutputWriteError(exc.errno, f"{doing}: {text}" if doing else text, str(path))


def _ensure_folder(folder, path):
    """Create path's folder (and its parents) if missing; an error names path and the culprit."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        return
    except FileExistsError:
        pass                                    # something that is not a folder is in the way
    except OSError as exc:
        raise _named(exc, path, f"cannot create its folder {folder}") from None
    probe = folder
    while probe != probe.parent and not probe.is_dir():
        if os.path.lexists(probe):
            st = os.stat(probe) if os.path.exists(probe) else os.lstat(probe)
            raise NotRegularFileError(errno.ENOTDIR, f"cannot create its folder: {probe} is "
                                      f"{kind_of(st.st_mode)}, not a folder", str(path))
        probe = probe.parent
    raise NotRegularFileError(errno.ENOTDIR, f"cannot create its folder {folder}", str(path))


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


def _temporary(path, suffix=""):
    """(fd, name) of a new temporary file beside path, `.NAME.PID.XXXXXXXX.tmp[SUFFIX]`, created
    with mode 0666 less the umask (suffix: for a writer that picks its format by the name's ending)."""
    for _ in range(100):
        tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp{suffix}")
        try:
            return os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"could not create a temporary file beside {path}")


def output_path(path, suffixes=None, name="path"):
    """The Path of a file a writer is asked to write, checked before any work (module docstring):
    a str or os.PathLike naming a file, with one of `suffixes` (".gif", ...) when given; absent or
    a regular file (check_target); its folder a folder or creatable (nothing but folders on the
    way), writable.  Stale temporary files of its name are removed.  OutputPathError (a crankgen
    error, one line) names the path and what is wrong."""
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if not isinstance(path, (str, os.PathLike)):
        raise OutputPathError(f"{name} must be a file path (a str or a pathlib.Path), got {path!r}"[:200])
    text = os.fspath(path)
    if isinstance(text, bytes):
        text = os.fsdecode(text)
    if not text.strip() or text.endswith(os.sep):
        raise OutputPathError(f"{name} must name a file, got {text!r}")
    path = Path(text)
    try:
        check_target(path)
    except NotRegularFileError as exc:
        raise OutputPathError(str(exc)) from None
    if suffixes and path.suffix.lower() not in suffixes:
        raise OutputPathError(f"{path}: this output is written as {' or '.join(suffixes)}; give a path ending "
                              "so")
    folder = path.parent
    probe = folder
    try:
        while not os.path.isdir(probe):
            if os.path.lexists(probe):
                st = os.stat(probe) if os.path.exists(probe) else os.lstat(probe)
                raise OutputPathError(f"{path}: cannot create its folder: {probe} is {kind_of(st.st_mode)}, "
                                      "not a folder")
            if probe.parent == probe:
                break
            probe = probe.parent
        if probe == folder:
            fd, tmp = _temporary(folder / path.name)          # writable? (root ignores mode bits)
            os.close(fd)
            os.unlink(tmp)
            remove_stale_temporaries(folder, [path.name])
        elif not os.access(probe, os.W_OK | os.X_OK):
            raise OutputPathError(f"{path}: cannot create its folder {folder}: {probe} is not writable")
    except OSError as exc:
        raise OutputPathError(f"{path}: cannot write there: {exc.strerror or exc}") from None
    return path


def output_folder(folder, names, name="folder"):
    """[Path] of the files `names` a writer puts in `folder`, each checked by output_path before the
    first is written (a folder argument that is None, empty or a file refused the same way)."""
    if isinstance(folder, bytes):
        folder = os.fsdecode(folder)
    if not isinstance(folder, (str, os.PathLike)) or not os.fspath(folder).strip():
        raise OutputPathError(f"{name} must be a folder path (a str or a pathlib.Path), got {folder!r}"[:200])
    folder = Path(os.fspath(folder))
    if os.path.lexists(folder) and not folder.is_dir():
        st = os.stat(folder) if os.path.exists(folder) else os.lstat(folder)
        raise OutputPathError(f"{folder} is {kind_of(st.st_mode)}, not a folder")
    return [output_path(folder / n) for n in names]


@contextlib.contextmanager
def atomic_path(path):
    """`with atomic_path(path) as tmp:` -- write the file named tmp (beside path, ending like path:
    for a writer that picks its format by the name, Pillow's or ffmpeg's), and path appears
    complete or not at all: tmp is moved into place when the block ends, removed when it raises
    (KeyboardInterrupt included).  path is checked first (output_path)."""
    path = output_path(path)
    target = check_target(path)
    _ensure_folder(target.parent, path)
    try:
        fd, tmp = _temporary(target, target.suffix)
        os.close(fd)
    except OSError as exc:
        raise _named(exc, path, f"cannot create a file in {target.parent}") from None
    with _moved_into_place(tmp, target, path):
        yield tmp
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())


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
    at all; text mode uses newline="" (CSV).  Refuses a path that is not a regular file (see
    check_target); an OSError while writing names path, not the temporary file."""
    path = output_path(path)
    target = check_target(path)
    _ensure_folder(target.parent, path)
    try:
        fd, tmp = _temporary(target)
    except OSError as exc:
        raise _named(exc, path, f"cannot create a file in {target.parent}") from None
    with _moved_into_place(tmp, target, path):
        kwargs = {"newline": ""} if "b" not in mode else {}
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())


@contextlib.contextmanager
def _moved_into_place(tmp, target, path):
    """The temporary file tmp becomes target when the block ends (and the folder is synced); on any
    exception (KeyboardInterrupt included) tmp is removed, target left as it was, and an OSError
    names path, not the temporary file."""
    try:
        yield
        os.replace(tmp, target)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        if isinstance(exc, OSError):
            raise _named(exc, path) from None
        raise
    fsync_dir(target.parent)


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
    """CSV of rows (mappings, any iterable: streamed, never held as one text) with the given
    column order, written atomically."""
    def write(fh):
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(columns)
        for row in rows:
            w.writerow([_cell(row.get(c)) for c in columns])
    return atomic_write(path, write, overwrite=overwrite)


def save_figure(fig, path, overwrite=True, dpi=120):
    """Save a matplotlib figure atomically as PNG (and close it when pyplot made it)."""
    try:
        return atomic_write(path, lambda fh: fig.savefig(fh, format="png", dpi=dpi), mode="wb",
                            overwrite=overwrite)
    finally:
        import sys
        if "matplotlib.pyplot" in sys.modules:
            sys.modules["matplotlib.pyplot"].close(fig)


def existing_outputs(folder, names):
    """The names (in order) that already exist in folder."""
    folder = Path(folder)
    return [n for n in names if (folder / n).exists()]


def prepare_folder(folder, names=(), force=False, subfolders=()):
    """Check, before any computing, that folder can receive the files `names` (which may lie in
    `subfolders`, e.g. "data/x.json"); create it and the subfolders if missing, and remove
    temporary files of those names left by a killed run.  Returns the list of folders created (for
    `remove_if_empty` if the run stops before writing anything).  Raises OutputPathError (an empty
    name, a file, under a file, not creatable, not writable, an output name taken by a folder, a
    device, a FIFO, a socket or a link out of the folder) or OutputExistsError (one of names is
    there and force is false)."""
    if isinstance(folder, str) and not folder.strip():
        raise OutputPathError("the output folder is an empty name; give a folder (. for the "
                              "current one)")
    folder = Path(folder)
    try:
        return _prepare(folder, names, force, subfolders)
    except OSError as exc:                          # e.g. a parent folder that cannot be read
        raise OutputPathError(f"cannot use {folder}: {exc.strerror or exc}") from None


def _prepare(folder, names, force, subfolders):
    if folder.exists() and not folder.is_dir():
        raise OutputPathError(f"{folder} is a file, not a folder")
    for sub in subfolders:
        if (folder / sub).exists() and not (folder / sub).is_dir():
            raise OutputPathError(f"{folder / sub} is a file, not a folder (it must hold outputs)")
    for name in names:
        try:
            check_target(folder / name, folder)
        except NotRegularFileError as exc:
            raise OutputPathError(str(exc)) from None
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
    for target in [folder] + [folder / sub for sub in subfolders]:
        if not target.exists() and target != folder:
            created.append(target)
        try:
            target.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            remove_if_empty(created)
            raise OutputPathError(f"cannot create {target}: {exc.strerror or exc}") from None
        try:                                        # writable? (root ignores mode bits, so try)
            fd, tmp = _temporary(target / "probe")
            os.close(fd)
            os.unlink(tmp)
        except OSError as exc:
            remove_if_empty(created)
            raise OutputPathError(f"cannot write to {target}: {exc.strerror or exc}") from None
    remove_stale_temporaries(folder, names)
    return created


def remove_stale_temporaries(folder, names):
    """Remove temporary files that an earlier, killed run left beside the outputs `names`
    (`.NAME.PID.XXXXXXXX.tmp`, or `.tmp.EXT` from atomic_path, whose process no longer exists);
    return how many were removed."""
    removed = 0
    for name in names:
        where = (Path(folder) / name).parent
        name = Path(name).name
        for tmp in where.glob(f".{glob_escape(name)}.*.tmp*"):
            parts = tmp.name[len(name) + 2:].split(".")
            if len(parts) not in (3, 4) or not parts[0].isdigit() or parts[2] != "tmp" or len(parts[1]) != 8:
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
            else:
                continue                            # this process's own: being written now
            try:
                if tmp.is_file() and not tmp.is_symlink():
                    tmp.unlink()
                    removed += 1
            except OSError:
                pass
    return removed


def glob_escape(name):
    """name with glob's special characters taken literally."""
    import glob
    return glob.escape(name)


def remove_if_empty(folders):
    """Remove the given folders (deepest first) where they are empty; ignore the others."""
    for folder in sorted((Path(f) for f in folders), key=lambda p: len(p.parts), reverse=True):
        try:
            folder.rmdir()
        except OSError:
            pass
