"""Continuation of periodic orbits and their bifurcations: a generic core on maps.Map (core,
diagram, sweeps), and the mechanism's crank-revolution map (mechanism, api); the continuation of
special points in two parameters on plane_maps.PlaneMap (defining, codim2, curve, follow) and the
mechanism's map in two parameters (mechanism_plane)."""

from .core import KINDS, Continuer, Settings, continue_map
from .diagram import BifurcationDiagram, Branch, SpecialPoint
from .maps import FunctionMap, Map, MapError
from .mechanism import MechanismMap
from .sweeps import PoincareDiagram, PoincarePoint, sweep_map
from .api import continuation, poincare
from .curve import Codim2Point, Curve
from .follow import follow, follow_map
from .plane_maps import FunctionPlaneMap, PlaneMap

__all__ = ["BifurcationDiagram", "Branch", "Codim2Point", "Continuer", "Curve", "FunctionMap",
           "FunctionPlaneMap", "KINDS", "Map", "MapError", "MechanismMap", "PlaneMap", "PoincareDiagram",
           "PoincarePoint", "Settings", "SpecialPoint", "continuation", "continue_map", "follow", "follow_map",
           "poincare", "sweep_map"]
