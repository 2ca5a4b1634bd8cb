"""A case: every parameter of one run, as one frozen record (the unit of sweeps and checkpoints).

Its fields come from the schema (derive/declaration.py): the mechanism's and its guide's parameters, the
run's (the crank motion and its parameters, n_elements, steps_per_rev, integrator, rho_inf), the
model options (formulation, approach, membrane, damping, rotary_inertia) and the audit's
switched-off term groups.  The model is chosen by preset and options, checked once:
`Case(model="paper")`, or the default model (`consistent`); an option given explicitly overrides
the preset's value, and a run parameter the preset sets (the paper's rho_inf = 1, Newmark) takes
the preset's value unless given.  Every
value is stored in canonical form (crankgen.declaration.schema), so that equal cases compare equal and share
one key however their values were typed; an unknown or incompatible option, or a parameter out of
range, raises ParameterError naming it when the case is built.
"""

from dataclasses import asdict, dataclass, fields

import numpy as np

from . import ingredients, schema
from .._generated import classes as _classes
from ..errors import ParameterError
from .parameters import Mechanism, check_full_turn, settle
from .plausibility import check_speeds
from . import values as _values

PARAMETER_FIELDS = tuple(schema.PARAMETERS)
OPTION_FIELDS = tuple(schema.OPTIONS)
_NOT_KEYED = ("model",)
_MEMO = "_views"          # the instance's dictionary entry holding its computed views (CaseRules._derived)


def _plain(value):
    """Tuples as lists, nested ones too (JSON reads them back so)."""
    return [_plain(v) for v in value] if isinstance(value, tuple) else value


class CaseRules:
    """The checks and views of a Case (its fields: generated/classes.py CaseFields)."""

    def __post_init__(self):
        given = {n for n in PARAMETER_FIELDS if getattr(self, n) is not None}
        settle(self, PARAMETER_FIELDS)
        check_speeds(self.parameters())
        check_full_turn(self.parameters())
        options = schema.resolve_options(self.model, **{n: getattr(self, n) for n in OPTION_FIELDS})
        for name, value in options.items():
            object.__setattr__(self, name, value)
        # the run settings that go with the model (the paper's Newmark rule): the preset the options
        # match, else the one asked for; a setting given explicitly is kept
        preset = schema.preset_of(options) or (self.model if self.model in schema.PRESETS
                                               else schema.DEFAULT_PRESET)
        for name, value in schema.PRESETS[preset].settings.items():
            if name not in given:
                object.__setattr__(self, name, _values.canonical(schema.PARAMETERS[name], value))
        object.__setattr__(self, "model", schema.preset_of(options))
        if not isinstance(self.groups_off, str):
            raise ParameterError(f"groups_off must be a string, got {self.groups_off!r}")
        off = ingredients.check_switched_off(self.groups_off, self.selection)
        object.__setattr__(self, "groups_off", ",".join(sorted(off)))
        for view in ("selection", "coefficients"):    # read groups_off before it was normalised
            self.__dict__.get(_MEMO, {}).pop(view, None)
        self._check_flexible_bodies()

    def _check_flexible_bodies(self):
        """A flexible body (a rocker with elements) carries its own mass: the families a rigid body of
        that name carries (Family.body: a rigid rocker's mass, weight and spring) are refused."""
        for body in schema.BODIES.values():
            if body.kind != "flexible" or body.elements is None or body.elements not in self.guide_record.parameters:
                continue
            count = getattr(self, body.elements)
            if not count:
                continue
            chosen = dict(zip((f.name for f in schema.FAMILIES), self.selection.families))
            rigid = [f for f in schema.FAMILIES if f.body == body.name and chosen[f.name] >= 0]
            if rigid:
                given = sorted({p for f in rigid for p in f.parameters       # those 0 by default and given
                                if p in schema.PARAMETERS and schema.PARAMETERS[p].default == 0 and getattr(self, p)})
                raise ParameterError(
                    f"a flexible {body.name} ({body.elements} = {count}) carries its own mass, weight and "
                    f"stiffness, its section's: the rigid {body.name}'s terms ({', '.join(f.name for f in rigid)}) "
                    f"cannot act on it too; leave {', '.join(given) or 'their parameters'} at 0 (or give "
                    f"{body.elements} = 0 for a rigid {body.name})")

    def _derived(self, name, build):
        """A view of the case computed once: a case never changes after it is built (frozen), and
        a continuation or a sweep asks for the same views of one case many times.  An array is
        handed out as a copy (a caller may change its own; compiled code gets the writable
        contiguous array it was compiled for)."""
        memo = self.__dict__.setdefault(_MEMO, {})
        if name not in memo:
            memo[name] = build()
        value = memo[name]
        return value.copy() if isinstance(value, np.ndarray) else value

    def __getstate__(self):
        """The fields alone (a pickled case carries no computed views)."""
        return {k: v for k, v in self.__dict__.items() if k != _MEMO}

    @classmethod
    def from_mechanism(cls, mech, **settings):
        """The case of a Mechanism (every one of its fields) with the given run settings and model."""
        if not isinstance(mech, Mechanism):
            raise ParameterError(f"mech must be a crankgen.Mechanism, got {type(mech).__name__}")
        return make_case(**mech.values(), **settings)

    @property
    def mechanism(self):
        return Mechanism(**{n: getattr(self, n) for n in schema.MECHANISM_PARAMETERS})

    def parameters(self):
        """{name: value} of every schema parameter."""
        return {n: getattr(self, n) for n in PARAMETER_FIELDS}

    @property
    def parameter_vector(self):
        """The parameter vector (schema.PARAMETER_VECTOR order): every parameter entering an equation."""
        return self._derived("parameter_vector", lambda: schema.parameter_vector(self.parameters()))

    @property
    def kinematic_parameters(self):
        """The kinematic parameter vector (schema.KINEMATIC_PARAMETERS order)."""
        return self._derived("kinematic_parameters", lambda: self.parameter_vector[list(schema.KINEMATIC_SLOTS)])

    @property
    def natural_sizes(self):
        """The natural size of each component of a node (schema.NODE order, units of L):
        schema.natural_sizes of the case's parameters."""
        return self._derived("natural_sizes", lambda: np.asarray(schema.natural_sizes_of(self.parameter_vector), dtype=float))

    @property
    def guide_record(self):
        """The schema's record of the case's guide (crankgen.declaration.records.Guide)."""
        return self._derived("guide", lambda: schema.GUIDES[schema.selected(self.parameters(), "guide")])

    @property
    def motion_record(self):
        """The schema's record of the case's crank motion (crankgen.declaration.records.Motion)."""
        return self._derived("motion", lambda: schema.MOTIONS[schema.selected(self.parameters(), "motion")])

    @property
    def options(self):
        """The model options, {name: value}."""
        return {name: getattr(self, name) for name in OPTION_FIELDS}

    @property
    def periodic(self):
        """True when the crank motion is periodic in the crank angle (periodic states exist)."""
        return self.motion_record.periodic

    @property
    def selection(self):
        """The term-family variants the options select (ingredients.Selection); families whose
        coefficients vanish for this case (gravity without gravity) are left out."""
        return self._derived("selection", lambda: ingredients.select(self.options, self.coefficients))

    @property
    def coefficients(self):
        """Coefficient vector of the element kernels (ingredients.COEFFICIENTS order)."""
        off = tuple(g for g in self.groups_off.split(",") if g)
        return self._derived("coefficients", lambda: ingredients.coefficients(self.parameter_vector, self.options, off))

    def body_coefficients(self, body):
        """Coefficient vector of another flexible body's elements (a flexible rocker's)."""
        off = tuple(g for g in self.groups_off.split(",") if g)
        return self._derived(f"coefficients_{body}", lambda: ingredients.body_coefficients(
            body, self.parameter_vector, self.options, off))

    def as_dict(self):
        """The fields as plain JSON-able values (pairs as lists, a torque curve as a list of them)."""
        return {k: _plain(v) for k, v in asdict(self).items() if k not in _NOT_KEYED}

    @classmethod
    def from_dict(cls, data):
        """Case from a mapping (extra keys ignored).  Text (from CSV) is converted by each
        parameter's kind: numbers, pairs "x,y", booleans "true"/"false"; an empty field (or None)
        is a parameter left at its default (a row leaves empty those its guide or crank motion does
        not read); anything else is validated and normalised by the constructor, which names the
        field."""
        kwargs = {}
        for f in fields(cls):
            if f.name not in data or f.name in _NOT_KEYED:
                continue
            value = data[f.name]
            kind = schema.PARAMETERS[f.name].kind if f.name in schema.PARAMETERS else None
            if kind is not None and (value is None or (isinstance(value, str) and not value.strip())):
                continue                      # an empty field: a parameter the case does not read
            if isinstance(value, str) and kind in ("real", "count", "sign"):
                try:
                    value = float(value)
                except ValueError:
                    pass                      # the constructor names the field
            elif kind == "pair" and isinstance(value, str):
                parts = [x for x in value.strip("()[] ").split(",") if x.strip()]
                try:
                    value = tuple(float(x) for x in parts)
                except ValueError:
                    pass
            elif kind == "pair" and isinstance(value, list):
                value = tuple(value)
            elif f.name in schema.OPTIONS and isinstance(value, str) and isinstance(schema.OPTIONS[f.name].default, bool):
                value = {"true": True, "false": False}.get(value.strip().lower(), value)
            kwargs[f.name] = value
        return make_case(**kwargs)

    def key(self):
        """Stable text key of the case (checkpoint identity), from the canonical field values."""
        return ";".join(f"{k}={v!r}" for k, v in sorted(self.as_dict().items()))


@dataclass(frozen=True)
class Case(CaseRules, _classes.CaseFields):
    __doc__ = (__doc__.split("\n\n")[0] + "\n\n" + "Fields: " + ", ".join(PARAMETER_FIELDS + OPTION_FIELDS)
               + ", groups_off (audit: term groups switched off), model (the preset; resolved into the "
               "options, then the name of the preset they match or None).")


def make_case(**kwargs):
    """Case(**kwargs) with an unknown keyword refused as a ParameterError naming it."""
    names = {f.name for f in fields(Case)}
    unknown = sorted(set(kwargs) - names)
    if unknown:
        raise ParameterError(f"unknown case parameter {unknown[0]!r}; the parameters are "
                             f"{', '.join(PARAMETER_FIELDS)}, the options {', '.join(OPTION_FIELDS)}, "
                             "model and groups_off")
    return Case(**kwargs)


def run_case(mech=None, case=None, *, model=None, omega=None, crank=None, **fields):
    """The Case of a run, checked once: `case` as given, or a Mechanism (default Mechanism(), built
    from the mechanism's parameters given as keywords) with the run's fields (omega, the crank
    motion `crank` as a record, any Case field) and the model (a preset name; explicit options
    override it).  A mechanism's parameter given both in `mech` and as a keyword is refused."""
    if case is not None:
        extra = [name for name, value in (("mech", mech), ("model", model), (schema.CRANK_SPEED, omega),
                                          ("crank", crank)) if value is not None] + sorted(fields)
        if extra:
            raise ParameterError(f"give either case= or a mechanism and its settings, not both "
                                 f"(got case= and {', '.join(extra)})")
        if not isinstance(case, Case):
            raise ParameterError(f"case must be None or a crankgen.Case, got {type(case).__name__} {case!r}")
        return case
    mechanism_fields = {n: fields.pop(n) for n in list(fields) if n in schema.MECHANISM_PARAMETERS}
    if mech is None:
        mech = Mechanism(**mechanism_fields)
    elif mechanism_fields:
        raise ParameterError(f"{', '.join(sorted(mechanism_fields))} given both in the mechanism and as a "
                             f"keyword: give it in one place (Mechanism(..., {next(iter(mechanism_fields))}=...))")
    if crank is not None:
        fields[schema.SELECTOR["motion"]] = crank
    if omega is not None:
        fields[schema.CRANK_SPEED] = omega
    return Case.from_mechanism(mech, model=model, **fields)


def exact_case(case):
    """The geometrically exact rod's case with the parameters and mesh of `case` (its model options
    dropped: the exact rod has none)."""
    values = case.as_dict()
    for option in ("formulation", "approach", "membrane", "damping", "groups_off"):
        values.pop(option, None)
    values = {k: tuple(v) if isinstance(v, list) else v for k, v in values.items()}   # pairs as tuples
    return Case(**values, model="exact")
