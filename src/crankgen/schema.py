"""The model schema as the runtime sees it: typed records of the generated tables (generated/schema.py).

Every parameter of a case, every option, preset, guide, motion and output is declared once, in
derive/model.py; this module gives the runtime their records and the rules that follow from them:
a parameter's check and canonical form (`Parameter.canonical`), the model options of a preset with
explicit options overriding it (`resolve_options`), the parameters a guide or motion reads.
Mechanism, Case, the command line's flags and the continuation's parameters are built from here.
"""

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ._generated import schema as _table
from .errors import ParameterError

KINEMATICS = _table.KINEMATICS
KINEMATIC_PARAMETERS = _table.KINEMATIC_PARAMETERS
KIN = {name: k for k, name in enumerate(KINEMATICS)}         # place of each entry of kin
ELEMENT_DOFS = _table.ELEMENT_DOFS
END_SLOTS = _table.END_SLOTS
END_MAP_ROWS = {name: k for k, name in enumerate(_table.END_MAP_ROWS)}
ELEMENT_MODES = _table.ELEMENT_MODES          # what an element kernel's one-element function adds
LANES, LANE_SIZE = _table.LANES, _table.LANE_SIZE       # an element kernel's lane function: elements at once,
LANE_ROWS = _table.LANE_ROWS                            # its buffer's size and the first row of each block


def _bracket(low, high, low_open, high_open):
    left = "-inf" if low is None else f"{low:g}"
    right = "inf" if high is None else f"{high:g}"
    return ("(" if low_open or low is None else "[") + f"{left}, {right}" + (")" if high_open or high is None else "]")


def _real(label, value):
    if isinstance(value, (bool, str, bytes, bytearray)) or not isinstance(value, (numbers.Real, np.generic)):
        raise ParameterError(f"{label} must be a number, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"{label} must be finite, got {value!r}")
    return x + 0.0                     # -0.0 -> 0.0: one canonical zero


@dataclass(frozen=True)
class Parameter:
    name: str
    kind: str
    default: object
    owner: str
    readers: tuple
    low: object
    high: object
    low_open: bool
    high_open: bool
    units: str
    cli: str
    metavar: str
    choices: tuple
    continuable: bool
    kinematic_index: int
    label: str
    doc: str

    @property
    def range_text(self):
        if self.kind == "real":
            return _bracket(self.low, self.high, self.low_open, self.high_open)
        if self.kind == "count":
            return f"an integer >= {self.low}"
        if self.kind == "sign":
            return "+1 or -1"
        if self.kind == "choice":
            return " or ".join(repr(c) for c in self.choices)
        return "two finite numbers"

    def canonical(self, value):
        """value checked and in canonical form (a Python float, int, str or a tuple of floats; -0.0
        is 0.0), or ParameterError naming the parameter and its allowed values."""
        label = self.label
        if self.kind == "real":
            x = _real(label, value)
            bad_low = self.low is not None and (x <= self.low if self.low_open else x < self.low)
            bad_high = self.high is not None and (x >= self.high if self.high_open else x > self.high)
            if bad_low or bad_high:
                raise ParameterError(f"{label} must be in {self.range_text}, got {x:g}")
            return x
        if self.kind == "pair":
            if isinstance(value, (str, bytes, dict, set, frozenset)) or not hasattr(value, "__len__") \
                    or not hasattr(value, "__getitem__") or len(value) != 2:
                raise ParameterError(f"{label} must be a sequence of two numbers ({self.metavar or 'X,Y'}), "
                                     f"got {value!r}")
            return tuple(_real(f"{label}[{k}]", value[k]) for k in range(2))
        if self.kind in ("count", "sign"):
            if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.generic)):
                raise ParameterError(f"{label} must be {self.range_text}, got {value!r}")
            x = float(value)
            if not (math.isfinite(x) and x.is_integer()):
                raise ParameterError(f"{label} must be {self.range_text}, got {value!r}")
            n = int(x)
            if (self.kind == "sign" and n not in (1, -1)) or (self.kind == "count" and n < self.low):
                raise ParameterError(f"{label} must be {self.range_text}, got {n}")
            return n
        if isinstance(value, np.generic):
            value = value.item()
        if not isinstance(value, str) or value not in self.choices:
            raise ParameterError(f"{label} must be {self.range_text}, got {value!r}")
        return value

    def read_by(self, guide, motion):
        """True when the case's guide / motion reads this parameter."""
        if self.owner == "guide":
            return guide in self.readers
        if self.owner == "motion":
            return motion in self.readers
        return True


@dataclass(frozen=True)
class Option:
    name: str
    choices: tuple
    default: object
    cli: str
    doc: str

    def canonical(self, value):
        if isinstance(value, np.generic):
            value = value.item()
        if value not in self.choices or type(value) is not type(self.choices[0]):
            allowed = ", ".join(repr(c) for c in self.choices)
            raise ParameterError(f"{self.name} must be one of {allowed}, got {value!r}")
        return value


@dataclass(frozen=True)
class Preset:
    name: str
    options: dict
    doc: str


@dataclass(frozen=True)
class Guide:
    name: str
    title: str
    parameters: tuple
    aliases: tuple               # ((keyword of the record, (parameter, ...)), ...)
    margins: tuple
    doc: str


@dataclass(frozen=True)
class Motion:
    name: str
    title: str
    parameters: tuple
    periodic: bool
    aliases: tuple
    doc: str


@dataclass(frozen=True)
class Output:
    name: str
    kind: str
    units: str
    arguments: tuple
    guides: tuple
    inputs: tuple
    doc: str
    kernels: tuple


PARAMETERS = {p["name"]: Parameter(**p) for p in _table.PARAMETERS}
OPTIONS = {o["name"]: Option(**o) for o in _table.OPTIONS}
PRESETS = {p["name"]: Preset(**p) for p in _table.PRESETS}
DEFAULT_PRESET = _table.DEFAULT_PRESET
GUIDES = {g["name"]: Guide(**g) for g in _table.GUIDES}
MOTIONS = {m["name"]: Motion(**m) for m in _table.MOTIONS}
OUTPUTS = {o["name"]: Output(**o) for o in _table.OUTPUTS}
MECHANISM_PARAMETERS = tuple(n for n, p in PARAMETERS.items() if p.owner in ("mechanism", "guide"))
RUN_PARAMETERS = tuple(n for n, p in PARAMETERS.items() if p.owner in ("run", "motion"))
CONTINUABLE = tuple(n for n, p in PARAMETERS.items() if p.continuable)
EXCLUSIONS = _table.EXCLUSIONS            # (option values, reason): refused together
QUADRATURE = _table.QUADRATURE            # element kernel -> its quadrature rule


def resolve_options(model=None, **options):
    """The model options of a case: the preset `model` (default: the default preset), then every
    explicit option (not None) overriding it, checked; ParameterError names a bad one."""
    name = DEFAULT_PRESET if model is None else model
    if name not in PRESETS:
        raise ParameterError(f"model must be one of {', '.join(repr(p) for p in PRESETS)}, got {model!r}")
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"unknown model option {unknown[0]!r}; the options are {', '.join(OPTIONS)}")
    out = {}
    for opt in OPTIONS.values():
        value = options.get(opt.name)
        if value is None:
            value = PRESETS[name].options.get(opt.name, opt.default)
        out[opt.name] = opt.canonical(value)
    for values, reason in EXCLUSIONS:
        if all(out[k] == v for k, v in values.items()):
            raise ParameterError(reason)
    return out


def preset_of(options):
    """Name of the preset whose option values the options have (the one setting the most of them
    when several do), or None."""
    matching = [(len(p.options), name) for name, p in PRESETS.items()
                if all(options.get(k) == v for k, v in p.options.items())]
    return max(matching, key=lambda m: m[0])[1] if matching else None
