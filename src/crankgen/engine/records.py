"""Named records the compiled engine passes around in place of positional vectors.

- RUN: one case's scalars (structured dtype: a record per case, fields read by name in compiled
  code): crank a*, guide offset, crank speed Omega*, time step dt, eps, the Newmark scheme code
  (newton.SCHEMES) and whether the one-pass scheme iterates with the printed eq. (37) matrices.
- A case's model is two arrays besides: `families` (variant index per declared term family, -1
  when absent: crankgen.ingredients) and `coef` (the kernels' coefficient vector).
- Work: the scratch arrays of one case's Newmark steps (allocated once per case and reused).
"""

from collections import namedtuple

import numpy as np

from .banded import KB_FIXED
from .compiled import jit

RUN = np.dtype([("a", np.float64), ("offset", np.float64), ("omega", np.float64), ("dt", np.float64),
                ("eps", np.float64), ("scheme", np.int64), ("printed", np.bool_)])

Work = namedtuple("Work", [
    "rE", "SE", "KE", "CE", "ME",       # element residuals, iteration and tangent matrices
    "R", "rhs",                         # assembled residual, right-hand side / solution (N + 5, 1)
    "W", "piv", "ext",                  # pivoted band LU storage
    "F", "diag",                        # fixed-bandwidth LU storage
    "kin",                              # (a, theta, thetad, phi, phid, phidd)
    "q", "qd", "qdd", "geo",            # one element's nodal vectors and (l, x0)
])


@jit
def make_work(n, N, kb):
    """Work arrays for n elements, N reduced DOFs, bandwidth kb."""
    return Work(np.zeros((n, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6)), np.zeros((n, 6, 6)),
                np.zeros((n, 6, 6)), np.zeros(N), np.zeros((N + KB_FIXED, 1)),
                np.zeros((N, 3 * kb + 1)), np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64),
                np.zeros((N + KB_FIXED, 2 * KB_FIXED + 1)), np.zeros(N), np.zeros(6),
                np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(2))
