"""Continuation of periodic orbits and their bifurcations (generic core on maps.Map)."""

from .core import KINDS, Continuer, Settings, continue_map
from .diagram import BifurcationDiagram, Branch, SpecialPoint
from .maps import FunctionMap, Map, MapError

__all__ = ["BifurcationDiagram", "Branch", "Continuer", "FunctionMap", "KINDS", "Map", "MapError",
           "Settings", "SpecialPoint", "continue_map"]
from .api import continuation, poincare
from .mechanism import MechanismMap
from .poincare import PoincareDiagram, PoincarePoint, sweep_map

__all__ += ["MechanismMap", "PoincareDiagram", "PoincarePoint", "continuation", "poincare", "sweep_map"]
