"""Stresses at the rod's outer fibres, and the peak loads, of a run or a steady orbit.

From the declared section forces of a result that stores its states (a simulation, a steady
state): the axial force N (output axial_force, N* = N L^2 / EI) and the bending moment M
(bending_moment, M* = M L / EI = v_xx), the normal stress of a fibre at distance y from the
neutral axis (positive towards the rod's e_j) is

    sigma = N / A - M y / I        (eq. 1 times E: the membrane strain less y v_xx)

at the two outer fibres of a crankgen.sections.Section, y = +c_top and y = -c_bottom.  In SI (a
run made in SI, or `si=` the crankgen.SIMechanism of the run) sigma is in Pa, x in m, t in s;
in crankgen's units sigma is in units of E (sigma / E, the fibre's strain: N* eps^2 - M* eps y/r),
x is x* and t is t*.

The stress is evaluated at the nodes and the element midpoints (u_x is constant and v_xx linear
in an element: at an interior node the mean of the two elements' values, as every field output).
`maximum` and `minimum` give the largest and smallest stress with where (x, fibre) and when (t,
theta); `ranges()` the stress range of every revolution (max - min over the revolution at the
point where it is largest), what fatigue needs; `range` the largest of the complete revolutions.
"""

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..declaration.si import SIMechanism
from ..declaration.sections import Section
from ..declaration.si import scales_of
from ..declaration.units import Scales, in_L
from ..declaration.ingredients import available

MATCH = 1e-3          # relative agreement asked of a section and the mechanism's rod (0.1 %)


@dataclass(frozen=True)
class StressPoint:
    """A stress and where and when: value (Pa or units of E), fibre ("top": towards e_j, or
    "bottom"), x (m or x*), t (s or t*), theta (crank angle, rad), step (index in the result)."""

    value: float
    fibre: str
    x: float
    t: float
    theta: float
    step: int


@dataclass(frozen=True)
class RevolutionRange:
    """The stress range of one revolution: max - min over it at the point (x, fibre) where it is
    largest; complete: the revolution was run to its end."""

    revolution: int
    range: float
    x: float
    fibre: str
    complete: bool


@dataclass(frozen=True)
class StressHistory:
    """Outer-fibre stresses of a result: top and bottom (steps, points) at positions x (points,),
    over t and theta (steps,), in `units` ("Pa" or "E": in units of Young's modulus)."""

    units: str
    section: Section
    x: np.ndarray
    t: np.ndarray
    theta: np.ndarray
    top: np.ndarray = field(repr=False)
    bottom: np.ndarray = field(repr=False)

    def _fibres(self):
        return (("top", self.top), ("bottom", self.bottom))

    def _point(self, pick):
        best = None
        for name, values in self._fibres():
            k, j = np.unravel_index(pick(values), values.shape)
            if best is None or pick(np.array([best.value, values[k, j]])) == 1:
                best = StressPoint(float(values[k, j]), name, float(self.x[j]), float(self.t[k]),
                                   float(self.theta[k]), int(k))
        return best

    @property
    def maximum(self):
        """The largest stress (tension) and where and when."""
        return self._point(np.argmax)

    @property
    def minimum(self):
        """The smallest stress (compression) and where and when."""
        return self._point(np.argmin)

    @property
    def largest(self):
        """The stress of largest magnitude."""
        hi, lo = self.maximum, self.minimum
        return hi if abs(hi.value) >= abs(lo.value) else lo

    def ranges(self):
        """The stress range of each revolution of the crank (from the first step's angle), a
        revolution's end step shared with the next."""
        turns = (self.theta - self.theta[0]) / (2 * math.pi)
        out = []
        for k in range(int(math.floor(turns[-1] + 1e-9)) + (0 if _whole(turns[-1]) else 1)):
            inside = (turns >= k - 1e-9) & (turns <= k + 1 + 1e-9)
            if np.count_nonzero(inside) < 2:
                continue
            best = None
            for name, values in self._fibres():
                span = values[inside].max(axis=0) - values[inside].min(axis=0)
                j = int(np.argmax(span))
                if best is None or span[j] > best[0]:
                    best = (float(span[j]), float(self.x[j]), name)
            out.append(RevolutionRange(k + 1, best[0], best[1], best[2], bool(turns[-1] >= k + 1 - 1e-9)))
        return out

    @property
    def range(self):
        """The largest stress range of a complete revolution (None: no complete revolution)."""
        done = [r.range for r in self.ranges() if r.complete]
        return max(done) if done else None

    def summary(self):
        """One line: the largest tension and compression with where and when, and the range."""
        si = self.units == "Pa"

        def show(p):
            value = f"{p.value / 1e6:.4g} MPa" if si else f"{p.value:.4g} E"
            where = f"x = {p.x:.4g} m" if si else f"x* = {p.x:.4g}"
            when = f"t = {p.t:.4g} s" if si else f"t* = {p.t:.4g}"
            return f"{value} at {where}, {p.fibre} fibre, {when}, crank angle {crank_degrees(p.theta):.1f} deg"
        r = self.range
        span = ("" if r is None else
                f"; largest range per revolution {r / 1e6:.4g} MPa" if si else f"; largest range per revolution {r:.4g} E")
        return f"stress: max {show(self.maximum)}; min {show(self.minimum)}{span}"


def crank_degrees(theta):
    """A crank angle (rad, unwrapped) in degrees within [0, 360), rounded to 1e-9 degree first (so
    that a full turn reads 0, not 360)."""
    return round(math.degrees(theta), 9) % 360.0


def _whole(turns):
    return abs(turns - round(turns)) < 1e-9


def _scales(result, section, si):
    """The SI scales of a result (None: crankgen's units), the section checked against the rod."""
    return check_section(section, si, getattr(result, "scales", None))


def check_section(section, si=None, scales=None):
    """The SI scales to compute stresses with (None: crankgen's units): those of the
    crankgen.SIMechanism si (whose A and I the section must have, within 0.1 %), else `scales`;
    the section's radius of gyration must be the rod's."""
    if si is not None:
        if not isinstance(si, SIMechanism):
            raise ParameterError(f"si must be a crankgen.SIMechanism, got {type(si).__name__}")
        for name in ("A", "I"):
            if abs(getattr(section, name) / getattr(si, name) - 1) > MATCH:
                raise ParameterError(f"the section's {name} = {getattr(section, name):.6g} differs from the "
                                     f"rod's ({name} = {getattr(si, name):.6g} in the SIMechanism) by more "
                                     f"than {MATCH:.1%}")
        scales = scales_of(si)
    if scales is not None:
        r = scales.eps * scales.L
        if abs(section.radius_of_gyration / r - 1) > MATCH:
            raise ParameterError(f"the section's radius of gyration sqrt(I/A) = "
                                 f"{section.radius_of_gyration:.6g} m differs from the rod's ({r:.6g} m) by "
                                 f"more than {MATCH:.1%}")
    return scales


def stress(result, section, si=None, x=None, scales=None):
    """The outer-fibre stresses of a result that stores its states (a SimulationResult, a
    SteadyState), for the rod's crankgen.sections.Section (module docstring).  si: the
    crankgen.SIMechanism of a run made in crankgen's units from its .mechanism and .omega
    (stresses in Pa); a run made in SI needs none.  x: the positions (x* in [0, 1], or m in SI;
    default the nodes and the element midpoints).  scales: the crankgen.units.Scales to give them in
    SI by (a result's SI view's), in place of si.  Returns a StressHistory."""
    if not isinstance(section, Section):
        raise ParameterError(f"section must be a crankgen.sections.Section (rectangle, circle, tube or "
                             f"Section(A=, I=, c_top=, c_bottom=)), got {type(section).__name__}")
    if getattr(result, "states", None) is None:
        raise ParameterError("stresses need a result that stores its states (simulate with history, "
                             "steady_state with an orbit)")
    scales = check_section(section, None, scales) if scales is not None and si is None else \
        _scales(result, section, si)
    n = result.case.n_elements
    length = 1.0 if scales is None else scales.L
    xs = (np.arange(2 * n + 1) / (2 * n) if x is None
          else np.atleast_1d(np.asarray(x, dtype=float)) / length)
    N = np.asarray(result.quantity("axial_force", xs), dtype=float).reshape(len(result.t), -1)
    M = np.asarray(result.quantity("bending_moment", xs), dtype=float).reshape(len(result.t), -1)
    eps = in_L("r", result.case.parameters())           # the slenderness r/L: r in units of L
    out = {}
    for name, y in section.fibres.items():
        if scales is None:                                 # sigma / E = N* eps^2 - M* eps y / r
            out[name] = N * eps ** 2 - M * eps * y / section.radius_of_gyration
        else:
            EI = scales.base["EI"]
            out[name] = N * EI / scales.L ** 2 / section.A - M * EI / scales.L * y / section.I
    t = np.asarray(result.t, dtype=float) * (1.0 if scales is None else scales.factor("1/omega_b"))
    return StressHistory("E" if scales is None else "Pa", section, xs * length, t,
                         np.asarray(result.theta, dtype=float), out["top"], out["bottom"])


@dataclass(frozen=True)
class PeakLoad:
    """The largest magnitude of a load over a result: value (its magnitude; for the torque signed),
    units, when (t, theta, step) and, for a force, its direction then (degrees from the inertial X
    axis, counter-clockwise; None for the torque)."""

    name: str
    value: float
    units: str
    t: float
    theta: float
    step: int
    direction: Optional[float] = None


def peak_loads(result, scales: Optional[Scales] = None):
    """The driving torque of largest magnitude, and the largest joint forces |F| over a result (the
    pins at A and B, the guide or the rocker at its tip, a rocker's ground pivot, and the crank's
    bearing when the crank has a mass), with when:
    crankgen's units, or SI with `scales`."""
    from ..declaration import schema

    def factor(units):                    # a declared unit in SI (as the result's SI view converts it)
        return 1.0 if scales is None else scales.factor(units)
    t = np.asarray(result.t, dtype=float) * factor("1/omega_b")
    out = []
    here = result.case.guide_record.name

    def declared(*choices):
        """(name, output) of the first choice whose output the case's guide has."""
        return next((name, out) for name, out in choices if here in schema.OUTPUTS[out + "_x"].guides)
    at_b = declared(("pin force at B (rod on slider)", "rod_on_slider"), ("pin force at B (rod on rocker tip)",
                                                                        "rod_on_tip"))
    guide = declared(("guide force (on slider)", "guide_on_slider"), ("rocker force (on its tip)", "rocker_on_tip"))
    loads = [("torque", ("torque",)), ("pin force at A (crank on rod)", ("crank_on_rod_x", "crank_on_rod_y")),
             (at_b[0], (at_b[1] + "_x", at_b[1] + "_y")), (guide[0], (guide[1] + "_x", guide[1] + "_y"))]
    if here in schema.OUTPUTS["ground_on_rocker_x"].guides:
        pivot = next(p for p in ("ground_on_rocker", "ground_on_flexible_rocker") if available(p + "_x", result.case))
        loads.append(("pivot force (ground on rocker)", (pivot + "_x", pivot + "_y")))
    bearing = [np.asarray(result.quantity(p + "_" + x)) for p in ("ground_on_crank", "crank_on_rod") for x in "xy"]
    if not (np.array_equal(bearing[0], bearing[2]) and np.array_equal(bearing[1], bearing[3])):
        # a crank with its own mass: the main bearing no longer carries just the pin's force
        loads.append(("main bearing force (ground on crank)", ("ground_on_crank_x", "ground_on_crank_y")))
    for name, parts in loads:
        if not available(parts[0], result.case):
            continue                      # a force a flexible rocker's joints do not give (yet)
        values = [np.asarray(result.quantity(p), dtype=float) * factor(schema.OUTPUTS[p].units) for p in parts]
        magnitude = np.sqrt(sum(v ** 2 for v in values))
        k = int(np.argmax(magnitude))
        value = float(values[0][k]) if len(parts) == 1 else float(magnitude[k])
        # the direction (+ 0.0: a Y component of -0 reads 180 degrees, not -180)
        direction = None if len(parts) == 1 else math.degrees(math.atan2(values[1][k] + 0.0, values[0][k]))
        declared = schema.OUTPUTS[parts[0]].units
        units = declared if scales is None else scales.si_name(declared)
        out.append(PeakLoad(name, value, units, float(t[k]), float(result.theta[k]), k, direction))
    return out
