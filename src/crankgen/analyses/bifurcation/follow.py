"""crankgen.follow: a special point of a BifurcationDiagram continued in a second parameter.

follow_map is the generic form on a PlaneMap (plane_maps.py); follow takes a SpecialPoint of a
mechanism's diagram (crankgen.continuation), builds the revolution map in both parameters
(mechanism_plane.py) and follows the point's curve both ways from it inside the box of the
first parameter's range (the diagram's, or `bounds`) and [start, stop] of the second.
"""

import math
import time
import numpy as np

from ...declaration import schema
from ...errors import ParameterError
from ...declaration.validation import in_range, integer
from .codim2 import CurveContinuer, CurveSettings
from .curve import make_curve
from .defining import KINDS, Defining
from .mechanism import PARAMETERS
from ...declaration import values as _values


def follow_map(fmap, kind, x, p, lo, hi, period=1, theta=None, settings=None, log=None, info=None,
               scale=None):
    """The Curve of `kind` points of period `period` of the PlaneMap fmap through the point near
    (x, p[, theta]), followed both ways inside lo <= p <= hi (scale: the parameters' units in the
    metric, default the box's widths)."""
    if kind not in KINDS:
        raise ParameterError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    scale = hi - lo if scale is None else np.asarray(scale, dtype=float)
    d = Defining(kind, fmap, period, scale, fd_step=(settings or CurveSettings()).fd_step)
    c = CurveContinuer(d, lo, hi, settings, log)
    start = c.start(np.asarray(x, dtype=float), np.asarray(p, dtype=float), theta)
    runs, found, reasons = [], [], []
    for direction in (-1.0, 1.0):
        pts, hits, reason = c.run(start, direction)
        runs.append(pts)
        found += hits
        reasons.append(reason)
    return make_curve(d, runs[0], runs[1], found, reasons, dict(info or {}))


def follow(point, parameter, start, stop, *, bounds=None, ds=0.02, ds_min=1e-5, ds_max=0.25, dq_max=0.02,
           max_points=300, tol=1e-9, fd_step=1e-5, progress=None):
    """Continue a special point of a mechanism's BifurcationDiagram (crankgen.continuation: a fold,
    period doubling or Neimark-Sacker point) in a second continuable parameter `parameter`, and
    return the Curve of such points (bifurcation/curve.py): its kind, period, both parameters by
    name (curve["omega"], curve["eps"]), the orbit's amplitude and multipliers along it, and the
    codimension-two points met (cusp, fold-flip, 1:2 resonance, ...; codim2.py).  The curve is
    followed both ways from the point inside the box: the first parameter within `bounds` (default
    the diagram's range), the second within [start, stop], which must hold the point's value.  Steps
    ds, ds_min, ds_max are arclengths in the metric |dy|^2 / dim + |dq|^2 (y the state (d, v) in
    v*-like units, generalized-alpha's algorithmic accelerations left out, q the parameters in units of the box's widths); no step changes a parameter by more than
    dq_max of its width.  tol: the corrector's tolerance; fd_step: the relative step of the second
    derivatives (defining.py); progress(text) receives progress lines."""
    from .diagram import SpecialPoint
    if not isinstance(point, SpecialPoint) or point.case is None:
        raise ParameterError("point must be a special point of a mechanism's BifurcationDiagram "
                             "(crankgen.continuation(...).special_points[k])")
    if progress is not None and not callable(progress):
        raise ParameterError(f"progress must be None or a function, got {progress!r}")
    first = point.parameter_name
    if parameter not in PARAMETERS:
        raise ParameterError(f"parameter must be one of {', '.join(PARAMETERS)}, got {parameter!r}")
    if parameter == first:
        raise ParameterError(f"the second parameter must differ from the diagram's ({first!r})")
    case = point.case
    record = schema.PARAMETERS[parameter]
    if not record.read_by(case.guide_record.name, case.motion_record.name):
        current = case.guide_record.name if record.owner == "guide" else case.motion_record.name
        raise ParameterError(f"cannot vary {record.label}: it belongs to the {' and '.join(record.readers)} "
                             f"{record.owner}; this case's {record.owner} is {current!r}")
    start, stop = in_range("start", start), in_range("stop", stop)
    if start == stop:
        raise ParameterError(f"start and stop must differ, got {start:g}")
    for v in (start, stop):
        _values.canonical(record, v)
    here = float(getattr(case, parameter))
    lo2, hi2 = min(start, stop), max(start, stop)
    if not lo2 <= here <= hi2:
        raise ParameterError(f"the point lies at {record.label} = {here:g}, outside [{lo2:g}, {hi2:g}]: the "
                             f"range of {parameter} must hold it")
    if bounds is None:
        bounds = point.range
    if bounds is None or len(bounds) != 2:
        raise ParameterError(f"bounds must be two numbers (the range of {first}), got {bounds!r}")
    lo1, hi1 = sorted(in_range(f"bounds ({first})", b) for b in bounds)
    if not lo1 <= point.parameter <= hi1 or lo1 == hi1:
        raise ParameterError(f"bounds [{lo1:g}, {hi1:g}] of {first} must hold the point's {first} = "
                             f"{point.parameter:g}")
    settings = CurveSettings(ds=in_range("ds", ds, 0, None, True), ds_min=in_range("ds_min", ds_min, 0, None, True),
                             ds_max=in_range("ds_max", ds_max, 0, None, True),
                             dq_max=in_range("dq_max", dq_max, 0, None, True),
                             max_points=integer("max_points", max_points, 2),
                             tol=in_range("tol", tol, 0, None, True),
                             fd_step=in_range("fd_step", fd_step, 0, None, True)).check()
    from .mechanism_plane import MechanismPlaneMap
    t0 = time.perf_counter()
    fmap = MechanismPlaneMap(case, (first, parameter))
    theta = None
    if point.kind == "neimark-sacker":
        theta = abs(math.atan2(point.multiplier.imag, point.multiplier.real))
    info = case.as_dict()
    for name in (first, parameter):
        info.pop(name, None)
    log = progress or (lambda text: None)
    log(f"{point.kind} of the period-{point.period} orbits at {first} = {point.parameter:.6g}, "
        f"{parameter} = {here:.6g}: following it in {parameter} from {start:g} to {stop:g}")
    curve = follow_map(fmap, point.kind, point.state / fmap.s, [point.parameter, here], [lo1, lo2], [hi1, hi2],
                       period=point.period, theta=theta, settings=settings, log=log, info=info)
    curve.info.update(kind=point.kind, period=point.period, parameters=[first, parameter],
                      bounds={first: [lo1, hi1], parameter: [lo2, hi2]},
                      origin={first: point.parameter, parameter: here}, shootings=fmap.shootings,
                      wall_time=time.perf_counter() - t0)
    return curve
