"""StabilityChart: the curves of a plane of two parameters, its regions named in words, the lines
of one-parameter continuations that name them; CSV and JSON (read back by StabilityChart.from_json)."""

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..bifurcation.curve import Curve, write_rows
from ..bifurcation.diagram_files import cell, jsonable
from ..bifurcation.diagram import BifurcationDiagram
from ...errors import ParameterError
from ...results.io import atomic_file, read_regular
from .regions import Raster

FORMAT = "crankgen-stability-chart-1"


@dataclass
class Region:
    """A piece of the plane between the curves: its verdict (key: ((period, count), ...) of the
    stable orbits; None when no line crosses it) in words, the cells of the lines that voted for it
    (votes: {words: cells}), the share of the majority (agreement), its area (share of the box) and
    where its name is written (x, y)."""

    index: int
    key: object
    words: str
    votes: dict
    agreement: float
    area: float
    x: float
    y: float
    room: float = 0.0            # cells from the label point to the piece's edge


@dataclass
class ChartLine:
    """A one-parameter continuation in x at y = level (diagram None: it failed, message says why)."""

    level: float
    diagram: object = None
    message: str = ""


@dataclass
class StabilityChart:
    """x, y: (name, lo, hi) of the axes; curves: the Curves of fold, period-doubling and
    Neimark-Sacker points in the box; lines: the continuations at fixed y; regions: the pieces of
    the plane with their verdicts; labels: (height, width) piece of each raster cell (0: a curve);
    deflection: (height, width) the stable orbits' largest deflection / L, interpolated between the
    lines (NaN: no stable orbit); notes: what failed or was skipped; info: the model."""

    x: tuple
    y: tuple
    curves: list
    lines: list
    regions: list
    labels: np.ndarray = field(repr=False)
    deflection: np.ndarray = field(repr=False)
    max_period: int = 2
    notes: list = field(default_factory=list)
    info: dict = field(default_factory=dict)

    @property
    def raster(self):
        h, w = self.labels.shape
        return Raster(self.x[1], self.x[2], self.y[1], self.y[2], w, h)

    @property
    def codim2(self):
        """Every codimension-two point of the curves, each once."""
        out = []
        for c in self.curves:
            for p in c.codim2:
                if not any(q.kind == p.kind and all(abs(q[n] - p[n]) <= 1e-6 * (abs(p[n]) + 1)
                                                    for n in (self.x[0], self.y[0])) for q in out):
                    out.append(p)
        return out

    def region_at(self, x, y):
        """The Region holding the point (x, y) (None on a curve or outside the box)."""
        r, c = self.raster.cell(x, y)
        r, c = int(np.floor(r)), int(np.floor(c))
        if not (0 <= r < self.labels.shape[0] and 0 <= c < self.labels.shape[1]) or self.labels[r, c] == 0:
            return None
        return next((g for g in self.regions if g.index == self.labels[r, c]), None)

    def summary(self):
        """Lines of text: the curves, the codimension-two points, the regions."""
        xn, yn = self.x[0], self.y[0]
        out = [f"stability chart in ({xn}, {yn}): {xn} {self.x[1]:g}..{self.x[2]:g}, {yn} "
               f"{self.y[1]:g}..{self.y[2]:g}; {len(self.lines)} lines of constant {yn}, "
               f"{len(self.curves)} curves"]
        for c in self.curves:
            out.append("  " + c.describe())
            out += [f"    ends: {r}" for r in c.stop_reasons if not r.startswith("reached")]
        out += [f"  {p.label} ({p.kind}) at {xn} = {p[xn]:.5g}, {yn} = {p[yn]:.5g}" for p in self.codim2]
        for g in sorted(self.regions, key=lambda g: -g.area):
            if g.key is not None:
                out.append(f"  region {g.index}: {g.words} ({g.area:.1%} of the box, "
                           f"{g.agreement:.0%} of its {sum(g.votes.values())} cells on the lines agree)")
        out += [f"  note: {n}" for n in self.notes]
        return out

    # -- files ------------------------------------------------------------------------------------
    def to_csv(self, folder):
        """curves.csv (every point of every curve: both parameters, amplitude, critical multiplier,
        deflection), codim2_points.csv, regions.csv, lines.csv (the special points the lines found)
        and curve_multipliers.csv (every multiplier of every curve point) in folder; returns the
        paths."""
        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        xn, yn = self.x[0], self.y[0]
        paths = [folder / n for n in ("curves.csv", "codim2_points.csv", "regions.csv", "lines.csv",
                                      "curve_multipliers.csv")]
        rows = [r for k, c in enumerate(self.curves) for r in c.rows(curve=k)]
        write_rows(paths[0], rows, None if rows else ["curve", "kind", "period", "point", xn, yn, "amplitude"])
        pts = []
        for k, c in enumerate(self.curves):
            pts += c.codim2_rows(curve=k)
        write_rows(paths[1], pts, ["curve", "kind", "label", "curve_kind", "period", "point", xn, yn, "amplitude",
                                   "multipliers", "description"])
        write_rows(paths[2], [dict(region=g.index, words=g.words, area=cell(g.area), agreement=cell(g.agreement),
                                   cells=sum(g.votes.values()), **{xn: cell(g.x), yn: cell(g.y)},
                                   votes="; ".join(f"{k}: {v}" for k, v in g.votes.items()))
                              for g in self.regions],
                   ["region", "words", "area", "agreement", "cells", xn, yn, "votes"])
        line_rows = []
        for ln in self.lines:
            if ln.diagram is None:
                line_rows.append({yn: cell(ln.level), "kind": "failed", "message": ln.message})
                continue
            for s in ln.diagram.special_points:
                line_rows.append({yn: cell(ln.level), "kind": s.kind, "period": s.period, xn: cell(s.parameter),
                                  "amplitude": cell(s.amplitude), "multiplier_re": cell(s.multiplier.real),
                                  "multiplier_im": cell(s.multiplier.imag), "message": ""})
        write_rows(paths[3], line_rows, [yn, "kind", "period", xn, "amplitude", "multiplier_re", "multiplier_im",
                                         "message"])
        write_rows(paths[4], [dict(curve=k, point=i, **{xn: cell(c[xn][i]), yn: cell(c[yn][i])}, index=j,
                                   re=cell(m.real), im=cell(m.imag), abs=cell(abs(m)))
                              for k, c in enumerate(self.curves) for i in range(len(c))
                              for j, m in enumerate(c.multipliers[i])],
                   ["curve", "point", xn, yn, "index", "re", "im", "abs"])
        return paths

    def as_dict(self):
        return dict(x=list(self.x), y=list(self.y), max_period=self.max_period,
                    curves=[c.as_dict() for c in self.curves],
                    lines=[dict(level=ln.level, message=ln.message,
                                diagram=None if ln.diagram is None else ln.diagram.as_dict()) for ln in self.lines],
                    regions=[dict(index=g.index, key=None if g.key is None else [list(k) for k in g.key],
                                  words=g.words, votes=g.votes, agreement=g.agreement, area=g.area, x=g.x, y=g.y,
                                  room=g.room) for g in self.regions],
                    labels=self.labels.tolist(),
                    deflection=[[None if not np.isfinite(v) else float(v) for v in row] for row in self.deflection],
                    notes=list(self.notes), info=jsonable(self.info))

    @classmethod
    def from_dict(cls, d):
        return cls(x=tuple(d["x"]), y=tuple(d["y"]), curves=[Curve.from_dict(c) for c in d["curves"]],
                   lines=[ChartLine(ln["level"], None if ln["diagram"] is None else BifurcationDiagram.from_dict(ln["diagram"]),
                               ln["message"]) for ln in d["lines"]],
                   regions=[Region(g["index"], None if g["key"] is None else tuple(tuple(k) for k in g["key"]),
                                   g["words"], dict(g["votes"]), g["agreement"], g["area"], g["x"], g["y"], g["room"])
                            for g in d["regions"]],
                   labels=np.array(d["labels"], dtype=int),
                   deflection=np.array([[np.nan if v is None else v for v in row] for row in d["deflection"]]),
                   max_period=int(d["max_period"]), notes=list(d["notes"]), info=dict(d["info"]))

    def to_json(self, path):
        """Everything (curves with their multipliers and states, the lines' diagrams, the regions
        and their raster) as JSON; StabilityChart.from_json reads it back."""
        with atomic_file(path) as fh:
            json.dump(dict(format=FORMAT, chart=self.as_dict()), fh)
        return Path(path)

    @classmethod
    def from_json(cls, path):
        d = json.loads(read_regular(path))
        if d.get("format") != FORMAT:
            raise ParameterError(f"{path} is not a crankgen stability chart file (format {d.get('format')!r})")
        return cls.from_dict(d["chart"])

    def plot(self, path, title=None):
        """The chart (charts/plot.py)."""
        from .plot import plot_chart
        return plot_chart(self, path, title)
