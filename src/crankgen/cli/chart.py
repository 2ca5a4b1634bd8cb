"""`crankgen chart`: the stability chart of a plane of two parameters."""

import sys

from ..declaration import schema
from ..analyses.charts.axes import X_DEFAULT, Y_DEFAULT
from .options import UsageError, _Outputs, _add_mechanism_options, _add_model_options, _add_output_options, _explicit

CHART_NAMES = ("curves.csv", "codim2_points.csv", "regions.csv", "lines.csv", "curve_multipliers.csv",
               "chart.json", "chart.png")
NAMES = {p.cli: name for name, p in schema.PARAMETERS.items() if p.continuable}


def _axis_spec(which):
    def parse(text):
        import argparse
        parts = [p.strip() for p in text.split(",")]
        if len(parts) != 3:
            raise argparse.ArgumentTypeError(f"expected PARAMETER,LOW,HIGH (e.g. omega,0.2,1.6), got {text!r}")
        name = NAMES.get(parts[0], parts[0])
        if name not in schema.CONTINUABLE:
            raise argparse.ArgumentTypeError(f"{parts[0]!r} is not a continuable parameter; those are "
                                             f"{', '.join(schema.CONTINUABLE)}")
        try:
            lo, hi = float(parts[1]), float(parts[2])
        except ValueError:
            raise argparse.ArgumentTypeError(f"LOW and HIGH must be numbers, got {parts[1]!r}, {parts[2]!r}")
        if not lo < hi:
            raise argparse.ArgumentTypeError(f"LOW must be below HIGH, got {lo:g}, {hi:g}")
        return (name, lo, hi)
    parse.__name__ = f"{which} axis"
    return parse


def add_command(sub):
    p = sub.add_parser("chart", help="stability chart: fold and period-doubling curves in two parameters, regions named",
                       description="The stability chart of a plane of two continuable parameters: "
                                   "continuations in the first at a few values of the second (the "
                                   "lines), every fold, period doubling and Neimark-Sacker point they "
                                   "find followed in the second parameter (crankgen.follow), the "
                                   "codimension-two points on those curves (cusp, fold-flip, 1:2 "
                                   "resonance, ...), and the regions between the curves named by what "
                                   "the lines find in them (stable period-1, period-2, two stable "
                                   "orbits coexisting). Writes " + ", ".join(CHART_NAMES) + ".")
    _add_mechanism_options(p)
    g = _add_model_options(p, integrator=False)
    g.title = "model (the chart's two parameters take their values from --x and --y)"
    a = p.add_argument_group("the plane")
    a.add_argument("--x", type=_axis_spec("--x"), default=X_DEFAULT, metavar="PARAMETER,LOW,HIGH",
                   help="the horizontal axis: a continuable parameter (" + ", ".join(schema.CONTINUABLE)
                        + ") and its range (default " + ",".join(map(str, X_DEFAULT)) + ")")
    a.add_argument("--y", type=_axis_spec("--y"), default=Y_DEFAULT, metavar="PARAMETER,LOW,HIGH",
                   help="the vertical axis (default " + ",".join(map(str, Y_DEFAULT)) + ")")
    a.add_argument("--lines", type=int, default=6,
                   help="continuations in the x parameter at this many values of the y parameter (default 6)")
    a.add_argument("--max-lines", type=int, default=10,
                   help="lines in all, with those added for regions no line crosses (default 10)")
    a.add_argument("--max-period", type=int, default=2,
                   help="period doublings followed up to this period, and the periods the regions "
                        "count (default 2)")
    _add_output_options(p, "chart", ", ".join(CHART_NAMES))
    p.set_defaults(func=_cmd_chart)


def _cmd_chart(args):
    from ..declaration.cases import make_case
    from ..analyses.charts import stability_chart
    from ..analyses.limits import count
    fields = _explicit(args)
    for axis in (args.x, args.y):
        name = axis[0]
        if name in fields:
            flag = schema.PARAMETERS[name].cli
            raise UsageError(f"--{flag} is an axis of the chart ({name}): its values are the axis' range; "
                             f"leave out --{flag}")
    count("lines", args.lines, "--lines")
    count("max_lines", args.max_lines, "--max-lines")
    count("max_period", args.max_period, "--max-period")
    fields[args.x[0]] = args.x[1]
    case = make_case(model=args.model, **fields)
    folder = _Outputs(args.out, CHART_NAMES, args.force)
    try:
        log = None if args.quiet else (lambda text: print(f"chart: {text}", file=sys.stderr, flush=True))
        chart = stability_chart(x=args.x, y=args.y, case=case, lines=args.lines, max_lines=args.max_lines,
                                max_period=args.max_period, progress=log)
        paths = [folder.wrote(p) for p in chart.to_csv(folder.folder)]
        paths.append(folder.wrote(chart.to_json(folder.path("chart.json"))))
        png = folder.wrote(chart.plot(folder.path("chart.png")))
    finally:
        folder.abandon()
    print("\n".join(chart.summary()))
    print(f"{len(chart.curves)} curves, {len(chart.codim2)} codimension-two points, "
          f"{sum(1 for g in chart.regions if g.key is not None)} named regions in "
          f"{chart.info['wall_time']:.1f} s; wrote {', '.join(str(p) for p in paths)} and {png}")
    return 0
