"""Continuation of periodic orbits and their bifurcations (generic core on maps.Map)."""

from .core import KINDS, Continuer, Settings, continue_map
from .diagram import BifurcationDiagram, Branch, SpecialPoint
from .maps import FunctionMap, Map, MapError

__all__ = ["BifurcationDiagram", "Branch", "Continuer", "FunctionMap", "KINDS", "Map", "MapError",
           "Settings", "SpecialPoint", "continue_map"]
from .api import continuation
from .mechanism import MechanismMap

__all__ += ["MechanismMap", "continuation"]
