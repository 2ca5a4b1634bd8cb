"""Continuation and Poincare diagrams in SI: the parameter in its SI unit (read from its declared
units: a crank speed in rad/s, a four-bar's c and d in m, the damping in s, ...) and the amplitude
and section samples (v*(1/2), in units of the radius of gyration r) in m.

`DiagramSI(diagram, si_mechanism)` is what `diagram.si` (a diagram computed with units="si") and
`diagram.si_view(si_mechanism)` give: its branches and special points with SI numbers, `to_csv`
(the diagram's own files with the SI columns named with their units: crank_speed_rad_per_s,
amplitude_m, value_m, and the branch points' quantities: peak_torque_N_m, ..., peak_v_m,
peak_stress_Pa) and `plot` (mm).  continuation.json and states.csv stay in crankgen's units (the
diagram's own, read back by BifurcationDiagram.from_json).
"""

import csv
import math
import re
import textwrap
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ...declaration import schema
from ...errors import ParameterError
from ...results.exports import column
from ...declaration.units import Scales

AMPLITUDE_UNITS = schema.OUTPUTS["v_mid"].units           # amplitudes and samples are of v*(1/2)


class DiagramSI:
    """A BifurcationDiagram or a PoincareDiagram in SI (module docstring)."""

    def __init__(self, diagram, si_mechanism):
        self.diagram, self.scales = diagram, si_mechanism.scales
        self.modulus = float(si_mechanism.E)              # Pa: a stress in units of E
        for unit, name in schema.UNIT_PARAMETERS.items():  # the diagram must be of this rod
            value = diagram.info.get(name)
            own = self.scales.base[unit] / self.scales.L
            if diagram.parameter_name != name and value is not None and abs(float(value) / own - 1) > 1e-9:
                raise ParameterError(f"the diagram's {schema.PARAMETERS[name].label} = {float(value):g} is not the "
                                     f"rod's ({own:g}, from its L, A and I): its SI form needs its own SIMechanism")
        self.parameter_name = diagram.parameter_name
        p = schema.PARAMETERS[self.parameter_name]
        self.units = p.units
        self.parameter_column = column(p.si or p.name, p.units, True)
        self.parameter_unit = Scales.si_name(p.units)

    def parameter(self, x):
        """Values of the parameter in SI."""
        return np.asarray(x, dtype=float) * self.scales.factor(self.units)

    def amplitude(self, x):
        """Amplitudes (v*(1/2)) in m."""
        return np.asarray(x, dtype=float) * self.scales.factor(AMPLITUDE_UNITS)

    def text(self, text):
        """A branch's origin or stop reason with every value of the parameter in SI ("reached
        omega = 1.175" -> "reached crank_speed = 1500 rad/s", "period-doubling of branch 0 at
        omega = 0.93" -> "... at crank_speed = 1193 rad/s")."""
        name = schema.PARAMETERS[self.parameter_name].si or self.parameter_name
        unit = "" if self.parameter_unit == "1" else f" {self.parameter_unit}"

        ends = [float(e) for e in (self.diagram.info.get("start"), self.diagram.info.get("stop")) if e is not None]

        def si(match):                        # as many significant digits as the value printed
            number = match.group(1)
            digits = len(re.split("[eE]", number)[0].lstrip("+-").replace(".", "").lstrip("0")) or 1
            value = float(number)
            for end in ends:                  # an end of the range, rounded when printed: the end
                if abs(value - end) <= 5 * 10.0 ** -digits * abs(end):
                    return f"{name} = {float(self.parameter(end)):.7g}{unit}"
            si = float(self.parameter(value))
            whole = int(math.floor(math.log10(abs(si)))) + 1 if si and math.isfinite(si) else 1
            return f"{name} = {si:.{max(digits, whole)}g}{unit}"        # 1256, not 1.26e+03
        return re.sub(rf"\b{re.escape(self.parameter_name)} = ([-+0-9.eE]+[0-9])", si, text)


    @property
    def branches(self):
        """Each branch: period, parameter (SI), amplitude (m), stable, origin and stop_reason (values of the parameter in SI)."""
        return [SimpleNamespace(period=b.period, parameter=self.parameter(b.parameter),
                                amplitude=self.amplitude(b.amplitude), stable=np.asarray(b.stable, dtype=bool),
                                origin=self.text(b.origin), stop_reason=self.text(b.stop_reason))
                for b in getattr(self.diagram, "branches", [])]

    @property
    def special_points(self):
        """Each special point: kind, parameter (SI), amplitude (m), period, multiplier."""
        return [SimpleNamespace(kind=s.kind, parameter=float(self.parameter(s.parameter)),
                                amplitude=float(self.amplitude(s.amplitude)), period=s.period,
                                multiplier=s.multiplier) for s in getattr(self.diagram, "special_points", [])]

    @property
    def points(self):
        """Each point of a Poincare diagram: direction, parameter (SI), classification, samples and
        amplitude (m)."""
        return [SimpleNamespace(direction=q.direction, parameter=float(self.parameter(q.parameter)),
                                classification=q.classification, period=q.period,
                                samples=self.amplitude(q.samples), message=q.message,
                                amplitude=None if q.amplitude is None else float(self.amplitude(q.amplitude)))
                for q in getattr(self.diagram, "points", [])]

    def _columns(self):
        """{column: (SI column, factor)} of the diagram's CSV files."""
        amplitude = self.scales.factor(AMPLITUDE_UNITS)
        out = {self.parameter_name: (self.parameter_column, self.scales.factor(self.units)),
               "amplitude": (column("amplitude", AMPLITUDE_UNITS, True), amplitude),
               "value": (column("value", AMPLITUDE_UNITS, True), amplitude)}
        for br in getattr(self.diagram, "branches", []):            # quantities with declared units
            for name, units in (getattr(br, "quantity_units", None) or {}).items():
                if units and name not in out:
                    out[name] = self._quantity(name, units)
        return out

    def _quantity(self, name, units):
        """(SI column, factor) of a branch quantity in its units ("r (v* = v/r)": r; "E": a
        stress in units of Young's modulus)."""
        units = units.split(" (")[0]
        if units == "E":
            return f"{name}_Pa", self.modulus
        if units == "Pa":
            return f"{name}_Pa", 1.0
        return column(name, units, True), self.scales.factor(units)

    def to_csv(self, folder):
        """The diagram's CSV files (its to_csv) with every column that has a unit in SI, named with
        it, and the branches' stop reasons in SI; returns the paths."""
        from ...results.io import atomic_file
        paths = self.diagram.to_csv(folder)
        convert = self._columns()
        for path in paths:
            with open(path, newline="") as fh:
                rows = list(csv.reader(fh))
            if not rows:
                continue
            head = rows[0]
            where = [(k, convert[c][1]) for k, c in enumerate(head) if c in convert]
            rows[0] = [convert[c][0] if c in convert else c for c in head]
            reasons = [k for k, c in enumerate(head) if c in ("stop_reason", "origin")]
            for row in rows[1:]:
                for k, f in where:
                    if row[k] != "":
                        row[k] = repr(float(row[k]) * f)
                for k in reasons:
                    row[k] = self.text(row[k])
            with atomic_file(path) as fh:
                csv.writer(fh).writerows(rows)
        return paths

    def plot(self, path, title=None, diagram=None, sweep=None):
        """The diagram's figure in SI: the parameter in its SI unit, amplitudes and samples in mm
        (the diagram's own plot, its amplitude's unit in L being then a millimetre: the range
        beyond the theory, |v|/L > 0.1, is shaded where it is); diagram: a continuation drawn over
        a Poincare diagram, sweep: a Poincare diagram drawn over a continuation (computed on the
        same SI mechanism)."""
        from ...results.io import output_path
        path = output_path(path)
        mm = 1e3
        d = self.diagram
        unit = {schema.UNIT_PARAMETERS[AMPLITUDE_UNITS]: 1.0 / (mm * self.scales.L)}   # 1 mm in L
        xlabel = (f"{(schema.PARAMETERS[self.parameter_name].si or self.parameter_name).replace('_', ' ')} "
                  f"({self.parameter_unit})")
        if hasattr(d, "branches"):
            under = None if sweep is None else self._other(sweep)._converted(mm, unit)
            return self._converted(mm, unit).plot(path, title=title or _title(self, "continuation"), xlabel=xlabel,
                                                  ylabel="max |v(L/2)| over the orbit (mm)", sweep=under)
        over = None if diagram is None else self._other(diagram)._converted(mm, unit)
        return self._converted(mm, unit).plot(path, diagram=over, title=title or _title(self, "Poincare sweep"),
                                              xlabel=xlabel, ylabel="v(L/2) at theta = 0, once per revolution (mm)")

    def _other(self, diagram):
        """Another diagram of the same SI mechanism in SI."""
        other = DiagramSI.__new__(DiagramSI)
        other.__dict__.update(self.__dict__, diagram=diagram, parameter_name=diagram.parameter_name)
        return other

    def _converted(self, mm, unit):
        """The diagram with its numbers in SI (amplitudes in mm) and its amplitude's unit in L."""
        d = self.diagram
        info = dict(d.info, **unit)
        if hasattr(d, "branches"):
            return replace(d, info=info,
                           branches=[replace(b, parameter=self.parameter(b.parameter),
                                             amplitude=self.amplitude(b.amplitude) * mm,
                                             section=None if b.section is None else self.amplitude(b.section) * mm)
                                     for b in d.branches],
                           special_points=[replace(s, parameter=float(self.parameter(s.parameter)),
                                                   amplitude=float(self.amplitude(s.amplitude)) * mm)
                                           for s in d.special_points])
        return replace(d, info=info, points=[replace(q, parameter=float(self.parameter(q.parameter)),
                                                     samples=self.amplitude(q.samples) * mm,
                                                     amplitude=None if q.amplitude is None else
                                                     float(self.amplitude(q.amplitude)) * mm) for q in d.points])


def _title(view, what):
    """The title of a diagram in SI: what, the parameter and the model; the rod's scales and every
    fixed parameter in SI."""
    from ...plots.figures import listed
    from ...declaration.si import describe_si
    d, sc = view.diagram, view.scales
    info = d.info
    from ...plots.figures import model_parts
    parts = model_parts(info)
    name = (schema.PARAMETERS[d.parameter_name].si or d.parameter_name).replace("_", " ")
    rod = [f"L = {sc.L:g} m", f"omega_b = {sc.omega_b:.5g} rad/s", f"rho A = {sc.rhoA:.4g} kg/m",
           f"r = {sc.base['r']:.4g} m"]
    values = {k: v for k, v in info.items() if k in schema.PARAMETERS}
    return (f"{what} in {name} ({view.parameter_unit}): " + ", ".join(p for p in parts if p) + "\n"
            + listed(rod) + "\n" + textwrap.fill(listed(describe_si(values, sc, skip=(d.parameter_name,))), 90))


def si_of(diagram):
    """The SI view of a diagram computed with units="si"."""
    si = getattr(diagram, "si_mechanism", None)
    if si is None:
        raise ParameterError("this diagram was computed in crankgen's units: .si needs one made with units='si' "
                             "from a crankgen.SIMechanism; .si_view(si_mechanism) converts any")
    return DiagramSI(diagram, si)
