"""The lock that keeps one sweep at a time on a checkpoint: an exclusive flock on a sidecar file,
CHECKPOINT.lock, which holds the owner's process id.

Taken without waiting: a second sweep on the same checkpoint, in any process, is refused at once
(CheckpointError) with that process id.  The file is removed at release; one left by a killed
sweep is unlocked (the kernel drops a dead process's flock) and the next sweep takes it over.
A file system without flock runs unlocked.  HELD lists the file descriptors of the locks and
checkpoints this process holds, so that a forked pool worker closes its copies
(pool_workers.worker_init) and no worker keeps a lock alive.
"""

import errno
import os

try:
    import fcntl
except ImportError:           # not on Windows: checkpoints are used unlocked there
    fcntl = None

from ..errors import CrankgenError
from ..results.io import check_target, open_regular

__all__ = ["CheckpointError", "SidecarLock", "HELD", "close_held"]

# file descriptors of the checkpoints and locks this process holds
HELD = set()


class CheckpointError(CrankgenError, ValueError):
    """A checkpoint that cannot be used: not a crankgen sweep checkpoint, another format version,
    or in use by another sweep.  The message names the file."""


def close_held():
    """Close this process's copies of the held checkpoints and locks (in a forked worker)."""
    for fd in list(HELD):
        try:
            os.close(fd)
        except OSError:
            pass
    HELD.clear()


class SidecarLock:
    """Exclusive flock on the sidecar file PATH.lock holding the owner's pid: acquire() takes it
    without waiting (CheckpointError naming the owner's process id when another process holds it),
    release() removes the file and lets it go."""

    def __init__(self, checkpoint):
        self.checkpoint = checkpoint
        self.path = checkpoint.with_name(checkpoint.name + ".lock")
        self.fd = None

    def acquire(self):
        for _ in range(20):
            fd = open_regular(check_target(self.path), os.O_RDWR | os.O_CREAT, follow=False)
            try:
                if fcntl is None:
                    raise OSError(errno.ENOTSUP, "no flock")
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                try:
                    owner = os.pread(fd, 64, 0).decode(errors="replace").strip() or "unknown"
                finally:
                    os.close(fd)
                raise CheckpointError(
                    f"checkpoint {self.checkpoint} is in use by another sweep (process {owner}, "
                    f"lock {self.path}); wait for it to finish, or choose another checkpoint"
                ) from None
            except OSError:                     # a file system without flock: run unlocked
                pass
            try:
                same = os.path.samestat(os.stat(self.path), os.fstat(fd))
            except FileNotFoundError:
                same = False
            if not same:                        # removed by its owner as we locked it: again
                os.close(fd)
                continue
            os.ftruncate(fd, 0)
            os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
            self.fd = fd
            HELD.add(fd)
            return self
        raise CheckpointError(f"could not lock checkpoint {self.checkpoint} ({self.path} keeps "
                              "changing)")

    def release(self):
        if self.fd is None:
            return
        try:
            if os.path.samestat(os.stat(self.path), os.fstat(self.fd)):
                os.unlink(self.path)
        except OSError:
            pass
        HELD.discard(self.fd)
        os.close(self.fd)
        self.fd = None
