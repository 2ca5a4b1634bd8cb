"""The records of the model, one class per concept, shared by the derivation and the runtime.

derive/declaration.py declares every ingredient with these classes (the derivation's own
subclasses add the SymPy forms: a parameter's symbol, a variant's residual, a guide's curve, an
output's expression); derive/representation.py fills in what follows from the declaration (a
parameter's owner and readers, its slots in the parameter vector, an option's effective default,
a variant's kernel name) and derive/schema.py prints the records into generated/schema.py as
`repr` of these very classes, which the runtime reads.  Nothing here imports SymPy, NumPy or the
generated code.

    Option, Preset        a model option (its choices) and a named set of option values
    Exclusion             option values that have no meaning together (a case choosing them is refused)
    Parameter             a parameter of a case: kind, default, range, units, flag, owner
    Guide, Motion         the curve the rod's end travels on; the crank's motion (prescribed or driven)
    Coordinate            a co-ordinate of the state with its own equation (a driven crank's angle, a rotor's)
    Family, Variant       a term family of the equations of motion and its option-selected variants
    Output                a quantity a result can give, with its kernels by option values
    Reduction             a peak, RMS, mean or range over time of a declared output (a revolution's)
    Primitive             what the engine accumulates for its outputs (a field at a point, an integral)
    Body                  a body of the mechanism: flexible (its elements and node layout) or rigid
    Constraint            a constraint of a node condensed out of the equations: a joint between bodies
    Layout                the entries of a vector a kernel reads (parameters, coefficients, ...)
    Spec                  a guide or motion with values of its parameters (crankgen.Line(...), ...)
"""

import math
import numbers
from dataclasses import dataclass, fields

from ..errors import ParameterError


@dataclass(frozen=True)
class Option:
    """A model option: one of `choices`.  default None in the declaration: the default preset's
    value.  cli: the command-line flag (default --<name>)."""

    name: str
    choices: tuple
    default: object = None
    doc: str = ""
    cli: str = None


@dataclass(frozen=True)
class Preset:
    """A named set of option values: a model.  Options a preset does not set keep their default;
    an option given explicitly overrides the preset's value.  settings: defaults of run parameters
    that go with the model (the paper's rho_inf = 1), used where the run does not give them."""

    name: str
    options: dict
    doc: str
    settings: dict = None

    def __post_init__(self):
        if self.settings is None:
            object.__setattr__(self, "settings", {})


@dataclass(frozen=True)
class Exclusion:
    """Option values that have no meaning together: a case choosing all of them is refused with
    `reason` (one line)."""

    options: dict
    reason: str


@dataclass(frozen=True)
class Parameter:
    """A parameter of a case.  kind: "real" (a finite number in low..high, open ends where
    low_open / high_open), "pair" (two finite numbers), "sign" (+1 or -1), "count" (an integer >=
    low), "choice" (one of `choices`), "curve" (a motor's per-unit torque-speed pairs:
    crankgen.torque_curve; it enters no equation vector, the runtime reads it).  owner: "mechanism" (a Mechanism field) or "run" (a setting
    of the run) as declared; the representation makes it "guide" or "motion" when guides or
    motions read it (`readers`: those that do; it must stay at its default for the others).
    units: the unit of the value (crankgen's units: L, rho A L, 1/omega_b, ...; crankgen.declaration.units),
    which converts it from SI.  continuable: a continuation may vary it.  slots: its entries'
    places in the parameter vector (a pair has two; () for a parameter that enters no equation: a
    choice, the mesh, the integrator).  si: its field's name in SI (crankgen.SIMechanism; default
    its name); si_default: its SI value when an SIMechanism leaves it out, where that is not the
    value its default gives (the damping of a real rod is unknown: 0)."""

    name: str
    kind: str
    default: object
    label: str                   # how messages, axes and titles name it
    doc: str
    owner: str = "mechanism"
    readers: tuple = ()
    low: float = None
    high: float = None
    low_open: bool = False
    high_open: bool = False
    units: str = "1"
    cli: str = None              # command-line flag (without --)
    metavar: str = None
    choices: tuple = ()
    continuable: bool = False
    slots: tuple = ()
    selects: str = None
    axis: str = None             # the text of an axis along it (plots of a continuation); default: its name
    si: str = None               # its name in SI (a crankgen.SIMechanism field; default: its name)
    si_default: object = None    # its SI value when left out, where not the default's (None: the default's)

    def read_by(self, guide, motion):
        """True when a case with this guide and motion reads the parameter."""
        if self.owner == "guide":
            return guide in self.readers
        if self.owner == "motion":
            return motion in self.readers
        return True

    def entries(self, value):
        """The parameter's entries in the parameter vector (one per slot) of a canonical value."""
        return tuple(float(x) for x in value) if self.kind == "pair" else (float(value),)


@dataclass(frozen=True)
class Guide:
    """A curve the rod's end travels on.  title: the class name of its record (crankgen.Line,
    ...); parameters: the parameters it reads besides the crank length; aliases: keywords its
    record accepts for parameters, ((keyword, (parameter, ...)), ...); margins: the conditions for
    the crank to turn a full revolution (each a text; the generated margins kernel gives their
    values, each > 0 when it holds); closure: "closed-form" or "numerical" (Newton at run time)."""

    name: str
    title: str
    parameters: tuple
    doc: str
    aliases: tuple = ()
    margins: tuple = ()
    closure: str = "closed-form"
    label: str = None            # how titles name the mechanism it makes (a slider, a four-bar)
    pivot: bool = False          # a link from a ground pivot carries the end (a rocker; kernel pivot_<name>)


@dataclass(frozen=True)
class Coordinate:
    """A co-ordinate of the state besides the rods' nodal co-ordinates, with its own equation (a
    driven crank's angle, a motor rotor's angle): a declared unknown of the DOF map.  units: its
    natural size's unit (Newton's scale: 1 of it); crank: its value is the crank angle, from which
    the kinematics of every rod follow, and its passage through its start value plus one turn is
    the section of the autonomous motion's map (a steady motion is periodic on it); motor: a motor's
    torque-speed curve drives it (its equation holds -T_m(its rate); a per-unit curve replaces the
    derivation's linear law at run time, crankgen.declaration.torque_curve)."""

    name: str
    doc: str
    units: str = "rad"
    crank: bool = False
    motor: bool = False


@dataclass(frozen=True)
class Motion:
    """A crank motion.  title: the class name of its record (crankgen.Constant, ...);
    parameters: those it reads; periodic: periodic in the crank angle (a period, steady states);
    transient: the parameter that is the number of revolutions over which its speed changes before
    it settles (a run-up's ramp; None: none); coordinates: the co-ordinates it adds to the state,
    each with its equation (Coordinate; none for a prescribed motion): with them the crank angle is
    a degree of freedom (`driven`), its theta(t) is only the crank's start (theta0 at the initial
    speed) and its step period the fastest revolution it may make.
    characteristic: a driven crank's motor law as data, the names of its parameters (the per-unit
    torque-speed curve, its torque scale, its speed scale, the inertia the motor accelerates): the
    curve replaces the derivation's linear law at run time (crankgen.declaration.torque_curve); ()
    for a prescribed motion."""

    name: str
    title: str
    parameters: tuple
    doc: str
    aliases: tuple = ()
    periodic: bool = True
    transient: str = None
    label: str = None            # how titles name it
    driven: bool = False
    characteristic: tuple = ()
    coordinates: tuple = ()


@dataclass(frozen=True)
class Variant:
    """One variant of a term family, selected by option values (`when`; absent options: any
    value; a tuple of values: any of them).  kernel: its element kernel (<family>_<variant>); groups:
    the switchable term groups it carries; energy: the energy kernel it derives from (None: none);
    quadrature: the rule its element integrals use ("gauss-legendre 3" ...; None: closed form)."""

    name: str
    when: dict
    doc: str
    groups: tuple = ()
    energy: str = None
    kernel: str = None
    quadrature: str = None


@dataclass(frozen=True)
class Family:
    """A term family of the equations of motion.  part: where it acts ("rod": every element;
    "end": the end node, the end mass); energy_kind: what its variants' energy kernels give
    ("kinetic", "potential", "dissipation"); vanishes_with: coefficients whose vanishing (all of
    them) leaves the family out of a case; body: the body whose own force the family is when it is
    not the part's (None): "rocker" for a four-bar rocker's spring, weight and inertia, written on
    the tip's node but carried by the rocker, so that the force the rocker applies to the tip mass
    leaves them out."""

    name: str
    part: str
    doc: str
    energy_kind: str
    variants: tuple = ()
    vanishes_with: tuple = ()
    body: str = None
    parameters: tuple = ()       # the parameters its vanishing coefficients read (what leaves it out)


@dataclass(frozen=True)
class Output:
    """A quantity a result can give.  kind: "step" (one value per stored step), "field" (per stored
    step at any x* in [0, 1]) or "reduction" (per stored step, a sum or integral over the rod: its
    kernel gives each element's part); engine: the engine computes it at every step (v_mid, u_end,
    extension: every result has it, with or without states; its kernel is the generated
    `per_step`).  units: its unit (SI views multiply by it); arguments: a field's extra arguments;
    guides: the guides it exists for; options: the model options its expression depends on;
    inputs: the inputs its kernels read; kernels: ((option values, kernel name), ...); rigid: the
    bodies its expression takes as rigid (a rigid rocker's momentum balance: none with a flexible one);
    flexible: the bodies it needs flexible (a flexible rocker's pivot force)."""

    name: str
    kind: str
    doc: str
    units: str
    arguments: tuple = ()
    guides: tuple = None
    options: tuple = ()
    engine: bool = False
    inputs: tuple = ()
    kernels: tuple = ()
    rigid: tuple = ()            # bodies its expression takes as rigid (not given when they are flexible)
    flexible: tuple = ()         # bodies it needs flexible (given only when they are)


@dataclass(frozen=True)
class Reduction:
    """A reduction over time of a declared output, along a steady revolution, a branch point's orbit
    or a run's last revolution: kind "peak" (the value of largest magnitude, signed), "max", "min",
    "range" (max - min), "mean" or "rms" (time means by the trapezoidal rule on the stored steps).
    output: the declared output; at: its x* for a field, with its other `arguments` ((name, value),
    ...); units: the output's (the representation fills them in); guides: those it exists for
    (the output's)."""

    name: str
    output: str
    kind: str
    doc: str
    at: float = None
    arguments: tuple = ()
    units: str = None
    guides: tuple = None


@dataclass(frozen=True)
class Primitive:
    """A quantity of the nodal state the engine accumulates at every step for the outputs it
    computes: kind "point", the interpolated `field` (u, v or psi) at x* = `at` (the shape
    functions of the element holding it); kind "integral", an integral over the rod of a quadratic
    form in each element's nodal vector, sum of q^T G q with G the generated `kernel` (of the
    element length)."""

    name: str
    kind: str
    field: str = None
    at: float = None
    kernel: str = None


@dataclass(frozen=True)
class Body:
    """A body of the mechanism: kind "flexible" (a beam of finite elements, its nodes' components
    `node` in its own moving frame, its element count the parameter `elements`) or "rigid" (its
    motion the rigid closure's, or a declared co-ordinate's); `frame`: what its moving frame follows
    (the crank angle, the chord of the rigid linkage, the guide).  The DOF map numbers the flexible
    bodies' nodal unknowns in the declared order, then the motion's co-ordinates; the joints between
    bodies are the constraints (Constraint.body, .joint).  `conditional`: components a node has only
    under some model options (`components`).  A flexible body whose element count may be 0 (a
    rocker) is present only where it is not; `frame_map` gives the kinematics vector its elements'
    kernels read (its moving frame's: a rocker's turns with the rocker, its origin the fixed pivot)."""

    name: str
    kind: str
    doc: str
    frame: str
    node: tuple = ()
    elements: str = None
    conditional: tuple = ()
    length: str = None           # the parameter giving a flexible body's length (None: L, the rod's)
    frame_map: tuple = ()        # a flexible body's kinematics vector as a linear map of the mechanism's
                                 # (rows and columns: schema.KINEMATICS; () for the mechanism's own)

    def components(self, options):
        """The node's components a case with these model options has: `conditional` holds
        (component, option, values) for a component present only where the option takes one of
        the values (the exact rod's axial slope chi); the others are always present."""
        absent = {c for c, option, values in self.conditional if options.get(option) not in values}
        return tuple(c for c in self.node if c not in absent)


@dataclass(frozen=True)
class Constraint:
    """A constraint of one of the rod's nodes, condensed out of the equations of motion (the DOF
    map): its node (0: the first, -1: the last, k: an interior node), the node's components it
    eliminates, and the reduced co-ordinates that replace them (each in the place of an eliminated
    component, in order; none: the components are held at zero), given by the generated map `map`
    of the case's guide (kernel <map>_<guide>: the eliminated components, their rates and their
    derivatives in the reduced co-ordinates).  The equations of the eliminated components become
    the reduced co-ordinates' by d'Alembert's projection (constraints.py, engine/elements.py);
    their residual rows before it are the force the constraint applies (an output input named
    after the constraint)."""

    name: str
    node: int
    eliminated: tuple
    doc: str = ""
    reduced: tuple = ()
    map: str = None
    body: str = None             # the flexible body whose node it holds
    joint: str = None            # the body it joins that node to (a pin)
    requires: str = None         # a flexible body that must be present (its element count > 0) for it to apply
    excludes: str = None         # a flexible body whose presence replaces it

    def applies(self, present):
        """Whether the constraint is one of a case's, `present` the names of its flexible bodies."""
        return ((self.requires is None or self.requires in present)
                and (self.excludes is None or self.excludes not in present))


@dataclass(frozen=True)
class Layout:
    """The entries of a vector a kernel reads, in order (the kinematics vector kin, the parameter
    vector, the coefficient vector, the rows of the end map, ...)."""

    name: str
    entries: tuple
    doc: str = ""

    def __len__(self):
        return len(self.entries)

    def index(self, entry):
        return self.entries.index(entry)

    def __getitem__(self, entry):
        """The place of an entry."""
        return self.entries.index(entry)


class Spec:
    """A guide or crank motion with the values of its parameters (`values`, by parameter name): the
    base of the classes generated for each guide and motion (crankgen.Line, crankgen.Circle,
    crankgen.Constant, ...), whose `declaration` is its Guide or Motion record.  A record only
    gathers the values (keyword aliases expanded); Mechanism (guides) and Case (motions) check
    them like every parameter."""

    kind = None              # "guide" or "motion"
    declaration = None       # its Guide or Motion record
    defaults = {}            # its parameters' defaults: a value not given is the default

    def __init__(self, **kwargs):
        values, given_as = {}, {}
        aliases = dict(self.declaration.aliases)
        for key, value in kwargs.items():
            if key in aliases:
                names = aliases[key]
                parts = (value,) if len(names) == 1 else value
                if len(names) > 1 and (isinstance(value, (str, bytes, dict, set)) or not hasattr(value, "__len__")
                                       or len(value) != len(names)):
                    raise ParameterError(f"{type(self).__name__}: {key} must be a sequence of "
                                         f"{len(names)} numbers ({', '.join(names)}), got {value!r}")
                pairs = list(zip(names, parts))
            elif key in self.declaration.parameters:
                pairs = [(key, value)]
            else:
                accepted = list(aliases) + list(self.declaration.parameters)
                raise ParameterError(f"{type(self).__name__} takes no argument {key!r}; it takes "
                                     f"{', '.join(dict.fromkeys(accepted))}")
            for name, part in pairs:             # one value per parameter: c=... and radius=... is two
                if name in values:
                    raise ParameterError(f"{type(self).__name__}: {name} is given twice ({given_as[name]} "
                                         f"and {key}={value!r}); give it once")
                values[name], given_as[name] = part, f"{key}={kwargs[key]!r}"
        self.values = values

    @classmethod
    def of(cls, values):
        """The record holding these parameter values (no alias expansion)."""
        record = cls.__new__(cls)
        record.values = dict(values)
        return record

    @property
    def name(self):
        return self.declaration.name

    def __repr__(self):
        args = ", ".join(f"{k}={v!r}" for k, v in self.values.items())
        return f"{type(self).__name__}({args})"

    def _complete(self):
        return {**self.defaults, **self.values}

    def __eq__(self, other):
        return type(other) is type(self) and other._complete() == self._complete()

    def __hash__(self):
        return hash((type(self).__name__, tuple(sorted(self._complete().items()))))


def project(obj, cls, **changes):
    """The record of class `cls` holding obj's values of cls's fields (obj: an instance of a
    subclass of cls, e.g. the derivation's Parameter with its symbol), with `changes` applied."""
    values = {f.name: getattr(obj, f.name) for f in fields(cls)}
    values.update(changes)
    return cls(**values)


__all__ = ["Option", "Preset", "Exclusion", "Parameter", "Guide", "Coordinate", "Motion", "Body", "Variant", "Family", "Output", "Reduction", "Primitive",
           "Constraint", "Layout", "Spec", "project"]
