"""`crankgen animate`: run the mechanism (a transient from rest, or its steady orbit) and write
its motion as a GIF (or an MP4 where ffmpeg is installed)."""

from .options import (_Outputs, _add_mechanism_options, _add_model_options, _add_output_options, _case,
                      _describe, _say)


def add_command(sub):
    p = sub.add_parser("animate", help="watch the mechanism move: its deforming motion as a GIF (or MP4)",
                       description="Run the mechanism and write its motion, in the inertial frame, as "
                                   "mechanism.gif (or mechanism.mp4 with --format mp4 where ffmpeg is "
                                   "installed): the crank, the rod (its deflections magnified by the "
                                   "factor the title states), the slider on its guide or the rocker "
                                   "on its pivot. By default a transient from rest (--revolutions); "
                                   "--steady: the periodic orbit (one revolution). The first frame is "
                                   "the first step: the rigid mechanism's position for a run from rest.")
    _add_mechanism_options(p)
    g = _add_model_options(p)
    g.add_argument("--revolutions", type=float, default=2,
                   help="crank revolutions of the transient from rest, > 0 (default 2)")
    g.add_argument("--steady", action="store_true",
                   help="animate the steady periodic orbit (shooting, as `crankgen steady`) instead")
    a = p.add_argument_group("the animation")
    a.add_argument("--magnify", type=float, default=None,
                   help="magnification of the elastic displacements, > 0 (default: the largest "
                        "deflection drawn as about 8 %% of the rod's length, rounded to 1, 2 or 5 "
                        "times a power of ten)")
    a.add_argument("--frames", type=int, default=None,
                   help="number of frames, >= 1 (default 24 per revolution, at most 240)")
    a.add_argument("--fps", type=float, default=20, help="frames per second (default 20)")
    a.add_argument("--format", choices=("gif", "mp4"), default="gif",
                   help="gif (Pillow) or mp4 (needs ffmpeg) (default gif)")
    p.add_argument("--si", metavar="FILE", default=None,
                   help="the mechanism in SI from a JSON file (as `crankgen simulate --si`), drawn in "
                        "metres and seconds")
    from . import si_file
    si_file.add_rpm_option(p)
    _add_output_options(p, "animation", "mechanism.gif (or mechanism.mp4)")
    p.set_defaults(func=_cmd_animate)


def _cmd_animate(args):
    from matplotlib import animation as mpl_animation

    from ..errors import ParameterError
    from ..analyses.limits import count
    from ..declaration.validation import in_range

    from . import si_file
    si = si_file.mechanism(args)
    case = _case(args) if si is None else si_file.case(args, si)
    revolutions = in_range("revolutions", args.revolutions, 0, None, True)
    if args.magnify is not None:
        in_range("--magnify", args.magnify, 0, None, True)
    if args.frames is not None:
        count("frames", args.frames, "--frames")
    in_range("--fps", args.fps, 0, 100, True)
    if args.format == "mp4" and not mpl_animation.writers.is_available("ffmpeg"):
        raise ParameterError("--format mp4 needs ffmpeg, which is not installed here; write a gif")
    if args.steady:
        from .runs import _resolved
        _resolved(case, speed=si_file.speed_words(args, None))
    name = f"mechanism.{args.format}"
    out = _Outputs(args.out, [name], args.force)
    try:
        result = _run(args, case, revolutions)
        from ..plots.animation import Frames, animate
        from ..progress import Progress
        from ..declaration.si import scales_of
        scales = None if si is None else scales_of(si)
        movie = Frames(result, args.magnify, args.frames, scales=scales)
        with Progress("animate (frames)", len(movie), enabled=not args.quiet) as progress:
            out.wrote(animate(result, out.path(name), magnification=movie.magnification,
                              frames=len(movie), fps=args.fps, scales=scales, progress=progress))
    finally:
        out.abandon()
    print(f"wrote {out.path(name)}: {len(movie)} frames, deflections magnified {movie.magnification:g}x")
    return 0


def _run(args, case, revolutions):
    from ..errors import ConvergenceError
    from ..progress import Progress

    if args.steady:
        from ..analyses.steady import steady_states
        _say(args, f"animate: the steady orbit of {_describe(case)}")
        st = steady_states([case])[0]
        if st.states is None:
            raise ConvergenceError(f"no periodic orbit to animate: {st.status}, {st.message}")
        return st
    from ..analyses.simulation import run_length, simulate
    steps = run_length(case, revolutions)[1]
    _say(args, f"animate: {_describe(case)}, {revolutions:g} revolutions ({steps} steps)")
    with Progress("animate", steps, enabled=not args.quiet) as progress:
        try:
            return simulate(case=case, revolutions=revolutions, progress=progress)
        except ConvergenceError as exc:
            if exc.partial is None or len(exc.partial.t) < 2:
                raise
            _say(args, f"animate: the run failed ({exc}); animating it up to the failure")
            return exc.partial
