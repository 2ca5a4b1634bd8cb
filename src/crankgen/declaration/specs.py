"""Records of a guide and of a crank motion: one class per guide and motion of the schema.

    crankgen.Line(offset=0.05)                                  # the slider on the line Y = e
    crankgen.Circle(center=(1.0, 0.0), radius=0.8, branch=1)    # a rocker: the four-bar linkage
    crankgen.Constant(omega=0.8)
    crankgen.RunUp(start=0.2, stop=1.2, revolutions=30)
    crankgen.Fluctuation(omega=0.8, amplitude=0.1, order=2)

The classes are generated from the declaration (generated/classes.py: each a crankgen.declaration.records.Spec
whose `declaration` is its Guide or Motion record, with the keyword aliases its record accepts,
e.g. a circle's `center=(d, offset)` and `radius=c`); a record only gathers the values, which
Mechanism (guides) and Case (motions) check like every parameter.
"""

from .._generated import classes as _classes
from .records import Spec

GUIDES = {cls.declaration.name: cls for cls in _classes.GUIDE_CLASSES}
MOTIONS = {cls.declaration.name: cls for cls in _classes.MOTION_CLASSES}
RECORDS = {"guide": GUIDES, "motion": MOTIONS}
__all__ = ["Spec"] + [cls.__name__ for cls in (*GUIDES.values(), *MOTIONS.values())]


def __getattr__(name):
    """crankgen.declaration.specs.Line, ...: the generated record classes by their names."""
    for cls in (*GUIDES.values(), *MOTIONS.values()):
        if cls.__name__ == name:
            return cls
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
