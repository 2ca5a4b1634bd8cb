"""Compiled engine: the model of model.py / newmark.py compiled with numba for speed.

Split by concern:
- compiled.py: numba compilation, the on-disk cache keyed by the code's hash (read-only and
  home-less installs included), repair of an unreadable cache;
- kernels.py: the generated kernels, compiled one at a time when a model first needs them, and
  tables of their native addresses (calls.py; the engine is compiled once for every model);
- records.py: the named records the engine passes (kernel tables, cases, mesh, scheme, work arrays);
- elements.py: the element loop (gather, end map, the selected families, projection) and per-step outputs;
- banded.py: assembly and banded LU solvers;
- step.py: one Newton step of Newmark or generalized-alpha (decisions shared with newmark.py
  through newton.py; the schemes' coefficients: crankgen.time_scheme);
- march.py: Batch (cases packed as records) and march, lock-step batches on every core;
- motor.py: the motor-driven crank (its angle a DOF): the bordered step and its march;
- shooting.py: the revolution map and its exact linearization (in the state and, optionally, a parameter);
- borrow.py: arrays without a memory owner for the hot loops (no atomic reference counting).
The NumPy implementation (model.py, newmark.py) stays the reference: tests check that both give
the same numbers and the same iteration counts.
"""

from .banded import (KB_FIXED, assemble_band, assemble_band_newmark, assemble_fixed, assemble_vector,  # noqa: F401
                     band_factor, band_lu_solve, band_matmul, band_solve, factor_fixed, solve_fixed)
from .compiled import CACHE, CODE_HASH, KERNELS_HASH, is_warm  # noqa: F401
from .elements import FULL, NEWMARK, RESIDUAL, element_terms  # noqa: F401
from .motor import march_motor  # noqa: F401  (registers the entry point `motor`)
from .march import Batch, MarchResult, join_state, march, march_state, split_state  # noqa: F401
from .records import Work, new_work as make_work  # noqa: F401
from .shooting import Revolution, revolution, shoot  # noqa: F401
from .step import (DIVERGED, NOT_CONVERGED, NOT_FINITE, OK, SINGULAR, STATUS_TEXT, TOO_LARGE,  # noqa: F401
                   initial_acceleration, newmark_step)
