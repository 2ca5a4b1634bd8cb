"""Continuation of periodic orbits and their bifurcations: a generic core on maps.Map (core,
diagram, sweeps), and the mechanism's crank-revolution map (mechanism, api)."""

from .core import KINDS, Continuer, Settings, continue_map
from .diagram import BifurcationDiagram, Branch, SpecialPoint
from .maps import FunctionMap, Map, MapError
from .mechanism import MechanismMap
from .sweeps import PoincareDiagram, PoincarePoint, sweep_map
from .api import continuation, poincare

__all__ = ["BifurcationDiagram", "Branch", "Continuer", "FunctionMap", "KINDS", "Map", "MapError",
           "MechanismMap", "PoincareDiagram", "PoincarePoint", "Settings", "SpecialPoint",
           "continuation", "continue_map", "poincare", "sweep_map"]
