"""Exceptions raised by crankgen."""


class CrankgenError(Exception):
    """Base class of every error crankgen raises on purpose."""


class ParameterError(CrankgenError, ValueError):
    """An input is outside its allowed range; the message names the parameter and the range."""


class ConvergenceError(CrankgenError, RuntimeError):
    """Newton's method did not converge (or the solution stopped being finite) in a time step."""

    def __init__(self, message, step=None, time=None, residual=None, partial=None):
        super().__init__(message)
        self.step, self.time, self.residual = step, time, residual
        # what was computed before the failure (a SimulationResult up to the last good step), if any
        self.partial = partial


class NoResultError(CrankgenError, RuntimeError):
    """A computation ran and found nothing to go on from: no periodic state to start a
    continuation at, no periodic orbit near a starting point.  The command line exits 1 (a run
    that failed), not 2 (a usage error)."""
