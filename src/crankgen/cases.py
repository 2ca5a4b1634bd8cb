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
        Mechanism(self.a, self.eps, self.ms, self.mu)           # validates
        object.__setattr__(self, "omega", in_range("omega (crank speed Omega*)", self.omega, 0, None, True))
        select_kernels(self.formulation, self.approach, self.damping, self.membrane)
        object.__setattr__(self, "n_elements", integer("n_elements", self.n_elements, 1))
        object.__setattr__(self, "steps_per_rev", integer("steps_per_rev", self.steps_per_rev, 4))
        NewmarkSettings(scheme=self.integrator)
        if self.groups_off:
            from .engine import SWITCHABLE_GROUPS
            names = [g.strip() for g in self.groups_off.split(",") if g.strip()]
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
        """Case from a mapping (extra keys ignored; numeric strings from CSV converted)."""
        kwargs = {}
        for f in fields(cls):
            if f.name in data:
                value = data[f.name]
                if f.type in ("float", float):
                    value = float(value)
                elif f.type in ("int", int):
                    value = int(float(value))
                kwargs[f.name] = value
        return cls(**kwargs)

    def key(self):
        """Stable text key of the case (checkpoint identity)."""
        return ";".join(f"{k}={v!r}" for k, v in sorted(self.as_dict().items()))
