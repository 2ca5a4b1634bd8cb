"""Mechanisms in SI, read from the declaration: crankgen.SIMechanism and the SI side of every analysis.

An SIMechanism is the rod in SI (crankgen.declaration.units.ROD: its length L in m, Young's modulus E in Pa,
density rho in kg/m^3, section area A in m^2, second moment of area I in m^4), which sets
crankgen's units (crankgen.declaration.units.Scales: L, rho A, omega_b, r), and every parameter of the
mechanism, its guide and its crank motion in SI: each declared parameter (derive/declaration.py)
under its SI name (`Parameter.si`, default its own name: `slider_mass` for ms, `damping` for mu,
`crank_speed` for omega; `a`, `gravity`, `offset`, `c`, `d`, `omega0`, ...) in the SI unit of its
declared units (crankgen.declaration.units: "L" -> m, "rhoA L" -> kg, "1/omega_b" -> s, "omega_b" -> rad/s,
"L omega_b^2" -> m/s^2; "rad", "rev" and "1" are the same numbers in both).  Its value in
crankgen's units is the SI value over one unit's SI value (`Scales.factor`).  A parameter that is a
unit (the slenderness eps: r = eps L, schema.UNIT_PARAMETERS) is the section's, not a field.  Nothing
here names a parameter or a unit: both come from the schema.

A field left out (None) takes the parameter's default where that default means the same in SI
(zero, or a dimensionless number: the guide and motion, branch, the ramp's revolutions, the
fluctuation, theta0) or where the declaration gives an SI default (`si_default`: the damping, 0);
the others (the crank length, the end mass, the crank speed; c and d of a four-bar, a run-up's
start speed) must be given when the guide or motion reads them.

Every analysis takes an SIMechanism with units="si" (`resolve`) and its result gives the SI view.
"""

import math
from dataclasses import dataclass, field, fields, make_dataclass

from . import schema, specs
from .._generated import classes as _classes
from ..errors import ParameterError
from .units import ROD, Scales, rod_powers, same_in_si
from .validation import finite_number, in_range
from . import values as _values

UNITS = ("crankgen", "si")
FIELDS = schema.SI_FIELDS           # the declared parameters an SIMechanism holds, by SI name
SI_NAME = {p.name: si for si, p in FIELDS.items()}
ROD_UNITS = {name: unit for name, unit, _ in ROD}
assert tuple(f.name for f in fields(_classes.SIFields)) == tuple(FIELDS), "generated/classes.py is stale"

# a scale or number an SIMechanism gives must lie within 10^-MAGNITUDE .. 10^MAGNITUDE
MAGNITUDE = 50


def si_unit(name):
    """The SI unit of a parameter (by its name), as crankgen.declaration.units names it (m, kg, s, rad/s, ...)."""
    return Scales.si_name(schema.PARAMETERS[name].units)


def dimensioned(p):
    """True when the parameter's value differs between SI and crankgen's units (a unit that is not
    a plain number, an angle or revolutions)."""
    return p.kind in ("real", "pair") and not same_in_si(p.units)


def _zero(value):
    return all(x == 0 for x in (value if isinstance(value, tuple) else (value,)))


def required(p, guide, motion):
    """True when an SIMechanism must give the parameter p for this guide and motion: read, with no
    SI default (a declared si_default, a zero default, or a dimensionless one)."""
    return (p.read_by(guide, motion) and p.si_default is None and dimensioned(p)
            and not (isinstance(p.default, (int, float, tuple)) and _zero(p.default)))


def to_crankgen(name, value, scales):
    """The value of parameter `name` given in SI, in crankgen's units (a pair: a tuple)."""
    p = schema.PARAMETERS[name]
    if p.kind not in ("real", "pair"):
        return value
    f = scales.factor(p.units)
    return tuple(x / f for x in value) if p.kind == "pair" else value / f


def to_si(name, value, scales):
    """The value of parameter `name` in crankgen's units, in SI (its declared units' SI unit)."""
    p = schema.PARAMETERS[name]
    if p.kind not in ("real", "pair") or value is None:
        return value
    f = scales.factor(p.units)
    return tuple(float(x) * f for x in value) if p.kind == "pair" else float(value) * f


@dataclass(frozen=True)
class RodFields:
    """The rod in SI (crankgen.declaration.units.ROD), which sets crankgen's units."""

    L: float = None
    E: float = None
    rho: float = None
    A: float = None
    I: float = None


assert tuple(f.name for f in fields(RodFields)) == tuple(ROD_UNITS)

def rad_per_s(rpm):
    """A speed in rpm in rad/s: rpm x 2 pi / 60."""
    return rpm * 2.0 * math.pi / 60.0
# every SI speed field (rad/s) also taken in rpm: crank_speed_rpm, omega0_rpm, ...
RPM_FIELDS = {f"{si}_rpm": si for si, p in FIELDS.items()
              if p.kind == "real" and dimensioned(p) and si_unit(p.name) == "rad/s"}

# the speeds in rpm (converted into their rad/s field when the SIMechanism is made, then None) and
# the plausibility checks a user switches off (crankgen.declaration.plausibility)
ExtraFields = make_dataclass(
    "ExtraFields", [(name, object, field(default=None)) for name in RPM_FIELDS]
    + [("unchecked", object, field(default=()))], frozen=True)
ExtraFields.__doc__ = ("An SIMechanism's speeds in rpm (" + ", ".join(RPM_FIELDS) + "), and `unchecked`: the "
                       "plausibility checks to skip (crankgen.declaration.plausibility.CHECKS).")


class SIRules:
    """The checks and views of an SIMechanism (its fields: the rod's, RodFields, and the declared
    parameters', generated/classes.py SIFields)."""

    def __post_init__(self):
        self._from_rpm()
        for name, unit in ROD_UNITS.items():
            value = getattr(self, name)
            if value is None:
                raise ParameterError(f"SIMechanism: missing {name} ({unit}); the rod's fields are "
                                     f"{', '.join(f'{n} ({u})' for n, u in ROD_UNITS.items())}")
            object.__setattr__(self, name, in_range(f"{name} ({unit})", value, 0, None, True))
        for kind, key in schema.SELECTOR.items():
            self._expand(kind, SI_NAME[key])
        for si, p in FIELDS.items():
            value = getattr(self, si)
            if value is not None:
                object.__setattr__(self, si, self._checked(si, p, value))
        chosen = self._chosen()
        missing = [si for si, p in FIELDS.items() if getattr(self, si) is None and required(p, *chosen)]
        if missing:
            p = FIELDS[missing[0]]
            who = (f", which the {chosen[0] if p.owner == 'guide' else chosen[1]} {p.owner} reads"
                   if p.owner in ("guide", "motion") else "")
            raise ParameterError(f"SIMechanism: missing {missing[0]} ({si_unit(p.name)}: the {p.doc}{who}); "
                                 f"the fields are {', '.join(self.field_names())}")
        self._check_magnitudes()
        scales = self.scales
        for si, p in FIELDS.items():                   # the range, in crankgen's units
            value = getattr(self, si)
            if value is not None and dimensioned(p):
                try:
                    _values.canonical(p, to_crankgen(p.name, value, scales))
                except ParameterError as exc:
                    raise ParameterError(f"SIMechanism: {si} = {_values.text(p, value)} {si_unit(p.name)} is "
                                         f"{_values.text(p, to_crankgen(p.name, value, scales))} in crankgen's units: {exc}") from None
        try:
            self.mechanism
        except ParameterError as exc:
            raise ParameterError(f"SIMechanism (in units of L = {self.L:g} m): {exc}") from None
        self._check_plausible()

    def _from_rpm(self):
        """A speed given in rpm (crank_speed_rpm, ...) into its field in rad/s (rad/s = rpm 2 pi / 60);
        both given is refused."""
        for rpm, si in RPM_FIELDS.items():
            value = getattr(self, rpm)
            if value is None:
                continue
            value = finite_number(f"{rpm} (rpm)", value)
            if getattr(self, si) is not None:
                raise ParameterError(f"SIMechanism: {si} ({getattr(self, si)!r} rad/s) and {rpm} ({value:g} rpm) "
                                     f"are the same speed: give one")
            object.__setattr__(self, si, rad_per_s(value))
            object.__setattr__(self, rpm, None)

    def _check_plausible(self):
        """The unit mistakes the numbers give away (crankgen.declaration.plausibility), after the checks above."""
        from . import plausibility
        unchecked = self.unchecked
        if isinstance(unchecked, str) or not all(isinstance(x, str) for x in (unchecked or ())):
            raise ParameterError(f"SIMechanism: unchecked must be a list of the checks to skip, of "
                                 f"{', '.join(plausibility.CHECKS)}; got {unchecked!r}")
        unknown = sorted(set(unchecked) - set(plausibility.CHECKS))
        if unknown:
            raise ParameterError(f"SIMechanism: unchecked names no check {unknown[0]!r}; the checks are "
                                 f"{', '.join(plausibility.CHECKS)}")
        object.__setattr__(self, "unchecked", tuple(sorted(set(unchecked))))
        plausibility.check_rod(self.L, self.E, self.rho, self.A, self.I, self.unchecked)
        # the end mass: the mechanism's mass, in rod masses rhoA L
        mass = next((SI_NAME.get(n) for n, p in schema.PARAMETERS.items()
                     if p.owner == "mechanism" and p.units == "rhoA L"), None)
        if mass is not None:
            plausibility.check_mass(getattr(self, mass), self.rho * self.A * self.L, self.unchecked)
        omega_b = self.omega_b
        for si in RPM_FIELDS.values():
            plausibility.check_si_speed(si, getattr(self, si), omega_b)

    def _expand(self, kind, si):
        """A guide or motion record given as the value of its selecting field: its name there, its
        values (in SI) in the fields."""
        value = getattr(self, si)
        if isinstance(value, type) and issubclass(value, specs.Spec):
            value = value()
        if not isinstance(value, specs.Spec):
            return
        if value.kind != kind:
            raise ParameterError(f"SIMechanism: {si} must be a {kind} or its name, got {value!r}")
        for name, given in value.values.items():
            field = SI_NAME[name]
            current = getattr(self, field)
            if current is not None and current != given:
                raise ParameterError(f"SIMechanism: {field} is given twice: {current!r} and {given!r} in {value!r}")
            object.__setattr__(self, field, given)
        object.__setattr__(self, si, value.name)

    @staticmethod
    def _checked(si, p, value):
        """A field's SI value checked: a real in the parameter's range scaled to SI (the factor is
        positive, so the bounds scale), a pair of numbers, or a dimensionless value as the
        parameter takes it."""
        unit = si_unit(p.name)
        label = f"{si} ({unit})" if unit != "1" else si
        if p.kind == "real" and dimensioned(p):
            return finite_number(label, value) + 0.0
        try:
            return _values.canonical(p, value)
        except ParameterError as exc:
            raise ParameterError(f"SIMechanism: {label}: {exc}") from None

    def _chosen(self):
        return tuple(getattr(self, SI_NAME[schema.SELECTOR[k]]) or schema.PARAMETERS[schema.SELECTOR[k]].default
                     for k in ("guide", "motion"))

    @classmethod
    def field_names(cls):
        return [f.name for f in fields(cls)]

    def _check_magnitudes(self):
        """Refuse fields whose scales or dimensionless numbers overflow or underflow in floating
        point (or come near it), naming the field that weighs most; computed on logarithms, so
        nothing overflows here."""
        logs = {name: math.log10(getattr(self, name)) for name in ROD_UNITS}

        def check(what, terms, offset=0.0):
            exponent = sum(terms.values()) + offset
            if abs(exponent) > MAGNITUDE:
                name = max(terms, key=lambda n: abs(terms[n]))
                value = getattr(self, name)
                unit = ROD_UNITS.get(name) or si_unit(FIELDS[name].name)
                raise ParameterError(
                    f"SIMechanism: {name} = {value:g} makes {what} about 1e{exponent:+.0f}, beyond "
                    f"1e-{MAGNITUDE} .. 1e{MAGNITUDE} (floating point would overflow or underflow); "
                    f"give {name} in SI units ({unit}) of a real mechanism")

        def powers(units):
            rod, pi = rod_powers(units)
            return {q: p * logs[q] for q, p in rod.items()}, pi * math.log10(math.pi)

        for base in ("L", "omega_b", "rhoA", "r"):
            check(f"the unit {base}", *powers(base))
        for unit, name in schema.UNIT_PARAMETERS.items():
            terms, pi = powers(f"{unit}/L")
            check(f"{schema.PARAMETERS[name].label}", terms, pi)
        for si, p in FIELDS.items():
            value = getattr(self, si)
            if not dimensioned(p) or value is None:
                continue
            for x in (value if isinstance(value, tuple) else (value,)):
                if x == 0:
                    continue
                terms, pi = powers(p.units)
                terms = {si: math.log10(abs(x)), **{q: -t for q, t in terms.items()}}
                check(p.label, terms, -pi)

    # ---- views ------------------------------------------------------------------------------
    @property
    def scales(self):
        """crankgen's units in SI for this rod (crankgen.declaration.units.Scales)."""
        return Scales.of_rod(**{name: getattr(self, name) for name in ROD_UNITS})

    @property
    def omega_b(self):
        """Lowest bending natural frequency of the pinned-pinned rod, rad/s."""
        return self.scales.omega_b

    @property
    def radius_of_gyration(self):
        return self.scales.base["r"]

    def values(self):
        """{parameter: value in crankgen's units} of every field given, and of the units that are
        parameters (the slenderness r/L of the section)."""
        scales = self.scales
        out = {name: scales.base[unit] / scales.L for unit, name in schema.UNIT_PARAMETERS.items()}
        for si, p in FIELDS.items():
            value = getattr(self, si)
            if value is not None:
                out[p.name] = to_crankgen(p.name, value, scales)
        for p in schema.PARAMETERS.values():                    # left out: its SI default, if declared
            if p.si_default is not None and p.name not in out:
                out[p.name] = to_crankgen(p.name, p.si_default, scales)
        return out

    @property
    def mechanism(self):
        """The dimensionless crankgen.Mechanism."""
        from .parameters import Mechanism
        values = self.values()
        return Mechanism(**{n: values[n] for n in schema.MECHANISM_PARAMETERS if n in values})

    def motion_values(self):
        """{parameter: value in crankgen's units} of the crank motion given (the motion, its speeds,
        ramp, fluctuation, start angle)."""
        values = self.values()
        return {n: v for n, v in values.items() if n in schema.RUN_PARAMETERS}

    @property
    def omega(self):
        """The crank's (nominal) speed in crankgen's units, Omega* = crank speed / omega_b."""
        values = self.values()
        return values.get(schema.CRANK_SPEED, schema.PARAMETERS[schema.CRANK_SPEED].default)

    @property
    def crank(self):
        """The crank motion as its record in crankgen's units (crankgen.Constant(omega=...), ...)."""
        values = self.motion_values()
        cls = specs.MOTIONS[self._chosen()[1]]
        return cls.of({n: values[n] for n in cls.declaration.parameters if n in values})

    def case(self, **settings):
        """The crankgen.Case of this mechanism and crank motion with the run's settings (n_elements,
        the model options, model=, ...); a parameter this SIMechanism gives is refused there."""
        from .cases import run_case
        given = self.values()
        clash = sorted(set(settings) & set(given))
        if clash:
            raise ParameterError(f"{clash[0]} is given by the SIMechanism (as {SI_NAME.get(clash[0], clash[0])} "
                                 f"in SI): leave it out of the run's settings")
        model = settings.pop("model", None)
        return run_case(self.mechanism, None, model=model, **self.motion_values(), **settings)

    @classmethod
    def of_case(cls, rod, case):
        """The SIMechanism of a case's parameters on the rod `rod` (an SIMechanism whose L, E, rho,
        A, I are taken): every parameter in SI; the case's slenderness must be the rod's."""
        scales = rod.scales
        for unit, name in schema.UNIT_PARAMETERS.items():
            own = scales.base[unit] / scales.L
            if abs(getattr(case, name) / own - 1) > 1e-9:
                raise ParameterError(f"the case's {schema.PARAMETERS[name].label} = {getattr(case, name):g} is not the "
                                     f"rod's ({own:g}): its SI form needs its own rod")
        values = {si: to_si(p.name, getattr(case, p.name), scales) for si, p in FIELDS.items()}
        return cls(**{name: getattr(rod, name) for name in ROD_UNITS}, **values)

    def si_values(self):
        """{SI name: value} of the fields given."""
        return {si: getattr(self, si) for si in FIELDS if getattr(self, si) is not None}


@dataclass(frozen=True, kw_only=True)
class SIMechanism(SIRules, ExtraFields, _classes.SIFields, RodFields):
    __doc__ = ("A mechanism and its crank motion in SI units (module crankgen.declaration.si): the rod, "
               + ", ".join(f"{n} ({u})" for n, u in ROD_UNITS.items()) + ", and "
               + ", ".join(f"{si} ({si_unit(p.name)})" if dimensioned(p) else si for si, p in FIELDS.items())
               + "; a speed in rpm by its name with _rpm (" + ", ".join(RPM_FIELDS) + "; rpm = rad/s 60 / "
                 "(2 pi)), converted into its field in rad/s; `unchecked`: the plausibility checks to "
                 "skip (crankgen.declaration.plausibility: a field's, E, rho, L, A, I, slider_mass, or slenderness), "
                 "for numbers meant as given.  `.mechanism`, `.omega` (Omega*), `.crank` and "
                 "`.case(**settings)` give the dimensionless form, `.scales` the units.")


def si_input(mech, units, fields, *, what="this analysis", crank=None, **given):
    """(mechanism, crank, scales) of an analysis' input: with units="si" an SIMechanism, whose
    dimensionless Mechanism, crank motion (its record, in crankgen's units) and scales are
    returned; a crank motion of the analysis' own (`crank`, and `given`: omega, case, ... not None)
    and a field that the SIMechanism gives are refused.  With units="crankgen": (mech, crank, None),
    an SIMechanism refused."""
    from .validation import choice
    choice("units", units, UNITS)
    if units == "si":
        if not isinstance(mech, SIMechanism):
            raise ParameterError(f"units='si' needs the mechanism as a crankgen.SIMechanism, got "
                                 f"{type(mech).__name__}")
        passed = [name for name, value in dict(given, crank=crank).items() if value is not None]
        if passed:
            raise ParameterError(f"with units='si' the SIMechanism gives the mechanism and its crank motion "
                                 f"(its {SI_NAME[schema.CRANK_SPEED]}, ...): give {what} no {', '.join(passed)}")
        for name in sorted(set(fields) & set(schema.OPTIONS) & set(SIMechanism.field_names())):
            value = fields[name]         # a field of the SIMechanism that is also a model option's name
            if value is not None and not isinstance(value, str):
                choices = " or ".join(repr(c) for c in schema.OPTIONS[name].choices)
                raise ParameterError(f"{name}={value!r}: with units='si' the keyword {name} is the model option "
                                     f"({choices}); the SI value goes in the SIMechanism's field {name}")
        clash = sorted(set(fields) & set(mech.values()))
        if clash:
            raise ParameterError(f"{clash[0]} is given by the SIMechanism (as {SI_NAME.get(clash[0], clash[0])} in "
                                 f"SI): leave it out of {what}'s arguments")
        return mech.mechanism, mech.crank, mech.scales
    if isinstance(mech, SIMechanism):
        raise ParameterError("a crankgen.SIMechanism needs units='si' (or use its .mechanism and .case())")
    return mech, crank, None


def scales_of(si_mechanism):
    """Scales of a crankgen.SIMechanism."""
    if not isinstance(si_mechanism, SIMechanism):
        raise ParameterError(f"expected a crankgen.SIMechanism, got {type(si_mechanism).__name__}")
    return si_mechanism.scales


def describe_si(values, scales, skip=()):
    """The parameters of a case (a mapping of values in crankgen's units) in SI, as text for titles:
    ["a = 0.03 m", "slider mass = 0.0756 kg", "gravity = (0, -9.81) m/s^2", ...], those its guide and
    crank motion read, by SI name, `skip` (names) and the choices left out."""
    guide, motion = schema.selected(values, "guide"), schema.selected(values, "motion")
    out = []
    for si, p in FIELDS.items():
        if p.name in skip or p.selects or not p.read_by(guide, motion):
            continue
        value = values.get(p.name, p.default)
        value = to_si(p.name, tuple(value) if isinstance(value, list) else value, scales)
        unit = si_unit(p.name)
        out.append(f"{si.replace('_', ' ')} = {_values.text(p, value)}" + (f" {unit}" if unit != "1" and p.kind in ("real", "pair") else ""))
    return out
