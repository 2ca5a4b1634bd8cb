"""crankgen.stability_chart: the curves of fold, period-doubling and Neimark-Sacker points in a
plane of two parameters, and its regions named in words.

1. Lines: a continuation in x (crankgen.continuation, period-doubling branches up to max_period) at
   `lines` values of y, the centres of equal bands of [y_lo, y_hi], over the x range widened by
   `margin` on both sides (from the other end where the first has no periodic start).
2. Curves: every special point the lines found that lies on no curve found before (of its kind and
   period, within a hundredth of the box) is followed in y (crankgen.follow) inside the box.
3. Regions (regions.py): the curves cut the box into pieces, each named by the verdict of the
   lines across it (stable period-1, period-2, two stable orbits coexisting, ...).  A piece of at
   least MIN_AREA of the box that no line crosses gets a line of its own through its middle, and
   the curves its special points lead to, up to max_lines lines in all.
4. The range of the theory: where a stable orbit's deflection (eps times its amplitude) exceeds
   0.1 L, between the lines.
"""

import math
import time
from dataclasses import replace

import numpy as np

from ...declaration import schema
from ..bifurcation import continuation, follow
from ..bifurcation.api import make_case
from ..bifurcation.mechanism import PARAMETERS
from ...errors import CrankgenError, NoResultError, ParameterError
from ...declaration.validation import in_range, integer
from . import regions as _regions
from .axes import R, X_DEFAULT, Y_DEFAULT
from .record import ChartLine, Region, StabilityChart
from ...declaration import values as _values

MIN_AREA = 0.01        # a piece without a verdict this large (share of the box) gets a line
ON_CURVE = 0.01        # a special point this close to a curve (in units of the box) lies on it
FAILURES = (CrankgenError, ArithmeticError, np.linalg.LinAlgError)


def _axis(which, spec):
    if isinstance(spec, (str, bytes)) or not hasattr(spec, "__len__") or len(spec) != 3:
        raise ParameterError(f"{which} must be (parameter, low, high), e.g. ('omega', 0.2, 1.6), got {spec!r}")
    name, lo, hi = spec
    if name not in PARAMETERS:
        raise ParameterError(f"{which}'s parameter must be one of {', '.join(PARAMETERS)}, got {name!r}")
    lo, hi = in_range(f"{which} low ({name})", lo), in_range(f"{which} high ({name})", hi)
    if not lo < hi:
        raise ParameterError(f"{which} must have low < high, got {lo:g}, {hi:g}")
    record = schema.PARAMETERS[name]
    _values.canonical(record, lo), _values.canonical(record, hi)
    return (name, lo, hi)


def _near(curve, point, xn, yn, box):
    """Distance (in units of the box) from a special point to a curve's polyline."""
    if curve.kind != point.kind or curve.period != point.period:
        return math.inf
    (x_lo, x_hi), (y_lo, y_hi) = box
    px = (point.parameter - x_lo) / (x_hi - x_lo)
    py = (float(getattr(point.case, yn)) - y_lo) / (y_hi - y_lo)
    cx = (curve[xn] - x_lo) / (x_hi - x_lo)
    cy = (curve[yn] - y_lo) / (y_hi - y_lo)
    if len(cx) == 1:
        return math.hypot(cx[0] - px, cy[0] - py)
    ax, ay, bx, by = cx[:-1], cy[:-1], cx[1:], cy[1:]
    dx, dy = bx - ax, by - ay
    t = np.clip(((px - ax) * dx + (py - ay) * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0, 1)
    return float(np.min(np.hypot(ax + t * dx - px, ay + t * dy - py)))




def stability_chart(mech=None, x=X_DEFAULT, y=Y_DEFAULT, *, model=None, lines=6,
                    max_lines=10, max_period=2, margin=0.25, case=None, progress=None, follow_settings=None,
                    **fields):
    """The stability chart of the mechanism in the plane of x = (parameter, low, high) and y = (...),
    two continuable parameters (crankgen.declaration.schema.CONTINUABLE): a StabilityChart with its curves
    (crankgen.Curve), the regions named in words, the codimension-two points, the lines of
    one-parameter continuations behind them (module docstring), to_csv, to_json and plot.  The case
    as in continuation (a Mechanism with the run's fields and model=, or case=); lines: the first
    lines of constant y; max_lines: with the lines added for pieces no line crosses;
    max_period: the period-doubling branches followed (and the periods the regions count);
    margin: the lines run beyond the box by this share of its width on each side (halfway to a
    bound of the parameter at most), so that a branch folding back just outside still shows its
    stable orbits inside;
    follow_settings: keywords for crankgen.follow (ds, dq_max, max_points, tol);
    progress(text) receives progress lines."""
    if progress is not None and not callable(progress):
        raise ParameterError(f"progress must be None or a function, got {progress!r}")
    log = progress or (lambda text: None)
    (xn, x_lo, x_hi), (yn, y_lo, y_hi) = _axis("x", x), _axis("y", y)
    if xn == yn:
        raise ParameterError(f"x and y must be two different parameters, got {xn!r} twice")
    lines = integer("lines", lines, 1)
    margin = in_range("margin", margin, 0, None)
    max_lines = max(integer("max_lines", max_lines, 1), lines)
    max_period = integer("max_period", max_period, 1)
    follow_settings = dict(follow_settings or {})
    base = make_case(mech, xn, x_lo, case, model=model, **fields)
    make_case(None, xn, x_hi, base)
    for v in (y_lo, y_hi):
        make_case(None, yn, v, base)
    t0 = time.perf_counter()
    box = ((x_lo, x_hi), (y_lo, y_hi))
    raster = _regions.Raster(x_lo, x_hi, y_lo, y_hi)
    chart_lines, curves, notes = [], [], []
    eps_of = (lambda level: (lambda xv: level)) if yn == R else (
        (lambda level: (lambda xv: xv)) if xn == R else (lambda level: (lambda xv: getattr(base, R))))

    record = schema.PARAMETERS[xn]
    ext_lo, ext_hi = x_lo - margin * (x_hi - x_lo), x_hi + margin * (x_hi - x_lo)
    if record.low is not None:
        ext_lo = max(ext_lo, 0.5 * (record.low + x_lo))
    if record.high is not None:
        ext_hi = min(ext_hi, 0.5 * (record.high + x_hi))

    def add_line(level):
        c = replace(base, **{yn: float(level)})
        log(f"line {len(chart_lines) + 1}: continuation in {xn} at {yn} = {level:.6g}")
        line = None
        for start, stop in ((ext_lo, ext_hi), (ext_hi, ext_lo)):
            try:
                d = continuation(None, xn, start, stop, case=c, max_period=max_period,
                                 progress=lambda text: log(f"  {yn} = {level:.4g}: {text}"))
                line = ChartLine(float(level), d)
                break
            except NoResultError as exc:
                line = ChartLine(float(level), None, str(exc))
            except FAILURES as exc:
                line = ChartLine(float(level), None, f"{type(exc).__name__}: {exc}")
                break
        if line.diagram is None:
            notes.append(f"the continuation at {yn} = {level:.6g} failed: {line.message}")
        chart_lines.append(line)
        return line

    def add_curves(line):
        if line.diagram is None:
            return
        for sp in line.diagram.special_points:
            if sp.period > max_period or not x_lo <= sp.parameter <= x_hi or any(
                    _near(cv, sp, xn, yn, box) < ON_CURVE for cv in curves):
                continue
            log(f"curve {len(curves) + 1}: the {sp.kind} of the period-{sp.period} orbits at {xn} = "
                f"{sp.parameter:.6g}, {yn} = {line.level:.6g}, followed in {yn}")
            try:
                cv = follow(sp, yn, y_lo, y_hi, bounds=(x_lo, x_hi),
                            progress=lambda text: log(f"  {text}"), **follow_settings)
            except FAILURES as exc:
                notes.append(f"the {sp.kind} at {xn} = {sp.parameter:.6g}, {yn} = {line.level:.6g} could not be "
                             f"followed: {exc}")
                continue
            curves.append(cv)

    for k in range(lines):
        add_curves(add_line(y_lo + (k + 0.5) / lines * (y_hi - y_lo)))
    while True:
        wall = raster.barriers([(cv[xn], cv[yn]) for cv in curves])
        labels, count = _regions.pieces(wall)
        votes, defl = _regions.vote(raster, labels, count, [(ln.level, ln.diagram) for ln in chart_lines],
                                    max_period, eps_of)
        empty = [g for g in range(1, count + 1) if not votes[g]
                 and np.mean(labels == g) >= MIN_AREA]
        if not empty or len(chart_lines) >= max_lines:
            break
        g = max(empty, key=lambda g: np.mean(labels == g))
        _, level, _ = _regions.interior_point(raster, labels, g)
        if any(raster.row(level) == raster.row(ln.level) for ln in chart_lines):
            break
        add_curves(add_line(level))
    found = []
    for g in range(1, count + 1):
        area = float(np.mean(labels == g))
        px, py, room = _regions.interior_point(raster, labels, g)
        if votes[g]:
            key, cells = max(votes[g].items(), key=lambda kv: kv[1])
            text = _regions.words(key, max_period)
            agreement = cells / sum(votes[g].values())
        else:
            key, text, agreement = None, "no line crosses it", math.nan
        found.append(Region(g, key, text, {_regions.words(k, max_period): v for k, v in votes[g].items()},
                            agreement, area, px, py, room))
        if votes[g] and agreement < 0.9:
            notes.append(f"region {g} ({text}): only {agreement:.0%} of its cells on the lines agree; "
                         f"a boundary is missing there")
    info = base.as_dict()
    for n in (xn, yn):
        info.pop(n, None)
    info.update(x=xn, y=yn, lines=len(chart_lines), max_period=max_period, margin=margin,
                wall_time=time.perf_counter() - t0)
    chart = StabilityChart((xn, x_lo, x_hi), (yn, y_lo, y_hi), curves, chart_lines, found, labels,
                           _regions.deflection_field(raster, [ln.level for ln in chart_lines], defl),
                           max_period, notes, info)
    log(f"stability chart: {len(curves)} curves, {len(chart.codim2)} codimension-two points, "
        f"{sum(1 for g in found if g.key is not None)} named regions, {info['wall_time']:.1f} s")
    return chart
