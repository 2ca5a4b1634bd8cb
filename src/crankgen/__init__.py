"""crankgen: dynamics of flexible slider-crank mechanisms (derived, generated, fast).

The public names are loaded on first use (PEP 562), so that `import crankgen` (and the command
line) starts at once; the compiled engine and numba are imported only by what needs them.
"""

from importlib import import_module

from .errors import ConvergenceError, CrankgenError, NoResultError, ParameterError
from .provenance import VERSION as __version__  # noqa: F401

# public name -> module that defines it
_LAZY = {
    "Mechanism": "parameters", "SIMechanism": "si", "Case": "cases", "Model": "model",
    "InitialState": "initial", "Scales": "units", "SIView": "outputs",
    "NewmarkSettings": "newmark", "integrate": "newmark",
    "SimulationResult": "simulation", "simulate": "simulation", "simulate_many": "simulation",
    "SteadyState": "steady", "steady_state": "steady", "steady_states": "steady",
    "SweepTable": "sweeps", "sweep": "sweeps", "CheckpointError": "sweeps",
    "BifurcationDiagram": "bifurcation", "PoincareDiagram": "bifurcation",
    "continuation": "bifurcation", "poincare": "bifurcation", "follow": "bifurcation", "Curve": "bifurcation",
    "stability_chart": "charts", "StabilityChart": "charts",
    "Modes": "vibration", "modes": "vibration", "campbell": "campbell_diagram", "CampbellDiagram": "campbell_diagram",
    "animate": "animation", "Section": "sections", "stress": "stresses", "peak_loads": "stresses", "StressHistory": "stresses",
}
# the choices of the model options (declared in derive/declaration.py), read from the generated table
_CHOICE_NAMES = {"FORMULATIONS": "formulation", "APPROACHES": "approach", "DAMPING_MODELS": "damping",
                 "MEMBRANE_OPTIONS": "membrane"}

# public modules, loaded on first use too: crankgen.sections.rectangle(b, h), crankgen.torque_curve.per_unit, ...
_MODULES = ("sections", "torque_curve")


def _classes():
    """generated/classes.py: the record class of each guide and crank motion (crankgen.Line, ...),
    loaded on first use, so that importing crankgen (or crankgen.records, as derive/ does) never
    loads the generated code."""
    return import_module("._generated.classes", __name__)


def _records():
    classes = _classes()
    return tuple(cls.__name__ for cls in classes.GUIDE_CLASSES + classes.MOTION_CLASSES)


def _public():
    return (["ConvergenceError", "CrankgenError", "NoResultError", "ParameterError"] + list(_LAZY) + list(_records())
            + list(_CHOICE_NAMES) + list(_MODULES))


def __getattr__(name):
    if name == "__all__":
        value = _public()
    elif name in _MODULES:
        value = import_module(f".{name}", __name__)
    elif name in _LAZY:
        value = getattr(import_module(f".{_LAZY[name]}", __name__), name)
    elif name[:1].isupper() and name in _records():     # a record class (CamelCase): never a submodule
        value = getattr(_classes(), name)
    elif name in _CHOICE_NAMES:
        value = import_module(".ingredients", __name__).CHOICES[_CHOICE_NAMES[name]]
    else:
        raise AttributeError(f"module 'crankgen' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_public()))
