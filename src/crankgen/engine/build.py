"""Compile what a run needs before it starts: its kernels and the engine's entry points, on two
processes, shared safely with any other process compiling at the same time.

The work is a list of items: a kernel in one calling variant ("kernel:<kind>:<name>") or an entry
point of the engine ("entry:march", "entry:revolution"; the engine is compiled once for every
model: it takes the kernels as tables of native addresses, engine/kernels.py and calls.py).  An item done
once on this machine has a marker in the cache folder and is only loaded afterwards.

Items are processed under a per-item file lock taken without waiting: a process compiles the
items whose lock it gets and leaves the others to whoever holds them, then waits for those.  This
process walks the list from the front while a helper process (`python -m crankgen.engine.build
ITEM ...`) walks it from the back, so a cold start compiles on two cores; two runs started at once
on a cold cache split the work the same way instead of both compiling everything.  Where the
cache folder is read-only, everything is compiled here, in memory.  $CRANKGEN_BUILD_LOG, when
set, receives a line per item compiled (by any of the processes); CRANKGEN_BUILD_PROCESSES=1
compiles in this process only.
"""

import contextlib
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from . import cache
from .cache import READ_ONLY

try:
    import fcntl
except ImportError:           # pragma: no cover - not on Linux/macOS: no helper, no locks
    fcntl = None

ENTRIES = ("march", "revolution")
# name -> the function that compiles that entry point: registered by the module defining it
# (entry_point), so that this module needs none of them
_ENTRY_COMPILERS = {}


def entry_point(name):
    """Register the decorated function as the compiler of the engine's entry point `name`."""
    def register(compile_entry):
        _ENTRY_COMPILERS[name] = compile_entry
        return compile_entry
    return register


def label(item):
    """A build item as a reader would name it."""
    kind, rest = item.split(":", 1)
    if kind == "entry":
        return f"the engine's {rest} loop"
    variant, name = rest.split(":", 1)
    return f"kernel {name}{variant}" if variant.startswith("_") else f"{variant} {name}"


def _marker(item):
    return cache.kernel_mark(item.replace(":", "-"))


def done(item):
    return _marker(item).exists()


def _mark(item):
    cache.mark_kernel(item.replace(":", "-"))


@contextlib.contextmanager
def _lock(item, wait):
    """The item's lock: yields True when held (False: another process holds it and wait=False)."""
    if fcntl is None or READ_ONLY:
        yield True
        return
    path = cache.CACHE / "locks" / f"{item.replace(':', '-')}.lock"
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fh = open(path, "a")
    except OSError:
        yield True
        return
    try:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            yield False
            return
        try:
            yield True
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)
    finally:
        fh.close()


def compile_item(item):
    """Compile (or load) one item in this process."""
    from . import kernels
    kind, rest = item.split(":", 1)
    if kind == "kernel":
        variant, name = rest.split(":", 1)
        kernels.compiled(variant, name)
    else:
        _compile_entry(rest)


def _compile_entry(name):
    """Compile an engine entry point with the compiler its module registered (the module is
    imported by whoever asks for the entry: a Batch, `crankgen compile`, the helper process)."""
    if name not in _ENTRY_COMPILERS:
        raise RuntimeError(f"no compiler registered for the engine entry {name!r}: import its module first")
    _ENTRY_COMPILERS[name]()


def _run(items, progress, start, compiled=None):
    """One pass over items: compile those whose lock this process gets (appended to `compiled`);
    return the others."""
    left = []
    for item in items:
        if done(item):
            continue
        with _lock(item, wait=False) as held:
            if not held:
                left.append(item)
                continue
            if done(item):
                continue
            if progress is not None:
                progress(item, start)
            compile_item(item)
            _mark(item)
            _log(item)
            _log(item, "CRANKGEN_BUILD_REPORT")
            if compiled is not None:
                compiled.append(item)
    return left


def _log(item, variable="CRANKGEN_BUILD_LOG"):
    """Append the item to $CRANKGEN_BUILD_LOG, when set (which process compiled what)."""
    path = os.environ.get(variable)
    if path:
        try:
            with open(path, "a") as fh:
                fh.write(f"{item}\n")
        except OSError:
            pass


def _helper(items, report):
    """Start the helper process on the reversed list (None when it cannot help); it lists the
    items it compiled in the file `report`."""
    if READ_ONLY or fcntl is None or len(items) < 2 or (os.cpu_count() or 1) < 2 \
            or os.environ.get("CRANKGEN_BUILD_PROCESSES") == "1":
        return None
    env = dict(os.environ, CRANKGEN_CACHE_DIR=str(cache.CACHE.parent),
               CRANKGEN_BUILD_PARENT=str(os.getpid()), CRANKGEN_BUILD_REPORT=str(report))
    try:
        return subprocess.Popen([sys.executable, "-m", "crankgen.engine.helper", *reversed(items)],
                                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, env=env, start_new_session=False)
    except OSError:
        return None


def _say(text):
    try:
        print(text, file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass


def _wait_for(left, todo, quiet, start, every=0.5):
    """Wait until the items other processes hold are done, saying how far the compilation is."""
    shown = None
    while True:
        pending = [item for item in left if not done(item)]
        if not pending or not any(_held(item) for item in pending):
            return
        finished = sum(done(item) for item in todo)
        if not quiet and finished != shown:
            shown = finished
            _say(f"crankgen: compiling: {finished}/{len(todo)} done ({time.perf_counter() - start:.0f} s; "
                 f"the rest on another process)")
        time.sleep(every)


def _held(item):
    """True while another process holds the item's lock."""
    with _lock(item, wait=False) as held:
        return not held


def prepare(items, quiet=False):
    """Compile every item not done yet (module docstring), with progress lines on stderr.
    Returns the items this process and its helper compiled (not those another run compiled
    meanwhile, nor those done before)."""
    from numba.core import config
    if config.DISABLE_JIT:                        # plain Python: nothing to compile
        return []
    quiet = quiet or bool(cache.QUIET)
    todo = [item for item in items if not done(item)]
    if not todo:
        return []
    start = time.perf_counter()
    count, compiled = [0], []
    with tempfile.TemporaryDirectory(prefix="crankgen-build-") as folder:
        _prepare(todo, quiet, start, count, compiled, Path(folder) / "helper.txt")
    return compiled


def _prepare(todo, quiet, start, count, compiled, report):

    def progress(item, t0):
        count[0] += 1
        if not quiet:
            finished = sum(done(i) for i in todo)
            _say(f"crankgen: compiling {label(item)} ({finished}/{len(todo)} done, "
                 f"{time.perf_counter() - t0:.0f} s)")
    helper = _helper(todo, report)
    if not quiet:
        _say(f"crankgen: compiling {len(todo)} item(s) for this machine, once (the engine and the "
             f"model's kernels, on {2 if helper else 1} process(es); later runs load them)")
    try:
        left = _run(todo, progress, start, compiled)
        _wait_for(left, todo, quiet, start)
        for item in left:                         # held by another process: wait for it
            with _lock(item, wait=True):
                pass
            if not done(item):                    # that process stopped without finishing
                compile_item(item)
                _mark(item)
                _log(item)
                compiled.append(item)
    finally:
        if helper is not None:
            try:
                helper.wait(timeout=600)
            except subprocess.TimeoutExpired:
                helper.kill()
            try:
                compiled.extend(line for line in report.read_text().split() if line in todo)
            except OSError:
                pass
    if not quiet:
        _say(f"crankgen: compiled in {time.perf_counter() - start:.1f} s")


def _die_with_parent():
    """Linux: this helper gets SIGTERM when the process that started it dies."""
    parent = int(os.environ.get("CRANKGEN_BUILD_PARENT", "0"))
    try:
        import ctypes
        import signal
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGTERM)          # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
    if parent and os.getppid() != parent:     # the parent died before prctl took effect
        sys.exit(0)


def main(argv=None):
    _die_with_parent()
    items = sys.argv[1:] if argv is None else argv
    _run(items, None, time.perf_counter())
    return 0

