"""The Campbell diagram: the mechanism's natural frequencies against crank speed, with the crank
orders.

At each crank speed the mechanism is frozen at `angles` crank angles over a revolution
(crankgen.modes, crankgen.analyses.modes: the rod straight and stretched by the axial loads of the
rigid motion, the model's own tangent there); the j-th lowest frequency varies over the revolution, since the axial
force does (tension near the outer dead centre raises the bending frequencies, compression near
the inner one lowers them), so each mode is a band: its lowest, mean and highest value over the
revolution.  A crank order k is the line f = k Omega (k excitations per revolution); where it
meets a band, the order can drive that mode: a resonance.  The crossings are listed per order,
mode and edge of the band: where the order line enters the band (meets its low edge), crosses its
mean, and leaves it (meets its high edge), found on the speed grid by linear interpolation.

A band that reaches 0 holds angles at which the frozen rod buckles (the axial force beyond its
buckling load, lambda < 0: `divergent` is the fraction of the revolution where it does).

Units: speeds Omega* and frequencies in units of omega_b; for a crankgen.SIMechanism (units="si")
speeds in rad/s and frequencies in rad/s (the table and the figure add rpm and Hz).
"""

import csv
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Optional

import numpy as np

from ..declaration import schema
from ..errors import ParameterError
from .modes import AXIAL_SHARE, FrozenModel, frozen_case
from ..declaration.units import Scales
from ..declaration.validation import finite_number, integer

EDGES = ("low", "mean", "high")
EDGE_WORDS = {"low": "enters the band", "mean": "crosses its mean", "high": "leaves the band"}


@dataclass(frozen=True)
class Crossing:
    """A crank order line k Omega meeting the band of mode `mode` (1-based) at `edge` ("low":
    the order enters the band, "mean", "high": it leaves), at crank speed `speed` (Omega*, or
    rad/s in SI) and frequency k speed."""

    order: int
    mode: int
    kind: str
    edge: str
    speed: float
    frequency: float


@dataclass
class CampbellDiagram:
    """speeds (S,), angles (A,) rad; omega_squared (S, A, count) the eigenvalues of the frozen
    mechanism; axial_share likewise; low, mean, high (S, count) the bands of the frequencies over a
    revolution; divergent (S, count) the fraction of angles where the mode buckles; kinds (S, count)
    "bending" or "axial"; crossings: a list of Crossing; orders; scales (SI) or None.  Speeds and
    frequencies in crankgen's units (omega_b), or rad/s with scales."""

    speeds: np.ndarray
    angles: np.ndarray
    omega_squared: np.ndarray = field(repr=False)
    axial_share: np.ndarray = field(repr=False)
    orders: tuple
    crossings: list
    info: dict = field(default_factory=dict, repr=False)
    scales: Optional[Scales] = field(default=None, repr=False)

    @property
    def frequencies(self):
        return np.sqrt(np.maximum(self.omega_squared, 0.0)) * self._unit

    @property
    def _unit(self):
        return 1.0 if self.scales is None else self.scales.omega_b

    @property
    def low(self):
        return self.frequencies.min(axis=1)

    @property
    def mean(self):
        return self.frequencies.mean(axis=1)

    @property
    def high(self):
        return self.frequencies.max(axis=1)

    @property
    def divergent(self):
        return np.mean(self.omega_squared < 0, axis=1)

    @property
    def kinds(self):
        share = self.axial_share.mean(axis=1)
        return np.where(share > AXIAL_SHARE, "axial", "bending")

    def band(self, edge):
        return {"low": self.low, "mean": self.mean, "high": self.high}[edge]

    def to_csv(self, folder):
        """campbell.csv (one row per speed and mode: the band, its kind, the divergent share) and
        crossings.csv (one row per crossing) in folder; returns the paths."""
        from ..results.io import atomic_file
        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        si = self.scales is not None
        speed_cols = ["crank_speed_rad_per_s", "crank_speed_rpm"] if si else [schema.CRANK_SPEED]
        freq = (lambda name: [f"{name}_rad_per_s", f"{name}_Hz"]) if si else (lambda name: [name])
        paths = [folder / "campbell.csv", folder / "crossings.csv"]
        with atomic_file(paths[0]) as fh:
            w = csv.writer(fh)
            w.writerow(speed_cols + ["mode", "kind"] + freq("low") + freq("mean") + freq("high")
                       + ["divergent_share"])
            for i, speed in enumerate(self.speeds):
                for j in range(self.low.shape[1]):
                    w.writerow(self._speed(speed) + [j + 1, self.kinds[i, j]]
                               + self._freq(self.low[i, j]) + self._freq(self.mean[i, j])
                               + self._freq(self.high[i, j]) + [repr(float(self.divergent[i, j]))])
        with atomic_file(paths[1]) as fh:
            w = csv.writer(fh)
            w.writerow(["order", "mode", "kind", "edge"] + speed_cols + freq("frequency"))
            for c in self.crossings:
                w.writerow([c.order, c.mode, c.kind, c.edge] + self._speed(c.speed) + self._freq(c.frequency))
        return paths

    def _speed(self, speed):
        if self.scales is None:
            return [repr(float(speed))]
        return [repr(float(speed)), repr(float(speed * 60 / (2 * np.pi)))]

    def _freq(self, value):
        if self.scales is None:
            return [repr(float(value))]
        return [repr(float(value)), repr(float(value / (2 * np.pi)))]

    def summary(self):
        """One line per crossing of a band's mean, in speed order."""
        unit = "rad/s" if self.scales is not None else ""
        rows = sorted((c for c in self.crossings if c.edge == "mean"), key=lambda c: c.speed)
        return [f"{c.order}x crosses mode {c.mode} ({c.kind}) at crank speed "
                f"{'Omega* = ' if not unit else ''}{c.speed:.4g}{' ' + unit if unit else ''}"
                + (f" ({c.speed * 60 / (2 * np.pi):.4g} rpm, {c.frequency / (2 * np.pi):.4g} Hz)" if unit else
                   f", frequency {c.frequency:.4g}") for c in rows]

    def plot(self, path, title=None):
        """The bands (shaded between low and high, the mean drawn), the crank-order lines and the
        crossings of the means, written atomically to path (returned).  SI: crank speed in rpm,
        frequencies in Hz."""
        from ..plots.campbell import campbell_figure
        from ..results.io import save_figure
        return save_figure(campbell_figure(self, title), path, dpi=130)


def _crossings(speeds, bands, kinds, orders):
    """Every crossing of k speed with a band edge on the grid, by linear interpolation."""
    out = []
    for k in orders:
        for j in range(bands["mean"].shape[1]):
            for edge in EDGES:
                g = k * speeds - bands[edge][:, j]
                for i in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
                    w = g[i] / (g[i] - g[i + 1])
                    speed = float(speeds[i] + w * (speeds[i + 1] - speeds[i]))
                    kind = kinds[i + (w > 0.5), j]
                    out.append(Crossing(int(k), j + 1, str(kind), edge, speed, k * speed))
                for i in np.flatnonzero(g == 0):
                    if 0 < i < len(speeds) - 1 or speeds[i] > 0:
                        out.append(Crossing(int(k), j + 1, str(kinds[i, j]), edge, float(speeds[i]),
                                            float(k * speeds[i])))
    return sorted(out, key=lambda c: (c.speed, c.order, c.mode, EDGES.index(c.edge)))


def campbell(mech=None, speeds=None, *, angles=36, count=4, orders=(1, 2, 3, 4, 5, 6), model=None,
             case=None, units="crankgen", progress=None, **fields):
    """The Campbell diagram of the mechanism (module docstring): the `count` lowest natural
    frequencies of the mechanism frozen at `angles` equally spaced crank angles of a revolution,
    at each crank speed of `speeds` (Omega*; rad/s with units="si" and a crankgen.SIMechanism;
    default 81 speeds from 0 to 1.6 omega_b), and their crossings with the crank orders `orders`.
    The case as in crankgen.modes.  progress(done, total) after each speed.  Returns a
    CampbellDiagram."""
    c, scales = frozen_case(mech, None, model=model, case=case, units=units, **fields)
    unit = 1.0 if scales is None else scales.omega_b
    if speeds is None:
        speeds = np.linspace(0.0, 1.6, 81) * unit
    if isinstance(speeds, (str, bytes)) or not hasattr(speeds, "__iter__"):
        raise ParameterError(f"speeds must be a sequence of crank speeds, got {speeds!r}")
    speeds = np.array([finite_number("speeds", s) for s in speeds], dtype=float)
    if speeds.size < 2 or np.any(speeds < 0) or np.any(np.diff(speeds) <= 0):
        raise ParameterError("speeds must be two or more increasing crank speeds >= 0")
    angles = integer("angles", angles, 2)
    count = integer("count", count, 1)
    orders = tuple(integer("orders", k, 1) for k in np.atleast_1d(orders))
    if progress is not None and not callable(progress):
        raise ParameterError(f"progress must be None or a function, got {progress!r}")
    theta = 2 * np.pi * np.arange(angles) / angles
    lam, share = [], []
    for i, speed in enumerate(speeds):
        fm = FrozenModel(replace(c, **{schema.CRANK_SPEED: float(speed / unit)}))
        count = min(count, fm.N)
        _, _, lam_i, vec, M = fm.eigen(theta)
        lam.append(lam_i[:, :count])
        share.append(fm.axial_share(vec[:, :, :count], M))
        if progress is not None:
            progress(i + 1, len(speeds))
    omega_squared, axial_share = np.array(lam), np.array(share)
    # a frozen mechanism has no crank motion: its parameters are left out of the description
    motion = {n for n, p in schema.PARAMETERS.items() if p.owner == "motion"} | {schema.SELECTOR["motion"]}
    info = {k: v for k, v in c.as_dict().items() if k not in motion}
    diagram = CampbellDiagram(speeds, theta, omega_squared, axial_share, orders, [],
                              info=dict(info, angles=angles, count=count), scales=scales)
    bands = {edge: diagram.band(edge) for edge in EDGES}
    diagram.crossings = _crossings(speeds, bands, diagram.kinds, orders)
    return diagram
