"""crankgen: dynamics of flexible slider-crank mechanisms (derived, generated, fast).

The public names are loaded on first use (PEP 562), so that `import crankgen` (and the command
line) starts at once; the compiled engine and numba are imported only by what needs them.
"""

from importlib import import_module

from .errors import ConvergenceError, CrankgenError, NoResultError, ParameterError
from .results.provenance import VERSION as __version__  # noqa: F401

# public name -> module that defines it
_LAZY = {
    "Mechanism": "declaration.parameters", "SIMechanism": "declaration.si", "Case": "declaration.cases", "Model": "discrete.system",
    "InitialState": "discrete.initial", "Scales": "declaration.units", "SIView": "results.outputs",
    "NewmarkSettings": "discrete.newmark", "integrate": "discrete.newmark",
    "SimulationResult": "analyses.simulation", "simulate": "analyses.simulation", "simulate_many": "analyses.simulation",
    "SteadyState": "analyses.steady", "steady_state": "analyses.steady", "steady_states": "analyses.steady",
    "SweepTable": "analyses.sweeps", "sweep": "analyses.sweeps", "CheckpointError": "analyses.sweeps",
    "BifurcationDiagram": "analyses.bifurcation", "PoincareDiagram": "analyses.bifurcation",
    "continuation": "analyses.bifurcation", "poincare": "analyses.bifurcation", "follow": "analyses.bifurcation", "Curve": "analyses.bifurcation",
    "stability_chart": "analyses.charts", "StabilityChart": "analyses.charts",
    "Modes": "analyses.modes", "modes": "analyses.modes", "campbell": "analyses.campbell", "CampbellDiagram": "analyses.campbell",
    "compare": "analyses.rigid", "Comparison": "analyses.rigid", "Verdict": "analyses.model_error",
    "animate": "plots.animation", "Section": "declaration.sections", "stress": "analyses.stresses", "peak_loads": "analyses.stresses", "StressHistory": "analyses.stresses",
}
# the choices of the model options (declared in derive/declaration.py), read from the generated table
_CHOICE_NAMES = {"FORMULATIONS": "formulation", "APPROACHES": "approach", "DAMPING_MODELS": "damping",
                 "MEMBRANE_OPTIONS": "membrane"}

# public modules, loaded on first use too: crankgen.sections.rectangle(b, h), crankgen.torque_curve.per_unit, ...
_MODULES = {"sections": "declaration.sections", "torque_curve": "declaration.torque_curve"}


def _classes():
    """generated/classes.py: the record class of each guide and crank motion (crankgen.Line, ...),
    loaded on first use, so that importing crankgen (or crankgen.declaration.records, as derive/ does) never
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
        value = import_module(f".{_MODULES[name]}", __name__)
    elif name in _LAZY:
        value = getattr(import_module(f".{_LAZY[name]}", __name__), name)
    elif name[:1].isupper() and name in _records():     # a record class (CamelCase): never a submodule
        value = getattr(_classes(), name)
    elif name in _CHOICE_NAMES:
        value = import_module(".declaration.ingredients", __name__).CHOICES[_CHOICE_NAMES[name]]
    else:
        raise AttributeError(f"module 'crankgen' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_public()))
