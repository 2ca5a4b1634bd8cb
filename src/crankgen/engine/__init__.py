"""Compiled engine: the discrete system of crankgen.discrete (system.py, newmark.py) compiled with numba for speed.

Split by concern:
- cache.py: where compiled code is kept, keyed by the code's hash (no numba import);
- compiled.py: numba compilation, the on-disk cache keyed by the code's hash (read-only and
  home-less installs included), repair of an unreadable cache;
- kernels.py: the generated kernels, compiled one at a time when a model first needs them, and
  tables of their native addresses (calls.py; the engine is compiled once for every model);
- records.py: the named records the engine passes (kernel tables, cases, mesh, scheme, work arrays);
- elements.py: the element loop (gather, end map, the selected families, projection) and per-step outputs;
- banded.py: assembly and banded LU solvers;
- step.py: one Newton step of Newmark or generalized-alpha (decisions shared with newmark.py
  through newton.py; the schemes' coefficients: crankgen.discrete.time_scheme);
- batch.py: Batch (cases packed as records) and march, lock-step batches on every core;
- motor.py: the motor-driven crank (its angle a DOF): the bordered step and its march;
- shooting.py: the revolution map and its exact linearization (in the state and, optionally, a parameter);
- borrow.py: arrays without a memory owner for the hot loops (no atomic reference counting);
- build.py: compile ahead (entries and kernels, under file locks, with a helper process: helper.py).
The names below load their module on first use (PEP 562): `crankgen.engine.cache` needs no numba.
The NumPy implementation (crankgen.discrete: system.py, newmark.py) stays the reference: tests check that both give
the same numbers and the same iteration counts.
"""

from importlib import import_module

# public name -> the engine module that defines it
_NAMES = {
    "banded": ("KB_FIXED", "assemble_band", "assemble_band_newmark", "assemble_fixed", "assemble_vector",
               "band_factor", "band_lu_solve", "band_matmul", "band_solve", "factor_fixed", "solve_fixed"),
    "compiled": ("CACHE", "CODE_HASH", "KERNELS_HASH", "is_warm"),
    "elements": ("FULL", "NEWMARK", "RESIDUAL", "element_terms"),
    "motor": ("march_motor",),
    "batch": ("Batch", "MarchResult", "join_state", "march", "march_state", "split_state"),
    "records": ("Work", "make_work"),
    "shooting": ("Revolution", "revolution", "shoot"),
    "step": ("DIVERGED", "NOT_CONVERGED", "NOT_FINITE", "OK", "SINGULAR", "STATUS_TEXT", "TOO_LARGE",
             "initial_acceleration", "newmark_step"),
}
_WHERE = {name: module for module, names in _NAMES.items() for name in names}
_ALIASES = {"make_work": "new_work"}          # engine.make_work: records.new_work (Python-side)
__all__ = sorted(_WHERE)


def __getattr__(name):
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(f".{module}", __name__), _ALIASES.get(name, name))
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
