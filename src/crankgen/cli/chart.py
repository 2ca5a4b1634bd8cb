"""`crankgen chart`: the stability chart of a plane of two parameters."""

import sys

from ..declaration import schema
from ..analyses.charts.axes import X_DEFAULT, Y_DEFAULT
from .options import UsageError, _Outputs, _add_mechanism_options, _add_model_options, _add_output_options, _explicit

CHART_NAMES = ("curves.csv", "codim2_points.csv", "regions.csv", "lines.csv", "curve_multipliers.csv",
               "chart.json", "chart.png", "curves_si.csv")
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
    a.add_argument("--quick", action="store_true",
                   help="a quick chart: the plane " + ",".join(map(str, QUICK_X)) + " by " + ",".join(map(str, QUICK_Y))
                        + " (unless --x, --y are given: crank speed against crank length, where the theory "
                        "holds over most of the box), 4 elements, 50 steps per revolution, 3 lines (at most "
                        "4), period 1 (unless given): about half a minute once compiled (36 s measured on 2 busy "
                        "cores), its period doublings within 0.05 %% of 16 elements' and 100 steps' "
                        "(docs/howto/designer.md)")
    from . import si_file
    si_file.add_option(p, "--x and --y are then in the parameters' SI units (omega: rad/s, a: m, ...; the "
                          "slenderness is the rod's section), the figure's axes and title in SI, and curves_si.csv "
                          "holds the curves in SI")
    a.add_argument("--rpm", action="store_true", help="with --si: a crank-speed axis in rpm (in and in the figure)")
    _add_output_options(p, "chart", ", ".join(CHART_NAMES) + " (curves_si.csv with --si)")
    p.set_defaults(func=_cmd_chart)


# the crank length: the mechanism's own length (units L; the guides' lengths are the guides')
CRANK_LENGTH = next(n for n, p in schema.PARAMETERS.items() if p.owner == "mechanism" and p.units == "L")
QUICK_X, QUICK_Y = (schema.CRANK_SPEED, 0.4, 1.4), (CRANK_LENGTH, 0.02, 0.1)
QUICK = {"n_elements": 4, "steps_per_rev": 50}                   # and lines 3, max-lines 4, period 1


def _quick(args, argv_given):
    """--quick: the quick plane and settings, where the command line gives none of its own."""
    if not args.quick:
        return
    if "x" not in argv_given:
        args.x = QUICK_X
    if "y" not in argv_given:
        args.y = QUICK_Y
    for name, value in QUICK.items():
        if getattr(args, name, None) is None:
            setattr(args, name, value)
    for name, value in (("lines", 3), ("max_lines", 4), ("max_period", 1)):
        if name not in argv_given:
            setattr(args, name, value)


def _given(args):
    """The chart's own options given on the command line (those whose value is not the default)."""
    defaults = {"x": X_DEFAULT, "y": Y_DEFAULT, "lines": 6, "max_lines": 10, "max_period": 2}
    return {k for k, v in defaults.items() if getattr(args, k) != v}


def _cmd_chart(args):
    from ..declaration.cases import make_case
    from ..analyses.charts import stability_chart
    from ..analyses.limits import count
    from . import si_file
    given = _given(args)
    _quick(args, given)
    si = si_file.read(args.si) if args.si is not None else None
    if args.rpm and si is None:
        raise UsageError("--rpm (a crank-speed axis in rpm) needs the rod in SI: --si FILE")
    if si is not None:                     # an axis given is in SI; a default one in crankgen's units
        from ..analyses.charts import si_view
        args.x, args.y = (si_view.to_model(a, si.scales, args.rpm) if which in given else a
                          for which, a in (("x", args.x), ("y", args.y)))
    fields = _explicit(args) if si is None else si_file.run_fields(args, si, keep=(args.x[0], args.y[0]))
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
    if si is None:
        case = make_case(model=args.model, **fields)
    else:                          # the file's mechanism, the axes' parameters from the axes
        from dataclasses import replace
        axes = {args.x[0]: args.x[1], args.y[0]: args.y[1]}
        case = replace(si.case(model=args.model, **{k: v for k, v in fields.items() if k not in axes}), **axes)
    folder = _Outputs(args.out, CHART_NAMES, args.force)
    try:
        log = None if args.quiet else (lambda text: print(f"chart: {text}", file=sys.stderr, flush=True))
        chart = stability_chart(x=args.x, y=args.y, case=case, lines=args.lines, max_lines=args.max_lines,
                                max_period=args.max_period, progress=log)
        paths = [folder.wrote(p) for p in chart.to_csv(folder.folder)]
        paths.append(folder.wrote(chart.to_json(folder.path("chart.json"))))
        if si is None:
            png = folder.wrote(chart.plot(folder.path("chart.png")))
        else:
            from ..analyses.charts import si_view
            paths.append(folder.wrote(si_view.to_csv(chart, folder.path("curves_si.csv"), si.scales, args.rpm)))
            png = folder.wrote(si_view.plot(chart, folder.path("chart.png"), si.scales, args.rpm))
    finally:
        folder.abandon()
    print("\n".join(chart.summary()))
    if si is not None:
        from ..analyses.charts import si_view
        print("\n".join(si_view.describe(chart, si.scales, args.rpm)))
    print(f"{len(chart.curves)} curves, {len(chart.codim2)} codimension-two points, "
          f"{sum(1 for g in chart.regions if g.key is not None)} named regions in "
          f"{chart.info['wall_time']:.1f} s; wrote {', '.join(str(p) for p in paths)} and {png}")
    return 0
