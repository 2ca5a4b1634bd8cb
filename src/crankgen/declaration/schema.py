"""The model schema as the runtime sees it: the records of generated/schema.py, by name.

Every parameter of a case, every option, preset, guide, motion, family and output is declared once,
in derive/declaration.py, and reaches the runtime as records of crankgen.declaration.records (printed into
generated/schema.py).  This module gives them by name, the layouts of the vectors the kernels read,
and the rules that follow: the model options of a preset with explicit options overriding it
(`resolve_options`), the parameter that selects the guide or the motion, the parameters that
belong to the mechanism or to the run.  Mechanism, Case, the command line's flags and the
continuation's parameters are built from here; nothing in the runtime restates a record.
"""

from .._generated import schema as _table
from ..errors import ParameterError
from . import values as _values

PARAMETERS = {p.name: p for p in _table.PARAMETERS}
OPTIONS = {o.name: o for o in _table.OPTIONS}
PRESETS = {p.name: p for p in _table.PRESETS}
DEFAULT_PRESET = _table.DEFAULT_PRESET
GUIDES = {g.name: g for g in _table.GUIDES}
MOTIONS = {m.name: m for m in _table.MOTIONS}
OUTPUTS = {o.name: o for o in _table.OUTPUTS}
ENGINE_OUTPUTS = tuple(o.name for o in _table.OUTPUTS if o.engine)   # computed by the engine at every step
PRIMITIVES = _table.PRIMITIVES                # what the engine accumulates for them (per_step's prims)
FAMILIES = _table.FAMILIES

# the layouts of the vectors the kernels read, as tuples of entry names
PARAMETER_VECTOR = _table.PARAMETER_VECTOR.entries        # every parameter entering an equation
KINEMATIC_PARAMETERS = _table.KINEMATIC_PARAMETERS.entries  # the slots the guides and motions read
PARAMETER_SYMBOLS = _table.PARAMETER_SYMBOLS.entries       # the symbol of each slot in the derivation
KINEMATIC_SLOTS = tuple(PARAMETER_VECTOR.index(n) for n in KINEMATIC_PARAMETERS)
KINEMATICS = _table.KINEMATICS.entries
KIN = {name: k for k, name in enumerate(KINEMATICS)}         # place of each entry of kin
COEFFICIENTS = _table.COEFFICIENTS.entries
ELEMENT_DOFS = _table.ELEMENT_DOFS
NODE = _table.NODE.entries                    # the components of a node (eq. 14)
BODIES = {b.name: b for b in _table.BODIES}   # the mechanism's bodies (records.Body)
REDUCTIONS = _table.REDUCTIONS                # reductions over time of the outputs (records.Reduction)
CONSTRAINTS = _table.CONSTRAINTS              # the DOF map: the constraints condensed out
END_MAP_ROWS = {name: k for k, name in enumerate(_table.END_MAP_ROWS.entries)}
ELEMENT_MODES = _table.ELEMENT_MODES          # what an element kernel's one-element function adds
LANES, LANE_SIZE = _table.LANES, _table.LANE_SIZE       # an element kernel's lane function: elements at once,
LANE_ROWS = _table.LANE_ROWS                            # its buffer's size and the first row of each block

CRANK_SPEED = _table.CRANK_SPEED             # the crank's (nominal) speed parameter
CRANK_ANGLE = _table.CRANK_ANGLE             # the crank's angle at t = 0
UNIT_PARAMETERS = _table.UNIT_PARAMETERS      # {unit: the parameter giving its value in L}
# the choice parameters that select the guide and the crank motion: {"guide": name, "motion": name}
SELECTOR = {p.selects: p.name for p in PARAMETERS.values() if p.selects}
MECHANISM_PARAMETERS = tuple(n for n, p in PARAMETERS.items() if p.owner in ("mechanism", "guide"))
RUN_PARAMETERS = tuple(n for n, p in PARAMETERS.items() if p.owner in ("run", "motion"))
CONTINUABLE = tuple(n for n, p in PARAMETERS.items() if p.continuable)
EXCLUSIONS = _table.EXCLUSIONS            # option values refused together (records.Exclusion)
# the parameters of a mechanism and its crank motion in SI (crankgen.SIMechanism's fields beside the
# rod's), by SI name: those entering an equation, choosing the guide or motion or read by them (a
# motor's torque curve), but the units that are parameters (the rod's section gives them)
SI_FIELDS = {p.si or p.name: p for p in PARAMETERS.values()
             if (p.slots or p.selects or p.owner in ("guide", "motion")) and p.name not in UNIT_PARAMETERS.values()}


def resolve_options(model=None, **options):
    """The model options of a case: the preset `model` (default: the default preset), then every
    explicit option (not None) overriding it, checked; ParameterError names a bad one."""
    name = DEFAULT_PRESET if model is None else model
    if name not in PRESETS:
        raise ParameterError(f"model must be one of {', '.join(repr(p) for p in PRESETS)}, got {model!r}")
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"unknown model option {unknown[0]!r}; the options are {', '.join(OPTIONS)}")
    out = {}
    for opt in OPTIONS.values():
        value = options.get(opt.name)
        if value is None:
            value = PRESETS[name].options.get(opt.name, opt.default)
        out[opt.name] = _values.option_value(opt, value)
    for x in EXCLUSIONS:
        if all(out[k] == v for k, v in x.options.items()):
            raise ParameterError(x.reason)
    return out


def preset_of(options):
    """Name of the preset whose option values the options have (the one setting the most of them
    when several do), or None."""
    matching = [(len(p.options), name) for name, p in PRESETS.items()
                if all(options.get(k) == v for k, v in p.options.items())]
    return max(matching, key=lambda m: m[0])[1] if matching else None


def selected(values, kind):
    """The name of the guide (kind "guide") or motion ("motion") of a mapping of parameter values
    (its default when absent)."""
    p = PARAMETERS[SELECTOR[kind]]
    return values.get(p.name, p.default)


_IN_VECTOR = tuple(p for p in PARAMETERS.values() if p.slots)     # the parameters entering an equation


def parameter_vector(values):
    """The parameter vector (PARAMETER_VECTOR order) of a mapping of canonical parameter values;
    absent ones take their default."""
    import numpy as np
    out = [0.0] * len(PARAMETER_VECTOR)
    for p in _IN_VECTOR:
        for slot, x in zip(p.slots, p.entries(values.get(p.name, p.default)), strict=True):
            out[slot] = x
    return np.array(out)


def natural_sizes(values):
    """The natural size of each component of a node (NODE order, units of L) for a mapping of
    parameter values (absent ones at their default): the declared formulas (u: eps^2, v, psi: eps)."""
    return natural_sizes_of(parameter_vector(values))


def natural_sizes_of(vector):
    """natural_sizes of a parameter vector (PARAMETER_VECTOR order)."""
    return _table.natural_sizes(vector)


# a rigid body's own parameters, named after it (crank_mass, crank_centre, crank_inertia): titles
# list them only away from their defaults (a massless crank by default)
BODY_PARAMETERS = tuple(n for n, p in PARAMETERS.items() if p.owner == "mechanism"
                         and n.split("_")[0] in BODIES and BODIES[n.split("_")[0]].kind == "rigid")


def describe(values, skip=()):
    """A case's parameters as text, from their records: (main, other), two lists of "axis = value".
    main: the mechanism's real parameters and the continuable parameters of the crank motion;
    other: the guide or motion when not the default one, named by its record's label with every
    parameter of its geometry or law (a kinematic parameter: "four-bar: rocker length c/L = 0.8,
    ...") and every other one it reads that is not at its default (a rocker's spring or mass), and
    any other parameter entering an equation that is not at its default (gravity, an offset, a
    start angle, a rigid crank's mass).  The run's settings
    (mesh, steps, integrator) are left to the caller; `skip`: names left out."""
    chosen = {"guide": selected(values, "guide"), "motion": selected(values, "motion")}
    records = {"guide": GUIDES[chosen["guide"]], "motion": MOTIONS[chosen["motion"]]}
    main, other, groups = [], [], {"guide": [], "motion": []}
    for p in PARAMETERS.values():
        if p.name in skip or p.selects or not p.read_by(chosen["guide"], chosen["motion"]):
            continue
        value = _values.canonical(p, values.get(p.name, p.default))        # a pair from JSON: a list
        item = f"{p.axis} = {_values.text(p, value)}"
        if p.name in BODY_PARAMETERS:             # a rigid body's mass, centre, inertia: when given
            if value != p.default:
                other.append(item)
        elif (p.owner == "mechanism" and p.kind == "real") or (p.owner == "motion" and p.continuable):
            main.append(item)
        elif p.owner in groups and chosen[p.owner] != PARAMETERS[SELECTOR[p.owner]].default:
            if p.name in KINEMATIC_PARAMETERS or value != p.default:
                groups[p.owner].append(item)
        elif p.slots and value != p.default:
            other.append(item)
    for kind, items in groups.items():
        if chosen[kind] != PARAMETERS[SELECTOR[kind]].default:
            other.append(f"{records[kind].label or records[kind].name}" + (": " + ", ".join(items) if items else ""))
    return main, other
