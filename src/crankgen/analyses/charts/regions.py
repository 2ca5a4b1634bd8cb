"""The regions of a stability chart: the plane cut by the curves, each piece named by what the
one-parameter continuations along lines of constant y found in it.

The box is a raster of cells; every curve is drawn into it as a barrier (its segments sampled at
a quarter cell, an 8-connected line, which no 4-connected region crosses), and the cells left are
split into 4-connected pieces (scipy.ndimage.label).  Along each line y = level the continuation's
branches say, at each cell's x, how many stable orbits of each period there are (a stable stretch of
a branch between two stable points, or between a stable point and a special point, covers the x
between them; a branch folding back covers an x once per stretch).  Each piece takes the verdict most of its cells on the lines give (the
agreement is kept: a piece where the verdicts differ has a boundary the curves miss); a piece
that no line crosses has none (None).  The deflection of the stable orbits (eps times the
amplitude, the largest over the orbits of a cell) is interpolated linearly between the lines
(constant beyond the outer ones), for the range of the theory.
"""

import math
from dataclasses import dataclass

import numpy as np

from ..theory import DEFLECTION_LIMIT

WIDTH, HEIGHT = 320, 200          # cells of the raster


def words(key, max_period):
    """The verdict in words: key is ((period, count), ...) of the stable orbits."""
    total = sum(n for _, n in key)
    if total == 0:
        return f"no stable orbit of period <= {max_period}"
    parts = []
    for period, n in key:
        parts += [f"period-{period}"] * n
    if total == 1:
        return f"stable {parts[0]}"
    if len(set(parts)) == 1:
        return f"{'two' if total == 2 else total} stable {parts[0]} orbits coexist"
    return " and ".join(parts) + " coexist (stable)"


def stable_orbits(diagram, x, max_period, eps=None):
    """(key, deflection): the stable orbits at x on a line's diagram, ((period, count), ...) sorted
    by period, and the largest deflection eps * amplitude among them (NaN: none, or no eps)."""
    counts, defl = {}, math.nan
    for b, br in enumerate(diagram.branches):
        if br.period > max_period:
            continue
        p, st, amp = br.parameter, np.asarray(br.stable, dtype=bool), br.amplitude
        # a special point (a multiplier on the unit circle) bounds a stretch: it takes its neighbour's
        # stability
        special = {i for s in diagram.special_points if s.branch == b
                   for i in np.flatnonzero(p == s.parameter)}
        for i in range(len(br) - 1):
            lo, hi = sorted((p[i], p[i + 1]))
            stable = (st[i] or i in special) and (st[i + 1] or i + 1 in special) and not (
                i in special and i + 1 in special)
            if stable and lo <= x <= hi and hi > lo:
                counts[br.period] = counts.get(br.period, 0) + 1
                if eps is not None:
                    a = amp[i] + (amp[i + 1] - amp[i]) * (x - p[i]) / (p[i + 1] - p[i])
                    d = abs(eps(x) * a)
                    defl = d if not d <= defl else defl
    return tuple(sorted(counts.items())), defl


def covered(diagram):
    """The x range where a line's diagram tells the verdict: that of its crank-period branch."""
    first = diagram.branches[0].parameter
    return float(np.min(first)), float(np.max(first))


@dataclass
class Raster:
    """The box as cells: x and y of the cell centres."""

    x_lo: float
    x_hi: float
    y_lo: float
    y_hi: float
    width: int = WIDTH
    height: int = HEIGHT

    @property
    def xs(self):
        return self.x_lo + (np.arange(self.width) + 0.5) / self.width * (self.x_hi - self.x_lo)

    @property
    def ys(self):
        return self.y_lo + (np.arange(self.height) + 0.5) / self.height * (self.y_hi - self.y_lo)

    def cell(self, x, y):
        """(row, column) float co-ordinates of (x, y), cells of unit size."""
        return ((np.asarray(y) - self.y_lo) / (self.y_hi - self.y_lo) * self.height,
                (np.asarray(x) - self.x_lo) / (self.x_hi - self.x_lo) * self.width)

    def row(self, y):
        r = int(math.floor(self.cell(0.0, y)[0]))
        return min(max(r, 0), self.height - 1)

    def barriers(self, polylines):
        """Boolean (height, width): the cells the polylines (x, y arrays) pass through."""
        wall = np.zeros((self.height, self.width), dtype=bool)
        for x, y in polylines:
            r, c = self.cell(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
            for k in range(len(r) - 1):
                n = int(math.ceil(4 * max(abs(r[k + 1] - r[k]), abs(c[k + 1] - c[k]), 1e-9))) + 1
                rr = np.linspace(r[k], r[k + 1], n + 1)
                cc = np.linspace(c[k], c[k + 1], n + 1)
                keep = np.isfinite(rr) & np.isfinite(cc)
                ri, ci = np.floor(rr[keep]).astype(int), np.floor(cc[keep]).astype(int)
                ok = (ri >= 0) & (ri < self.height) & (ci >= 0) & (ci < self.width)
                wall[ri[ok], ci[ok]] = True
        return wall


def pieces(wall):
    """(labels (height, width), count): the 4-connected pieces of the cells off the walls (label 0
    on a wall, 1..count)."""
    from scipy import ndimage
    labels, count = ndimage.label(~wall, structure=[[0, 1, 0], [1, 1, 1], [0, 1, 0]])
    return labels, count


def interior_point(raster, labels, piece):
    """(x, y) of the cell of the piece farthest from its edge (where its name is written)."""
    from scipy import ndimage
    mask = np.pad(labels == piece, 1)
    dist = ndimage.distance_transform_edt(mask)[1:-1, 1:-1]
    r, c = np.unravel_index(int(np.argmax(dist)), dist.shape)
    return float(raster.xs[c]), float(raster.ys[r]), float(dist[r, c])


def vote(raster, labels, count, lines, max_period, eps_of):
    """Per piece: {key: cells} of the lines' verdicts, and the lines' deflection (levels, width)."""
    votes = [dict() for _ in range(count + 1)]
    xs = raster.xs
    defl = np.full((len(lines), raster.width), np.nan)
    for j, (level, diagram) in enumerate(lines):
        if diagram is None or not diagram.branches:
            continue
        r = raster.row(level)
        lo, hi = covered(diagram)
        eps = eps_of(level)
        for c, x in enumerate(xs):
            if not lo <= x <= hi:
                continue
            key, d = stable_orbits(diagram, x, max_period, eps)
            defl[j, c] = d
            piece = labels[r, c]
            if piece:
                votes[piece][key] = votes[piece].get(key, 0) + 1
    return votes, defl


def deflection_field(raster, levels, defl):
    """(height, width): the lines' deflection interpolated linearly in y between the lines."""
    order = np.argsort(levels)
    lv, dv = np.asarray(levels, dtype=float)[order], defl[order]
    out = np.full((raster.height, raster.width), np.nan)
    ys = raster.ys
    for c in range(raster.width):
        ok = np.isfinite(dv[:, c])
        if ok.sum() == 0:
            continue
        if ok.sum() == 1:
            out[:, c] = dv[ok, c][0]
            continue
        out[:, c] = np.interp(ys, lv[ok], dv[ok, c])
    return out


def beyond_mask(field):
    return np.nan_to_num(field, nan=0.0) > DEFLECTION_LIMIT
