"""Process pools whose workers die with the sweep that made them (the command line's --workers):
on Linux the kernel kills a worker whose parent died (prctl PR_SET_PDEATHSIG), and everywhere a
watchdog thread in the worker checks that its parent is still there.  A worker leaves Ctrl-C to
the parent and closes the checkpoint and lock files it inherited."""

import os
import threading

from .file_lock import close_held

__all__ = ["worker_init"]

PR_SET_PDEATHSIG = 1


def worker_init(parent, interval=0.5):
    """Initializer of the command line's pool workers: the worker dies with the process that
    made the pool (`parent`, its pid), even if that one is killed with SIGKILL.  On Linux the
    kernel sends the worker SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG); everywhere, a
    watchdog thread checks every `interval` seconds that the parent is still there and ends the
    worker when it is not.  Ctrl-C is left to the parent (which shuts the pool down), and the
    checkpoint and lock files the parent held when it forked the worker are closed in it."""
    import signal

    close_held()
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
