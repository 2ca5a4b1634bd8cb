"""`crankgen compile`: compile the engine and the kernels of every model into the cache, once.

Run by the owner of an installation (for a system-wide install: the administrator), it fills the
installation's own cache folder, which every user then loads read-only; run by a user, it fills
the cache crankgen would use for that user (crankgen.engine.cache)."""

import time


def _cmd_compile(args):
    from ..engine import helper  # noqa: F401  (the modules of the entry points, registered)
    from ..engine.cache import CACHE, READ_ONLY, WHY_READ_ONLY
    from ..engine.build import ENTRIES, done, prepare
    from ..engine.kernels import all_build_items

    items = [f"entry:{e}" for e in ENTRIES] + all_build_items()
    todo = [item for item in items if not done(item)]
    if READ_ONLY:
        print(f"crankgen compile: the cache {CACHE} {WHY_READ_ONLY}: nothing can be kept; "
              "run this command as the owner of the installation, or set CRANKGEN_CACHE_DIR "
              "to a writable folder")
        return 1
    start = time.perf_counter()
    compiled = prepare(todo, quiet=args.quiet)
    others = len(todo) - len(compiled)
    print(f"{len(compiled)} item(s) compiled, {len(items) - len(todo)} already there"
          + (f", {others} compiled meanwhile by another crankgen process" if others else "")
          + f"; cache {CACHE} ({time.perf_counter() - start:.1f} s)")
    return 0
