"""Independent pieces of a reproduction step side by side on threads.

The continuations of a step (one per model and slenderness, one per mechanism and model) share
nothing; their compiled revolution maps release the GIL, so two of them on two cores take little
more than the longer one.  Each piece's result is the same as when run alone (every number of
`crankgen reproduce` is unchanged); its log lines interleave with the other's, each naming its
piece.  When the step is interrupted (Ctrl-C) or a piece fails, the `stop` event is set: a piece
still running ends at its next log line (Context.log raises Stopped in it), and the interruption
or the failure goes on once every piece has ended."""

import threading
from concurrent.futures import ThreadPoolExecutor


class Stopped(BaseException):
    """Raised in a piece on a worker thread when its step was interrupted or another piece failed."""


def stopping(stop):
    """Raise Stopped when `stop` is set and this is a piece's thread (never on the main thread)."""
    if stop is not None and stop.is_set() and threading.current_thread() is not threading.main_thread():
        raise Stopped("the step was interrupted")


def map_in_threads(fn, items, workers=None, stop=None):
    """[fn(item) for item in items], on up to `workers` threads (default: the cores this process may
    use, crankgen.engine.threads); in order; the first exception raised is raised again, after the
    other pieces have ended (`stop`, a threading.Event, is set for them to see)."""
    from ..engine.batch import threads

    items = list(items)
    if stop is not None:
        stop.clear()                # a step's own pieces: an earlier step's stop does not carry over
    workers = min(len(items), threads() if workers is None else int(workers))
    if workers <= 1:
        return [fn(item) for item in items]
    pool = ThreadPoolExecutor(workers, thread_name_prefix="crankgen-step")
    futures = [pool.submit(fn, item) for item in items]
    try:
        return [f.result() for f in futures]
    except BaseException:
        if stop is not None:
            stop.set()
        for f in futures:
            f.cancel()
        raise
    finally:
        pool.shutdown(wait=True)
