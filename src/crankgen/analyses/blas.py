"""One BLAS thread for crankgen's small dense problems: the eigenvalues of a monodromy matrix
(shooting's Floquet multipliers, the continuation's test functions), bordered and Newton solves of
size up to a few hundred, the frozen linkage's eigenproblem.  A multi-threaded OpenBLAS spends far
longer on them than one thread: measured on this project's 2-core machine with the other core
busy, eigenvalues of 98 x 98, 147 x 147 and 196 x 196 matrices took 84, 54 and 1030 ms on two
threads against 9, 21 and 42 ms on one (the threads wait on each other).  The context manager
sets NumPy's bundled OpenBLAS to one thread and restores the previous count when the last block
closes; where that library is not found it does nothing."""

import contextlib
import ctypes
import glob
import os
import threading

_LIB = None


def _lib():
    global _LIB
    if _LIB is None:
        _LIB = False
        import numpy
        root = os.path.dirname(os.path.dirname(numpy.__file__))
        for path in glob.glob(os.path.join(root, "numpy.libs", "*openblas*")):
            try:
                lib = ctypes.CDLL(path)
            except OSError:
                continue
            for get, put in (("scipy_openblas_get_num_threads64_", "scipy_openblas_set_num_threads64_"),
                             ("openblas_get_num_threads64_", "openblas_set_num_threads64_"),
                             ("openblas_get_num_threads", "openblas_set_num_threads")):
                if hasattr(lib, get) and hasattr(lib, put):
                    getter, setter = getattr(lib, get), getattr(lib, put)
                    getter.restype = ctypes.c_int
                    setter.argtypes = [ctypes.c_int]
                    _LIB = (getter, setter)
                    break
            if _LIB:
                break
    return _LIB


_LOCK = threading.Lock()
_HELD = [0, None]            # how many single_thread blocks are open (in any thread), the count before


@contextlib.contextmanager
def single_thread():
    """One BLAS thread while any such block is open in any thread (continuations run side by side
    on threads: crankgen.experiments.threads), the previous count restored when the last closes."""
    lib = _lib()
    if not lib:
        yield
        return
    getter, setter = lib
    with _LOCK:
        if _HELD[0] == 0:
            _HELD[1] = getter()
            setter(1)
        _HELD[0] += 1
    try:
        yield
    finally:
        with _LOCK:
            _HELD[0] -= 1
            if _HELD[0] == 0:
                setter(_HELD[1])
