"""The warnings crankgen gives once per call, and quiet(): a call that warned for all its parts
(a sweep, for its cases) runs the parts quietly.

- StepWarning (crankgen.discrete.time_scheme): a run's step leaves a mode of the rod unresolved and the
  time scheme does not damp it;
- BeyondTheoryWarning (crankgen.analyses.theory): a response leaves the range of the theory.
The command line reports the range of the theory in its own lines and files, and silences the
second."""

import contextlib
import contextvars
import warnings

_QUIET = contextvars.ContextVar("crankgen_quiet_warnings", default=())


class StepWarning(UserWarning):
    """A run's step leaves a mode of the rod unresolved and the time scheme does not damp it."""


class BeyondTheoryWarning(UserWarning):
    """A response leaves the range of the theory (crankgen.analyses.theory)."""


@contextlib.contextmanager
def quiet(*categories):
    """No warning of these categories (default: both) from crankgen inside."""
    token = _QUIET.set(tuple(_QUIET.get()) + (categories or (StepWarning, BeyondTheoryWarning)))
    try:
        yield
    finally:
        _QUIET.reset(token)


def silenced(category):
    """True inside quiet() for this category."""
    return any(issubclass(category, c) for c in _QUIET.get())


def warn(category, text, stacklevel=3):
    """Warn, unless inside quiet() for this category."""
    if silenced(category):
        return
    warnings.warn(category(text), stacklevel=stacklevel + 1)
