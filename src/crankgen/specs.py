"""Records of a guide and of a crank motion, one class per guide and motion of the schema.

    crankgen.Line(offset=0.05)                                  # the slider on the line Y = e
    crankgen.Circle(center=(1.0, 0.0), radius=0.8, branch=1)    # a rocker: the four-bar linkage
    crankgen.Constant(omega=0.8)
    crankgen.RunUp(start=0.2, stop=1.2, revolutions=30)
    crankgen.Fluctuation(omega=0.8, amplitude=0.1, order=2)

Each class is made from the schema's declaration of its guide or motion (its parameters and the
keyword aliases its record accepts, e.g. a circle's `center=(d, offset)` and `radius=c`); a record
only gathers the values, which Mechanism (guides) and Case (motions) check like every parameter.
"""

from . import schema
from .errors import ParameterError


class Spec:
    """A guide or crank motion with the values of its parameters (`values`, by parameter name)."""

    kind = None        # "guide" or "motion"
    name = None        # its name in the schema
    declaration = None

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
                accepted = list(aliases) + [p for p in self.declaration.parameters]
                raise ParameterError(f"{type(self).__name__} takes no argument {key!r}; it takes "
                                     f"{', '.join(dict.fromkeys(accepted))}")
            for name, part in pairs:             # one value per parameter: c=... and radius=... is two
                if name in values:
                    raise ParameterError(f"{type(self).__name__}: {name} is given twice ({given_as[name]} "
                                         f"and {key}={value!r}); give it once")
                values[name], given_as[name] = part, f"{key}={kwargs[key]!r}"
        self.values = values

    def __repr__(self):
        args = ", ".join(f"{k}={v!r}" for k, v in self.values.items())
        return f"{type(self).__name__}({args})"

    def __eq__(self, other):
        return type(other) is type(self) and other.values == self.values

    def __hash__(self):
        return hash((type(self).__name__, tuple(sorted(self.values.items()))))


def _make(kind, declaration):
    doc = f"{declaration.doc}.  Parameters: {', '.join(declaration.parameters)}" + (
        "; keywords " + ", ".join(f"{k} = ({', '.join(v)})" for k, v in declaration.aliases)
        if declaration.aliases else "") + "."
    return type(declaration.title, (Spec,), {"kind": kind, "name": declaration.name,
                                             "declaration": declaration, "__doc__": doc,
                                             "__module__": __name__})


GUIDES = {name: _make("guide", g) for name, g in schema.GUIDES.items()}
MOTIONS = {name: _make("motion", m) for name, m in schema.MOTIONS.items()}
globals().update({cls.__name__: cls for cls in (*GUIDES.values(), *MOTIONS.values())})
__all__ = [cls.__name__ for cls in (*GUIDES.values(), *MOTIONS.values())]
