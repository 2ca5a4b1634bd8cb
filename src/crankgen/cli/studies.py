"""`crankgen reproduce`, `crankgen audit`, `crankgen continue`, `crankgen poincare`: studies."""

import argparse
import difflib
import sys

from ..declaration import schema
from . import si_file
from .options import UsageError, _Outputs, _add_model_options, _explicit, _model_options, _say


def _cmd_reproduce(args):
    from ..experiments import ReproduceConfig, reproduce

    from ..experiments.runner import DATA, all_files

    config = ReproduceConfig.quick() if args.quick else ReproduceConfig.full()
    # a usable folder and data/ subfolder, and no output name taken by a folder, a device, ...:
    # checked first (which files are kept or refused is reproduce's decision)
    out = _Outputs(args.out, all_files(), True, subfolders=(DATA,))
    try:
        res = reproduce(args.out, config=config, force=args.force, quiet=args.quiet,
                        figures=args.figures)
        out.wrote(res["out"])
    finally:
        out.abandon()
    print(f"{len(res['computed'])} step(s) computed, {len(res['kept'])} kept (complete and current); "
          f"wrote {len(res['files'])} files to {res['out']} ({res['out'] / 'findings.md'}) "
          f"in {res['wall_time']:.1f} s")
    return 0


def _cmd_audit(args):
    import time

    from ..audit import SECTIONS, TITLES, write_report

    sections = args.sections or list(SECTIONS)
    out = _Outputs(args.out, ("report.md",), True)   # regenerated: replaced, atomically
    start = time.perf_counter()

    def progress(k):
        _say(args, f"audit: section {k}, {TITLES[k]} ({time.perf_counter() - start:.0f} s)")
    try:
        path = out.wrote(write_report(args.out, sections=sections, progress=progress))
    finally:
        out.abandon()
    print(f"wrote {path} in {time.perf_counter() - start:.1f} s")
    return 0


# --- crankgen continue / crankgen poincare ----------------------------------------------------

def _continuable(text):
    """A continued parameter's name, or its flag's name; refused in one readable line with the
    closest names (the declaration grows: --help lists them all)."""
    if text in schema.CONTINUABLE or text in PARAMETER_FLAGS:
        return text
    close = difflib.get_close_matches(text, list(schema.CONTINUABLE) + list(PARAMETER_FLAGS), n=3)
    hint = f"did you mean {' or '.join(close)}? " if close else ""
    raise argparse.ArgumentTypeError(f"invalid choice: {text!r} ({hint}one of the {len(schema.CONTINUABLE)} "
                                     "continuable parameters, such as omega, eps or mu, listed by --help)")


def _add_branch_model_options(p):
    """Model options of continue and poincare (the continued parameter's own option is ignored)."""
    g = _add_model_options(p, integrator=False)
    g.title = "model (the continued parameter takes its values from --from and --to)"
    g.add_argument("--parameter", type=_continuable, default=schema.CRANK_SPEED,
                   metavar="{" + ",".join(schema.CONTINUABLE) + "}",
                   help=f"the parameter varied (default {schema.CRANK_SPEED}); a parameter whose flag has "
                        "another name is also accepted by its flag's name (" + ", ".join(
                            f"{flag} for {name}" for flag, name in PARAMETER_FLAGS.items()) + ")")
    g.add_argument("--from", dest="start", type=float, required=True, help="first value of the parameter")
    g.add_argument("--to", dest="stop", type=float, required=True, help="last value of the parameter")


# the continuable parameters whose flag has another name (--rocker for c, --ground for d): accepted
# by --parameter under either name
PARAMETER_FLAGS = {p.cli: name for name, p in schema.PARAMETERS.items()
                   if p.continuable and p.cli != name}


def _parameter(args):
    """The continued parameter's name (c for --parameter rocker, d for ground)."""
    return PARAMETER_FLAGS.get(args.parameter, args.parameter)


def _branch_model(args):
    """The case of the first point, checked (the continued parameter set to the range's start).
    Refused: the continued parameter also given by its own flag (its values are --from/--to), and
    a parameter the case's guide or crank motion does not read."""
    from ..declaration.cases import make_case

    args.parameter = _parameter(args)
    fields = _explicit(args)
    p = schema.PARAMETERS[args.parameter]
    if args.parameter in fields:
        raise UsageError(f"--{p.cli} is the parameter varied (--parameter {args.parameter}): its values "
                         "are --from and --to; leave out --" + p.cli)
    si = getattr(args, "si_mechanism", None)
    if si is not None:                          # the file's mechanism, the range's start in its place
        from dataclasses import replace
        return replace(si.case(model=args.model, **si_file.run_fields(args, si)), **{args.parameter: args.start})
    guide = fields.get("guide", schema.PARAMETERS["guide"].default)
    motion = fields.get("motion", schema.PARAMETERS["motion"].default)
    if not p.read_by(guide, motion):
        owner = "--guide" if p.owner == "guide" else "--crank"
        current = guide if p.owner == "guide" else motion
        raise UsageError(f"--parameter {args.parameter} ({p.label.split('(', 1)[-1].rstrip(')')}) belongs "
                         f"to the {' and '.join(p.readers)} {p.owner} ({owner} {' or '.join(p.readers)}); "
                         f"this case's {p.owner} is {current}")
    fields[args.parameter] = args.start
    return make_case(model=args.model, **fields)


def _si_range(args, values=None):
    """With --si: the file's SIMechanism (args.si_mechanism) and --from, --to (and the swept values)
    converted from the parameter's SI unit into crankgen's units (args.si_range keeps them in SI);
    the slenderness, the rod's section, cannot be varied in SI.  Returns the values (converted)."""
    args.si_mechanism = None
    if args.si is None:
        if getattr(args, "rpm", False):
            raise UsageError("--rpm (--from and --to in rpm) needs the rod in SI: --si FILE")
        return values
    from ..declaration.si import to_crankgen
    from ..declaration.validation import in_range
    args.parameter = _parameter(args)
    if args.parameter in schema.UNIT_PARAMETERS.values():
        raise UsageError(f"with --si, {schema.PARAMETERS[args.parameter].label} is the rod's section (sqrt(I/A)/L): "
                         "vary it without --si, or give the file's I and A")
    si = si_file.read(args.si)
    start, stop = in_range("--from", args.start), in_range("--to", args.stop)
    if getattr(args, "rpm", False):                 # --from, --to in rpm: into rad/s
        if args.parameter != schema.CRANK_SPEED:
            raise UsageError(f"--rpm says --from and --to are crank speeds in rpm; --parameter is {args.parameter}")
        from ..declaration.si import rad_per_s
        start, stop = rad_per_s(start), rad_per_s(stop)
        values = None if values is None else [rad_per_s(v) for v in values]
    args.si_range = (start, stop)
    args.start, args.stop = (to_crankgen(args.parameter, v, si.scales) for v in (start, stop))
    args.si_mechanism = si
    return None if values is None else [to_crankgen(args.parameter, v, si.scales) for v in values]


def _checked_branch_model(args, continuation, values=()):
    """Every option of continue / poincare checked before anything is created or computed: the
    case at both ends of the range (and at every swept value), the continuation's own settings
    when it runs, and the steady state it starts from.  Returns the case of the first point.
    With --si a refusal in crankgen's units says what the range given in SI is in them."""
    from ..errors import ParameterError
    try:
        return _checked(args, continuation, values)
    except ParameterError as e:
        if getattr(args, "si_mechanism", None) is None:
            raise
        from ..declaration.si import si_unit
        unit = si_unit(args.parameter)
        lo, hi = args.si_range
        raise UsageError(f"{e} (with --si: --from {lo:g} --to {hi:g}{'' if unit == '1' else ' ' + unit} "
                         f"is {args.start:g} to {args.stop:g} in crankgen's units)") from None


def _checked(args, continuation, values):
    from ..declaration import schema
    from ..analyses.bifurcation.api import make_case
    from ..declaration.validation import in_range, integer
    from .runs import _resolved

    start, stop = in_range("--from", args.start), in_range("--to", args.stop)
    case = _branch_model(args)
    speed = args.parameter == schema.CRANK_SPEED
    if speed and min(start, stop) <= 0:
        lo, hi = getattr(args, "si_range", None) or (start, stop)       # as given: in SI with --si
        raise UsageError(f"--parameter {args.parameter}: the range must stay above 0 (a crank at rest has no "
                         f"revolution to follow), got --from {lo:g} --to {hi:g}")
    for value in (start, stop, *values):
        make_case(None, args.parameter, value, case)
    if continuation:
        if start == stop:
            raise UsageError(f"--from and --to must differ for a continuation, got {start:g} twice")
        integer("--max-period", args.max_period, 1)
        first = min(start, stop) if speed else start
        _resolved(make_case(None, args.parameter, first, case),
                  "the continuation starts from a steady state: " if speed else "")
    return case


CONTINUE_NAMES = ("branches.csv", "special_points.csv", "multipliers.csv", "states.csv", "continuation.png")
POINCARE_NAMES = ("poincare_summary.csv", "poincare_samples.csv", "poincare.png")


def _cmd_continue(args):
    import numpy as np

    from ..analyses.bifurcation import continuation, poincare
    from ..progress import Progress
    from ..analyses.limits import count

    if args.sweep is not None:
        count("sweep", args.sweep, "--sweep")
    _si_range(args)
    section = None
    if args.section is not None:                 # with --si: the rod's, its stresses in Pa
        from ..declaration.sections import parse
        from ..analyses.stresses import check_section
        section = parse(args.section)
        check_section(section, args.si_mechanism)
    case = _checked_branch_model(args, continuation=True)
    folder = _Outputs(args.out, CONTINUE_NAMES + ("continuation.json",)
                      + (POINCARE_NAMES[:2] if args.sweep else ()), args.force)
    try:
        log = None if args.quiet else (lambda text: print(f"continue: {text}", file=sys.stderr, flush=True))
        d = continuation(parameter=args.parameter, start=args.start, stop=args.stop, case=case,
                         max_period=args.max_period, progress=log, section=section)
        view = _in_si(args, d)
        paths = [folder.wrote(p) for p in view.to_csv(folder.folder)]
        paths.append(folder.wrote(d.to_json(folder.path("continuation.json"))))     # crankgen's units
        pc = None
        if args.sweep:
            values = np.linspace(args.start, args.stop, args.sweep)
            with Progress("continue: sweep up and down", 2 * args.sweep, enabled=not args.quiet) as progress:
                pc = poincare(parameter=args.parameter, values=values, direction="both", case=case,
                              transient=100, samples=16, progress=progress)
            paths += [folder.wrote(p) for p in _in_si(args, pc).to_csv(folder.folder)]
        if view is d:
            png = folder.wrote(d.plot(folder.path("continuation.png"), title=_title(args, "continuation"),
                                      ylabel="max |v*(1/2)| over the orbit", xlabel=_axis(args.parameter), sweep=pc))
        else:
            png = folder.wrote(view.plot(folder.path("continuation.png"), sweep=pc))
    finally:
        folder.abandon()
    name, unit, amp = _printed(args, view)
    for s in view.special_points:
        print(f"{s.kind} on the period-{s.period} branch at {name} = {s.parameter:.7g}{unit}, "
              f"amplitude {s.amplitude:.6g}{amp}, multiplier {s.multiplier.real:.6g}{s.multiplier.imag:+.6g}j")
    for k, (b, v) in enumerate(zip(d.branches, view.branches)):
        print(f"branch {k} (period {b.period}, {getattr(v, 'origin', b.origin)}): {len(b)} points, {name} from "
              f"{v.parameter[0]:.6g} to {v.parameter[-1]:.6g}{unit}; ends: {getattr(v, 'stop_reason', b.stop_reason)}")
    print(f"{len(d.branches)} branches, {sum(len(b) for b in d.branches)} points, "
          f"{len(d.special_points)} special points in {d.info['wall_time']:.1f} s; wrote "
          f"{', '.join(str(p) for p in paths)} and {png}")
    return 0


def _in_si(args, diagram):
    """The diagram, or with --si its SI view (bifurcation/si_view.py)."""
    si = getattr(args, "si_mechanism", None)
    return diagram if si is None else diagram.si_view(si)


def _printed(args, view):
    """(the parameter's name, ' unit', ' unit of the amplitude') for the printed lines."""
    if getattr(args, "si_mechanism", None) is None:
        return args.parameter, "", ""
    p = schema.PARAMETERS[args.parameter]
    return p.si or p.name, f" {view.parameter_unit}" if view.parameter_unit != "1" else "", " m"


def _axis(parameter):
    from ..analyses.bifurcation.diagram import axis
    return axis(parameter)


def _title(args, what):
    from ..analyses.bifurcation.diagram import describe
    c = _branch_model(args)
    return describe(c.as_dict(), what, args.parameter)


def _cmd_poincare(args):
    import numpy as np

    from ..analyses.bifurcation import continuation, poincare
    from ..progress import Progress

    from ..analyses.limits import count
    from ..declaration.validation import integer

    integer("--values", args.values, 2)
    count("values", args.values, "--values")
    count("transient", args.transient, "--transient")
    count("samples", args.samples, "--samples")
    values = _si_range(args, np.linspace(args.start, args.stop, args.values))
    case = _checked_branch_model(args, args.with_continuation, values)
    names = POINCARE_NAMES + (CONTINUE_NAMES[:4] if args.with_continuation else ())
    folder = _Outputs(args.out, names, args.force)
    try:
        total = args.values * (2 if args.direction == "both" else 1)
        with Progress("poincare", total, enabled=not args.quiet) as progress:
            pc = poincare(parameter=args.parameter, values=values, direction=args.direction, case=case,
                          transient=args.transient, samples=args.samples, progress=progress)
        diagram = None
        if args.with_continuation:
            log = None if args.quiet else (lambda text: print(f"continue: {text}", file=sys.stderr, flush=True))
            diagram = continuation(parameter=args.parameter, start=min(args.start, args.stop),
                                   stop=max(args.start, args.stop), case=case,
                                   max_period=args.max_period, progress=log)
            for p in _in_si(args, diagram).to_csv(folder.folder):
                folder.wrote(p)
        view = _in_si(args, pc)
        paths = [folder.wrote(p) for p in view.to_csv(folder.folder)]
        if view is pc:
            png = folder.wrote(pc.plot(folder.path("poincare.png"), diagram, title=_title(args, "Poincare sweep"),
                                       ylabel="v*(1/2) at theta = 0, once per revolution",
                                       xlabel=_axis(args.parameter)))
        else:
            png = folder.wrote(view.plot(folder.path("poincare.png"), diagram=diagram))
    finally:
        folder.abandon()
    counts = {}
    for q in pc.points:
        counts[q.classification] = counts.get(q.classification, 0) + 1
    print(", ".join(f"{k}: {v}" for k, v in sorted(counts.items())) +
          f" in {pc.info['wall_time']:.1f} s; wrote {', '.join(str(p) for p in paths)} and {png}")
    return 0
