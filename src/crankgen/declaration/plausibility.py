"""Plausibility of a mechanism's numbers: the unit mistakes their size gives away, named before any work.

A modulus given in GPa (`E = 210`), a density in g/cm^3 (`rho = 7.85`) or t/mm^3, lengths in mm,
a slider's mass in grams or a crank speed in rad/s passed as the dimensionless Omega* make a valid
mechanism of no real kind: the run then diverges or is beyond every theory, and the message says
so in numbers that do not point at the cause.  These checks run when the mechanism is made:

- each rod field of a crankgen.SIMechanism against the range real connecting rods span (BANDS):
  Young's modulus from rubber to diamond, a density from balsa to osmium, a length from a
  millimetre to 20 m, an area and a second moment of area of such rods' sections;
- the rod's slenderness sqrt(I/A)/L (L, A and I in one system of units) and the end mass over the
  rod's mass (SLENDERNESS, MASS_RATIO);
- every speed against the rod's first bending frequency omega_b: a crank (or motor) speed more
  than SPEED_LIMIT times omega_b is no mechanism's.  Omega* = 1 is the crank turning at the rod's
  first pinned-pinned bending frequency; the theory's range (moderate deflections) ends near
  Omega* = 1-2 for the paper's mechanisms and, measured, by Omega* = 20 even for a crank of 1 % of
  the rod's length without a slider (|v|/L = 0.105 at eps = 0.01): at 50 every mechanism tried is
  beyond it.  The check applies to the dimensionless Case too (check_speeds), where a crank speed
  in rad/s passed as Omega* is the likely mistake.

A refusal is one line: the field, its value, the range, and the unit mistake that would bring it
into the range ("E = 210 Pa ...: in GPa? 210 GPa = 2.1e+11 Pa").  A value meant as given (a
rubber rod, a hair-thin wire) passes when its check is named in the SIMechanism's `unchecked`
(e.g. unchecked=("E",)); the speed limit has no such switch.
"""

import math
from dataclasses import dataclass

from ..errors import ParameterError

SPEED_LIMIT = 50.0           # Omega*: a speed more than this times omega_b is no mechanism's
SLENDERNESS = (1e-4, 0.3)    # sqrt(I/A)/L of a rod: a fishing line to a block
MASS_RATIO = 1e3             # end mass over the rod's mass rho A L


@dataclass(frozen=True)
class Band:
    """The range of a quantity over real connecting rods: low, high (SI), a typical value (the
    centre the likely mistake is measured from), what it spans in words, and the units a mistaken
    number may be in: ((name, SI value of one of them), ...)."""

    low: float
    high: float
    typical: float
    what: str
    mistakes: tuple


BANDS = {
    "E": Band(1e6, 1.5e12, 1e11, "the Young's moduli of solids (rubber, about 1e6 Pa, to diamond, 1.2e12 Pa)",
              (("GPa", 1e9), ("MPa (N/mm^2)", 1e6), ("kPa", 1e3))),
    "rho": Band(50.0, 25000.0, 5000.0, "the densities of solids (balsa, about 100 kg/m^3, to osmium, 22600 kg/m^3)",
                (("g/cm^3", 1e3), ("g/mm^3", 1e6), ("kg/mm^3", 1e9), ("t/mm^3", 1e12))),
    "L": Band(1e-3, 20.0, 0.3, "the lengths of connecting rods (1 mm to 20 m)", (("mm", 1e-3), ("cm", 1e-2))),
    "A": Band(1e-10, 1.0, 1e-4, "the section areas of rods (1e-10 m^2, a 10 micrometre wire, to 1 m^2)",
              (("mm^2", 1e-6), ("cm^2", 1e-4))),
    "I": Band(1e-22, 1.0, 1e-9, "the second moments of area of rods' sections (1e-22 m^4, a 10 micrometre wire, to 1 m^4)",
              (("mm^4", 1e-12), ("cm^4", 1e-8))),
}
CHECKS = tuple(BANDS) + ("slenderness", "slider_mass")     # what `unchecked` may name


def _text(x):
    return f"{x:.4g}"


def _likely(band, value):
    """(unit name, value in SI) of the mistaken unit that brings `value` nearest the band's typical
    value inside the band, or None."""
    best = None
    for name, factor in band.mistakes:
        si = value * factor
        if band.low <= si <= band.high:
            distance = abs(math.log10(si / band.typical))
            if best is None or distance < best[0]:
                best = (distance, name, si)
    return None if best is None else best[1:]


def _hatch(name, value=""):
    return f"or unchecked=[\"{name}\"] if {value or 'it'} is meant"


def check_rod(L, E, rho, A, I, unchecked=()):
    """Refuse (ParameterError, one line) a rod field outside its band (BANDS), then a slenderness
    sqrt(I/A)/L outside SLENDERNESS, naming the likely unit mistake.  Fields named in `unchecked`
    are not checked."""
    values = dict(L=L, E=E, rho=rho, A=A, I=I)
    units = {"L": "m", "E": "Pa", "rho": "kg/m^3", "A": "m^2", "I": "m^4"}
    for name, band in BANDS.items():
        value = values[name]
        if name in unchecked or band.low <= value <= band.high:
            continue
        likely = _likely(band, value)
        hint = (f": in {likely[0]}? {_text(value)} {likely[0]} = {likely[1]:.4g} {units[name]}" if likely else "")
        raise ParameterError(f"SIMechanism: {name} = {_text(value)} {units[name]} is outside {band.what}{hint}; "
                             f"give {name} in {units[name]} ({_hatch(name, f'{_text(value)} {units[name]}')})")
    if "slenderness" in unchecked:
        return
    r = math.sqrt(I / A)
    eps = r / L
    low, high = SLENDERNESS
    if low <= eps <= high:
        return
    # the mistakes that change the slenderness: lengths of the section in mm or cm, or L in mm
    fixes = (("A in mm^2 and I in mm^4", 1e-3), ("I in mm^4", 1e-6), ("A in cm^2 and I in cm^4", 1e-2),
             ("L in mm", 1e3), ("L in cm", 1e2))
    likely = sorted((abs(math.log10(eps * f / 0.01)), what) for what, f in fixes if low <= eps * f <= high)
    hint = (": " + ", or ".join(what for _, what in likely) + "?") if likely else ""
    raise ParameterError(f"SIMechanism: the rod's slenderness sqrt(I/A)/L = {eps:.3g} (radius of gyration "
                         f"sqrt(I/A) = {r:.4g} m, L = {_text(L)} m) is no rod's ({low:g} to {high:g}){hint} "
                         f"give L in m, A in m^2 and I in m^4 ({_hatch('slenderness')})")


def check_mass(slider_mass, rod_mass, unchecked=()):
    """Refuse an end mass more than MASS_RATIO times the rod's (a mass in grams, likely)."""
    if "slider_mass" in unchecked or slider_mass is None or rod_mass <= 0:
        return
    ratio = slider_mass / rod_mass
    if ratio <= MASS_RATIO:
        return
    grams = (f": in g? {_text(slider_mass)} g = {slider_mass / 1e3:.4g} kg"
             if slider_mass / 1e3 / rod_mass <= MASS_RATIO else "")
    raise ParameterError(f"SIMechanism: slider_mass = {_text(slider_mass)} kg is {ratio:.3g} times the rod's "
                         f"mass (rho A L = {rod_mass:.4g} kg), more than {MASS_RATIO:g} times{grams}; give it "
                         f"in kg ({_hatch('slider_mass')})")


def check_si_speed(field, value, omega_b):
    """Refuse an SI speed (rad/s) more than SPEED_LIMIT times the rod's first bending frequency."""
    if value is None or omega_b <= 0 or abs(value) <= SPEED_LIMIT * omega_b:
        return
    raise ParameterError(
        f"SIMechanism: {field} = {_text(value)} rad/s is {abs(value) / omega_b:.4g} times the rod's first "
        f"bending frequency omega_b = {omega_b:.4g} rad/s (from L, E, rho, A and I): no mechanism runs "
        f"beyond {SPEED_LIMIT:g} times it; are the rod's fields in SI (L in m, E in Pa, rho in kg/m^3, A in "
        f"m^2, I in m^4) and the speed in rad/s ({field}_rpm takes rpm)?")


def check_speeds(values):
    """Refuse (ParameterError) a dimensionless speed (a parameter in units of omega_b: the crank
    speed Omega*, a run-up's start speed, a motor's speeds) above SPEED_LIMIT: a speed in rad/s or
    rpm given where Omega* is meant, likely."""
    from . import schema
    for name, p in schema.PARAMETERS.items():
        value = values.get(name)
        if p.units != "omega_b" or p.kind != "real" or value is None or abs(value) <= SPEED_LIMIT:
            continue
        raise ParameterError(
            f"{p.label} = {value:g} is a speed in units of the rod's first bending frequency omega_b "
            f"(1 is that resonance): no mechanism runs beyond {SPEED_LIMIT:g}; are your inputs in SI? A "
            f"speed in rad/s or rpm goes in a crankgen.SIMechanism ({p.si or p.name} or "
            f"{p.si or p.name}_rpm) with units='si' (--si FILE, --rpm on the command line)")
