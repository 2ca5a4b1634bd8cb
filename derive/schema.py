"""Stage 8: the schema the runtime reads (generated/schema.py), printed from the model
representation (derive/representation.py) alone.

It holds, as plain literals: the options with their choices, defaults and help, the presets, every
parameter of a case (kind, default, range, units, label, help, command-line flag, which guides or
motions read it, its place in the kinematic parameter vector), the layouts of the kinematics and
kinematic parameter vectors, the coefficients and their formula (`coefficients(...)`, printed as
code), the term families with each variant's selecting option values, the guides and motions, and
the outputs with their kernels and units.  crankgen's Mechanism, Case, command-line flags,
continuation parameters and engine records are built from it; nothing in the runtime restates a
parameter, an option or a preset.
"""

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from . import representation as ir
from . import symbols as _symbols
from .emit import ELEMENT_MODES, LANES, lane_rows
from .guides import END_MAP_ROWS


def _printer():
    return PythonCodePrinter({"fully_qualified_modules": True, "inline": True})


def _coefficients_source(rep):
    printer = _printer()
    args = ["eps", "ms", "mu", "gX", "gY", "with_rotary_inertia"] + [f"off_{g}" for g in rep.switchable_groups]
    lines = [f"def coefficients({', '.join(args)}):",
             '    """The coefficient vector of the element kernels (COEFFICIENTS order, crankgen\'s units:',
             "    rho A = 1, E I = 1/pi^4, E A = 1/(pi^4 eps^2), rho I = eps^2 or 0 without rotary inertia,",
             '    term weights 1, or 0 for a switched-off group)."""',
             "    return ("]
    for c in rep.coefficients:
        lines.append(f"        float({printer.doprint(c.formula)}),    # {c.name}")
    lines.append("    )")
    return "\n".join(lines) + "\n"


def _record(fields):
    return "dict(" + ", ".join(f"{k}={v!r}" for k, v in fields.items()) + ")"


def _table_source(rep):
    out = ["# model options: name, choices, default (the default preset's value where it sets one), help, flag",
           "OPTIONS = ("]
    for o in rep.options:
        out.append(f"    {_record(dict(name=o.name, choices=o.choices, default=o.default, cli=o.cli))[:-1]},\n"
                   f"         doc={o.doc!r}),")
    out.append(")")
    out.append("# named models: a set of option values each (explicit options override them)")
    out.append("PRESETS = (")
    for p in rep.presets:
        out.append(f"    dict(name={p.name!r}, options={dict(p.options)!r},\n         doc={p.doc!r}),")
    out.append(")")
    out.append(f"DEFAULT_PRESET = {rep.default_preset!r}")
    out.append("# every parameter of a case; owner: mechanism, guide, motion or run; readers: the guides or")
    out.append("# motions that read it; kinematic_index: its place in the kinematic parameter vector (-1: none)")
    out.append("PARAMETERS = (")
    for p in rep.parameters:
        fields = dict(name=p.name, kind=p.kind, default=p.default, owner=p.owner, readers=p.readers,
                      low=p.low, high=p.high, low_open=p.low_open, high_open=p.high_open, units=p.units,
                      cli=p.cli, metavar=p.metavar, choices=p.choices, continuable=p.continuable,
                      kinematic_index=p.kinematic_index)
        out.append(f"    {_record(fields)[:-1]},\n         label={p.label!r},\n         doc={p.doc!r}),")
    out.append(")")
    out.append(f"KINEMATICS = {rep.kinematics!r}")
    out.append(f"KINEMATIC_PARAMETERS = {rep.kinematic_parameters!r}")
    out.append(f"ELEMENT_DOFS = {rep.element_dofs!r}")
    out.append(f"END_SLOTS = {rep.end_slots!r}")
    out.append(f"END_MAP_ROWS = {END_MAP_ROWS!r}")
    out.append("# what an element kernel's one-element function adds, by its mode argument (derive/emit.py)")
    out.append(f"ELEMENT_MODES = {ELEMENT_MODES!r}")
    rows, size = lane_rows(rep.element_dofs, len(_symbols.GEOMETRY))
    out.append("# an element kernel's lane function: LANES elements at once, on a buffer of LANE_SIZE values whose")
    out.append("# blocks start at LANE_ROWS (rows of LANES values; derive/emit.py)")
    out.append(f"LANES = {LANES!r}")
    out.append(f"LANE_ROWS = {rows!r}")
    out.append(f"LANE_SIZE = {size * LANES!r}")
    out.append(f"COEFFICIENTS = {tuple(c.name for c in rep.coefficients)!r}")
    out.append(f"SWITCHABLE_GROUPS = {rep.switchable_groups!r}")
    out.append("# crank motions: name, record title, parameters it reads, periodic in the crank angle, the record's")
    out.append("# keyword aliases of parameters, help")
    out.append("MOTIONS = (")
    for m in rep.motions:
        out.append(f"    dict(name={m.name!r}, title={m.title!r}, parameters={m.parameters!r}, "
                   f"periodic={m.period is not None!r}, aliases={m.aliases!r},\n         doc={m.doc!r}),")
    out.append(")")
    out.append("# guides: name, record title, parameters it reads, the record's keyword aliases of parameters,")
    out.append("# the full-turn conditions (margins > 0), help")
    out.append("GUIDES = (")
    for g in rep.guides:
        out.append(f"    dict(name={g.name!r}, title={g.title!r}, parameters={g.parameters!r}, "
                   f"aliases={g.aliases!r},\n         margins={g.margin_texts!r},\n         doc={g.doc!r}),")
    out.append(")")
    out.append("# family name, part ('rod': every element; 'end': the rod's end node), doc, energy kind of its")
    out.append("# energy kernels, the coefficients whose vanishing leaves it out, variants:")
    out.append("# (name, element kernel, selecting option values, switchable groups it carries, energy kernel)")
    out.append("FAMILIES = (")
    for f in rep.families:
        out.append(f"    ({f.name!r}, {f.part!r}, {f.doc!r}, {f.energy_kind!r}, {f.vanishes_with!r}, (")
        for v in f.variants:
            out.append(f"        ({v.name!r}, {v.kernel!r}, {dict(v.when)!r}, {v.groups!r}, {v.energy!r}),")
        out.append("    )),")
    out.append(")")
    out.append("# outputs: name, kind (engine, step, field), doc, units, extra arguments, guides it exists for,")
    out.append("# kernel inputs, kernels by option values")
    out.append("OUTPUTS = (")
    for o in rep.outputs:
        variants = tuple((dict(v.when), v.kernel) for v in o.variants)
        out.append(f"    dict(name={o.name!r}, kind={o.kind!r}, units={o.units!r}, arguments={o.arguments!r}, "
                   f"guides={o.guides!r},\n         inputs={o.inputs!r},\n         doc={o.doc!r},\n"
                   f"         kernels={variants!r}),")
    out.append(")")
    out.append("# option values under which the one-pass scheme iterates with the printed eq. (37) matrices")
    out.append(f"PRINTED_ITERATION = {dict(rep.printed_iteration)!r}")
    out.append("# option values that have no meaning together: a case choosing all of them is refused with the reason")
    out.append("EXCLUSIONS = (")
    for options, reason in rep.exclusions:
        out.append(f"    ({dict(options)!r},\n     {reason!r}),")
    out.append(")")
    out.append("# element kernels whose integrals use a quadrature rule (derive/quadrature.py): kernel -> rule,")
    out.append("# its points and the polynomial degree it integrates exactly; the others are integrated in closed form")
    out.append("QUADRATURE = {")
    for f in rep.families:
        for v in f.variants:
            if v.quadrature is not None:
                rule = v.quadrature
                out.append(f"    {v.kernel!r}: dict(rule='gauss-legendre', points={len(rule.points)!r}, "
                           f"degree={rule.degree!r}),")
    out.append("}")
    return "\n".join(out) + "\n"


def emit_schema(derive_command, spec_hash, element_names):
    rep = ir.representation()
    header = [
        '"""The model schema, generated from the declaration in derive/model.py through its representation.',
        "",
        f"Autogenerated by `{derive_command}` from derive/ -- do not edit by hand.",
        f"Kernels specification sha256 {spec_hash}.",
        "The runtime builds its Mechanism, Case, command-line flags, continuation parameters and engine",
        "records from these tables (crankgen.schema, crankgen.ingredients).",
        '"""',
        "",
        "import math",
        "",
        f"KERNELS_HASH = {spec_hash[:16]!r}",
        f"ELEMENT_KERNELS = {tuple(sorted(element_names))!r}",
        "",
    ]
    return "\n".join(header) + "\n" + _table_source(rep) + "\n\n" + _coefficients_source(rep)
