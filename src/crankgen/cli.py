"""Command-line interface: `crankgen simulate | steady | sweep | reproduce | audit`.

Exit codes: 0 success; 1 a run that failed (simulate: the integration stopped, and what was
computed up to the failure is written; steady: status "failed"; a file that could not be written);
2 a usage error (a bad option or parameter, an unusable --out, outputs already there without
--force), reported on one line before anything is computed or created; 130 interrupted.
"""

import argparse
import math
import sys
import warnings
from pathlib import Path

from .audit import SECTIONS as AUDIT_SECTIONS
from .errors import ConvergenceError, CrankgenError
from .ingredients import CHOICES
from .newmark import SCHEMES
from .provenance import VERSION

# the choices of the model options, from the declared model (derive/model.py)
APPROACHES, FORMULATIONS = CHOICES["approach"], CHOICES["formulation"]
DAMPING_MODELS, MEMBRANE_OPTIONS = CHOICES["damping"], CHOICES["membrane"]

# The two models the project compares (see README): --model sets these three options; an explicit
# --formulation, --damping or --membrane overrides the model's value for that option.
MODELS = {
    "paper": dict(formulation="paper", damping="paper", membrane="pointwise"),
    "consistent": dict(formulation="lagrange", damping="kelvin-voigt", membrane="averaged"),
}
MODEL_HELP = ("paper: the printed form (formulation paper, damping paper, membrane pointwise); "
              "consistent: formulation lagrange, damping kelvin-voigt, membrane averaged "
              "(default consistent). An explicit --formulation, --damping or --membrane overrides "
              "the model's value for that option")


class UsageError(CrankgenError):
    """A command-line mistake found after parsing (exit code 2)."""


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error message (and exit code 2), pointing to --help."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


# ---- options shared by the commands ------------------------------------------------------------
def _add_mechanism_options(p, grid=False):
    g = p.add_argument_group("mechanism (dimensionless, section 5 of the paper)"
                             + (": each takes a value, a list 0.1,0.2 or a range START:STOP:STEP" if grid else ""))
    kind = _float_grid if grid else float
    g.add_argument("--a", type=kind, default=0.1, help="crank length over rod length a* = a/L, 0 < a* < 1 (default 0.1)")
    g.add_argument("--eps", type=kind, default=0.01, help="slenderness eps = r/L, r the radius of gyration, > 0 (default 0.01)")
    g.add_argument("--ms", type=kind, default=0.5, help="slider mass ms* = m_s/(rho A L), >= 0 (default 0.5)")
    g.add_argument("--mu", type=kind, default=0.5, help="damping mu* = omega_b mu, >= 0 (default 0.5)")
    g.add_argument("--offset", type=kind, default=0.0,
                   help="guide offset e/L: the slider moves on the line Y = e; a* + |e| < 1 (default 0)")
    g.add_argument("--gravity", type=_pair, default=(0.0, 0.0), metavar="GX,GY",
                   help="gravity (gX, gY) in units of L omega_b^2, X along the guide towards the slider, "
                        "Y perpendicular (crank pin at a* (cos theta, sin theta)) (default 0,0)")


def _add_model_options(p, grid=False, integrator=True):
    g = p.add_argument_group("model and integration"
                             + (" (lists allowed: A,B or 8,16)" if grid else ""))
    many = " (a list of them allowed)" if grid else ""
    g.add_argument("--omega", type=_float_grid if grid else float, default=0.8,
                   help="crank speed Omega* = Omega/omega_b, > 0 (default 0.8)"
                        + ("; e.g. 0.2:1.6:0.05 (stop included)" if grid else ""))
    g.add_argument("--model", type=_choices("model", tuple(MODELS), grid), default=None,
                   help=MODEL_HELP + many)
    g.add_argument("--approach", type=_choices("approach", APPROACHES, grid), default="A",
                   help="strain energy: A full non-linear (eq. 2), B without the quartic v_x^4 term, "
                        "C linear strain (default A)" + many)
    g.add_argument("--formulation", type=_choices("formulation", FORMULATIONS, grid), default=None,
                   help="lagrange: exact Euler-Lagrange equations; paper: the printed matrix form "
                        "eqs. (17)-(29) (default: the model's)" + many)
    g.add_argument("--damping", type=_choices("damping", DAMPING_MODELS, grid), default=None,
                   help="paper: C = mu (K_lin + K_non), eq. (24); kelvin-voigt: strain-rate damping of "
                        "each approach's strain (default: the model's)" + many)
    g.add_argument("--membrane", type=_choices("membrane", MEMBRANE_OPTIONS, grid), default=None,
                   help="pointwise: the element as derived from eq. (2); averaged: element-mean "
                        "membrane strain, free of membrane locking (default: the model's)" + many)
    g.add_argument("--rotary-inertia", type=_choices("rotary-inertia", ("on", "off"), grid), default="on",
                   help="on: keep the rho I terms of the kinetic energy; off: drop them (default on)" + many)
    g.add_argument("--elements", type=_int_list("elements", 1) if grid else int, default=16,
                   help="number of rod elements, >= 1 (default 16)")
    g.add_argument("--steps-per-rev", type=_int_list("steps-per-rev", 4) if grid else int, default=100,
                   help="Newmark steps per crank revolution, >= 4 (default 100)")
    if integrator:
        g.add_argument("--integrator", type=_choices("integrator", SCHEMES, grid), default="newton",
                       help="newton: Newton iterations on the exact tangent, its factorization reused "
                            "while they converge fast; full-newton: the tangent refreshed at every "
                            "iteration; one-pass: the paper's eqs. (34)-(39) (default newton)" + many)
    return g


def _add_output_options(p, default_out, names):
    p.add_argument("--out", default=default_out,
                   help=f"output folder (created if missing; default ./{default_out}); it receives "
                        f"{names}. Files already there are refused unless --force; each file is "
                        "written atomically (a temporary file moved into place)")
    p.add_argument("--force", action="store_true", help="overwrite output files left in --out by an earlier run")
    p.add_argument("--quiet", action="store_true", help="no progress output")


# ---- argument types ----------------------------------------------------------------------------
def _pair(text):
    """argparse type: two numbers 'X,Y'."""
    parts = [p for p in text.replace(" ", "").split(",") if p]
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected two numbers GX,GY, got {text!r}")
    return tuple(_number(p) for p in parts)


def _number(text):
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None


def _clean(x):
    """A grid value without floating-point noise (0.30000000000000004 -> 0.3)."""
    return float(f"{x:.12g}")


def _float_grid(text):
    """argparse type: '0.8', '0.01,0.1' or '0.2:1.6:0.05' (stop included), or a comma list of such."""
    values = []
    for item in (s.strip() for s in text.split(",")):
        if not item:
            continue
        if ":" in item:
            parts = item.split(":")
            if len(parts) != 3:
                raise argparse.ArgumentTypeError(f"a range is START:STOP:STEP, got {item!r}")
            start, stop, step = (_number(s) for s in parts)
            if not (math.isfinite(start) and math.isfinite(stop) and math.isfinite(step)) \
                    or step <= 0 or stop < start:
                raise argparse.ArgumentTypeError(
                    f"a range START:STOP:STEP needs finite numbers, STEP > 0 and STOP >= START, got {item!r}")
            n = int(math.floor((stop - start) / step + 1e-9))
            if n >= 100000:
                raise argparse.ArgumentTypeError(f"the range {item!r} has more than 100000 values")
            values += [_clean(start + k * step) for k in range(n + 1)]
        else:
            values.append(_number(item))
    if not values:
        raise argparse.ArgumentTypeError(f"expected a number, a list or a range, got {text!r}")
    return list(dict.fromkeys(values))


def _int_list(what, low):
    def parse(text):
        try:
            values = [int(s) for s in text.replace(" ", "").split(",") if s]
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected an integer or a comma-separated list, got {text!r}") from None
        if not values or any(v < low for v in values):
            raise argparse.ArgumentTypeError(f"{what} must be integers >= {low}, got {text!r}")
        return list(dict.fromkeys(values))
    return parse


def _choices(what, allowed, many):
    def parse(text):
        values = [s.strip() for s in text.split(",") if s.strip()] if many else [text]
        for v in values or [text]:
            if v not in allowed:
                raise argparse.ArgumentTypeError(
                    f"{what} must be {' or '.join(allowed) if len(allowed) < 3 else 'one of ' + ', '.join(allowed)}"
                    f", got {v!r}")
        return list(dict.fromkeys(values)) if many else text
    return parse


def _number_list(what, low, high):
    """argparse type: a comma-separated list of integers between low and high (sorted, unique)."""
    def parse(text):
        try:
            values = sorted({int(x) for x in text.replace(" ", "").split(",") if x})
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a comma-separated list of {what} numbers, got {text!r}")
        if not values or any(v < low or v > high for v in values):
            raise argparse.ArgumentTypeError(f"{what} numbers must be between {low} and {high}, got {text!r}")
        return values
    return parse


_figure_list = _number_list("figure", 2, 8)


# ---- helpers -----------------------------------------------------------------------------------
def _model_options(args):
    """formulation, damping, membrane: the model's (default consistent), explicit options winning;
    and rotary_inertia."""
    chosen = dict(MODELS[args.model or "consistent"])
    for name in chosen:
        if getattr(args, name) is not None:
            chosen[name] = getattr(args, name)
    chosen["rotary_inertia"] = args.rotary_inertia == "on"
    return chosen


def _case(args):
    from .cases import Case
    return Case(a=args.a, eps=args.eps, ms=args.ms, mu=args.mu, omega=args.omega,
                gravity=args.gravity, offset=args.offset, approach=args.approach,
                n_elements=args.elements, steps_per_rev=args.steps_per_rev,
                integrator=args.integrator, **_model_options(args))


def _describe(case):
    return (f"approach {case.approach}, {case.formulation} formulation, {case.damping} damping, "
            f"{case.membrane} membrane, Omega* = {case.omega:g}, eps = {case.eps:g}, "
            f"n = {case.n_elements}")


def _say(args, text):
    if not args.quiet:
        print(text, file=sys.stderr, flush=True)


class _Outputs:
    """The output folder of a command: checked (and created) before computing; if the command
    stops before writing anything, the folders it created are removed again."""

    def __init__(self, folder, names, force):
        from .compile_cache import announce
        from .io import prepare_folder
        self.folder = Path(folder)
        self.created = prepare_folder(self.folder, names, force)
        self.written = []
        announce()                  # arguments and folder are fine: computing starts now

    def path(self, name):
        return self.folder / name

    def wrote(self, path):
        self.written.append(Path(path))
        return path

    def abandon(self):
        from .io import remove_if_empty
        if not self.written:
            remove_if_empty(self.created)


# ---- simulate ----------------------------------------------------------------------------------
SIM_COLUMNS = ["t", "theta", "v_mid", "u_end", "extension", "status"]


def _cmd_simulate(args):
    from .validation import in_range

    case = _case(args)                                       # validates every parameter ...
    revolutions = in_range("revolutions", args.revolutions, 0, None, True)
    in_range("tol", args.tol, 0, None, True)
    names = ["simulation.csv", "v_mid.png"] + (["nodes.csv"] if args.nodes else [])
    out = _Outputs(args.out, names, args.force)             # ... and the output folder, first
    try:
        return _simulate(args, case, revolutions, out)
    finally:
        out.abandon()


def _simulate(args, case, revolutions, out):
    import numpy as np

    from .io import atomic_write, write_csv
    from .parameters import Mechanism
    from .plotting import plot_deflection
    from .progress import Progress
    from .simulation import simulate

    mech = Mechanism(a=case.a, eps=case.eps, ms=case.ms, mu=case.mu)
    steps = max(1, int(round(revolutions * case.steps_per_rev)))
    _say(args, f"simulate: {_describe(case)}, {revolutions:g} revolutions ({steps} steps)")
    failure = None
    with Progress("simulate", steps, enabled=not args.quiet) as progress:
        try:
            res = simulate(mech, omega=case.omega, approach=case.approach, formulation=case.formulation,
                           n_elements=case.n_elements, steps_per_rev=case.steps_per_rev,
                           revolutions=revolutions, integrator=case.integrator, damping=case.damping,
                           membrane=case.membrane, store_nodes=args.nodes, tol=args.tol,
                           progress=progress)
        except ConvergenceError as exc:
            if exc.partial is None:
                raise
            failure, res = exc, exc.partial
    rows = [dict(t=t, theta=th, v_mid=v, u_end=u, extension=e, status="ok")
            for t, th, v, u, e in zip(res.t, res.theta, res.v_mid, res.u_end, res.extension)]
    if failure is not None:
        rows.append(dict(t=failure.time, theta=case.omega * failure.time, status=f"failed: {failure}"))
    out.wrote(write_csv(out.path("simulation.csv"), SIM_COLUMNS, rows))
    if args.nodes and res.nodes is not None:
        note = "" if failure is None else f"; run failed at step {failure.step}: history up to the failure"
        out.wrote(atomic_write(out.path("nodes.csv"), lambda fh: np.savetxt(
            fh, res.nodes, delimiter=",", comments="# ",
            header=f"full nodal vector per step: u, v, psi of nodes 0..n{note}")))
    out.wrote(plot_deflection(res, out.path("v_mid.png"), failure=failure))
    if failure is not None:
        print(f"crankgen simulate: run failed: {failure}; wrote the history up to the failure "
              f"({len(res.t)} points, marked in the status column) to {out.path('simulation.csv')}",
              file=sys.stderr)
        return 1
    last = res.v_mid[-case.steps_per_rev:]
    print(f"wrote {out.path('simulation.csv')} and {out.path('v_mid.png')}; "
          f"max |v*| over the last revolution {np.max(np.abs(last)):.6g}")
    return 0


# ---- steady ------------------------------------------------------------------------------------
STEADY_NAMES = ["steady.csv", "orbit.csv", "orbit.png"]
ORBIT_COLUMNS = ["theta", "t", "v_mid", "u_end", "extension"]


def _cmd_steady(args):
    from .validation import in_range, integer

    case = _case(args)
    in_range("tol", args.tol, 0, None, True)
    integer("max_revolutions", args.max_revolutions, 1)
    out = _Outputs(args.out, STEADY_NAMES, args.force)
    try:
        return _steady(args, case, out)
    finally:
        out.abandon()


def _steady(args, case, out):
    from .io import write_csv
    from .plotting import plot_orbit
    from .steady import steady_states

    _say(args, f"steady: {_describe(case)}; {args.method}, tolerance {args.tol:g}")
    st = steady_states([case], tol=args.tol, max_revolutions=args.max_revolutions,
                       method=args.method)[0]
    row = st.row()
    out.wrote(write_csv(out.path("steady.csv"), list(row), [row]))
    if st.v_mid is not None:
        rows = [dict(zip(ORBIT_COLUMNS, values))
                for values in zip(st.theta, st.t, st.v_mid, st.u_end, st.extension)]
        out.wrote(write_csv(out.path("orbit.csv"), ORBIT_COLUMNS, rows))
        out.wrote(plot_orbit(st, out.path("orbit.png")))
    else:                                    # no orbit: leave no orbit of an earlier run beside it
        for name in ("orbit.csv", "orbit.png"):
            out.path(name).unlink(missing_ok=True)

    def num(x, fmt):
        return "—" if x is None or not math.isfinite(x) else fmt.format(x)
    print(f"status {st.status}; amplitude max|v*| {num(st.amplitude, '{:.6g}')}, half peak-to-peak "
          f"{num(st.half_peak_to_peak, '{:.6g}')}; largest |Floquet multiplier| "
          f"{num(st.multiplier, '{:.4f}')}; {st.iterations} shooting iterations, {st.periods} "
          f"revolutions marched, residual {num(st.residual, '{:.2e}')}"
          + (f"; {st.message}" if st.message else ""))
    print(f"wrote {', '.join(str(p) for p in out.written)}")
    if st.status == "failed":
        print(f"crankgen steady: run failed: {st.message}", file=sys.stderr)
        return 1
    return 0


# ---- sweep -------------------------------------------------------------------------------------
GRID_FIELDS = [("a", "a"), ("eps", "eps"), ("ms", "ms"), ("mu", "mu"), ("offset", "offset"),
               ("omega", "omega"), ("approach", "approach"), ("n_elements", "elements"),
               ("steps_per_rev", "steps_per_rev"), ("integrator", "integrator")]


def _listed(value):
    return value if isinstance(value, list) else [value]


def _sweep_cases(args):
    """The grid: every combination of the listed values (models expanded first), validated."""
    import itertools

    from .cases import Case
    from .errors import ParameterError

    models = []
    for model in _listed(args.model or ["consistent"]):
        base = dict(MODELS[model])
        options = [[(name, v) for v in _listed(getattr(args, name))] if getattr(args, name) is not None
                   else [(name, base[name])] for name in base]
        options.append([("rotary_inertia", v == "on") for v in _listed(args.rotary_inertia)])
        for combo in itertools.product(*options):
            if dict(combo) not in models:
                models.append(dict(combo))
    axes = [[(field, v) for v in _listed(getattr(args, attr))] for field, attr in GRID_FIELDS]
    cases = []
    for model in models:
        for combo in itertools.product(*axes):
            try:
                cases.append(Case(**dict(combo), **model, gravity=args.gravity))
            except ParameterError as exc:
                raise ParameterError(f"{exc} (in the grid: {dict(combo, **model)})") from None
    return list(dict.fromkeys(cases))


def _cmd_sweep(args):
    from .validation import in_range, integer

    cases = _sweep_cases(args)
    in_range("tol", args.tol, 0, None, True)
    integer("max_revolutions", args.max_revolutions, 1)
    integer("batch_size", args.batch_size, 1)
    integer("workers", args.workers, 1)
    checkpoint = Path(args.checkpoint) if args.checkpoint else Path(args.out) / "sweep.jsonl"
    _check_checkpoint(checkpoint, Path(args.out))
    out = _Outputs(args.out, ["sweep.csv"], args.force)
    try:
        return _sweep(args, cases, checkpoint, out)
    finally:
        out.abandon()


def _check_checkpoint(path, out):
    if path.is_dir():
        raise UsageError(f"checkpoint {path} is a folder, not a file")
    if path.parent != out and not path.parent.is_dir():
        raise UsageError(f"checkpoint {path}: its folder {path.parent} does not exist")
    if path.exists():
        with open(path, "rb") as fh:
            head = fh.read(40)
        if head and not head.startswith(b'{"format": "crankgen-sweep-checkpoint"'[:len(head)]):
            raise UsageError(f"{path} exists and is not a crankgen sweep checkpoint; choose another "
                             "--checkpoint or --out")


def _sweep(args, cases, checkpoint, out):
    from collections import Counter

    from .progress import Progress
    from .sweep import sweep

    if args.force and checkpoint.exists():
        checkpoint.unlink()
        _say(args, f"sweep: --force: {checkpoint} removed, every case is computed afresh")
    elif checkpoint.exists():
        _say(args, f"sweep: resuming from {checkpoint}: cases recorded there are not recomputed"
                   + ("" if args.retry_failed else " (failed ones included; --retry-failed reruns them)"))
    _say(args, f"sweep: {len(cases)} cases; checkpoint {checkpoint}")
    executor = None
    if args.workers > 1:
        import concurrent.futures as cf
        executor = cf.ProcessPoolExecutor(args.workers)
    try:
        with Progress("sweep (cases)", len(cases), enabled=not args.quiet) as progress:
            table = sweep(cases, executor=executor, checkpoint=checkpoint, batch_size=args.batch_size,
                          tol=args.tol, max_revolutions=args.max_revolutions,
                          retry_failed=args.retry_failed, progress=progress)
    finally:
        if executor is not None:
            executor.shutdown(cancel_futures=True)
    from .io import write_csv
    out.wrote(write_csv(out.path("sweep.csv"), table.columns, table.rows))
    counts = Counter(row["status"] for row in table.rows)
    print(f"wrote {out.path('sweep.csv')}: {len(table)} cases, "
          + ", ".join(f"{n} {status}" for status, n in sorted(counts.items())))
    return 0


# ---- reproduce, audit --------------------------------------------------------------------------
def _cmd_reproduce(args):
    from .experiments import ReproduceConfig, reproduce

    config = ReproduceConfig.quick() if args.quick else ReproduceConfig.full()
    out = _Outputs(args.out, (), True)     # a usable folder, checked first (reproduce keeps its files)
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

    from .audit import SECTIONS, TITLES, write_report

    sections = args.sections or list(SECTIONS)
    out = _Outputs(args.out, (), True)            # report.md is regenerated: replaced, atomically
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

def _add_branch_model_options(p):
    """Model options of continue and poincare (the continued parameter's own option is ignored)."""
    g = _add_model_options(p, integrator=False)
    g.title = "model (the option of the continued parameter is replaced by its range)"
    from .bifurcation.mechanism import PARAMETERS
    g.add_argument("--parameter", choices=PARAMETERS, default="omega",
                   help="the parameter varied (default omega)")
    g.add_argument("--from", dest="start", type=float, required=True, help="first value of the parameter")
    g.add_argument("--to", dest="stop", type=float, required=True, help="last value of the parameter")


def _branch_model(args):
    from .parameters import Mechanism

    base = dict(a=args.a, eps=args.eps, ms=args.ms, mu=args.mu, offset=args.offset, gravity=args.gravity)
    if args.parameter in base:       # replaced by the range; the other values must be valid
        base[args.parameter] = args.start
    mech = Mechanism(**base)
    model = dict(omega=args.omega, approach=args.approach, n_elements=args.elements,
                 steps_per_rev=args.steps_per_rev, **_model_options(args))
    return mech, model


CONTINUE_NAMES = ("branches.csv", "special_points.csv", "multipliers.csv", "continuation.png")
POINCARE_NAMES = ("poincare_summary.csv", "poincare_samples.csv", "poincare.png")


def _cmd_continue(args):
    from .bifurcation import continuation

    mech, model = _branch_model(args)
    folder = _Outputs(args.out, CONTINUE_NAMES, args.force)
    try:
        log = None if args.quiet else (lambda text: print(f"continue: {text}", file=sys.stderr, flush=True))
        d = continuation(mech, args.parameter, args.start, args.stop, max_period=args.max_period,
                         progress=log, **model)
        paths = [folder.wrote(p) for p in d.to_csv(folder.folder)]
        png = folder.wrote(d.plot(folder.path("continuation.png"), title=_title(args, "continuation"),
                                  ylabel="max |v*(1/2)| over the orbit", xlabel=_AXIS[args.parameter]))
    finally:
        folder.abandon()
    for s in d.special_points:
        print(f"{s.kind} on the period-{s.period} branch at {args.parameter} = {s.parameter:.7g}, "
              f"amplitude {s.amplitude:.6g}, multiplier {s.multiplier.real:.6g}{s.multiplier.imag:+.6g}j")
    print(f"{len(d.branches)} branches, {sum(len(b) for b in d.branches)} points, "
          f"{len(d.special_points)} special points in {d.info['wall_time']:.1f} s; wrote "
          f"{', '.join(str(p) for p in paths)} and {png}")
    return 0


_AXIS = {"omega": "Omega*", "eps": "eps", "ms": "ms*", "mu": "mu*", "a": "a*", "offset": "offset e/L"}


def _title(args, what):
    m = _model_options(args)
    return (f"{what} in {args.parameter}: approach {args.approach}, {m['formulation']} / {m['damping']} "
            f"damping, {m['membrane']} membrane, n = {args.elements}, eps = {args.eps:g}"
            if args.parameter != "eps" else
            f"{what} in eps: approach {args.approach}, {m['formulation']} / {m['damping']} damping, "
            f"{m['membrane']} membrane, n = {args.elements}, Omega* = {args.omega:g}")


def _cmd_poincare(args):
    import numpy as np

    from .bifurcation import continuation, poincare
    from .progress import Progress

    mech, model = _branch_model(args)
    if args.values < 2:
        raise UsageError("--values must be >= 2")
    names = POINCARE_NAMES + (CONTINUE_NAMES[:3] if args.with_continuation else ())
    folder = _Outputs(args.out, names, args.force)
    try:
        values = np.linspace(args.start, args.stop, args.values)
        total = args.values * (2 if args.direction == "both" else 1)
        with Progress("poincare", total, enabled=not args.quiet) as progress:
            pc = poincare(mech, args.parameter, values, args.direction, transient=args.transient,
                          samples=args.samples, progress=progress, **model)
        diagram = None
        if args.with_continuation:
            log = None if args.quiet else (lambda text: print(f"continue: {text}", file=sys.stderr, flush=True))
            diagram = continuation(mech, args.parameter, min(args.start, args.stop),
                                   max(args.start, args.stop), max_period=args.max_period, progress=log,
                                   **model)
            for p in diagram.to_csv(folder.folder):
                folder.wrote(p)
        paths = [folder.wrote(p) for p in pc.to_csv(folder.folder)]
        png = folder.wrote(pc.plot(folder.path("poincare.png"), diagram, title=_title(args, "Poincare sweep"),
                                   ylabel="v*(1/2) at theta = 0, once per revolution",
                                   xlabel=_AXIS[args.parameter]))
    finally:
        folder.abandon()
    counts = {}
    for q in pc.points:
        counts[q.classification] = counts.get(q.classification, 0) + 1
    print(", ".join(f"{k}: {v}" for k, v in sorted(counts.items())) +
          f" in {pc.info['wall_time']:.1f} s; wrote {', '.join(str(p) for p in paths)} and {png}")
    return 0




# ---- parser ------------------------------------------------------------------------------------
def build_parser():
    from .provenance import kernels_hash

    parser = _Parser(
        prog="crankgen",
        description="Dynamics of flexible slider-crank mechanisms (rigid crank at constant speed, "
                    "flexible finite-element connecting rod, slider on a straight guide).",
        epilog="Exit codes: 0 success; 1 a run that failed (what it computed before failing is "
               "written); 2 a usage error (bad option or parameter, unusable --out, outputs already "
               "there without --force); 130 interrupted.")
    parser.add_argument("--version", action="version",
                        version=f"crankgen {VERSION} (generated kernels {kernels_hash()})")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("simulate", help="one run from zero initial conditions; writes CSV and a PNG of v*(t*)",
                       description="Integrate one mechanism from the paper's zero initial conditions and "
                                   "write simulation.csv (t*, theta, v* at x*=1/2, u*(1), extension delta*, "
                                   "status) and v_mid.png to the output folder. If the integration fails, "
                                   "the history up to the failure is written, a last row with status "
                                   "'failed: <reason>' marks the failure (also marked in the plot), and "
                                   "the exit code is 1.")
    _add_mechanism_options(p)
    g = _add_model_options(p)
    g.add_argument("--revolutions", type=float, default=10, help="number of crank revolutions to simulate, > 0 (default 10)")
    g.add_argument("--tol", type=float, default=1e-10, help="Newton tolerance on the scaled displacement increment (default 1e-10)")
    p.add_argument("--nodes", action="store_true", help="also write the nodal history nodes.csv")
    _add_output_options(p, "out", "simulation.csv, v_mid.png (and nodes.csv with --nodes)")
    p.set_defaults(func=_cmd_simulate)

    p = sub.add_parser("steady", help="one periodic steady state: amplitude, status, Floquet multiplier; CSV and PNG of the orbit",
                       description="Find the periodic response over one crank revolution by shooting "
                                   "(crankgen.steady_state) and write steady.csv (one row: the case, "
                                   "status, amplitude max|v*|, half peak-to-peak, iterations, residual, "
                                   "largest |Floquet multiplier|, message), orbit.csv (theta, t*, v*, "
                                   "u*(1), delta* over the revolution) and orbit.png. Status: periodic, "
                                   "unstable (orbit exists, multiplier > 1), not-periodic (no orbit, no "
                                   "orbit files) or failed (exit code 1). A missing number is an empty "
                                   "CSV field.")
    _add_mechanism_options(p)
    g = _add_model_options(p)
    _add_steady_options(g)
    g.add_argument("--method", choices=("shooting", "march"), default="shooting",
                   help="shooting: Newton on the revolution map; march: revolution by revolution (default shooting)")
    _add_output_options(p, "out", "steady.csv, orbit.csv and orbit.png")
    p.set_defaults(func=_cmd_steady)

    p = sub.add_parser("sweep", help="steady states over a grid of parameters; checkpointed and resumable; CSV out",
                       description="Steady states (as `crankgen steady`) of every combination of the "
                                   "values given, e.g. --omega 0.2:1.6:0.05 --eps 0.01,0.1 --model "
                                   "paper,consistent. Finished cases are appended to a checkpoint "
                                   "(default OUT/sweep.jsonl) as they complete; running the same command "
                                   "again after an interruption resumes from it. sweep.csv (one row per "
                                   "case, in grid order; missing numbers are empty fields) is written at "
                                   "the end. Cases that fail or have no periodic state are rows with their "
                                   "status and message; the exit code is 0 once every case has a row.")
    _add_mechanism_options(p, grid=True)
    g = _add_model_options(p, grid=True)
    _add_steady_options(g)
    g.add_argument("--batch-size", type=int, default=64, help="cases per batch (per task with --workers) (default 64)")
    g.add_argument("--workers", type=int, default=1,
                   help="processes (a process pool) when > 1; default 1: this process, whose compiled "
                        "batches already use every core")
    p.add_argument("--checkpoint", default=None,
                   help="checkpoint file (JSON Lines; default OUT/sweep.jsonl); cases recorded there "
                        "with the same tolerances are reused. --force starts it afresh")
    p.add_argument("--retry-failed", action="store_true", help="recompute cases recorded as failed in the checkpoint")
    _add_output_options(p, "out", "sweep.csv and the checkpoint sweep.jsonl")
    p.set_defaults(func=_cmd_sweep)

    p = sub.add_parser("reproduce", help="recompute the paper's Figures 2-8 and findings.md (paper and consistent models)",
                       description="Recompute Figures 2-8 of the source paper for the paper model (paper "
                                   "formulation, paper damping) and the consistent model (lagrange "
                                   "formulation, kelvin-voigt damping, averaged membrane): one PNG and one "
                                   "CSV per figure, convergence.png/.csv (element-count check) and "
                                   "findings.md, whose numbers are all computed from the runs.")
    p.add_argument("--out", default="results",
                   help="output folder (created if missing; default ./results); a rerun keeps what is "
                        "complete and current there (manifest.json) and computes the rest")
    p.add_argument("--quick", action="store_true",
                   help="coarse pass: fewer speeds, eps values, slider masses and revolutions, element "
                        "ladder up to 64")
    p.add_argument("--force", action="store_true",
                   help="recompute every selected step, and overwrite files of the output names that "
                        "no recorded run made")
    p.add_argument("--figures", type=_figure_list, default=[2, 3, 4, 5, 6, 7, 8], metavar="LIST",
                   help="comma-separated figures to compute, e.g. 5,6 (default: all, 2-8); the "
                        "element-count check always runs")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_reproduce)

    p = sub.add_parser("audit", help="symbolic audit report audit/report.md: what each approach and formulation keeps, and what it weighs",
                       description="Write a Markdown report (LaTeX formulas) that opens with a summary "
                                   "(the effect of the quartic term; where the printed equations differ "
                                   "from the exact Lagrange equations and how much it matters), then: 1 "
                                   "energies and dissipation functions by order, 2 element Euler-Lagrange "
                                   "equations by kind, 3 the printed matrix form against the derivation, "
                                   "with each transcription problem of the printed equations checked, 4 "
                                   "weights of the term groups along steady trajectories, 5 the quartic "
                                   "term, 6 element convergence and membrane locking. Offline; under a minute on 2 cores "
                                   "once the engine is compiled.")
    p.add_argument("--out", default="audit",
                   help="output folder (default ./audit); report.md is regenerated (replaced atomically)")
    p.add_argument("--sections", type=_number_list("section", min(AUDIT_SECTIONS), max(AUDIT_SECTIONS)),
                   default=None, metavar="LIST",
                   help="comma-separated sections to write (default: all, 1-6)")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_audit)

    p = sub.add_parser("continue", help="continuation of the periodic response: branches, stability, folds, period doublings, Neimark-Sacker points",
                       description="Follow the periodic response as one parameter varies (pseudo-arclength "
                                   "continuation of the crank-revolution map), with its stability, folds, "
                                   "period doublings and Neimark-Sacker points, and the period-2 (4, ...) "
                                   "branches born at period doublings. Writes branches.csv, "
                                   "special_points.csv, multipliers.csv and continuation.png.")
    _add_mechanism_options(p)
    _add_branch_model_options(p)
    p.add_argument("--max-period", type=int, default=4,
                   help="follow period doublings up to this period (default 4)")
    _add_output_options(p, "continuation", ", ".join(CONTINUE_NAMES))
    p.set_defaults(func=_cmd_continue)

    p = sub.add_parser("poincare", help="brute-force bifurcation diagram: sweep a parameter, sample v* once per revolution, classify",
                       description="March the mechanism at evenly spaced values of one parameter, each "
                                   "value starting from the last state of the previous one (sweep up, "
                                   "down or both, so hysteresis shows), sample v*(1/2) at theta = 0 once "
                                   "per revolution after a transient and classify each value (period-k, "
                                   "quasi-periodic, irregular, unsettled) with its evidence. Writes "
                                   "poincare_summary.csv, poincare_samples.csv and poincare.png.")
    _add_mechanism_options(p)
    _add_branch_model_options(p)
    p.add_argument("--values", type=int, default=57, help="number of parameter values, >= 2 (default 57)")
    p.add_argument("--direction", choices=("up", "down", "both"), default="both",
                   help="sweep direction (default both: up, then down)")
    p.add_argument("--transient", type=int, default=100, help="revolutions marched before sampling (default 100)")
    p.add_argument("--samples", type=int, default=64, help="revolutions sampled per value (default 64)")
    p.add_argument("--with-continuation", action="store_true",
                   help="also run the continuation over the same range and draw its branches over the samples")
    p.add_argument("--max-period", type=int, default=4,
                   help="with --with-continuation: follow period doublings up to this period (default 4)")
    _add_output_options(p, "poincare", ", ".join(POINCARE_NAMES) + " (and, with --with-continuation, "
                        + ", ".join(CONTINUE_NAMES[:3]) + ")")
    p.set_defaults(func=_cmd_poincare)
    return parser


def _add_steady_options(g):
    g.add_argument("--tol", type=float, default=1e-8,
                   help="periodicity tolerance on the scaled change of the state over one revolution (default 1e-8)")
    g.add_argument("--max-revolutions", type=int, default=400,
                   help="revolutions marched at most when shooting does not converge (default 400)")


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    print(f"crankgen: warning: {message}", file=sys.stderr, flush=True)


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    name = f"crankgen {args.command}"
    previous = warnings.showwarning
    warnings.showwarning = _one_line_warning
    try:
        return args.func(args)
    except ConvergenceError as exc:                          # a run that failed
        print(f"{name}: run failed: {exc}", file=sys.stderr)
        return 1
    except CrankgenError as exc:                             # parameters, --out, existing outputs
        print(f"{name}: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:                                   # writing an output failed mid-run
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"{name}: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        resume = ("; the finished cases are in the checkpoint: the same command resumes"
                  if args.command == "sweep" else "")
        print(f"{name}: interrupted{resume}", file=sys.stderr)
        return 130
    finally:
        warnings.showwarning = previous


if __name__ == "__main__":
    sys.exit(main())
