"""The model's ingredients as the runtime sees them: the generated table of derive/declaration.py.

Everything that depends on which options a case chose goes through here: validation of the
options, the selection of each term family's variant (`Selection.families`, an index per family,
-1 when absent), the coefficient vector of the element kernels, the vectorized kernels of the
NumPy reference, and the field kernels of the declared outputs.  No module of the runtime names a
family, a kernel or an option value beyond what this table holds.
"""

import functools
from dataclasses import dataclass

import numpy as np

from . import schema
from .._generated import elements as _elements
from .._generated import energy as _energy
from .._generated import fields as _fields
from .._generated import schema as _table
from ..errors import ParameterError

OPTION_NAMES = tuple(schema.OPTIONS)
CHOICES = {name: o.choices for name, o in schema.OPTIONS.items()}
DEFAULTS = schema.resolve_options()
OPTION_DOCS = {name: o.doc for name, o in schema.OPTIONS.items()}
COEFFICIENTS = schema.COEFFICIENTS
SWITCHABLE_GROUPS = _table.SWITCHABLE_GROUPS
FAMILIES = tuple(f.name for f in schema.FAMILIES)
PARTS = {f.name: f.part for f in schema.FAMILIES}
ENERGY_KINDS = {f.name: f.energy_kind for f in schema.FAMILIES}
OUTPUTS = schema.OUTPUTS
KERNELS_HASH = _table.KERNELS_HASH


def check_options(options):
    """The options (dict) completed with the default model's values and checked: an unknown option
    or value raises ParameterError naming it and its choices."""
    return schema.resolve_options(**{k: v for k, v in options.items()})


def _matches(when, options):
    """Whether options have the values `when` names (a tuple of values: any of them)."""
    return all(options[k] in v if isinstance(v, tuple) else options[k] == v for k, v in when.items())


@dataclass(frozen=True)
class Selection:
    """The family variants one set of options selects."""

    options: dict
    families: tuple        # per family: variant index, or -1 when the family is absent
    kernels: tuple         # per family: element kernel name, or None
    energies: tuple        # per family: its energy kernel name, or None
    groups: frozenset      # switchable term groups present in the selected variants

    @property
    def printed_iteration(self):
        """True when the one-pass scheme iterates with the printed matrices of eq. (37)."""
        return _matches(_table.PRINTED_ITERATION, self.options)

    def energy_kernels(self, kind):
        """[(family name, part, vectorized energy kernel)] of the selected families whose energy kind
        is 'kinetic', 'potential' or 'dissipation'."""
        return [(name, PARTS[name], getattr(_energy, energy)) for name, energy in zip(FAMILIES, self.energies)
                if energy is not None and ENERGY_KINDS[name] == kind]

    def vectorized(self, part):
        """[(family name, vectorized kernel)] of the families selected for part 'rod' or 'end'."""
        return [(name, getattr(_elements, kernel)) for name, kernel in zip(FAMILIES, self.kernels)
                if kernel is not None and PARTS[name] == part]


def select(options, coefficients=None):
    """Selection of checked options (see check_options).  With the case's coefficient vector, a
    family whose scaling coefficients all vanish (gravity without gravity) is left out: it would
    add zeros at the cost of a kernel call per element and iteration.  One Selection per options
    and vanishing families (a continuation builds a case per parameter value)."""
    vanished = None
    if coefficients is not None:
        vanished = tuple(f.name for f in schema.FAMILIES if f.vanishes_with and all(
            coefficients[COEFFICIENTS.index(c)] == 0.0 for c in f.vanishes_with))
    try:
        key = tuple(sorted(options.items()))
        hash(key)
    except TypeError:                   # an unhashable option value: no sharing
        return _select(dict(options), vanished)
    return _select_shared(key, vanished)


@functools.lru_cache(maxsize=256)
def _select_shared(key, vanished):
    return _select(dict(key), vanished)


def _select(options, vanished):
    """The Selection of options, leaving out the families named in `vanished` (None: none)."""
    families, kernels, energies, groups = [], [], [], set()
    for family in schema.FAMILIES:
        hits = [(k, v) for k, v in enumerate(family.variants) if _matches(v.when, options)]
        if hits and vanished is not None and family.name in vanished:
            hits = []
        if len(hits) > 1:
            raise ParameterError(f"options {options} select several variants of {family.name}")
        if hits:
            k, variant = hits[0]
            families.append(k)
            kernels.append(variant.kernel)
            energies.append(variant.energy)
            groups.update(variant.groups)
        else:
            families.append(-1)
            kernels.append(None)
            energies.append(None)
    return Selection(dict(options), tuple(families), tuple(kernels), tuple(energies), frozenset(groups))


def check_switched_off(groups_off, selection):
    """Tuple of the switched-off group names (comma-separated text or iterable), each of which must
    be a switchable group present in the selected model (ParameterError otherwise)."""
    names = groups_off.split(",") if isinstance(groups_off, str) else list(groups_off)
    names = tuple(dict.fromkeys(g.strip() for g in names if g.strip()))
    for g in names:
        if g not in SWITCHABLE_GROUPS:
            raise ParameterError(f"groups_off must name groups among {', '.join(SWITCHABLE_GROUPS)}, got {g!r}")
        if g not in selection.groups:
            present = ", ".join(sorted(selection.groups)) or "none"
            raise ParameterError(f"groups_off: the selected model has no '{g}' group to switch off "
                                 f"(its switchable groups: {present})")
    return names


def _output_kernels(options):
    """Per declared output with kernels: the name of the one the options select (None: none)."""
    return tuple(next((k for when, k in o.kernels if _matches(when, options)), None)
                 for o in OUTPUTS.values() if not o.engine)


def applies(option, options):
    """Whether the model option `option` makes a difference under the other `options` (a case's
    options, or as_dict()): whether another of its choices selects another variant of some family or
    another kernel of some output.  The membrane option does not apply to approach C (no v_x^2 in
    its strain) nor to the exact rod (its strain is pointwise whatever it says), read off the
    declaration, not restated."""
    base = check_options({k: options[k] for k in schema.OPTIONS if k in options})
    return _applies(option, tuple(sorted(base.items())))


@functools.lru_cache(maxsize=256)
def _applies(option, key):
    base = dict(key)
    ref = (_select(base, None).kernels, _output_kernels(base))
    for value in schema.OPTIONS[option].choices:
        if value == base[option]:
            continue
        try:
            other = check_options(dict(base, **{option: value}))
        except ParameterError:          # a combination the declaration refuses
            continue
        if (_select(other, None).kernels, _output_kernels(other)) != ref:
            return True
    return False


def coefficients(vector, options, switched_off=()):
    """Coefficient vector (COEFFICIENTS order) of the element kernels for a parameter vector
    (schema.PARAMETER_VECTOR order), the model options and the switched-off term groups."""
    return np.array(_table.coefficients(vector, options, tuple(switched_off)), dtype=float)


def body_coefficients(body, vector, options, switched_off=()):
    """The coefficient vector of another flexible body's elements (a flexible rocker's: the rod's with
    its own section's; generated coefficients_<body>)."""
    return np.array(getattr(_table, f"coefficients_{body}")(vector, options, tuple(switched_off)), dtype=float)


def flexible_bodies(case):
    """The names of a case's flexible bodies beside the rod: those whose element count (a parameter of
    its guide) is above 0 (a four-bar's flexible rocker)."""
    return tuple(b.name for b in schema.BODIES.values()
                 if b.kind == "flexible" and b.elements is not None and b.elements in case.guide_record.parameters
                 and getattr(case, b.elements))


# the inputs of an output that a flexible rocker has no value of: the guide's reduced co-ordinate s
# (the rigid rocker's angle); the force at the rod's end is the tip constraint's then
UNAVAILABLE_WITH_FLEXIBLE_LINKS = ("s",)


def available(name, case):
    """Whether the declared output `name` has a value for the case: not those reading the rigid
    rocker's co-ordinate (s), nor those whose expression takes a body as rigid (Output.rigid: a rigid
    rocker's momentum balance), when that body is flexible; not those needing a body flexible
    (Output.flexible) when it is not."""
    spec = OUTPUTS[name]
    present = flexible_bodies(case)
    if any(b not in present for b in spec.flexible) or any(b in present for b in spec.rigid):
        return False
    return not (present and set(spec.inputs) & set(UNAVAILABLE_WITH_FLEXIBLE_LINKS))


def output_kernel(output, options):
    """The vectorized kernel of a declared step or field output for the options."""
    spec = OUTPUTS.get(output)
    if spec is None or spec.engine:
        names = ", ".join(n for n, o in OUTPUTS.items() if not o.engine)
        raise ParameterError(f"no output {output!r} with a kernel; those outputs are {names}")
    for when, kernel in spec.kernels:
        if _matches(when, options):
            return getattr(_fields, kernel)
    raise ParameterError(f"output {output!r} is not declared for options {options}")


def field_kernel(output, options):
    """The vectorized field kernel of a declared field output for the options."""
    spec = OUTPUTS.get(output)
    if spec is None or spec.kind != "field":
        fields = ", ".join(n for n, o in OUTPUTS.items() if o.kind == "field")
        raise ParameterError(f"no field output {output!r}; the field outputs are {fields}")
    return output_kernel(output, options)
