"""A case: every parameter of one run, as one frozen record (the unit of sweeps and checkpoints)."""

from dataclasses import asdict, dataclass, fields

from .kernels import select_kernels
from .newmark import NewmarkSettings
from .parameters import Mechanism
from .errors import ParameterError
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
    groups_off: str = ""          # audit only: comma-separated term groups removed (engine.SWITCHABLE_GROUPS)

    def __post_init__(self):
        """Validate every field and store it in canonical form (Python float / int / str), so that
        equal cases compare equal and share one key however their numbers were typed."""
        mech = Mechanism(self.a, self.eps, self.ms, self.mu)          # validates, returns floats
        for name in ("a", "eps", "ms", "mu"):
            object.__setattr__(self, name, getattr(mech, name))
        object.__setattr__(self, "omega", in_range("omega (crank speed Omega*)", self.omega, 0, None, True))
        for name in ("approach", "formulation", "damping", "integrator", "membrane", "groups_off"):
            value = getattr(self, name)
            if not isinstance(value, str):
                raise ParameterError(f"{name} must be a string, got {value!r}")
            object.__setattr__(self, name, str(value))
        select_kernels(self.formulation, self.approach, self.damping, self.membrane)
        object.__setattr__(self, "n_elements", integer("n_elements", self.n_elements, 1))
        object.__setattr__(self, "steps_per_rev", integer("steps_per_rev", self.steps_per_rev, 4))
        NewmarkSettings(scheme=self.integrator)
        names = sorted({g.strip() for g in self.groups_off.split(",") if g.strip()})
        object.__setattr__(self, "groups_off", ",".join(names))
        if names:
            from .engine import SWITCHABLE_GROUPS
            for g in names:
                if g not in SWITCHABLE_GROUPS:
                    raise ParameterError(f"groups_off must name groups among {', '.join(SWITCHABLE_GROUPS)}, got {g!r}")
            if self.formulation != "lagrange" or self.approach != "A":
                raise ParameterError("groups_off applies to the lagrange formulation with approach A only")

    @property
    def mechanism(self):
        return Mechanism(self.a, self.eps, self.ms, self.mu)

    def as_dict(self):
        return asdict(self)

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
                kwargs[f.name] = value
        return cls(**kwargs)

    def key(self):
        """Stable text key of the case (checkpoint identity), from the canonical field values."""
        return ";".join(f"{k}={v!r}" for k, v in sorted(self.as_dict().items()))
