"""Stage 6: the model representation, typed immutable records between the declaration and code
generation.

`representation()` turns the declaration (derive/model.py, with the derivations it names:
energies, printed form, guides, motions) into the records below.  Code generation needs nothing
else: derive/kernels.py makes the kernel specifications of a record from that record alone, and
derive/schema.py prints the runtime's schema (generated/schema.py) from the records; neither
looks back at the declaration or the derivation (the rule of FFCx's intermediate representation).

Records:
- OptionRecord, PresetRecord: the model options (choice, effective default, help) and the named
  models;
- ParameterRecord: every parameter of a case (kind, default, range, units, label, help, flag, the
  guides or motions that read it, its place in the kinematic parameter vector);
- CoefficientRecord: the element kernels' coefficients as formulas;
- MotionRecord: a crank motion's theta, thetad, thetadd in t and the kinematic parameters, and its
  period (None: not periodic);
- GuideRecord: a guide's rigid kinematics kin(theta, thetad, thetadd, params), its end map, its
  rigid end point, its full-turn margins and the natural size of its reduced co-ordinate;
- FamilyRecord / VariantRecord: the term families with each variant's element residual;
- EnergyRecord: energy and dissipation functions per element (or on the end node);
- OutputRecord: each declared output with its expression per option case, the kernel inputs it
  reads and its units;
- Representation: all of the above and the calling conventions' layouts (kinematics vector,
  kinematic parameters, element size, end slots).
"""

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import energies as en
from . import guides as gd
from . import model
from . import motions as mo
from . import quadrature
from . import symbols as s
from .euler_lagrange import gradient, kinetic_residual
from .groups import ELEMENT_VARS, ROD_AXIAL_ROWS, SLIDER_AXIAL_ROWS, SLIDER_VARS, group_vector
from .shape_functions import B_V, N_PSI, N_U, N_V, integrate_element

ELEMENT_DOFS = 6                 # (u, v, psi) of the element's two nodes, eq. (14)
END_SLOTS = (3, 4)               # (u, v) of the rod's end node in the last element's vector
KINEMATIC_SYMBOLS = tuple(p.symbol for p in model.PARAMETERS if p.symbol is not None)
CRANK_SYMBOLS = (s.theta, s.thetad, s.thetadd)
END_COORDINATES = (gd.sp_s, gd.sp_sd, gd.sp_sdd)


@dataclass(frozen=True)
class OptionRecord:
    name: str
    choices: tuple
    default: object
    doc: str
    cli: str


@dataclass(frozen=True)
class PresetRecord:
    name: str
    options: tuple               # ((option, value), ...)
    doc: str


@dataclass(frozen=True)
class ParameterRecord:
    name: str
    kind: str                    # real, pair, sign, count, choice
    default: object
    label: str
    doc: str
    owner: str                   # mechanism, guide, motion, run
    readers: tuple               # the guides (owner guide) or motions (owner motion) that read it; () otherwise
    low: object
    high: object
    low_open: bool
    high_open: bool
    units: str
    cli: str
    metavar: str
    choices: tuple
    continuable: bool
    kinematic_index: int         # place in the kinematic parameter vector, or -1


@dataclass(frozen=True)
class CoefficientRecord:
    name: str
    formula: sp.Expr             # in eps, ms, mu, gX, gY, with_rotary_inertia, off_<group>


@dataclass(frozen=True)
class MotionRecord:
    name: str
    title: str
    parameters: tuple
    crank: sp.Matrix             # (theta, thetad, thetadd) in t and the kinematic parameters
    period: object               # time of one revolution (None: not periodic)
    step_period: sp.Expr         # the time steps_per_rev steps divide
    doc: str
    aliases: tuple


@dataclass(frozen=True)
class GuideRecord:
    name: str
    title: str
    parameters: tuple
    kinematics: sp.Matrix        # kin in (theta, thetad, thetadd) and the kinematic parameters
    end_map: sp.Matrix           # (8, 2), rows guides.END_MAP_ROWS, in (s, sd, sdd), kin, parameters
    rigid_end: sp.Matrix         # (X, Y) of the rigid end point in kin and the parameters
    margins: sp.Matrix           # each > 0 iff the crank turns a full revolution
    margin_texts: tuple
    end_scale: sp.Expr           # natural size of the reduced co-ordinate s, in eps and the parameters
    doc: str
    aliases: tuple


@dataclass(frozen=True)
class VariantRecord:
    name: str
    kernel: str                  # element kernel name: <family>_<variant>
    when: tuple                  # ((option, value), ...) that select it
    groups: tuple
    energy: str
    doc: str
    residual: sp.Matrix          # element residual (6,) in q, qd, qdd, geo, coef, kin
    printed_stiffness: object    # "exact", "none" or a 6x6 Matrix
    tangents: tuple = None       # (K, C, M) derived with the residual (quadrature); None: differentiate r
    quadrature: object = None    # the quadrature.Rule of its element integrals (None: closed form)
    definitions: tuple = ()      # ((point field, its linear form), ...) the residual and tangents use


@dataclass(frozen=True)
class FamilyRecord:
    name: str
    part: str                    # rod, end
    doc: str
    energy_kind: str
    vanishes_with: tuple
    variants: tuple


@dataclass(frozen=True)
class EnergyRecord:
    name: str
    doc: str
    expr: sp.Expr                # in q, qd, geo, coef, kin (end-node energies on the last element's slots)


@dataclass(frozen=True)
class OutputVariant:
    when: tuple                  # ((option, value), ...)
    kernel: str
    expr: sp.Expr


@dataclass(frozen=True)
class OutputRecord:
    name: str
    kind: str                    # engine, step, field
    doc: str
    units: str
    arguments: tuple
    guides: tuple                # the guides it exists for
    inputs: tuple                # kernel input names (OUTPUT_INPUTS order)
    variants: tuple


@dataclass(frozen=True)
class Representation:
    options: tuple
    presets: tuple
    default_preset: str
    parameters: tuple
    coefficients: tuple
    switchable_groups: tuple
    kinematics: tuple            # names of the kinematics vector's entries
    kinematic_parameters: tuple  # names of the kinematic parameter vector's entries
    motions: tuple
    guides: tuple
    families: tuple
    energies: tuple
    outputs: tuple
    printed_iteration: tuple
    exclusions: tuple            # ((((option, value), ...), reason), ...): combinations refused
    element_dofs: int
    end_slots: tuple


# ---- options, presets, parameters ----------------------------------------------------------------

def _options():
    preset = dict(next(p for p in model.PRESETS if p.name == model.DEFAULT_PRESET).options)
    out = []
    for o in model.OPTIONS:
        default = preset.get(o.name, o.default)
        if default not in o.choices:
            raise ValueError(f"option {o.name}: no default (neither its own nor the default preset's)")
        out.append(OptionRecord(o.name, o.choices, default, o.doc, o.cli or o.name.replace("_", "-")))
    return tuple(out)


def _presets():
    names = {o.name: o for o in model.OPTIONS}
    for p in model.PRESETS:
        for option, value in p.options.items():
            if value not in names[option].choices:
                raise ValueError(f"preset {p.name}: {option}={value!r} is not a choice")
    return tuple(PresetRecord(p.name, tuple(sorted(p.options.items())), p.doc) for p in model.PRESETS)


def _exclusions():
    names = {o.name: o for o in model.OPTIONS}
    for x in model.EXCLUSIONS:
        for option, value in x.options.items():
            if value not in names[option].choices:
                raise ValueError(f"exclusion {x.reason!r}: {option}={value!r} is not a choice")
    return tuple((tuple(sorted(x.options.items())), x.reason) for x in model.EXCLUSIONS)


def _readers(owner):
    if ":" not in owner:
        return owner, ()
    kind, names = owner.split(":")
    return kind, tuple(names.split(","))


def _parameters():
    out = []
    for p in model.PARAMETERS:
        owner, readers = _readers(p.owner)
        index = KINEMATIC_SYMBOLS.index(p.symbol) if p.symbol is not None else -1
        out.append(ParameterRecord(
            p.name, p.kind, p.default, p.label, p.doc, owner, readers, p.low, p.high, p.low_open,
            p.high_open, p.units, p.cli or p.name.replace("_", "-"), p.metavar, p.choices,
            p.continuable, index))
    names = [p.name for p in out]
    for guide in model.GUIDES:
        assert set(guide.parameters) <= set(names), guide.name
    for motion in model.MOTIONS:
        assert set(motion.parameters) <= set(names), motion.name
    return tuple(out)


def _parameter_symbol_names():
    """{derivation symbol: the parameter's name} of the kinematic parameters."""
    return {p.symbol: p.name for p in model.PARAMETERS if p.symbol is not None}


# ---- kinematics -------------------------------------------------------------------------------------

def _motions():
    names = _parameter_symbol_names()
    out = []
    for m in model.MOTIONS:
        mo.check(m)
        crank = sp.Matrix(mo.rates(m))
        assert {names[sym] for sym in crank.free_symbols if sym in names} <= set(m.parameters), m.name
        out.append(MotionRecord(m.name, m.title, m.parameters, crank, m.period, m.step_period, m.doc,
                                m.aliases))
    return tuple(out)


def _guides():
    names = _parameter_symbol_names()
    out = []
    for g in model.GUIDES:
        margins = sp.Matrix([m for m, _ in g.margin])
        out.append(GuideRecord(
            g.name, g.title, g.parameters, gd.kinematics(g), gd.end_map(g), gd.rigid_end(g), margins,
            tuple(text for _, text in g.margin), g.end_scale, g.doc, g.aliases))
        assert all(names.get(sym, "?") in g.parameters + ("a",) for sym in margins.free_symbols), g.name
    return tuple(out)


# ---- families and energies ----------------------------------------------------------------------------

def _families():
    out = []
    for f in model.FAMILIES:
        variants = []
        for v in f.variants:
            term = v.build()
            variants.append(VariantRecord(
                v.name, f"{f.name}_{v.name}", tuple(sorted(v.when.items())), v.groups, v.energy, v.doc,
                sp.Matrix(term.residual), term.printed_stiffness, term.tangents, v.quadrature,
                term.definitions))
        out.append(FamilyRecord(f.name, f.part, f.doc, f.energy_kind, f.vanishes_with, tuple(variants)))
    return tuple(out)


def _energies():
    on_end = model._ON_LAST_ELEMENT
    out = [
        EnergyRecord("rod_kinetic_energy", "Element kinetic energy T_i of the rod, eqs. (4)-(5).",
                     en.rod_kinetic_energy()),
        EnergyRecord("slider_kinetic_energy", "Kinetic energy T_s of the end mass, eqs. (6)-(7), on "
                     "the last element.", en.slider_kinetic_energy().subs(on_end)),
        EnergyRecord("rod_gravity_potential", "Element potential of gravity V_i.", en.rod_gravity_potential()),
        EnergyRecord("slider_gravity_potential", "Potential of gravity on the end mass, on the last "
                     "element.", en.slider_gravity_potential().subs(on_end)),
    ]
    for ap in en.APPROACHES:
        for averaged in ((False, True) if ap != "C" else (False,)):
            suffix = "_averaged" if averaged else ""
            U = (en.strain_energy_averaged if averaged else en.strain_energy)(ap)
            D = (en.kelvin_voigt_dissipation_averaged if averaged else en.kelvin_voigt_dissipation)(ap)
            out.append(EnergyRecord(
                f"strain_energy_{ap}{suffix}",
                f"Element strain energy U_i of approach {ap}{', element-mean membrane strain' if averaged else ''}.", U))
            out.append(EnergyRecord(
                f"dissipation_{ap}{suffix}",
                f"Kelvin-Voigt Rayleigh dissipation function D of approach {ap}"
                f"{', element-mean membrane strain rate' if averaged else ''}.", D))
    out += _exact_energies()
    return tuple(out)


def _exact_energies():
    """The exact rod's energy kernels: its kinetic energy (the centre line's closed form, the exact
    section rotation's by the rule), strain energy and dissipation by the rule, in q and qd."""
    space = quadrature.PointSpace(model.EXACT_RULE, en.QUANTITIES, en.ELEMENT_FIELDS, en.POINT_FIELDS)

    def in_q(energy):
        return space.in_nodal(energy)
    f = dict(en.fields(s.q, s.qd), x=s.x0 + s.l * s.zeta)
    kinetic = model.integrate_centre_line(f) + in_q(en.element_rotary_kinetic_energy(space))
    rule = model.EXACT_RULE.text
    out = [EnergyRecord("rod_kinetic_energy_exact", "Element kinetic energy of the geometrically exact "
                        f"rod (centre line and exact section rotation; the rotation by {rule} quadrature).",
                        kinetic)]
    for membrane, suffix in (("pointwise", ""), ("averaged", "_averaged")):
        what = "element-mean stretch" if membrane == "averaged" else "pointwise stretch"
        out.append(EnergyRecord(f"strain_energy_exact{suffix}", f"Element strain energy of the exact rod, "
                                f"{what}, by {rule} quadrature.",
                                in_q(en.element_strain_energy(space, "exact", membrane))))
        out.append(EnergyRecord(f"dissipation_exact{suffix}", f"Kelvin-Voigt Rayleigh dissipation function "
                                f"of the exact rod, {what} rate, by {rule} quadrature.",
                                in_q(en.element_dissipation(space, "exact", membrane))))
    return out


# ---- outputs ------------------------------------------------------------------------------------------

# The inputs an output kernel may read, in the order of its arguments, with the symbols of each.
OUTPUT_INPUTS = (
    ("q", tuple(s.q)), ("zeta", (s.zeta,)), ("geo", s.GEOMETRY), ("coef", s.COEFFICIENTS),
    ("kin", s.KINEMATICS), ("params", tuple(x for x in KINEMATIC_SYMBOLS if x != s.a)),
    ("q_end", tuple(model.q_end)), ("qd_end", tuple(model.qd_end)),
    ("s", (model.s_end,)), ("pin", tuple(model.pin)), ("end", tuple(model.end_force)),
    ("fiber", (model.fiber,)),
)
# option cases that give every field output its distinct expressions
FIELD_OPTION_CASES = ({"approach": "A", "membrane": "pointwise"}, {"approach": "A", "membrane": "averaged"},
                      {"approach": "C", "membrane": "pointwise"})


def _output_inputs(expr, name):
    used = expr.free_symbols
    inputs = [n for n, syms in OUTPUT_INPUTS if used & set(syms)]
    known = set().union(*(set(syms) for _, syms in OUTPUT_INPUTS))
    if used - known:
        raise ValueError(f"output {name}: symbols outside the output inputs: {used - known}")
    return inputs


# the exact rod's option cases (its outputs' kernels are named by _field_key: exact, exact_averaged)
EXACT_OPTION_CASES = ({"approach": "exact", "membrane": "pointwise"}, {"approach": "exact", "membrane": "averaged"})


def _field_key(options):
    if options["approach"] == "exact":
        return "exact_averaged" if options["membrane"] == "averaged" else "exact"
    if options["approach"] == "C":
        return "linear"
    return "averaged" if options["membrane"] == "averaged" else "pointwise"


def _outputs():
    guide_names = tuple(g.name for g in model.GUIDES)
    out = []
    for o in model.OUTPUTS:
        guides = o.guides or guide_names
        if o.kind == "engine":
            out.append(OutputRecord(o.name, o.kind, o.doc, o.units, (), guides, (), ()))
            continue
        cases = FIELD_OPTION_CASES if o.kind == "field" else ({"approach": "A", "membrane": "pointwise"},)
        exprs = {}
        for options in cases:
            exprs.setdefault(sp.expand(o.build(options)), []).append(options)
        variants, inputs = [], set()
        distinct = len(exprs) > 1
        for expr, option_sets in exprs.items():
            suffix = f"_{_field_key(option_sets[0])}" if distinct else ""
            kernel = f"{o.kind}_{o.name}{suffix}"
            for ap in ("A", "B", "C"):
                for membrane in ("pointwise", "averaged"):
                    opts = {"approach": ap, "membrane": membrane}
                    if not distinct or _field_key(opts) == _field_key(option_sets[0]):
                        variants.append(OutputVariant(tuple(sorted(opts.items())), kernel, expr))
            inputs.update(_output_inputs(expr, o.name))
        legacy = o.build({"approach": "A", "membrane": "pointwise"})
        for opts in EXACT_OPTION_CASES:          # the exact rod's: a kernel of its own where it differs
            expr = o.build(opts)                 # (not expanded: its square roots would multiply out)
            if expr == legacy:
                kernel, expr = variants[0].kernel, variants[0].expr
            else:
                kernel = next((v.kernel for v in variants if v.expr == expr), None)
            if kernel is None:
                kernel = f"{o.kind}_{o.name}_{_field_key(opts)}"
                inputs.update(_output_inputs(expr, o.name))
            variants.append(OutputVariant(tuple(sorted(opts.items())), kernel, expr))
        if o.kind == "field":
            inputs.update({"q", "zeta", "geo", "coef"})
        ordered = tuple(n for n, _ in OUTPUT_INPUTS if n in inputs)
        out.append(OutputRecord(o.name, o.kind, o.doc, o.units, o.arguments, guides, ordered, tuple(variants)))
    return tuple(out)


@lru_cache(maxsize=None)
def representation():
    """The model representation of the declaration (built once per process)."""
    return Representation(
        options=_options(), presets=_presets(), default_preset=model.DEFAULT_PRESET,
        parameters=_parameters(),
        coefficients=tuple(CoefficientRecord(sym.name, sp.sympify(expr)) for sym, expr in model.COEFFICIENTS.items()),
        switchable_groups=s.SWITCHABLE_GROUPS,
        kinematics=tuple(sym.name for sym in s.KINEMATICS),
        kinematic_parameters=tuple(p.name for p in model.PARAMETERS if p.symbol is not None),
        motions=_motions(), guides=_guides(), families=_families(), energies=_energies(),
        outputs=_outputs(), printed_iteration=tuple(sorted(model.PRINTED_ITERATION.items())),
        exclusions=_exclusions(),
        element_dofs=ELEMENT_DOFS, end_slots=END_SLOTS)


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


SHAPES = {"N_u": N_U, "N_v": N_V, "N_psi": N_PSI,
          "slope_gram": (B_V * B_V.T).applyfunc(integrate_element)}
