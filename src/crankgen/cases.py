"""A case: every parameter of one run, as one frozen record (the unit of sweeps and checkpoints).

Its model options (formulation, approach, membrane, damping, rotary_inertia) are those declared in
derive/model.py and are checked against the generated table (crankgen.ingredients) when the case
is built: an unknown or incompatible option raises ParameterError naming it.
"""

from dataclasses import asdict, dataclass, fields

from . import ingredients
from .errors import ParameterError
from .newmark import NewmarkSettings
from .parameters import Mechanism
from .validation import in_range, integer


@dataclass(frozen=True)
class Case:
    a: float = 0.1
    eps: float = 0.01
    ms: float = 0.5
    mu: float = 0.5
    omega: float = 0.8
    approach: str = "A"
    formulation: str = "lagrange"
    damping: str = "paper"
    n_elements: int = 16
    steps_per_rev: int = 100
    integrator: str = "newton"
    membrane: str = "pointwise"
    groups_off: str = ""          # audit: comma-separated term groups switched off (weights set to 0)
    rotary_inertia: bool = True
    gravity: tuple = (0.0, 0.0)
    offset: float = 0.0

    def __post_init__(self):
        """Validate every field and store it in canonical form (Python float / int / str / bool,
        gravity a pair of floats), so that equal cases compare equal and share one key however
        their values were typed."""
        mech = Mechanism(self.a, self.eps, self.ms, self.mu, self.gravity, self.offset)   # validates
        for name in ("a", "eps", "ms", "mu", "gravity", "offset"):
            object.__setattr__(self, name, getattr(mech, name))
        object.__setattr__(self, "omega", in_range("omega (crank speed Omega*)", self.omega, 0, None, True))
        for name in ("integrator", "groups_off"):
            value = getattr(self, name)
            if not isinstance(value, str):
                raise ParameterError(f"{name} must be a string, got {value!r}")
            object.__setattr__(self, name, str(value))
        options = ingredients.check_options({name: getattr(self, name) for name in ingredients.OPTION_NAMES})
        for name, value in options.items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "n_elements", integer("n_elements", self.n_elements, 1))
        object.__setattr__(self, "steps_per_rev", integer("steps_per_rev", self.steps_per_rev, 4))
        NewmarkSettings(scheme=self.integrator)
        off = ingredients.check_switched_off(self.groups_off, self.selection)
        object.__setattr__(self, "groups_off", ",".join(sorted(off)))

    @classmethod
    def from_mechanism(cls, mech, **settings):
        """The case of a Mechanism (every one of its fields) with the given run settings."""
        return cls(**{f.name: getattr(mech, f.name) for f in fields(mech)}, **settings)

    @property
    def mechanism(self):
        return Mechanism(self.a, self.eps, self.ms, self.mu, self.gravity, self.offset)

    @property
    def options(self):
        """The model options, {name: value} (ingredients.OPTION_NAMES)."""
        return {name: getattr(self, name) for name in ingredients.OPTION_NAMES}

    @property
    def selection(self):
        """The term-family variants the options select (ingredients.Selection); families whose
        coefficients vanish for this case (gravity without gravity) are left out."""
        return ingredients.select(self.options, self.coefficients)

    @property
    def coefficients(self):
        """Coefficient vector of the element kernels (ingredients.COEFFICIENTS order)."""
        off = tuple(g for g in self.groups_off.split(",") if g)
        return ingredients.coefficients(self.mechanism, self.options, off)

    def as_dict(self):
        """The fields as plain JSON-able values (gravity as a list)."""
        return {k: list(v) if isinstance(v, tuple) else v for k, v in asdict(self).items()}

    @classmethod
    def from_dict(cls, data):
        """Case from a mapping (extra keys ignored).  Numeric strings (from CSV) are converted;
        anything else is validated and normalised by the constructor."""
        kwargs = {}
        for f in fields(cls):
            if f.name in data:
                value = data[f.name]
                if isinstance(value, str) and f.type in ("float", float, "int", int):
                    try:
                        value = float(value)
                    except ValueError:
                        pass                      # the constructor names the field
                elif f.type in ("bool", bool) and isinstance(value, str):
                    value = {"true": True, "false": False}.get(value.strip().lower(), value)
                elif f.type in ("tuple", tuple) and value is not None:
                    if isinstance(value, str):
                        value = [x for x in value.strip("()[] ").split(",") if x.strip()]
                    try:
                        value = tuple(float(x) for x in value)
                    except (TypeError, ValueError):
                        pass                      # the constructor names the field
                kwargs[f.name] = value
        return cls(**kwargs)

    def key(self):
        """Stable text key of the case (checkpoint identity), from the canonical field values."""
        return ";".join(f"{k}={v!r}" for k, v in sorted(self.as_dict().items()))
