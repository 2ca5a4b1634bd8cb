"""Where the compiled engine is cached, keyed by a hash of the code it compiles (no numba import).

CODE_HASH covers the generated kernels' specification (generated/dispatch.py KERNELS_HASH) and the
source of every module the engine compiles (crankgen/engine/*.py, crankgen/newton.py): after
`make derive` or an edit of the engine, the cache folder changes and nothing stale runs.  The
folder is, in order of preference, $CRANKGEN_CACHE_DIR/numba-<hash>, `__pycache__/numba-<hash>`
inside the installed package, or ~/.cache/crankgen/numba-<hash> when the package is read-only.
`is_warm()` tells, without importing numba, whether this code has been compiled here already.
"""

import hashlib
import os
import re
import sys
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent
_WARM_MARK = "compiled.ok"


def _kernels_hash():
    """KERNELS_HASH of generated/dispatch.py, read from its text (the module itself is large)."""
    from importlib import resources
    text = resources.files("crankgen._generated").joinpath("dispatch.py").read_text()
    return re.search(r"^KERNELS_HASH = '([0-9a-f]+)'", text, re.M).group(1)


def _code_hash():
    h = hashlib.sha256(_kernels_hash().encode())
    for path in sorted((_PACKAGE / "engine").glob("*.py")) + [_PACKAGE / "newton.py"]:
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


CODE_HASH = _code_hash()


def _writable(folder):
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe = folder / f".probe-{os.getpid()}"
        probe.write_bytes(b"")
        probe.unlink()
        return True
    except OSError:
        return False


def cache_folder():
    """Folder of this code's compiled engine (see the module docstring)."""
    env = os.environ.get("CRANKGEN_CACHE_DIR")
    if env:
        return Path(env) / f"numba-{CODE_HASH}"
    inside = _PACKAGE / "__pycache__" / f"numba-{CODE_HASH}"
    if _writable(inside):
        return inside
    return Path.home() / ".cache" / "crankgen" / f"numba-{CODE_HASH}"


CACHE = cache_folder()


def is_warm():
    """True once a run has completed with this code's compiled engine (nothing left to compile)."""
    return (CACHE / _WARM_MARK).exists()


COLD_START = ("crankgen: compiling the engine for this machine, once (about 1-3 minutes on 2 cores; "
              "later runs start at once)")
_announced = []


def announce():
    """Print COLD_START to stderr, once per process, if the engine is not compiled here yet."""
    if not _announced and not is_warm():
        _announced.append(True)
        print(COLD_START, file=sys.stderr, flush=True)


def mark_warm():
    try:
        (CACHE / _WARM_MARK).touch()
    except OSError:
        pass
