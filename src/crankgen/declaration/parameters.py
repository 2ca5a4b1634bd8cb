"""The mechanism: its dimensionless parameters as the schema declares them, and their SI origin.

Units used inside crankgen: length L (rod length), mass rho*A*L, time 1/omega_b with
omega_b = (pi/L)^2 sqrt(EI / (rho A)) the lowest bending frequency of the pinned-pinned rod.
In these units rho*A = 1, E*I = 1/pi^4, E*A = 1/(pi^4 eps^2), rho*I = eps^2 (I = A r^2), and the
paper's scaled outputs are  v* = v / eps,  u* = u / eps^2  (v, u in units of L).

`Mechanism`'s fields are the schema's mechanism and guide parameters (derive/declaration.py PARAMETERS):
a, eps, ms, mu, gravity, the guide (line or circle) and the guide's parameters (offset; c, d,
branch).  `settle` gives every parameter its canonical form (crankgen.declaration.schema.Parameter.canonical),
expands a guide or motion record (crankgen.Line, crankgen.Circle, crankgen.RunUp, ...) into its
parameters, refuses a parameter that the chosen guide or motion does not read unless it keeps its
default, and refuses a geometry whose crank cannot turn a full revolution (the guide's declared
margins).
"""

from dataclasses import dataclass, fields

import numpy as np

from . import schema, specs
from .._generated import classes as _classes
from .._generated import kinematics as _kinematics
from ..errors import ParameterError
from . import values as _values


def _expand_record(obj, kind):
    """A guide or motion record given as the value of its selecting parameter: its name there, its
    values in the fields."""
    key = schema.SELECTOR[kind]
    value = getattr(obj, key)
    if isinstance(value, type) and issubclass(value, specs.Spec):
        value = value()
    if not isinstance(value, specs.Spec):
        return
    if value.kind != kind:
        raise ParameterError(f"{key} must be a {kind} ({', '.join(c.__name__ for c in specs.RECORDS[kind].values())}) "
                             f"or its name, got {value!r}")
    for name, given in value.values.items():
        current = getattr(obj, name)
        if current is not None and current != given:
            raise ParameterError(f"{name} is given twice: {current!r} and {given!r} in {value!r}")
        object.__setattr__(obj, name, given)
    object.__setattr__(obj, key, value.name)


def settle(obj, names):
    """Give obj's parameter fields `names` their canonical values (None: the default)."""
    for kind, key in schema.SELECTOR.items():
        if key in names:
            _expand_record(obj, kind)
    for name in names:
        p = schema.PARAMETERS[name]
        value = getattr(obj, name)
        object.__setattr__(obj, name, p.default if value is None else _values.canonical(p, value))
    values = {n: getattr(obj, n) for n in names}
    guide, motion = schema.selected(values, "guide"), schema.selected(values, "motion")
    for name in names:
        p = schema.PARAMETERS[name]
        if not p.read_by(guide, motion) and getattr(obj, name) != p.default:
            current = guide if p.owner == "guide" else motion
            raise ParameterError(f"{p.label} applies to the {' and '.join(p.readers)} {p.owner} only "
                                 f"(the {p.owner} is {current!r}); leave it at its default {p.default!r}")


def kinematic_parameters(values):
    """The kinematic parameter vector (schema.KINEMATIC_PARAMETERS order) of a mapping of parameter
    values; absent ones take their default."""
    return schema.parameter_vector(values)[list(schema.KINEMATIC_SLOTS)]


# A full-turn margin (a length, in units of L) must exceed this: the margins are differences of
# lengths of order one, whose rounding (about 1e-16) could otherwise put a linkage exactly at its
# locking limit on the accepted side, where its first step fails.
MARGIN_TOLERANCE = 1e-9


CLOSURE_SAMPLES = 720       # crank angles at which a numerical closure is checked
CLOSURE_RESIDUAL = 1e-9     # |C(beta) - A|^2 - L^2 it must reach (units of L^2)
CLOSURE_SLOPE = 1e-6        # |d residual / d beta| it must keep: the rod not tangent to the guide


def _closure_failures(guide, params):
    """The full-turn conditions a numerical closure fails (texts): solved at CLOSURE_SAMPLES crank
    angles, it must reach the rod's length (residual) with the rod crossing the guide (slope)."""
    theta = np.linspace(0.0, 2 * np.pi, CLOSURE_SAMPLES, endpoint=False)
    crank = np.stack([theta, np.zeros_like(theta), np.zeros_like(theta)], axis=-1)
    with np.errstate(all="ignore"):
        beta, _, residual, slope = np.moveaxis(getattr(_kinematics, f"closure_{guide.name}")(crank, params), -1, 0)
    bad = ~(np.isfinite(beta) & (np.abs(residual) <= CLOSURE_RESIDUAL) & (np.abs(slope) > CLOSURE_SLOPE))
    if not bad.any():
        return []
    where = np.degrees(theta[bad])
    return [f"the closure |C(beta) - A| = L on the {guide.name} guide at every crank angle (it has no "
            f"solution, or the rod is tangent to the guide, at crank angles {where.min():.4g} to "
            f"{where.max():.4g} deg)"]


def check_full_turn(values):
    """Refuse a geometry whose crank cannot turn a full revolution (the guide's margins, each of
    which must exceed MARGIN_TOLERANCE)."""
    guide = schema.GUIDES[schema.selected(values, "guide")]
    if guide.closure == "numerical":
        failed = _closure_failures(guide, kinematic_parameters(values))
    else:
        margins = np.atleast_1d(getattr(_kinematics, f"margins_{guide.name}")(kinematic_parameters(values)))
        failed = [text for m, text in zip(margins, guide.margins) if not m > MARGIN_TOLERANCE]
    if failed:
        shown = ", ".join(f"{n} = {values.get(n, schema.PARAMETERS[n].default):g}"
                          for n in schema.KINEMATIC_PARAMETERS
                          if n in schema.PARAMETERS and n not in schema.BODY_PARAMETERS    # the geometry
                          if schema.PARAMETERS[n].owner == "mechanism" or n in guide.parameters
                          if schema.PARAMETERS[n].kind == "real")
        raise ParameterError(f"the crank cannot turn a full revolution: the {guide.name} guide needs "
                             f"{'; '.join(failed)}; got {shown}")


class MechanismRules:
    """Dimensionless mechanism: a* = a/L, eps = r/L, ms* = m_s/(rho A L), mu* = omega_b mu,
    gravity = (gX, gY) in units of L omega_b^2 (inertial frame: X along the guide, Y so that the
    crank pin is at a* (cos theta, sin theta)), and the guide the rod's end travels on: the line
    Y = offset (a slider; the default) or a circle of radius c about (d, offset) (a rigid
    rocker, massless unless given rocker_mass and rocker_inertia: a four-bar linkage with a flexible
    coupler).  guide may be given as a record,
    crankgen.Line(offset=e) or crankgen.Circle(center=(d, e), radius=c, branch=+1)."""

    def __post_init__(self):
        settle(self, schema.MECHANISM_PARAMETERS)
        check_full_turn(self.values())

    def values(self):
        """{parameter: value} of every field."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    @property
    def guide_record(self):
        """The guide as a record (crankgen.Line(...), crankgen.Circle(...))."""
        cls = specs.GUIDES[schema.selected(self.values(), "guide")]
        return cls.of({n: getattr(self, n) for n in cls.declaration.parameters})

    @property
    def section(self):
        """The section constants of the rod in crankgen's units (rho A, rho I, E A, E I), from the
        coefficients' formulas of the schema (with the rod's rotary inertia)."""
        from . import ingredients
        coef = ingredients.coefficients(schema.parameter_vector(self.values()), ingredients.DEFAULTS)
        return {name: float(coef[ingredients.COEFFICIENTS.index(name)]) for name in ("rhoA", "rhoI", "EA", "EI")}

    @property
    def rhoA(self):
        return self.section["rhoA"]

    @property
    def rhoI(self):
        return self.section["rhoI"]

    @property
    def EA(self):
        return self.section["EA"]

    @property
    def EI(self):
        return self.section["EI"]


@dataclass(frozen=True)
class Mechanism(MechanismRules, _classes.MechanismFields):
    __doc__ = MechanismRules.__doc__
