"""Curve: a curve of fold, period-doubling or Neimark-Sacker points in two parameters, with its
codimension-two points; CSV and JSON (read back by Curve.from_json)."""

import csv
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...declaration import schema
from ...errors import ParameterError
from ...results.io import atomic_file, read_regular
from .codim2 import CODIM2
from .diagram_files import cell, jsonable

FORMAT = "crankgen-curve-1"
LABELS = {"fold": "F", "period-doubling": "PD", "neimark-sacker": "NS"}


def _complex_list(a):
    a = np.asarray(a, dtype=complex)
    return [[float(z.real), float(z.imag)] for z in a.ravel()]


def _complex_array(rows, shape):
    a = np.array([complex(r, i) for r, i in rows], dtype=complex)
    return a.reshape(shape)


def _floats(a):
    return [None if not math.isfinite(float(v)) else float(v) for v in np.asarray(a, dtype=float).ravel()]


def _array(values):
    return np.array([math.nan if v is None else v for v in values], dtype=float)


@dataclass
class Codim2Point:
    """A codimension-two point on a curve: kind ("cusp", "1:2 resonance", ...), its short label
    (CP, R2, ...), both parameters by name, the orbit's amplitude, every multiplier (of P^period,
    by decreasing modulus), the state, where it lies on the curve (index) and on which kind of
    curve (curve_kind), its period."""

    kind: str
    parameters: dict
    amplitude: float
    multipliers: np.ndarray = field(repr=False)
    state: np.ndarray = field(repr=False)
    index: int = 0
    curve_kind: str = ""
    period: int = 1

    @property
    def label(self):
        return CODIM2[self.kind][0]

    @property
    def description(self):
        return CODIM2[self.kind][1]

    def __getitem__(self, name):
        return self.parameters[name]


@dataclass
class Curve:
    """Points of one kind (kind: "fold", "period-doubling", "neimark-sacker") of the orbits of
    period `period`, continued in two parameters (names).  Arrays along the curve by name:
    curve[names[0]], curve[names[1]], curve["amplitude"] (the orbit's max |observable|; the
    mechanism: max |v*(1/2)|), curve["theta"] (Neimark-Sacker: the angle of the critical pair),
    curve["critical"] (the critical multiplier, complex), curve["deflection_over_L"] (the
    mechanism: eps times the amplitude); multipliers (points, m) complex by decreasing modulus;
    states (points, dim); codim2: the Codim2Points met; stop_reasons: why each end ends (the end
    of lower then of higher second parameter at the start); info: the model and settings."""

    kind: str
    period: int
    names: tuple
    values: dict                        # name -> (points,) float arrays
    multipliers: np.ndarray = field(repr=False)
    states: np.ndarray = field(repr=False)
    codim2: list = field(default_factory=list)
    stop_reasons: tuple = ()
    info: dict = field(default_factory=dict)

    def __len__(self):
        return len(self.values[self.names[0]])

    def __getitem__(self, name):
        if name in self.values:
            return self.values[name]
        if name == "critical":
            return self._critical()
        if name == "deflection_over_L":         # v* is in units of r: the slenderness gives it in L
            r = schema.UNIT_PARAMETERS["r"]
            eps = self.values[r] if r in self.values else self.info.get(r)
            if eps is None:
                raise KeyError(f"deflection_over_L needs the mechanism's {r} (this curve has none)")
            return np.abs(np.asarray(eps, dtype=float) * self.values["amplitude"])
        raise KeyError(f"{name!r}: a curve has {', '.join(list(self.values) + ['critical'])}")

    def _critical(self):
        mu = self.multipliers
        if self.kind == "fold":
            target = np.ones(len(self))
        elif self.kind == "period-doubling":
            target = -np.ones(len(self))
        else:
            target = np.exp(1j * self.values["theta"])
        k = np.argmin(np.abs(mu - target[:, None]), axis=1)
        return mu[np.arange(len(self)), k]

    @property
    def label(self):
        return f"{LABELS[self.kind]}{self.period}"

    def describe(self):
        """One line: what the curve is and where it runs."""
        a, b = self.names
        return (f"{self.kind} curve of period-{self.period} orbits, {len(self)} points, {a} "
                f"{np.nanmin(self[a]):.4g}..{np.nanmax(self[a]):.4g}, {b} {np.nanmin(self[b]):.4g}.."
                f"{np.nanmax(self[b]):.4g}" + ("; " + ", ".join(
                    f"{p.label} at {a} = {p[a]:.5g}, {b} = {p[b]:.5g}" for p in self.codim2)
                    if self.codim2 else ""))

    # -- files ------------------------------------------------------------------------------------
    def rows(self, curve=None):
        """One dict per point (for CSV): the curve index (when given), kind, period, point, both
        parameters, amplitude, theta, the critical multiplier, max |multiplier| of the others, and
        for the mechanism deflection_over_L and beyond_theory."""
        from ..theory import beyond
        a, b = self.names
        crit = self["critical"]
        others = np.abs(self.multipliers).copy()
        if others.shape[1]:
            k = np.argmin(np.abs(self.multipliers - crit[:, None]), axis=1)
            others[np.arange(len(self)), k] = -np.inf
            if self.kind == "neimark-sacker":
                k2 = np.argmin(np.abs(self.multipliers - np.conj(crit)[:, None]), axis=1)
                others[np.arange(len(self)), k2] = -np.inf
        largest = others.max(axis=1) if others.shape[1] else np.full(len(self), np.nan)
        try:
            defl = self["deflection_over_L"]
        except KeyError:
            defl = None
        out = []
        for i in range(len(self)):
            row = {} if curve is None else {"curve": curve}
            row.update(kind=self.kind, period=self.period, point=i, **{a: cell(self[a][i]), b: cell(self[b][i])},
                       amplitude=cell(self["amplitude"][i]),
                       theta=cell(self.values["theta"][i]) if "theta" in self.values else "",
                       critical_re=cell(crit[i].real), critical_im=cell(crit[i].imag),
                       max_abs_other_multiplier=cell(largest[i]) if math.isfinite(largest[i]) else "")
            if defl is not None:
                row.update(deflection_over_L=cell(defl[i]), beyond_theory=beyond(deflection=float(defl[i])))
            out.append(row)
        return out

    def codim2_rows(self, curve=None):
        a, b = self.names
        out = []
        for p in self.codim2:
            row = {} if curve is None else {"curve": curve}
            row.update(kind=p.kind, label=p.label, curve_kind=p.curve_kind, period=p.period, point=p.index,
                       **{a: cell(p[a]), b: cell(p[b])}, amplitude=cell(p.amplitude),
                       multipliers=" ".join(f"{z.real:.10g}{z.imag:+.10g}j" for z in p.multipliers[:6]),
                       description=p.description)
            out.append(row)
        return out

    def to_csv(self, folder):
        """curve.csv (one row per point), codim2_points.csv (kind, label, both parameters,
        amplitude, the leading multipliers) and curve_multipliers.csv (every multiplier of every
        point, long format) in folder; returns the paths."""
        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        paths = [folder / "curve.csv", folder / "codim2_points.csv", folder / "curve_multipliers.csv"]
        write_rows(paths[0], self.rows())
        write_rows(paths[1], self.codim2_rows(), ["kind", "label", "curve_kind", "period", "point",
                                                  *self.names, "amplitude", "multipliers", "description"])
        a, b = self.names
        write_rows(paths[2], [dict(point=i, **{a: cell(self[a][i]), b: cell(self[b][i])}, index=j,
                                   re=cell(m.real), im=cell(m.imag), abs=cell(abs(m)))
                              for i in range(len(self)) for j, m in enumerate(self.multipliers[i])],
                   ["point", a, b, "index", "re", "im", "abs"])
        return paths

    def as_dict(self):
        return dict(kind=self.kind, period=int(self.period), names=list(self.names),
                    values={k: _floats(v) for k, v in self.values.items()},
                    multipliers=_complex_list(self.multipliers), multipliers_shape=list(self.multipliers.shape),
                    states=_floats(self.states), states_shape=list(self.states.shape),
                    codim2=[dict(kind=p.kind, parameters={k: float(v) for k, v in p.parameters.items()},
                                 amplitude=float(p.amplitude), multipliers=_complex_list(p.multipliers),
                                 state=_floats(p.state), index=int(p.index), curve_kind=p.curve_kind,
                                 period=int(p.period)) for p in self.codim2],
                    stop_reasons=list(self.stop_reasons), info=jsonable(self.info))

    @classmethod
    def from_dict(cls, d):
        m_shape = tuple(d["multipliers_shape"])
        return cls(kind=d["kind"], period=int(d["period"]), names=tuple(d["names"]),
                   values={k: _array(v) for k, v in d["values"].items()},
                   multipliers=_complex_array(d["multipliers"], m_shape),
                   states=_array(d["states"]).reshape(tuple(d["states_shape"])),
                   codim2=[Codim2Point(p["kind"], dict(p["parameters"]), p["amplitude"],
                                       _complex_array(p["multipliers"], (len(p["multipliers"]),)),
                                       _array(p["state"]), p["index"], p["curve_kind"], p["period"])
                           for p in d["codim2"]],
                   stop_reasons=tuple(d["stop_reasons"]), info=dict(d["info"]))

    def to_json(self, path):
        """The whole curve (every point's parameters, amplitude, multipliers and state, the
        codimension-two points, the stop reasons and the model) as JSON; Curve.from_json reads it."""
        with atomic_file(path) as fh:
            json.dump(dict(format=FORMAT, curve=self.as_dict()), fh)
        return Path(path)

    @classmethod
    def from_json(cls, path):
        d = json.loads(read_regular(path))
        if d.get("format") != FORMAT:
            raise ParameterError(f"{path} is not a crankgen curve file (format {d.get('format')!r})")
        return cls.from_dict(d["curve"])


def write_rows(path, rows, columns=None):
    """A CSV of dict rows (columns: their keys in order, or `columns`)."""
    if columns is None:
        columns = list(rows[0]) if rows else []
        for r in rows:
            columns += [k for k in r if k not in columns]
    with atomic_file(path) as fh:
        w = csv.DictWriter(fh, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    return Path(path)


def make_curve(defining, backward, forward, found, reasons, info):
    """The Curve of a continuation in both directions: backward and forward are the points of the
    two runs (both starting at the start point), found the (name, CurvePoint) codimension-two
    points of both."""
    pts = list(reversed(backward)) + list(forward[1:])
    d = defining
    names = d.map.names
    ps = np.array([d.p(pt.Z) for pt in pts])
    values = {names[0]: ps[:, 0], names[1]: ps[:, 1],
              "amplitude": np.array([pt.amplitude for pt in pts], dtype=float)}
    if d.complex:
        values["theta"] = np.array([pt.Z[-1] for pt in pts], dtype=float)
    mus = [np.asarray(pt.ev.mu) for pt in pts]
    m = max(len(mu) for mu in mus)
    multipliers = np.full((len(pts), m), np.nan + 0j)
    for i, mu in enumerate(mus):
        multipliers[i, :len(mu)] = mu
    states = np.array([d.map.physical(d.x(pt.Z)) for pt in pts])
    index = {id(pt): i for i, pt in enumerate(pts)}
    codim2 = []
    for name, sp in found:
        p = d.p(sp.Z)
        codim2.append(Codim2Point(name, {names[0]: float(p[0]), names[1]: float(p[1])},
                                  float(sp.amplitude), np.asarray(sp.ev.mu), d.map.physical(d.x(sp.Z)),
                                  index.get(id(sp), -1), d.kind, d.period))
    codim2.sort(key=lambda c: c.index)
    return Curve(d.kind, d.period, tuple(names), values, multipliers, states, codim2, tuple(reasons), info)
