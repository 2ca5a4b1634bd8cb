"""crankgen's units in SI: the conversion of every declared quantity, read from its units string.

Inside crankgen: length L (the rod's length), mass rho A L, time 1/omega_b with
omega_b = (pi/L)^2 sqrt(EI/(rho A)) (the lowest bending frequency of the pinned-pinned rod).  Every
parameter and output declares its unit (derive/declaration.py, derive/outputs.py) as a product of
the base symbols below, with integer powers and at most one "/": "r", "r^2/L", "L", "rad", "omega_b", "L omega_b",
"rhoA L", "rhoA L^2 omega_b^2", "rhoA L^3 omega_b^2", "EI/L^2", "EI/L", "1/omega_b", "rev", "1".
`Scales` gives the SI value of each base symbol for one mechanism; `Scales.factor(units)` the SI
value of one unit of a quantity, so that  value_SI = value * factor(units), and
`Scales.si_name(units)` the name of the SI unit (m, s, kg, rad/s, m/s, m/s^2, N, N m, ...), found
from the quantity's dimensions.

Base symbols and their SI values:
    L        the rod's length (m)
    r        its section's radius of gyration, eps L (m)
    omega_b  the lowest pinned-pinned bending frequency (rad/s)
    rhoA     mass per unit length (kg/m)
    EI, EA   bending and axial stiffness: EI = rhoA L^4 omega_b^2 / pi^4 (N m^2), EA = EI / r^2 (N)
    rad, rev, 1   dimensionless (an angle in radians; a number of crank revolutions)

The rod's SI quantities set these scales (ROD: its length L, Young's modulus E, density rho, the
section's area A and second moment of area I, the first fields of a crankgen.SIMechanism):
L = L, rhoA = rho A, r = sqrt(I/A), omega_b = (pi/L)^2 sqrt(E I / (rho A)) (OF_ROD: each base
symbol as a product of their powers).
"""

import math
from dataclasses import dataclass

from ..errors import ParameterError

# dimensions (metre, kilogram, second) of each base symbol
_DIMENSIONS = {
    "L": (1, 0, 0), "r": (1, 0, 0), "omega_b": (0, 0, -1), "rhoA": (-1, 1, 0),
    "EI": (3, 1, -2), "EA": (1, 1, -2), "rad": (0, 0, 0), "rev": (0, 0, 0), "1": (0, 0, 0),
}
_WORDS = ("rad", "rev", "1")          # dimensionless base symbols: names, not scales
_NAMES = {
    (0, 0, 0): "1", (1, 0, 0): "m", (0, 0, 1): "s", (0, 0, -1): "rad/s", (1, 0, -1): "m/s",
    (0, 0, -2): "rad/s^2", (1, 0, -2): "m/s^2", (1, 1, -2): "N", (2, 1, -2): "N m",
    (-1, 1, 0): "kg/m", (0, 1, 0): "kg", (3, 1, -2): "N m^2", (2, 1, 0): "kg m^2", (2, 1, -3): "W",
}


def parse(units):
    """{base symbol: integer power} of a units string ("rhoA L^2 omega_b^2", "r^2/L", "1")."""
    if not isinstance(units, str) or units.count("/") > 1:
        raise ValueError(f"units must be a product of base symbols with at most one '/', got {units!r}")
    powers = {}
    for sign, part in zip((1, -1), units.split("/")):
        tokens = part.split()
        if not tokens:
            raise ValueError(f"empty numerator or denominator in units {units!r}")
        for token in tokens:
            name, _, power = token.partition("^")
            if name not in _DIMENSIONS:
                raise ValueError(f"unknown base symbol {name!r} in units {units!r}; the symbols are "
                                 f"{', '.join(_DIMENSIONS)}")
            try:
                p = int(power) if power else 1
            except ValueError:
                raise ValueError(f"power {power!r} of {name} in units {units!r} is not an integer") from None
            if name not in _WORDS:
                powers[name] = powers.get(name, 0) + sign * p
    return {k: v for k, v in powers.items() if v != 0}


def same_in_si(units):
    """True when a quantity in `units` has the same number in SI as in crankgen's units (a plain
    number, an angle, a number of revolutions)."""
    return parse(units) == {}


# the rod's SI quantities that set crankgen's units: (name, SI unit, what it is)
ROD = (("L", "m", "the rod's length"), ("E", "Pa", "Young's modulus"), ("rho", "kg/m^3", "the density"),
       ("A", "m^2", "the section's area"),
       ("I", "m^4", "the section's second moment of area about its axis normal to the plane"))
# each base symbol as (powers of the rod's quantities, power of pi): omega_b = pi^2 L^-2 (E I / (rho A))^(1/2)
OF_ROD = {"L": ({"L": 1}, 0), "r": ({"I": 0.5, "A": -0.5}, 0), "rhoA": ({"rho": 1, "A": 1}, 0),
          "omega_b": ({"L": -2, "E": 0.5, "I": 0.5, "rho": -0.5, "A": -0.5}, 2),
          "EI": ({"E": 1, "I": 1}, 0), "EA": ({"E": 1, "A": 1}, 0)}


def rod_powers(units):
    """(powers of the rod's quantities, power of pi) of one unit `units`: its SI value is
    pi^k prod(q^p) (for magnitudes computed on logarithms, where nothing overflows)."""
    out, pi = {}, 0
    for name, power in parse(units).items():
        fields, k = OF_ROD[name]
        pi += power * k
        for q, p in fields.items():
            out[q] = out.get(q, 0) + power * p
    return {q: p for q, p in out.items() if p != 0}, pi


@dataclass(frozen=True)
class Scales:
    """crankgen's units in SI for one mechanism: the rod's length L (m), the slenderness eps = r/L,
    the frequency omega_b (rad/s) and the mass per unit length rhoA (kg/m)."""

    L: float
    eps: float
    omega_b: float
    rhoA: float

    @classmethod
    def of_rod(cls, L, E, rho, A, I):
        """The scales of a rod of length L (m), Young's modulus E (Pa), density rho (kg/m^3),
        section area A (m^2) and second moment of area I (m^4)."""
        values = dict(L=L, E=E, rho=rho, A=A, I=I)

        def base(name):
            powers, k = OF_ROD[name]
            return math.pi ** k * math.prod(float(values[q]) ** p for q, p in powers.items())
        return cls(L=float(L), eps=base("r") / float(L), omega_b=base("omega_b"), rhoA=base("rhoA"))

    @property
    def base(self):
        """SI value of each base symbol."""
        EI = self.rhoA * self.L ** 4 * self.omega_b ** 2 / math.pi ** 4
        r = self.eps * self.L
        return {"L": self.L, "r": r, "omega_b": self.omega_b, "rhoA": self.rhoA, "EI": EI, "EA": EI / r ** 2}

    def factor(self, units):
        """SI value of one unit `units` of crankgen (value_SI = value * factor)."""
        base = self.base
        out = 1.0
        for name, power in parse(units).items():
            out *= base[name] ** power
        return out

    @staticmethod
    def si_name(units):
        """Name of the SI unit of a quantity declared in `units` ("m", "N m", "rad/s", "1", ...)."""
        dims = [0, 0, 0]
        for name, power in parse(units).items():
            for k in range(3):
                dims[k] += power * _DIMENSIONS[name][k]
        dims = tuple(dims)
        words = [w for w in units.replace("/", " ").split() if w in ("rad", "rev")]
        if dims == (0, 0, 0) and words:
            return words[0]
        if dims in _NAMES:
            return _NAMES[dims]
        return " ".join(f"{n}^{p}" if p != 1 else n for n, p in zip(("m", "kg", "s"), dims) if p)


def in_L(units, values):
    """The value in crankgen's length L of one unit `units` made of lengths ("r", "r^2/L", "L"),
    for a case's parameter values (a mapping; absent ones at their default): a unit that is a
    parameter (the radius of gyration r = eps L) takes that parameter's value (schema.UNIT_PARAMETERS)."""
    from . import schema
    out = 1.0
    for name, power in parse(units).items():
        if name == "L":
            continue
        if name not in schema.UNIT_PARAMETERS:
            raise ValueError(f"{name} is not a length (units {units!r})")
        p = schema.PARAMETERS[schema.UNIT_PARAMETERS[name]]
        out *= float(values.get(p.name, p.default)) ** power
    return out
