"""Cross-sections of the rod, for the stresses at its outer fibres (crankgen.stress).

A Section holds the area A, the second moment of area I about the bending axis (perpendicular to
the mechanism's plane) and the distances of the two outer fibres from the neutral axis: c_top on
the side of the rod's e_j (a quarter turn counter-clockwise from the rod's axis, the side positive
deflections v go to) and c_bottom on the other side.  rectangle(b, h) (h in the mechanism's
plane), circle(d) and tube(d, t) build the usual ones; Section(A=..., I=..., c_top=...,
c_bottom=...) any other (an I-beam's, an asymmetric one's).

Lengths in metres for a mechanism in SI (the section must be the rod's: its radius of gyration
sqrt(I / A) is checked against the mechanism's); for a mechanism in crankgen's units only the
shape counts, the outer-fibre distances in radii of gyration (c / r), the size being the rod's
(eps = r / L)."""

import math
from dataclasses import dataclass

from ..errors import ParameterError
from .validation import in_range


@dataclass(frozen=True)
class Section:
    """A rod section: A (area), I (second moment of area about the bending axis), c_top and
    c_bottom (outer-fibre distances from the neutral axis, towards e_j and away from it), all > 0,
    in one length unit (m for SI); `kind` says how it was made."""

    A: float
    I: float
    c_top: float
    c_bottom: float
    kind: str = "given"

    def __post_init__(self):
        for name in ("A", "I", "c_top", "c_bottom"):
            object.__setattr__(self, name, in_range(f"section {name}", getattr(self, name), 0, None, True))

    @property
    def radius_of_gyration(self):
        return math.sqrt(self.I / self.A)

    @property
    def fibres(self):
        """{"top": y, "bottom": y}: the outer fibres' signed distances from the neutral axis
        (positive towards e_j)."""
        return {"top": self.c_top, "bottom": -self.c_bottom}

    def __str__(self):
        return (f"{self.kind} section: A = {self.A:.4g}, I = {self.I:.4g}, outer fibres at "
                f"+{self.c_top:.4g} / -{self.c_bottom:.4g}")


def rectangle(b, h):
    """A solid rectangle of width b (across the plane) and height h (in the plane, the bending
    direction)."""
    b, h = in_range("b (width)", b, 0, None, True), in_range("h (height)", h, 0, None, True)
    return Section(A=b * h, I=b * h ** 3 / 12, c_top=h / 2, c_bottom=h / 2, kind=f"rectangle {b:g} x {h:g}")


def circle(d):
    """A solid circle of diameter d."""
    d = in_range("d (diameter)", d, 0, None, True)
    return Section(A=math.pi * d ** 2 / 4, I=math.pi * d ** 4 / 64, c_top=d / 2, c_bottom=d / 2,
                   kind=f"circle d = {d:g}")


def tube(d, t):
    """A round tube of outer diameter d and wall thickness t (0 < t <= d / 2; t = d / 2 is the
    solid circle)."""
    d = in_range("d (outer diameter)", d, 0, None, True)
    t = in_range("t (wall thickness)", t, 0, d / 2, True)
    inner = d - 2 * t
    return Section(A=math.pi * (d ** 2 - inner ** 2) / 4, I=math.pi * (d ** 4 - inner ** 4) / 64,
                   c_top=d / 2, c_bottom=d / 2, kind=f"tube d = {d:g}, t = {t:g}")


def parse(text):
    """A Section from the command line's text: rectangle:B,H, circle:D, tube:D,T or A,I,C (or
    A,I,C_TOP,C_BOTTOM)."""
    kind, _, rest = str(text).partition(":")
    makers = {"rectangle": (rectangle, 2), "circle": (circle, 1), "tube": (tube, 2)}
    try:
        if rest or kind in makers:
            maker, count = makers[kind]
            values = [float(x) for x in rest.split(",") if x.strip()]
            if len(values) != count:
                raise ValueError
            return maker(*values)
        values = [float(x) for x in kind.split(",") if x.strip()]
        if len(values) not in (3, 4):
            raise ValueError
        A, I, c = values[:3]
        return Section(A=A, I=I, c_top=c, c_bottom=values[3] if len(values) == 4 else c)
    except (KeyError, ValueError):
        raise ParameterError(f"a section is rectangle:B,H, circle:D, tube:D,T or A,I,C[,C_BOTTOM] "
                             f"(numbers > 0), got {text!r}") from None
