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
- coordinates.py: the declared co-ordinates of a driven motion (a motor's crank angle, ...): their
  equations, the kinematics from the state, the border of the step's iteration matrix;
- shooting.py: the revolution map and its exact linearization (in the state and, optionally, a parameter);
- borrow.py: arrays without a memory owner for the hot loops (no atomic reference counting);
- build.py: compile ahead (entries and kernels, under file locks, with a helper process: helper.py).
Importing any module of the engine imports them all (the entry points register themselves with build.py).
The NumPy implementation (crankgen.discrete: system.py, newmark.py) stays the reference: tests check that both give
the same numbers and the same iteration counts.
"""


from .banded import (FIXED_WIDTHS, KB_FIXED, assemble_band, assemble_band_newmark, assemble_fixed, assemble_vector,  # noqa: F401
                     band_factor, band_lu_solve, band_matmul, band_solve, factor_fixed, fixed_width, solve_fixed,
                     solve_fixed_columns)
from .compiled import CACHE, CODE_HASH, KERNELS_HASH, is_warm  # noqa: F401
from .coordinates import hermite  # noqa: F401
from .elements import FULL, NEWMARK, RESIDUAL, element_terms  # noqa: F401
from .batch import Batch, MarchResult, join_state, march, march_state, split_state  # noqa: F401  (entry `march`)
from .records import Work, new_work as make_work  # noqa: F401
from .shooting import Revolution, revolution, shoot  # noqa: F401  (registers the entry point `revolution`)
from .step import (DIVERGED, NOT_CONVERGED, NOT_FINITE, OK, SINGULAR, STATUS_TEXT, TOO_LARGE,  # noqa: F401
                   initial_acceleration, newmark_step)
