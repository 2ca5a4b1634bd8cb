"""crankgen: dynamics of flexible slider-crank mechanisms (derived, generated, fast)."""

from .errors import ConvergenceError, CrankgenError, ParameterError
from .ingredients import CHOICES as _CHOICES
from .model import Model
from .newmark import NewmarkSettings, integrate
from .parameters import Mechanism, SIMechanism
from .cases import Case
from .simulation import SimulationResult, simulate, simulate_many
from .steady import SteadyState, steady_state, steady_states
from .sweep import SweepTable, sweep
from .bifurcation import BifurcationDiagram, PoincareDiagram, continuation, poincare

__all__ = [
    "APPROACHES", "Case", "DAMPING_MODELS", "FORMULATIONS", "ConvergenceError", "CrankgenError", "Mechanism",
    "Model", "NewmarkSettings", "ParameterError", "SIMechanism", "SimulationResult", "integrate",
    "simulate", "simulate_many", "SteadyState", "steady_state", "steady_states", "SweepTable", "sweep",
    "BifurcationDiagram", "PoincareDiagram", "continuation", "poincare",
]
from .provenance import VERSION as __version__

# the choices of the model options (declared in derive/model.py)
FORMULATIONS = _CHOICES["formulation"]
APPROACHES = _CHOICES["approach"]
DAMPING_MODELS = _CHOICES["damping"]
MEMBRANE_OPTIONS = _CHOICES["membrane"]
