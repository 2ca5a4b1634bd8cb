"""Newton-Newmark control: the schemes, their constants and the decisions of the iteration, in one
place for the NumPy reference (newmark.py) and the compiled engine (engine/step.py).

The functions take and return scalars only, so that the engine compiles the very same code with
numba (engine/compiled.py) and the reference calls it as plain Python.

Schemes (see newmark.py for the full description):
- "newton" (default): Newton on the exact tangent; the factorization of the first iteration is
  reused while the increments contract at least REFRESH_RATE-fold per iteration; besides the
  increment test the iteration stops when the estimated remaining error theta/(1 - theta) |delta|
  is below ESTIMATE_FRACTION of the tolerance (theta from two increments of the same kind).
  Safeguards: when a reused-factorization iteration stalls (theta > REFRESH_RATE) the tangent is
  refreshed; when it diverges (theta >= 1) its update is rejected (the iterate goes back to where
  it was) and the rest of the step runs as full Newton; when two fresh-tangent iterations in a
  row contract slowly, the rest of the step runs as full Newton too.  From a rejected update on,
  the step follows the very iterates "full-newton" would, so "newton" does not give up where
  "full-newton" converges.
- "one-pass": the paper's eqs. (34)-(39), one linear solve per step;
- "full-newton": a fresh tangent at every iteration.
"""

SCHEMES = ("newton", "one-pass", "full-newton")
NEWTON, ONE_PASS, FULL_NEWTON = 0, 1, 2
REFRESH_RATE = 0.1          # "newton" refreshes the iteration matrix when theta_k exceeds this
ESTIMATE_FRACTION = 0.1     # ... and stops when its error estimate is below this fraction of tol
HISTORY = 4                 # displacements kept for the starting guess (quartic extrapolation)
# A converged step whose displacements (units of L; rotations in rad) exceed this has diverged,
# whatever the scheme: the models are built for deflections of a fraction of the rod length.
DIVERGED = 10.0
DIVERGED_TEXT = "diverged: a displacement beyond 10 rod lengths (or a rotation beyond 10 rad)"


def extrapolation_weight(n_prev, k):
    """Weight of the displacement k steps back (k = 0: the current one) in the polynomial
    extrapolation one step ahead through the current and n_prev previous displacements
    (n_prev = 1 .. HISTORY: linear to quartic)."""
    if n_prev == 1:
        return (2.0, -1.0)[k]
    if n_prev == 2:
        return (3.0, -3.0, 1.0)[k]
    if n_prev == 3:
        return (4.0, -6.0, 4.0, -1.0)[k]
    return (5.0, -10.0, 10.0, -5.0, 1.0)[k]


def converged(increment, size, tol):
    """The increment test: largest scaled increment below tol (1 + largest scaled displacement)."""
    return increment <= tol * (1.0 + size)


def next_iteration(scheme, it, increment, previous, size, tol, refresh, reused_before, full):
    """Decision after iteration `it` (1-based) whose largest scaled increment is `increment`
    (`previous`: that of the last accepted iteration; `size`: largest scaled displacement).
    refresh: this iteration factorized a fresh tangent; reused_before: the previous one reused a
    factorization; full: the step already fell back to full Newton.
    Returns (done, reject, refresh_next, reused_before_next, full_next); reject: undo this
    iteration's update before going on."""
    limit = tol * (1.0 + size)
    if scheme == ONE_PASS or increment <= limit:
        return True, False, refresh, reused_before, full
    if scheme == FULL_NEWTON or full:
        return False, False, True, False, full
    if it == 1:
        return False, False, False, False, full
    rate = increment / previous
    if not refresh and rate >= 1.0:
        # a reused factorization that diverges: undo its update, continue as full Newton
        return False, True, True, False, True
    same_kind = refresh != reused_before
    if same_kind and rate < 1.0 and rate / (1.0 - rate) * increment <= ESTIMATE_FRACTION * limit:
        return True, False, refresh, reused_before, full
    if refresh and same_kind and rate > REFRESH_RATE:
        # two fresh-tangent iterations in a row that do not contract fast: Newton itself is in
        # trouble (large step, strong non-linearity); reusing factorizations would only slow it
        return False, False, True, False, True
    return False, False, rate > REFRESH_RATE, not refresh, full
