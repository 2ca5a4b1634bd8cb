"""Stage 8: the schema the runtime reads (generated/schema.py), printed from the model
representation (derive/representation.py) alone.

It holds the records of crankgen.declaration.records, each printed by `repr` of its fields (the very classes the
runtime imports, so nothing restates them): the options and presets, every parameter of a case
(kind, default, range, units, label, help, flag, owner and readers, slots in the parameter vector),
the guides and motions, the term families with their variants, the outputs with their kernels and
units, the layouts of the vectors the kernels read (the parameter vector, the kinematic parameters,
the kinematics, the coefficients, the end map's rows), the element modes and lane buffer, and the
function coefficients(p, options, off), printed as code from the coefficients' formulas.  The
runtime's Mechanism, Case, command-line flags, continuation parameters and engine records are built
from it (generated/classes.py: the runtime's classes of the schema).
"""

from dataclasses import fields, is_dataclass

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from . import representation as ir
from . import symbols as _symbols
from .emit import ELEMENT_MODES, LANES, lane_rows
from .guides import END_MAP_ROWS

RECORD_CLASSES = ("Body", "Constraint", "Coordinate", "Exclusion", "Family", "Guide", "Layout", "Motion", "Option", "Output", "Parameter", "Preset",
                  "Primitive", "Reduction", "Variant")


def _printer():
    return PythonCodePrinter({"fully_qualified_modules": True, "inline": True})


def literal(value, indent=""):
    """Source text of a value: a record (crankgen.declaration.records) as its class called with every field
    by keyword, one field a line; a tuple of records one record a line; anything else by repr."""
    inner = indent + "    "
    if is_dataclass(value):
        parts = [f"{f.name}={literal(getattr(value, f.name), inner)}" for f in fields(value)]
        return f"{type(value).__name__}(\n{inner}" + f",\n{inner}".join(parts) + ")"
    if isinstance(value, tuple) and value and all(is_dataclass(v) for v in value):
        return "(\n" + "".join(f"{inner}{literal(v, inner)},\n" for v in value) + f"{indent})"
    return repr(value)


def _coefficients_source(rep, forms=None, body=None):
    printer = _printer()
    schema = rep.schema
    forms = rep.coefficients if forms is None else forms
    formulas = [c.formula for c in forms]
    used = set().union(*(f.free_symbols for f in formulas))
    symbols = ir.parameter_symbols()
    if body is None:
        lines = ["def coefficients(p, options, off):",
                 '    """The coefficient vector of the element kernels (COEFFICIENTS order) for the parameter vector',
                 "    p (PARAMETER_VECTOR order), the model options {name: value} and the switched-off term",
                 "    groups `off` (crankgen\'s units: rho A = 1, E I = 1/pi^4, E A = 1/(pi^4 eps^2), rho I = eps^2",
                 '    or 0 without rotary inertia, term weights 1, or 0 for a switched-off group)."""']
    else:
        lines = [f"def coefficients_{body}(p, options, off):",
                 f'    """The coefficient vector of the {body}\'s elements (a flexible body beside the rod: the',
                 "    rod\'s coefficients with its own section\'s, BODY_COEFFICIENTS in derive/declaration.py), like",
                 '    coefficients(p, options, off)."""']
    for k, name in enumerate(schema.parameter_vector.entries):
        if symbols[name] in used:
            lines.append(f"    {symbols[name].name} = float(p[{k}])    # {name}")
    for name, option, value in schema.indicators:
        if sp.Symbol(name) in used:
            lines.append(f"    {name} = 1.0 if options[{option!r}] == {value!r} else 0.0")
    for g in schema.switchable_groups:
        if sp.Symbol(f"off_{g}") in used:
            lines.append(f"    off_{g} = 1.0 if {g!r} in off else 0.0")
    lines.append("    return (")
    for c in forms:
        lines.append(f"        float({printer.doprint(c.formula)}),    # {c.name}")
    lines.append("    )")
    return "\n".join(lines) + "\n"


def _natural_sizes_source(rep):
    printer = _printer()
    symbols = ir.parameter_symbols()
    used = set().union(*(c.formula.free_symbols for c in rep.natural_sizes))
    lines = ["def natural_sizes(p):",
             '    """The natural size of each component of a node (NODE order, units of L) for the parameter',
             '    vector p: the scales of Newton\'s increments and of the steady states\' convergence."""']
    for k, name in enumerate(rep.schema.parameter_vector.entries):
        if symbols[name] in used:
            lines.append(f"    {symbols[name].name} = float(p[{k}])    # {name}")
    lines.append("    return (")
    for c in rep.natural_sizes:
        lines.append(f"        float({printer.doprint(c.formula)}),    # {c.name}")
    lines.append("    )")
    return "\n".join(lines) + "\n"


def _table_source(schema):
    rows, size = lane_rows(schema.element_dofs, len(_symbols.GEOMETRY))
    end_map_rows = ir.Layout("E", END_MAP_ROWS, "the rows of a guide's end map (8, 2): the end node's (u, v), "
                             "their rates, and their derivatives in the reduced co-ordinate s and its rates")
    out = [
        "# model options (default: the default preset's value where it sets one) and presets (named models)",
        f"OPTIONS = {literal(schema.options)}",
        f"PRESETS = {literal(schema.presets)}",
        f"DEFAULT_PRESET = {schema.default_preset!r}",
        "# every parameter of a case; owner: mechanism, guide, motion or run; readers: the guides or",
        "# motions that read it; slots: its places in PARAMETER_VECTOR",
        f"PARAMETERS = {literal(schema.parameters)}",
        "# the crank's (nominal) speed (simulate's omega, the default continued parameter), its angle at",
        "# t = 0; the units that",
        "# are parameters ({unit: the parameter that is its value in L})",
        f"CRANK_SPEED = {schema.crank_speed!r}",
        f"CRANK_ANGLE = {schema.crank_angle!r}",
        f"UNIT_PARAMETERS = {schema.unit_parameters!r}",
        "# the vectors the kernels read",
        f"PARAMETER_VECTOR = {literal(schema.parameter_vector)}",
        f"PARAMETER_SYMBOLS = {literal(schema.parameter_symbols)}",
        f"KINEMATIC_PARAMETERS = {literal(schema.kinematic_parameters)}",
        f"KINEMATICS = {literal(schema.kinematics)}",
        f"COEFFICIENTS = {literal(schema.coefficients)}",
        f"END_MAP_ROWS = {literal(end_map_rows)}",
        "# the DOF map: the components of a node (eq. 14), an element's two nodes', the constraints of the",
        "# nodes condensed out of the equations",
        f"NODE = {literal(schema.node)}",
        f"ELEMENT_DOFS = {schema.element_dofs!r}",
        f"CONSTRAINTS = {literal(schema.constraints)}",
        "# the mechanism's bodies: the flexible ones' node layouts and element counts, the joints' ends",
        f"BODIES = {literal(schema.bodies)}",
        "# what an element kernel's one-element function adds, by its mode argument (derive/emit.py)",
        f"ELEMENT_MODES = {ELEMENT_MODES!r}",
        "# an element kernel's lane function: LANES elements at once, on a buffer of LANE_SIZE values whose",
        "# blocks start at LANE_ROWS (rows of LANES values; derive/emit.py)",
        f"LANES = {LANES!r}",
        f"LANE_ROWS = {rows!r}",
        f"LANE_SIZE = {size * LANES!r}",
        f"SWITCHABLE_GROUPS = {schema.switchable_groups!r}",
        "# crank motions and guides",
        f"MOTIONS = {literal(schema.motions)}",
        f"GUIDES = {literal(schema.guides)}",
        "# term families ('rod': every element; 'end': the rod's end node) with their variants",
        f"FAMILIES = {literal(schema.families)}",
        "# outputs: kind step, field or reduction (engine: computed by the engine at every step, all of them",
        "# by the kernel per_step), units, the guides it exists for, the options it depends on, the",
        "# kernels' inputs, its kernels by option values",
        f"OUTPUTS = {literal(schema.outputs)}",
        "# reductions over time of the outputs (a revolution's peak, RMS, mean, range), declared once",
        f"REDUCTIONS = {literal(schema.reductions)}",
        "# what the engine accumulates at every step for its outputs (per_step's prims, in this order)",
        f"PRIMITIVES = {literal(schema.primitives)}",
        "# option values under which the one-pass scheme iterates with the printed eq. (37) matrices",
        f"PRINTED_ITERATION = {schema.printed_iteration!r}",
        "# option values that have no meaning together: a case choosing all of them is refused with the reason",
        f"EXCLUSIONS = {literal(schema.exclusions)}",
    ]
    return "\n".join(out) + "\n"


def emit_schema(derive_command, spec_hash, element_names):
    rep = ir.representation()
    header = [
        '"""The model schema, generated from the declaration in derive/declaration.py through its representation.',
        "",
        f"Autogenerated by `{derive_command}` from derive/ -- do not edit by hand.",
        f"Kernels specification sha256 {spec_hash}.",
        "Records of crankgen.declaration.records, read by the runtime (crankgen.declaration.schema, crankgen.declaration.ingredients); the",
        "runtime's classes of this schema are in classes.py.",
        '"""',
        "",
        "import math",
        "",
        f"from crankgen.declaration.records import {', '.join(RECORD_CLASSES)}",
        "",
        f"KERNELS_HASH = {spec_hash[:16]!r}",
        f"ELEMENT_KERNELS = {tuple(sorted(element_names))!r}",
        "",
    ]
    bodies = "".join(_coefficients_source(rep, forms, body) + "\n\n" for body, forms in rep.body_coefficients)
    return ("\n".join(header) + "\n" + _table_source(rep.schema) + "\n\n" + _coefficients_source(rep) + "\n\n"
            + bodies + _natural_sizes_source(rep))


def _class_doc(record):
    aliases = "; keywords " + ", ".join(f"{k} = ({', '.join(v)})" for k, v in record.aliases) if record.aliases else ""
    return f"{record.doc}.  Parameters: {', '.join(record.parameters)}{aliases}."


def _fields_source(name, doc, names, extra=()):
    lines = ["@dataclass(frozen=True)", f"class {name}:", f'    """{doc}"""', ""]
    lines += [f"    {n}: object = None" for n in names]
    lines += [f"    {line}" for line in extra]
    return "\n".join(lines) + "\n"


def emit_classes(derive_command):
    """generated/classes.py: the fields of the runtime's Mechanism, Case and SIMechanism
    (crankgen.declaration.parameters, crankgen.declaration.cases, crankgen.declaration.si add their checks) and a record class per
    guide and crank motion."""
    schema = ir.schema()
    mechanism = [p.name for p in schema.parameters if p.owner in ("mechanism", "guide")]
    case = [p.name for p in schema.parameters] + [o.name for o in schema.options]
    # in SI: every parameter entering an equation or choosing the guide or motion, by its SI name,
    # but those that are units (r = eps L: the rod's section gives it)
    si = [p.si or p.name for p in schema.parameters
          if (p.slots or p.selects or p.owner in ("guide", "motion")) and p.name not in schema.unit_parameters.values()]
    out = [
        '"""The runtime\'s classes of the schema (schema.py): the fields of Mechanism, Case and SIMechanism, and a record',
        "class per guide and crank motion (crankgen.Line, crankgen.Circle, crankgen.Constant, ...).",
        "",
        f"Autogenerated by `{derive_command}` from derive/ -- do not edit by hand.",
        '"""',
        "",
        "from dataclasses import dataclass, field",
        "",
        "from crankgen.declaration.records import Spec",
        "",
        "from .schema import GUIDES, MOTIONS",
        "",
        "",
        _fields_source("MechanismFields", "The mechanism's parameters and its guide's (None: the default); "
                       "crankgen.Mechanism checks them.", mechanism),
        "",
        _fields_source("CaseFields", "Every parameter and model option of a case (None: the default), the audit's "
                       "switched-off term groups and the\n    model (a preset); crankgen.Case checks them.", case,
                       ('groups_off: str = ""', "model: object = field(default=None, compare=False, repr=False)")),
        "",
        _fields_source("SIFields", "The parameters of a mechanism and its crank motion in SI, each by its SI name and in the SI unit\n"
                       "    of its declared units (None: left out); crankgen.SIMechanism adds the rod's fields and\n"
                       "    checks them.", si),
    ]
    default = {p.name: p.default for p in schema.parameters}
    for kind, table, items in (("guide", "GUIDES", schema.guides), ("motion", "MOTIONS", schema.motions)):
        for k, record in enumerate(items):
            defaults = {name: default[name] for name in record.parameters}
            out += ["", f"class {record.title}(Spec):", f'    """{_class_doc(record)}"""', "",
                    f"    kind = {kind!r}", f"    declaration = {table}[{k}]    # {record.name}",
                    f"    defaults = {defaults!r}", ""]
    out += ["", f"GUIDE_CLASSES = ({', '.join(g.title for g in schema.guides)},)",
            f"MOTION_CLASSES = ({', '.join(m.title for m in schema.motions)},)"]
    return "\n".join(out) + "\n"
