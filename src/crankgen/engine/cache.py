"""Where the compiled engine is cached, keyed by a hash of the code it compiles (no numba import).

CODE_HASH covers the generated kernels' specification (generated/schema.py KERNELS_HASH), the
source of every module the engine compiles (crankgen/engine/*.py, crankgen/discrete/newton.py) and the
versions of Python, numba and llvmlite: after `make derive`, an edit of the engine or an upgrade
of numba, the cache folder changes, nothing stale runs, and the new compilation shows its progress
like any first run.

The folder (`CACHE`, named numba-<CODE_HASH>) is the first usable of:
1. $CRANKGEN_CACHE_DIR/numba-<hash>, when that variable is set;
2. `__pycache__/numba-<hash>` inside the installed package: one cache for every user of an
   install, written by whoever may write there (an administrator's `crankgen compile` fills it);
3. the user's own cache, $XDG_CACHE_HOME/crankgen or ~/.cache/crankgen (when 2 is read-only and
   was not filled, and a home exists);
4. folder 2 again, read-only: what was compiled there is loaded, the rest is compiled in memory
   for this run only (`READ_ONLY`; a note says how to make it permanent).
No step needs a home directory or a writable one.  `is_warm()` tells, without importing numba,
whether this code's engine has been compiled in CACHE already.
"""

import hashlib
import os
import re
import sys
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent.parent          # crankgen/


def _kernels_hash():
    """KERNELS_HASH of generated/schema.py, read from its text."""
    from importlib import resources
    text = resources.files("crankgen._generated").joinpath("schema.py").read_text()
    return re.search(r"^KERNELS_HASH = '([0-9a-f]+)'", text, re.M).group(1)


def _compiler_versions():
    """The Python, numba and llvmlite versions (from the installed packages' metadata: no numba
    import): compiled code is only valid for the compiler that made it."""
    from importlib import metadata
    out = [f"python {sys.version_info[0]}.{sys.version_info[1]}"]
    for name in ("numba", "llvmlite"):
        try:
            out.append(f"{name} {metadata.version(name)}")
        except metadata.PackageNotFoundError:
            out.append(f"{name} unknown")
    return "; ".join(out)


def _code_hash():
    h = hashlib.sha256(_kernels_hash().encode())
    h.update(_compiler_versions().encode())
    for path in sorted((_PACKAGE / "engine").glob("*.py")) + [_PACKAGE / "discrete" / "newton.py"]:
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


CODE_HASH = _code_hash()


def _unusable(folder):
    """None when compiled code can be kept in folder (created if needed), else what is in the way,
    in words: "is a file", "lies under /x, a dangling symbolic link to /y", "is read-only", ..."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe = folder / f".probe-{os.getpid()}"
        probe.write_bytes(b"")
        probe.unlink()
        return None
    except OSError as exc:
        return _obstacle(folder, exc)


def _obstacle(folder, exc):
    path = folder
    while not os.path.lexists(path) and path != path.parent:
        path = path.parent
    where = "is" if path == folder else f"lies under {path}, which is"
    if os.path.islink(path) and not os.path.exists(path):
        return f"{where} a dangling symbolic link (to {os.readlink(path)})"
    if os.path.lexists(path) and not os.path.isdir(path):
        return f"{where} a file, not a folder"
    if isinstance(exc, PermissionError) or exc.errno in (13, 30):      # EACCES, EROFS
        return "is read-only" if path == folder else f"cannot be created in {path}, which is read-only"
    return f"cannot be used ({exc.strerror or exc})"


def _writable(folder):
    return _unusable(folder) is None


def _user_cache():
    """The user's cache root, or None without a usable home."""
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg:
        return Path(xdg) / "crankgen"
    try:
        home = Path.home()
    except (RuntimeError, KeyError, OSError):
        return None
    return home / ".cache" / "crankgen" if str(home) not in ("", "/") else None


def cache_folder():
    """(folder, read_only) of this code's compiled engine (see the module docstring)."""
    name = f"numba-{CODE_HASH}"
    env = os.environ.get("CRANKGEN_CACHE_DIR")
    if env:
        folder = Path(env) / name
        return folder, not _writable(folder)
    shared = _PACKAGE / "__pycache__" / name
    if _writable(shared):
        return shared, False
    if (shared / "kernels" / "entry-march.ok").exists():
        return shared, True
    user = _user_cache()
    if user is not None and _writable(user / name):
        return user / name, False
    return shared, True


CACHE, READ_ONLY = cache_folder()
# what makes a read-only cache so, in words ("is read-only", "is a file, not a folder", "lies
# under /x, which is a dangling symbolic link (to /y)")
WHY_READ_ONLY = (_unusable(CACHE) or "is read-only") if READ_ONLY else None


def is_warm():
    """True once this code's engine (its marching entry point) has been compiled in CACHE."""
    return kernel_mark("entry-march").exists()


READ_ONLY_NOTE = (f"crankgen: the compiled-code cache {CACHE} {WHY_READ_ONLY or 'is read-only'}: compiling in memory for "
                  "this run (set CRANKGEN_CACHE_DIR to a writable folder, or have the owner of the "
                  "installation run `crankgen compile`, to keep the compiled code)")
_announced = []
QUIET = []                 # set by the command line's --quiet: no compilation progress either


def set_quiet(quiet=True):
    QUIET[:] = [True] if quiet else []


def _say(text):
    try:
        print(text, file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass


def announce():
    """Say once per process, on stderr, that compiled code cannot be kept (a read-only cache that
    lacks this code's engine); the compilation itself reports its progress (engine/build.py)."""
    if not _announced and READ_ONLY and not is_warm():
        _announced.append(True)
        _say(READ_ONLY_NOTE)


def kernel_mark(name):
    """Marker file of a kernel compiled into CACHE (no numba needed to ask whether it is there)."""
    return CACHE / "kernels" / f"{name}.ok"


def kernel_is_cached(name):
    return kernel_mark(name).exists()


def mark_kernel(name):
    if READ_ONLY:
        return
    try:
        path = kernel_mark(name)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.touch()
    except OSError:
        pass
