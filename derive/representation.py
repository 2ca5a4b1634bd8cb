"""Stage 6: the model representation, between the declaration and code generation.

`schema()` gives the declaration as the runtime sees it: records of crankgen.declaration.records (the
SymPy-free classes the runtime imports), with what follows from the declaration filled in (an
option's effective default, a parameter's owner, readers, flag and slots in the parameter vector,
a choice parameter's guides or motions, a variant's kernel name, an output's inputs and kernels),
and the layouts of the vectors the kernels read.  derive/schema.py prints these records into
generated/schema.py; tests/test_schema_records.py checks that the two agree.

`representation()` adds the SymPy forms code generation needs, each beside its record: a
variant's element residual, a guide's kinematics and end map, a motion's rates, an energy, an
output's expression per option case, the coefficients' formulas.  derive/kernels.py, emit.py and
schema.py read only this (the rule of FFCx's intermediate representation), never the declaration.

The parameter vector (the layout PARAMETERS): one slot per parameter that enters an equation (a
pair: two), in the order of the declaration.  The coefficient function coefficients(p, options,
off) of the element kernels and the kinematic parameter vector (KINEMATIC_PARAMETERS: the slots
the guides and motions read, found from their expressions) are generated from it.
"""

from dataclasses import dataclass, replace
from functools import lru_cache

import sympy as sp

from crankgen.declaration import records
from crankgen.declaration.records import Layout, project

from . import declaration as model
from . import energies as en
from . import guides as gd
from . import motions as mo
from . import outputs
from . import symbols as s
from .euler_lagrange import gradient, kinetic_residual
from .groups import ELEMENT_VARS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from .shape_functions import B_V, N_PSI, N_U, N_U_CUBIC, N_V, integrate_element

ELEMENT_DOFS = s.ELEMENT_DOFS    # (u, v, psi) of the element's two nodes, eq. (14)
CRANK_SYMBOLS = (s.theta, s.thetad, s.thetadd)
COEFFICIENT_SYMBOLS = tuple(model.COEFFICIENTS)   # the coefficient vector coef, in its order
END_COORDINATES = (gd.sp_s, gd.sp_sd, gd.sp_sdd)


# ---- the SymPy-free schema ------------------------------------------------------------------------

@dataclass(frozen=True)
class Schema:
    """The records of generated/schema.py (crankgen.declaration.records) and its layouts."""

    options: tuple
    presets: tuple
    default_preset: str
    parameters: tuple
    guides: tuple
    motions: tuple
    families: tuple
    outputs: tuple
    primitives: tuple            # what the engine accumulates for its outputs (crankgen.declaration.records.Primitive)
    printed_iteration: dict
    switchable_groups: tuple
    parameter_vector: Layout     # every parameter entering an equation, one slot each (a pair: two)
    parameter_symbols: Layout    # the symbol of each slot (kernels' arguments are named after them)
    kinematic_parameters: Layout  # the slots the guides' and motions' kernels read (params)
    kinematics: Layout           # the kinematics vector kin
    coefficients: Layout         # the element kernels' coefficient vector coef
    indicators: tuple            # ((symbol, option, value), ...) usable in the coefficients' formulas
    crank_speed: str             # the crank's (nominal) speed parameter
    crank_angle: str             # the crank's angle at t = 0
    unit_parameters: dict        # {unit: the parameter giving its value in L}
    element_dofs: int
    node: Layout                 # the components of a node, in the element's order (eq. 14)
    constraints: tuple           # the DOF map: the constraints condensed out (crankgen.declaration.records.Constraint)
    exclusions: tuple            # option values refused together (crankgen.declaration.records.Exclusion)
    bodies: tuple = ()           # the mechanism's bodies (records.Body): the flexible ones' meshes, the joints' ends
    reductions: tuple = ()       # reductions over time of the outputs (records.Reduction)


def _symbols(p):
    """The SymPy symbols of a parameter's slots ((): it enters no equation)."""
    if p.symbol is None:
        return ()
    return tuple(p.symbol) if isinstance(p.symbol, tuple) else (p.symbol,)


def _slot_names(p):
    syms = _symbols(p)
    return (p.name,) if len(syms) == 1 else tuple(f"{p.name}[{k}]" for k in range(len(syms)))


def parameter_symbols():
    """{slot name: SymPy symbol} of the parameter vector, in its order."""
    out = {}
    for p in model.PARAMETERS:
        out.update(zip(_slot_names(p), _symbols(p)))
    return out


def _kinematic_symbols():
    """The parameter symbols the guides' and motions' kinematics read (their curves, closures,
    margins; the motions' laws and periods), in the parameter vector's order."""
    exprs = []
    for g in model.GUIDES:
        exprs += [g.curve, g.step, g.phi, g.beta, g.guess] + [m for m, _ in g.margin]
    for m in model.MOTIONS:
        exprs += [m.theta, m.thetad, m.thetadd, m.period, m.step_period]
        exprs += [c.equation for c in m.coordinates] + [x for c in m.coordinates for x in c.start]
        if m.coordinates:           # a driven crank's equation reads the torque its load demands
            exprs.append(next(o for o in outputs.OUTPUTS if o.name == "torque").build({}))
    used = set().union(*(sp.sympify(e).free_symbols for e in exprs if e is not None))
    return tuple(sym for sym in parameter_symbols().values() if sym in used)


KINEMATIC_SYMBOLS = _kinematic_symbols()


def _options():
    preset = dict(next(p for p in model.PRESETS if p.name == model.DEFAULT_PRESET).options)
    out = []
    for o in model.OPTIONS:
        default = preset.get(o.name, o.default)
        if default not in o.choices:
            raise ValueError(f"option {o.name}: no default (neither its own nor the default preset's)")
        out.append(records.Option(o.name, o.choices, default, o.doc, o.cli or o.name.replace("_", "-")))
    return tuple(out)


def _presets():
    names = {o.name: o for o in model.OPTIONS}
    for p in model.PRESETS:
        for option, value in p.options.items():
            if value not in names[option].choices:
                raise ValueError(f"preset {p.name}: {option}={value!r} is not a choice")
        for name, value in p.settings.items():
            par = next((q for q in model.PARAMETERS if q.name == name), None)
            if par is None or par.owner != "run" or par.kind != "real" or not (
                    (par.low is None or value >= par.low) and (par.high is None or value <= par.high)):
                raise ValueError(f"preset {p.name}: {name}={value!r} is not a real run parameter's value")
    return tuple(records.Preset(p.name, dict(sorted(p.options.items())), p.doc,
                                dict(sorted((k, float(v)) for k, v in p.settings.items())))
                 for p in model.PRESETS)


def _readers(name, declared):
    """(owner, readers) of a parameter: the guides or the motions that read it (Guide.parameters,
    Motion.parameters), else its declared owner."""
    guides = tuple(g.name for g in model.GUIDES if name in g.parameters)
    motions = tuple(m.name for m in model.MOTIONS if name in m.parameters)
    if guides and motions:
        raise ValueError(f"parameter {name}: read by guides {guides} and motions {motions}")
    if guides and declared != "mechanism" or motions and declared != "run":
        raise ValueError(f"parameter {name}: a guide's parameter belongs to the mechanism, a motion's to "
                         f"the run (declared {declared!r})")
    if declared not in ("mechanism", "run"):
        raise ValueError(f"parameter {name}: owner must be 'mechanism' or 'run', got {declared!r}")
    return ("guide", guides) if guides else ("motion", motions) if motions else (declared, ())


def _choices(p):
    """(choice names, what they select) of a choice parameter."""
    selects = {id(model.GUIDES): "guide", id(model.MOTIONS): "motion"}.get(id(p.choices))
    names = tuple(c.name if hasattr(c, "name") else c for c in p.choices)
    return names, selects


def _parameters(vector):
    out = []
    for p in model.PARAMETERS:
        owner, readers = _readers(p.name, p.owner)
        choices, selects = _choices(p)
        slots = tuple(vector.index(n) for n in _slot_names(p))
        out.append(project(p, records.Parameter, owner=owner, readers=readers, choices=choices,
                           selects=selects, slots=slots, cli=p.cli or p.name.replace("_", "-"),
                           axis=p.axis or p.name))
    names = [p.name for p in out]
    for g in model.GUIDES:
        assert set(g.parameters) <= set(names), g.name
    for m in model.MOTIONS:
        assert set(m.parameters) <= set(names), m.name
        assert set(m.characteristic) <= set(m.parameters), m.name
        assert not m.characteristic or next(p for p in out if p.name == m.characteristic[0]).kind == "curve", m.name
    return tuple(out)


def _guide_record(g):
    closure = "closed-form" if g.phi is not None else "numerical"
    return project(g, records.Guide, margins=tuple(text for _, text in g.margin), closure=closure,
                   pivot=g.pivot is not None)


def _motion_record(m):
    return project(m, records.Motion, periodic=m.period is not None, driven=bool(m.coordinates),
                   coordinates=tuple(project(c, records.Coordinate) for c in m.coordinates))


def _energy_name(energy):
    return None if energy is None else energy.name


def _family_record(f):
    variants = tuple(project(v, records.Variant, when=dict(sorted(v.when.items())), kernel=f"{f.name}_{v.name}",
                             energy=_energy_name(v.energy),
                             quadrature=None if v.quadrature is None else v.quadrature.text)
                     for v in f.variants)
    names = {sym: name for name, sym in parameter_symbols().items()}
    formulas = {sym.name: sp.sympify(expr) for sym, expr in model.COEFFICIENTS.items()}
    read = set().union(*(formulas[c].free_symbols for c in f.vanishes_with)) if f.vanishes_with else set()
    parameters = tuple(name for sym, name in names.items() if sym in read)
    return project(f, records.Family, variants=variants, parameters=parameters)


def _exclusions():
    """The declared exclusions, their option values checked."""
    names = {o.name: o for o in model.OPTIONS}
    for x in model.EXCLUSIONS:
        for option, value in x.options.items():
            if option not in names or value not in names[option].choices:
                raise ValueError(f"exclusion {x.reason!r}: {option}={value!r} is not a choice")
    return tuple(records.Exclusion(dict(sorted(x.options.items())), x.reason) for x in model.EXCLUSIONS)


def _parameter_name(name):
    if name not in {p.name for p in model.PARAMETERS}:
        raise ValueError(f"{name!r} is not a parameter")
    return name


def _unit_parameters():
    return {unit: _parameter_name(name) for unit, name in sorted(model.UNIT_PARAMETERS.items())}


def _bodies():
    """The bodies, a flexible body's frame map (model.BODY_FRAMES: the entries of its kinematics
    vector that differ from the mechanism's, each linear in the mechanism's) as the matrix F of
    kin_body = F kin."""
    out = []
    for b in model.BODIES:
        frame = model.BODY_FRAMES.get(b.name)
        if frame is not None:
            rows = []
            for sym in s.KINEMATICS:
                expr = sp.sympify(frame.get(sym, sym))
                row = [expr.diff(k) for k in s.KINEMATICS]
                if any(not x.is_number for x in row) or sp.expand(expr - sum(x * k for x, k in zip(row, s.KINEMATICS))) != 0:
                    raise ValueError(f"body {b.name}: its frame's {sym} is not linear in the kinematics vector")
                rows.append(tuple(float(x) for x in row))
            b = replace(b, frame_map=tuple(rows))
        out.append(b)
    return tuple(out)


def _constraints():
    """The DOF map's constraints, checked: components of a node, one mapped constraint (the engine
    condenses one), which the 'end' families name."""
    optional = [b.name for b in model.BODIES if b.kind == "flexible" and b.name != "rod"]
    for present in [()] + [(name,) for name in optional]:
        mapped = [c for c in model.CONSTRAINTS if c.map is not None and c.applies(present)]
        if len(mapped) != 1:
            raise ValueError(f"the engine condenses exactly one mapped constraint, got {[c.name for c in mapped]} "
                             f"with the flexible bodies {present}")
    mapped = [c for c in model.CONSTRAINTS if c.map is not None]
    for c in model.CONSTRAINTS:
        if not set(c.eliminated) <= set(s.NODE) or len(c.reduced) > len(c.eliminated):
            raise ValueError(f"constraint {c.name}: eliminated {c.eliminated} must be components of a node "
                             f"{s.NODE}, at least as many as its reduced co-ordinates {c.reduced}")
    bodies = {b.name: b for b in model.BODIES}
    for c in model.CONSTRAINTS:
        if c.body not in bodies or bodies[c.body].kind != "flexible" or c.joint not in set(bodies) | {"ground"}:
            raise ValueError(f"constraint {c.name}: it must hold a node of a flexible body and join it to a "
                             f"declared body, got body {c.body!r}, joint {c.joint!r}")
        if not set(c.eliminated) <= set(bodies[c.body].node):
            raise ValueError(f"constraint {c.name}: {c.eliminated} are not components of {c.body}'s nodes")
    for f in model.FAMILIES:
        if f.part != "rod" and f.part != mapped[0].name:      # "end": the mapped constraint's node
            raise ValueError(f"family {f.name}: part {f.part!r} is neither 'rod' nor the mapped constraint")
    return tuple(model.CONSTRAINTS)


def _indicators():
    return tuple((sym.name, option, value) for sym, (option, value) in model.INDICATORS.items())


@lru_cache(maxsize=None)
def schema():
    """The declaration as records (see the module docstring)."""
    vector = Layout("parameters", tuple(parameter_symbols()),
                    "every parameter that enters an equation, one slot each (a pair: two), in the "
                    "order of the declaration")
    by_symbol = {sym: name for name, sym in parameter_symbols().items()}
    kinematic = Layout("params", tuple(by_symbol[sym] for sym in KINEMATIC_SYMBOLS),
                       "the slots of the parameter vector that the guides' and motions' kernels read")
    coefficients = Layout("coef", tuple(sym.name for sym in model.COEFFICIENTS),
                          "the element kernels' coefficients, each a formula in the parameters and "
                          "options (coefficients(p, options, off))")
    kin = Layout("kin", tuple(sym.name for sym in s.KINEMATICS),
                 "the rigid kinematics every kernel reads: the crank, the rod's chord angle, the "
                 "guide co-ordinate of the rigid end, with their rates")
    return Schema(
        options=_options(), presets=_presets(), default_preset=model.DEFAULT_PRESET,
        parameters=_parameters(vector.entries), guides=tuple(_guide_record(g) for g in model.GUIDES),
        motions=tuple(_motion_record(m) for m in model.MOTIONS),
        families=tuple(_family_record(f) for f in model.FAMILIES), outputs=_outputs_records(),
        primitives=_primitive_records(),
        printed_iteration=dict(sorted(model.PRINTED_ITERATION.items())),
        switchable_groups=s.SWITCHABLE_GROUPS, parameter_vector=vector,
        parameter_symbols=Layout("parameter symbols", tuple(sym.name for sym in parameter_symbols().values()),
                                 "the symbol of each slot of the parameter vector in the derivation"),
        kinematic_parameters=kinematic,
        kinematics=kin, coefficients=coefficients, indicators=_indicators(),
        crank_speed=_parameter_name(model.CRANK_SPEED), crank_angle=_parameter_name(model.CRANK_ANGLE),
        unit_parameters=_unit_parameters(),
        element_dofs=ELEMENT_DOFS, node=Layout("node", s.NODE, "the components of a node (eq. 14): axial "
                                                "and transverse displacement, slope"),
        constraints=_constraints(), exclusions=_exclusions(), bodies=_bodies(),
        reductions=_reductions())


# ---- the SymPy forms ----------------------------------------------------------------------------------

@dataclass(frozen=True)
class CoefficientForm:
    name: str
    formula: sp.Expr             # in the parameter symbols, the indicators and off_<group>


@dataclass(frozen=True)
class MotionForm:
    record: records.Motion
    crank: sp.Matrix             # (theta, thetad, thetadd) in t and the kinematic parameters
    period: object               # time of one revolution (None: not periodic)
    step_period: sp.Expr         # the time steps_per_rev steps divide
    equations: sp.Matrix = None  # a driven motion's co-ordinate equations and derivatives (coordinate_equations)
    start: sp.Matrix = None      # its co-ordinates' start (2, m): values, rates at t = 0
    inputs: tuple = ()           # the co-ordinate kernel's z vector: (z_j, zd_j, zdd_j of every co-ordinate)


def coordinate_symbols(m):
    """The symbols of a driven motion's co-ordinates: (values, rates, accelerations), each (m,)."""
    return tuple(tuple(getattr(c, k) for c in m.coordinates) for k in ("value", "rate", "acceleration"))


def coordinate_equations(m):
    """A driven motion's co-ordinate equations (derive/motions.py), ROD_TORQUE the output `torque`
    (the torque the rod demands, from the crank pin's force `pin` in the moving frame and the
    kinematics): (m, 3 m + 3), row i (g_i, dg_i/dz_j, dg_i/dzd_j, dg_i/dzdd_j for every co-ordinate
    j, dg_i/dpin_i, dg_i/dpin_j); the crank's z, zd, zdd are the kinematics' theta, thetad, thetadd
    (the derivatives are explicit: through the kinematics' other entries and the pin force the
    crank angle acts on the rod, which the runtime differences)."""
    torque = next(o for o in outputs.OUTPUTS if o.name == "torque").build({})
    variables = [x for group in coordinate_symbols(m) for x in group] + list(outputs.pin)
    rows = []
    for c in m.coordinates:
        g = c.equation.subs(mo.ROD_TORQUE, torque)
        rows.append([g] + [sp.diff(g, x) for x in variables])
    return sp.Matrix(rows)


def coordinate_inputs(m):
    """The symbols of the co-ordinate kernel's z vector, z_j, then zd_j, then zdd_j for every
    co-ordinate j: the co-ordinates' own symbols, a placeholder for the crank's (its kernel reads
    the kinematics' theta, thetad, thetadd, computed from the same numbers)."""
    crank = (s.theta, s.thetad, s.thetadd)
    return tuple(sp.Symbol(f"{kind}_{c.name}_unused") if x in crank else x
                 for kind, group in zip(("z", "zd", "zdd"), coordinate_symbols(m))
                 for c, x in zip(m.coordinates, group))


def coordinate_start(m):
    """(2, m): each co-ordinate's value and rate at t = 0."""
    return sp.Matrix([[c.start[0] for c in m.coordinates], [c.start[1] for c in m.coordinates]])


@dataclass(frozen=True)
class GuideForm:
    record: records.Guide
    kinematics: sp.Matrix        # kin in (theta, thetad, thetadd) and the kinematic parameters
    end_map: sp.Matrix           # (8, 2), rows guides.END_MAP_ROWS, in (s, sd, sdd), kin, parameters
    rigid_end: sp.Matrix         # (X, Y) of the rigid end point in kin and the parameters
    margins: sp.Matrix           # each > 0 iff the crank turns a full revolution
    end_scale: sp.Expr           # natural size of the reduced co-ordinate s, in eps and the parameters
    curve: sp.Matrix             # C(beta), the guide's curve
    pivot: sp.Matrix             # the ground pivot of the link carrying the end, or None
    closure: tuple               # a numerical closure (guides.closure), or None


@dataclass(frozen=True)
class VariantForm:
    record: records.Variant
    residual: sp.Matrix          # element residual (6,) in q, qd, qdd, geo, coef, kin
    printed_stiffness: object    # "exact", "none" or a 6x6 Matrix
    tangents: tuple = None       # (K, C, M) derived with the residual (quadrature); None: differentiate r
    definitions: tuple = ()      # stages of (symbol, expression) the residual and tangents are written in


@dataclass(frozen=True)
class FamilyForm:
    record: records.Family
    variants: tuple              # VariantForm, in the record's order


@dataclass(frozen=True)
class EnergyForm:
    name: str
    doc: str
    expr: sp.Expr                # in q, qd, geo, coef, kin (end-node energies on the last element's slots)


@dataclass(frozen=True)
class OutputVariant:
    when: dict                   # option values
    kernel: str
    expr: sp.Expr


@dataclass(frozen=True)
class OutputForm:
    record: records.Output
    variants: tuple              # OutputVariant


@dataclass(frozen=True)
class Representation:
    schema: Schema
    coefficients: tuple          # CoefficientForm
    motions: tuple               # MotionForm
    guides: tuple                # GuideForm
    families: tuple              # FamilyForm
    energies: tuple              # EnergyForm
    outputs: tuple               # OutputForm
    grams: tuple                 # GramForm, of the engine's integral primitives
    natural_sizes: tuple         # CoefficientForm per component of a node (units of L)
    body_coefficients: tuple = ()    # (body name, CoefficientForm tuple): another flexible body's coefficients


def _motions():
    names = {sym: name for name, sym in parameter_symbols().items()}
    out = []
    for m in model.MOTIONS:
        mo.check(m)
        crank = sp.Matrix(mo.rates(m))
        assert {names[sym] for sym in crank.free_symbols if sym in names} <= set(m.parameters), m.name
        driven = bool(m.coordinates)
        out.append(MotionForm(_motion_record(m), crank, m.period, m.step_period,
                              coordinate_equations(m) if driven else None, coordinate_start(m) if driven else None,
                              coordinate_inputs(m) if driven else ()))
    return tuple(out)


def _guides():
    names = {sym: name for name, sym in parameter_symbols().items()}
    out = []
    for g in model.GUIDES:
        margins = sp.Matrix([m for m, _ in g.margin]) if g.margin else None
        out.append(GuideForm(_guide_record(g), gd.kinematics(g), gd.end_map(g), gd.rigid_end(g), margins,
                             g.end_scale, g.curve, g.pivot, gd.closure(g)))
        if g.phi is None and g.guess is None:
            raise ValueError(f"guide {g.name}: neither a closed-form closure (phi, beta) nor a guess for Newton")
        assert margins is None or all(names.get(sym, "?") in g.parameters + ("a",) for sym in margins.free_symbols), g.name
    return tuple(out)


def _families():
    out = []
    for f in model.FAMILIES:
        record = _family_record(f)
        variants = []
        for v, vr in zip(f.variants, record.variants):
            term = v.build()
            variants.append(VariantForm(vr, sp.Matrix(term.residual), term.printed_stiffness, term.tangents,
                                        term.definitions))
        out.append(FamilyForm(record, tuple(variants)))
    return tuple(out)


def _energies():
    """Every energy a variant derives from, once (by kernel name)."""
    out = {}
    for f in model.FAMILIES:
        for v in f.variants:
            e = v.energy
            if e is not None and e.name not in out:
                out[e.name] = EnergyForm(e.name, e.doc, sp.sympify(e.build()))
    return tuple(out.values())


def _natural_sizes():
    """The natural size of each component of a node, a formula in the parameters."""
    allowed = set(parameter_symbols().values())
    out = []
    for component in s.NODE:
        expr = sp.sympify(model.NATURAL_SIZES[component])
        if expr.free_symbols - allowed:
            raise ValueError(f"natural size of {component}: symbols that are not parameters")
        out.append(CoefficientForm(component, expr))
    return tuple(out)


def _coefficients(replaced=None):
    """The coefficient vector's formulas (model.COEFFICIENTS), those in `replaced` replaced (another
    flexible body's: model.BODY_COEFFICIENTS)."""
    allowed = set(parameter_symbols().values()) | set(model.INDICATORS) | set(model.switched_off.values())
    out = []
    for sym, expr in model.COEFFICIENTS.items():
        expr = sp.sympify((replaced or {}).get(sym, expr))
        unknown = expr.free_symbols - allowed
        if unknown:
            raise ValueError(f"coefficient {sym.name}: symbols that are neither parameters nor indicators: "
                             f"{sorted(map(str, unknown))}")
        out.append(CoefficientForm(sym.name, expr))
    return tuple(out)


# ---- outputs ------------------------------------------------------------------------------------------

# The parameters' symbols as an output kernel's input `parameters` (the parameter vector; the crank
# length's slot holds an unused stand-in, kin carries it)
PARAMETERS_BESIDE_KIN = tuple(sp.Symbol(f"{sym.name}_param") if sym in s.KINEMATICS else sym
                              for sym in parameter_symbols().values())
# The inputs an output kernel may read, in the order of its arguments, with the symbols of each.
OUTPUT_INPUTS = (
    ("q", tuple(s.q)), ("qd", tuple(s.qd)), ("zeta", (s.zeta,)), ("geo", s.GEOMETRY), ("coef", COEFFICIENT_SYMBOLS),
    ("kin", s.KINEMATICS), ("parameters", PARAMETERS_BESIDE_KIN),
    ("q_end", tuple(outputs.q_end)), ("qd_end", tuple(outputs.qd_end)), ("qdd_end", tuple(outputs.qdd_end)),
    ("s", (outputs.s_end,)), ("pin", tuple(outputs.pin)), ("end", tuple(outputs.end_force)),
    ("rod_end", tuple(outputs.rod_end)), ("ground", tuple(outputs.ground_force)), ("fiber", (outputs.fiber,)),
)
# what a kind of output always reads (a field: its element and the point in it; a reduction: each element)
KIND_INPUTS = {"field": ("q", "zeta", "geo", "coef"), "reduction": ("q", "geo"), "step": ()}
# the engine's outputs: one kernel, per_step(prims, q_end, parameters), all of them at once
PRIMITIVE_SYMBOLS = tuple(p.symbol for p in outputs.PRIMITIVES.values())
ENGINE_INPUTS = (("prims", PRIMITIVE_SYMBOLS), ("q_end", tuple(outputs.q_end)),
                 ("parameters", tuple(parameter_symbols().values())))


def _output_inputs(expr, name, inputs=OUTPUT_INPUTS):
    """The inputs an output's expression reads, in argument order: those that hold its symbols, the
    one holding the most of them first where a symbol is in two (gravity is a coefficient and a
    parameter; a kernel takes at most one of the inputs that share it)."""
    used = expr.free_symbols
    known = set().union(*(set(syms) for _, syms in inputs))
    if used - known:
        raise ValueError(f"output {name}: symbols outside the output inputs: {used - known}")
    chosen, left = set(), set(used)
    while left:
        best = max(inputs, key=lambda item: len(left & set(item[1])))
        chosen.add(best[0])
        left -= set(best[1])
    return [n for n, _ in inputs if n in chosen]


def _option_cases(names):
    """Every combination of the choices of the options `names` ({} for none)."""
    cases = [{}]
    for name in names:
        option = next(o for o in model.OPTIONS if o.name == name)
        cases = [dict(c, **{name: v}) for c in cases for v in option.choices]
    return cases


def _coarse_key(options):
    """The membrane strain's cases: linear (approach C), pointwise or averaged; exact for the
    geometrically exact rod (whose strain is pointwise whatever the membrane option)."""
    if options.get("approach") == "C":
        return "linear"
    if options.get("approach") == model.EXACT:
        return "exact"
    return "averaged" if options.get("membrane") == "averaged" else "pointwise"


def _group_suffix(cases, every):
    """A kernel's suffix for the option cases sharing its expression (of `every` case of the
    output): their membrane strain's case when they share one; "exact" for the exact rod's cases
    alone; "" for all the cases of the other approaches (the classical strain's, e.g. the bending
    moment v_xx); None otherwise (the kernels are then named by the option values)."""
    keys = {_coarse_key(c) for c in cases}
    approaches = {c.get("approach") for c in cases}
    if len(keys) == 1:
        return keys.pop()
    if approaches == {model.EXACT}:
        return "exact"
    classical = [c for c in every if c.get("approach") != model.EXACT]
    return "" if sorted(map(str, cases)) == sorted(map(str, classical)) else None


def _output_expression(o, options):
    """An output's expression for the option values: expanded (the canonical form its kernels are
    grouped by), except the exact rod's own, whose square roots would multiply out."""
    expr = o.build(options)
    if options.get("approach") == model.EXACT and expr != o.build(dict(options, approach="A")):
        return expr
    return sp.expand(expr)


def _output_forms(o):
    """(inputs, variants) of a declared output with a build: its expression for every combination
    of the options it depends on, one kernel per distinct expression (named by the membrane strain's
    case when that tells them apart, _group_suffix, else by the option values)."""
    if o.engine:
        expr = sp.expand(o.build({}))
        if o.options or o.kind != "step":
            raise ValueError(f"output {o.name}: an engine output is a step output of no option")
        _output_inputs(expr, o.name, ENGINE_INPUTS)
        return (), (OutputVariant({}, "per_step", expr),)
    groups, every = {}, _option_cases(o.options)
    for options in every:
        groups.setdefault(_output_expression(o, options), []).append(options)
    suffixes = [_group_suffix(cases, every) for cases in groups.values()]
    by_coarse = None not in suffixes and len(set(suffixes)) == len(suffixes)
    variants, inputs = [], set(KIND_INPUTS[o.kind])
    for (expr, cases), coarse in zip(groups.items(), suffixes):
        suffix = "_" + "_".join(str(v) for v in cases[0].values()) if not by_coarse else f"_{coarse}" if coarse else ""
        kernel = f"{o.kind}_{o.name}{'' if len(groups) == 1 else suffix}"
        variants += [OutputVariant(dict(sorted(c.items())), kernel, expr) for c in cases]
        inputs.update(_output_inputs(expr, o.name))
    return tuple(n for n, _ in OUTPUT_INPUTS if n in inputs), tuple(variants)


def _output_record(o, forms):
    guides = o.guides or tuple(g.name for g in model.GUIDES)
    inputs, variants = forms
    kernels = () if o.engine else tuple((v.when, v.kernel) for v in variants)
    return project(o, records.Output, guides=guides, inputs=inputs, kernels=kernels)


@lru_cache(maxsize=None)
def _all_output_forms():
    return tuple((o, _output_forms(o)) for o in outputs.OUTPUTS)


def _outputs_records():
    return tuple(_output_record(o, forms) for o, forms in _all_output_forms())


def _outputs():
    return tuple(OutputForm(_output_record(o, forms), forms[1]) for o, forms in _all_output_forms())


REDUCTION_KINDS = ("peak", "max", "min", "range", "mean", "rms")


def _reductions():
    """The declared reductions over time (derive/outputs.py REDUCTIONS), checked, with their
    output's units and guides: a field at an x* in [0, 1] with its arguments, any other kind of
    output without."""
    records_by_name = {r.name: r for r in _outputs_records()}
    out = []
    for r in outputs.REDUCTIONS:
        o = records_by_name.get(r.output)
        if o is None or r.kind not in REDUCTION_KINDS:
            raise ValueError(f"reduction {r.name}: output {r.output!r} must be declared and kind {r.kind!r} one of "
                             f"{REDUCTION_KINDS}")
        if (o.kind == "field") != (r.at is not None) or (o.kind == "field" and not 0 <= r.at <= 1) \
                or set(dict(r.arguments)) != set(o.arguments if o.kind == "field" else ()):
            raise ValueError(f"reduction {r.name}: a field's needs its x* in [0, 1] and its arguments {o.arguments}")
        if r.name in records_by_name:
            raise ValueError(f"reduction {r.name}: the name of an output")
        out.append(project(r, records.Reduction, units=o.units, guides=o.guides))
    return tuple(out)


@dataclass(frozen=True)
class GramForm:
    name: str                    # the kernel gram_<primitive>(l)
    matrix: sp.Matrix            # G: the element's int integrand dx = q^T G q


def _primitive_records():
    return tuple(project(p, records.Primitive) for p in outputs.PRIMITIVES.values())


def _grams():
    """The Gram matrix of each integral primitive: int_element integrand dx = q^T G q."""
    out = []
    for p in outputs.PRIMITIVES.values():
        if p.kind != "integral":
            continue
        total = integrate_element(sp.expand(p.integrand))
        G = sp.hessian(total, s.q) / 2
        if G.free_symbols - {s.l} or sp.expand(total - (s.q.T * G * s.q)[0, 0]) != 0:
            raise ValueError(f"primitive {p.name}: the integrand is not a quadratic form in q with "
                             f"coefficients in the element length")
        out.append(GramForm(p.kernel, G))
    return tuple(out)


@lru_cache(maxsize=None)
def representation():
    """The model representation of the declaration (built once per process)."""
    return Representation(schema=schema(), coefficients=_coefficients(),
                          body_coefficients=tuple((name, _coefficients(replaced))
                                                  for name, replaced in model.BODY_COEFFICIENTS.items()), motions=_motions(), guides=_guides(),
                          families=_families(), energies=_energies(), outputs=_outputs(), grams=_grams(),
                          natural_sizes=_natural_sizes())


# ---- the audit's group kernels (the consistent model's forces split by kind) -------------------------

@dataclass(frozen=True)
class GroupRecord:
    name: str
    source: str
    group: str
    residual: sp.Matrix


@lru_cache(maxsize=None)
def audit_groups():
    """The consistent model's element forces (approach A: lagrange inertia, elastic force and
    Kelvin-Voigt damping, pointwise and averaged membrane) split by kind (derive/groups.py), in the
    element convention; the end mass's inertia groups act on the last element."""
    sources = [
        ("rod_inertia", kinetic_residual(en.rod_kinetic_energy(), s.q, s.qd, s.qdd), False),
        ("slider_inertia", kinetic_residual(en.slider_kinetic_energy(), s.qs, s.qsd, s.qsdd), True),
        ("rod_elastic_A", gradient(en.strain_energy("A"), s.q), False),
        ("rod_elastic_A_averaged", gradient(en.strain_energy_averaged("A"), s.q), False),
        ("kelvin_voigt_A", gradient(en.kelvin_voigt_dissipation("A"), s.qd), False),
        ("kelvin_voigt_A_averaged", gradient(en.kelvin_voigt_dissipation_averaged("A"), s.qd), False),
    ]
    out = []
    for name, residual, slider in sources:
        variables, rows = (SLIDER_VARS, SLIDER_AXIAL_ROWS) if slider else (ELEMENT_VARS, ROD_AXIAL_ROWS)
        for group, part in group_vector(sp.Matrix(residual), variables, rows).items():
            r = model.on_last_element(part) if slider else sp.Matrix(part)
            out.append(GroupRecord(f"{name}__{group}", name, group, r))
    return tuple(out)


SHAPES = {"N_u": N_U, "N_v": N_V, "N_psi": N_PSI, "N_u_cubic": N_U_CUBIC,
          "slope_gram": (B_V * B_V.T).applyfunc(integrate_element)}
