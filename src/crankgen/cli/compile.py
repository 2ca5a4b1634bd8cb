"""`crankgen compile`: compile the engine and the kernels of every model into the cache, once.

Run by the owner of an installation (for a system-wide install: the administrator), it fills the
installation's own cache folder, which every user then loads read-only; run by a user, it fills
the cache crankgen would use for that user (crankgen.compile_cache)."""

import time


def _cmd_compile(args):
    from ..compile_cache import CACHE, READ_ONLY
    from ..engine.build import ENTRIES, done, prepare
    from ..engine.kernels import all_build_items

    items = [f"entry:{e}" for e in ENTRIES] + all_build_items()
    todo = [item for item in items if not done(item)]
    if READ_ONLY:
        print(f"crankgen compile: the cache {CACHE} is read-only for this user: nothing can be kept; "
              "run this command as the owner of the installation, or set CRANKGEN_CACHE_DIR")
        return 1
    start = time.perf_counter()
    prepare(todo, quiet=args.quiet)
    print(f"{len(todo)} item(s) compiled, {len(items) - len(todo)} already there; "
          f"cache {CACHE} ({time.perf_counter() - start:.1f} s)")
    return 0
