"""Command-line interface: `crankgen simulate | steady | sweep | reproduce | audit | continue | poincare |
chart | modes | campbell | animate | compare | compile`.

Exit codes: 0 success; 1 a run that failed (simulate: the integration stopped, and what was
computed up to the failure is written; steady: status "failed"; continue: no periodic state to
start from; a file that could not be written);
2 a usage error (a bad option or parameter, an unusable --out, outputs already there without
--force, a run too large for the machine's memory, a checkpoint in use), reported on one line
before anything is computed or created; 130 interrupted (Ctrl-C), 143 terminated (SIGTERM).
"""

import argparse
import sys
import warnings

from ..audit import SECTIONS as AUDIT_SECTIONS
from ..errors import ConvergenceError, CrankgenError, NoResultError
from ..results.provenance import VERSION
from .options import (_Parser, _add_mechanism_options, _add_model_options, _add_output_options,
                      _figure_list, _float_grid, _number_list)
from . import si_file
from .compile import _cmd_compile
from .animate import add_command as add_animate_command
from .chart import add_command as add_chart_command
from .compare import add_command as add_compare_command
from .modes import add_commands as add_modes_commands
from .runs import _cmd_simulate, _cmd_steady, _cmd_sweep
from .studies import (CONTINUE_NAMES, POINCARE_NAMES, _add_branch_model_options, _cmd_audit,
                      _cmd_continue, _cmd_poincare, _cmd_reproduce)


# ---- parser ------------------------------------------------------------------------------------
def build_parser():
    from ..results.provenance import kernels_hash

    parser = _Parser(
        prog="crankgen",
        description="Dynamics of flexible slider-crank mechanisms and four-bar linkages (a rigid "
                    "crank with a prescribed motion: constant speed, a run-up or a speed "
                    "fluctuation; a flexible finite-element connecting rod; its end mass on a "
                    "straight guide, a slider, or on a rigid rocker, a four-bar).",
        epilog="Exit codes: 0 success; 1 a run that failed (what it computed before failing is "
               "written); 2 a usage error (bad option or parameter, unusable --out, outputs already "
               "there without --force, a run too large for this machine's memory); 130 interrupted, "
               "143 terminated.")
    parser.add_argument("--version", action="version",
                        version=f"crankgen {VERSION} (generated kernels {kernels_hash()})")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("simulate", help="one run from zero initial conditions; writes CSV and a PNG of v*(t*)",
                       description="Integrate one mechanism from the paper's zero initial conditions and "
                                   "write simulation.csv (every column named with its unit: t*, the crank "
                                   "angle, v* at x*=1/2, u*(1), the extension delta*, every declared step "
                                   "output of the guide: crank speed, slider position, chord angle, driving "
                                   "torque, pin and end forces, ...; the section forces at mid-span; the "
                                   "range-of-the-theory flags and a status; in SI with --si) and "
                                   "v_mid.png (against the crank speed for a run-up) to the output folder. "
                                   "If the integration fails, "
                                   "the history up to the failure is written, a last row with status "
                                   "'failed: <reason>' marks the failure (also marked in the plot), and "
                                   "the exit code is 1.")
    _add_mechanism_options(p)
    g = _add_model_options(p)
    g.add_argument("--revolutions", type=float, default=10, help="number of crank revolutions to simulate, > 0 (default 10; a motor-driven crank: no-load revolutions, 2 pi / Omega_nl each)")
    g.add_argument("--tol", type=float, default=1e-10, help="Newton tolerance on the scaled displacement increment (default 1e-10)")
    p.add_argument("--nodes", action="store_true", help="also write the nodal history nodes.csv")
    si_file.add_option(p, "simulation.csv is written in SI, every column named with its SI unit (t_s, "
                          "theta_rad, v_mid_m, ..., torque_N_m, crank_on_rod_x_N, ...; nodes.csv: u, v in m), "
                          "v_mid.png in mm against s")
    si_file.add_rpm_option(p)
    _add_section_option(p)
    _add_output_options(p, "out", "simulation.csv, v_mid.png (and nodes.csv with --nodes)")
    p.set_defaults(func=_cmd_simulate)

    p = sub.add_parser("steady", help="one periodic steady state: amplitude, status, Floquet multiplier; CSV and PNG of the orbit",
                       description="Find the periodic response over one crank revolution by shooting "
                                   "(crankgen.steady_state) and write steady.csv (one row: the case, "
                                   "status, amplitude max|v*|, half peak-to-peak, the range of the theory, "
                                   "the peak loads, iterations, residual, largest |Floquet multiplier|, "
                                   "message), orbit.csv (over the revolution, every column named with its "
                                   "unit: t*, the crank angle, v*, u*(1), delta*, every declared step output "
                                   "of the guide, driving torque and joint forces included, the section "
                                   "forces at mid-span, the range of the theory) and orbit.png (v*, delta* and the "
                                   "driving torque against the crank angle); in SI with "
                                   "--si. Status: periodic, "
                                   "unstable (orbit exists, multiplier > 1), not-periodic (no orbit, no "
                                   "orbit files) or failed (exit code 1). A missing number is an empty "
                                   "CSV field.")
    _add_mechanism_options(p)
    g = _add_model_options(p)
    _add_steady_options(g)
    g.add_argument("--method", choices=("shooting", "march"), default="shooting",
                   help="shooting: Newton on the revolution map; march: revolution by revolution (default shooting)")
    si_file.add_option(p, "steady.csv adds the case and the results in SI, orbit.csv and orbit.png are in SI "
                          "(t_s, theta_rad, v_mid_m, ..., torque_N_m, ...)")
    si_file.add_rpm_option(p)
    _add_section_option(p)
    _add_output_options(p, "out", "steady.csv, orbit.csv and orbit.png")
    p.set_defaults(func=_cmd_steady)

    p = sub.add_parser("sweep", help="steady states over a grid of parameters; checkpointed and resumable; CSV out",
                       description="Steady states (as `crankgen steady`) of every combination of the "
                                   "values given, e.g. --omega 0.2:1.6:0.05 --eps 0.01,0.1 --model "
                                   "paper,consistent. Finished cases are appended to a checkpoint "
                                   "(default OUT/sweep.jsonl) batch by batch; running the same command "
                                   "again after an interruption resumes from it, and a command with more "
                                   "values (--force to replace sweep.csv) reuses it. sweep.csv (one row per "
                                   "case, in grid order: the case's parameters, empty where its guide or "
                                   "crank motion does not read them, its model and options, status, "
                                   "amplitude, the range of the theory, the peak loads over the orbit, "
                                   "...; missing numbers are empty fields), sweep_columns.csv (what every "
                                   "column is, with its units) and sweep.png are written at the end. Cases "
                                   "that fail or have no periodic state are rows with their status and "
                                   "message; the exit code is 0 once every case has a row.")
    _add_mechanism_options(p, grid=True)
    g = _add_model_options(p, grid=True)
    _add_steady_options(g)
    g.add_argument("--batch-size", type=int, default=8,
                   help="cases per batch (per task with --workers); each finished batch is added to the "
                        "checkpoint and reported (default 8)")
    g.add_argument("--workers", type=int, default=1,
                   help="processes (a process pool) when > 1; default 1: this process, whose compiled "
                        "batches already use every core")
    p.add_argument("--checkpoint", default=None,
                   help="checkpoint file (JSON Lines; default OUT/sweep.jsonl); cases recorded there "
                        "with the same tolerances are reused, so a sweep resumes, or is extended with "
                        "more values, without recomputing them. One sweep at a time uses it "
                        "(lock file CHECKPOINT.lock)")
    p.add_argument("--fresh", action="store_true",
                   help="discard the checkpoint's records and compute every case again")
    p.add_argument("--retry-failed", action="store_true", help="recompute cases recorded as failed in the checkpoint")
    si_file.add_option(p, "every value of a parameter the file holds (--omega, --a, --ms, ...) is then in the "
                          "file's SI unit for it and replaces the file's field, and sweep.csv adds every row's "
                          "columns in SI (crank_speed_rad_per_s, amplitude_m, peak_torque_N_m, ...)")
    p.add_argument("--rpm", type=_float_grid, default=None, metavar="VALUES",
                   help="with --si: crank speeds in rpm, a value, a list or START:STOP:STEP (in place of "
                        "--omega in rad/s and of the file's crank speed)")
    _add_output_options(p, "out", "sweep.csv (one row per case), sweep_columns.csv (every column's units "
                        "and meaning), sweep.png (the amplitude and the peak driving torque against the "
                        "parameter swept with the most values) and the checkpoint sweep.jsonl (--force "
                        "replaces them and keeps the checkpoint's records)")
    p.set_defaults(func=_cmd_sweep)

    p = sub.add_parser("reproduce", help="recompute the paper's Figures 2-8 and findings.md (paper and consistent models)",
                       description="Recompute Figures 2-8 of the source paper for the paper model (paper "
                                   "formulation, paper damping) and the consistent model (lagrange "
                                   "formulation, kelvin-voigt damping, averaged membrane): one PNG and one "
                                   "CSV per figure, convergence.png/.csv (element-count check), the "
                                   "continuation of approach A over 0.1 <= Omega* <= 1.6 for both models "
                                   "(bifurcations.csv, drawn over Figure 6), the geometrically exact rod "
                                   "beside both models in Figures 5 and 6 and, with Figure 6, the consistent "
                                   "model's special points re-read on it (continuation of both, slider-crank "
                                   "and four-bar: exact_rod.png, exact_rod_points.csv; its response at "
                                   "Omega* 1.2 classified: exact_rod_character.csv), and findings.md: the "
                                   "paper's claims beside both models, every number computed from the runs. A "
                                   "rerun keeps what is complete and current (manifest.json).")
    p.add_argument("--out", default="results",
                   help="output folder (created if missing; default ./results); a rerun keeps what is "
                        "complete and current there (manifest.json) and computes the rest")
    p.add_argument("--quick", action="store_true",
                   help="coarse pass: fewer speeds, eps values, slider masses and revolutions, element "
                        "ladder up to 64, continuation with 4 elements, 50 steps per revolution, period 2")
    p.add_argument("--force", action="store_true",
                   help="recompute every selected step, overwrite files of the output names that no "
                        "recorded run made, and replace a run of the other preset (a folder holds one "
                        "run: --quick into a full run's folder, or the reverse, is refused without it)")
    p.add_argument("--figures", type=_figure_list, default=[2, 3, 4, 5, 6, 7, 8], metavar="LIST",
                   help="comma-separated figures to compute, e.g. 5,6 (default: all, 2-8); the "
                        "element-count check always runs")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_reproduce)

    p = sub.add_parser("compile", help="compile the engine and every model's kernels into the cache, once",
                       description="Compile the compiled engine and the kernels of every model (every "
                                   "formulation, approach, membrane, damping, guide and crank motion) into "
                                   "the compiled-code cache, on two processes, so that no later run "
                                   "waits for a compilation. Run by the owner of an installation it fills "
                                   "the installation's cache, which every user loads (read-only is "
                                   "fine); otherwise the cache of the user running it (or "
                                   "$CRANKGEN_CACHE_DIR). Items already compiled are kept.")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_compile)

    p = sub.add_parser("audit", help="symbolic audit report audit/report.md: what each approach and formulation keeps, and what it weighs",
                       description="Write a Markdown report (LaTeX formulas) that opens with a summary "
                                   "(the effect of the quartic term; where the printed equations differ "
                                   "from the exact Lagrange equations and how much it matters), then: 1 "
                                   "energies and dissipation functions by order, 2 element Euler-Lagrange "
                                   "equations by kind, 3 the printed matrix form against the derivation, "
                                   "with each transcription problem of the printed equations checked, 4 "
                                   "weights of the term groups along steady trajectories, 5 the quartic "
                                   "term, 6 element convergence and membrane locking, 7 approach A against the exact "
                                   "strain (its series, weighed along the same steady revolutions). Offline; a minute or two on 2 cores "
                                   "once the engine is compiled.")
    p.add_argument("--out", default="audit",
                   help="output folder (default ./audit); report.md is regenerated (replaced atomically)")
    p.add_argument("--sections", type=_number_list("section", min(AUDIT_SECTIONS), max(AUDIT_SECTIONS)),
                   default=None, metavar="LIST",
                   help="comma-separated sections to write (default: all, 1-7)")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_audit)

    p = sub.add_parser("continue", help="continuation of the periodic response: branches, stability, folds, period doublings, Neimark-Sacker points",
                       description="Follow the periodic response as one parameter varies (pseudo-arclength "
                                   "continuation of the crank-revolution map), with its stability, folds, "
                                   "period doublings and Neimark-Sacker points, and the period-2 (4, ...) "
                                   "branches born at period doublings; every point with the physical "
                                   "quantities of its orbit (peak torque, pin and end forces, axial "
                                   "force, |v*|, outer-fibre strain; stress with --section; with --crank "
                                   "motor also the mean speed, revolution time, crank-speed range, "
                                   "peak and RMS motor torque and mean motor power). Writes "
                                   "branches.csv, special_points.csv, multipliers.csv, states.csv, "
                                   "continuation.json (read back by "
                                   "crankgen.BifurcationDiagram.from_json) and continuation.png.")
    _add_mechanism_options(p)
    _add_branch_model_options(p)
    p.add_argument("--max-period", type=int, default=4,
                   help="follow period doublings up to this period (default 4)")
    p.add_argument("--section", metavar="SPEC", default=None,
                   help="the rod's cross-section (rectangle:B,H, circle:D, tube:D,T or A,I,C), for the "
                        "peak outer-fibre stress of every point's orbit (in units of Young's modulus E; "
                        "only its shape counts; with --si the rod's section, the stress in Pa) beside the "
                        "peak torque, forces and strain")
    p.add_argument("--sweep", type=int, default=None, metavar="VALUES",
                   help="also march the mechanism at VALUES evenly spaced values, up then down (each from "
                        "the previous value's state: the hysteresis a run-up and a run-down show), and draw "
                        "the marched amplitudes over the branches; writes poincare_summary.csv and "
                        "poincare_samples.csv too")
    si_file.add_option(p, f"--from and --to are then in the parameter's SI unit ({si_file.range_text()}), the "
                          "CSV files and the figure in SI (the parameter with its unit, amplitudes and the "
                          "quantities in m, N, N m, Pa, the figure in mm)")
    si_file.add_rpm_option(p, single=False)
    _add_output_options(p, "continuation", ", ".join(CONTINUE_NAMES + ("continuation.json",)))
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
    si_file.add_option(p, f"--from and --to are then in the parameter's SI unit ({si_file.range_text()}), the "
                          "CSV files and the figure in SI (samples in m, the figure in mm)")
    si_file.add_rpm_option(p, single=False)
    _add_output_options(p, "poincare", ", ".join(POINCARE_NAMES) + " (and, with --with-continuation, "
                        + ", ".join(CONTINUE_NAMES[:4]) + ")")
    p.set_defaults(func=_cmd_poincare)
    add_modes_commands(sub)
    add_animate_command(sub)
    add_chart_command(sub)
    add_compare_command(sub)
    return parser


def _add_section_option(p):
    p.add_argument("--section", metavar="SPEC", default=None,
                   help="the rod's cross-section, to print the peak loads and the outer-fibre stresses "
                        "(largest tension and compression with where and when, the largest range per "
                        "revolution): rectangle:B,H (H in the plane of the mechanism), circle:D, "
                        "tube:D,T or A,I,C (A,I,C_TOP,C_BOTTOM); in m with --si (stresses in Pa; the "
                        "section must be the rod's of the file), otherwise only its shape counts "
                        "(stresses in units of Young's modulus E, loads in crankgen's units)")


def _add_steady_options(g):
    g.add_argument("--tol", type=float, default=1e-8,
                   help="periodicity tolerance on the scaled change of the state over one revolution (default 1e-8)")
    g.add_argument("--max-revolutions", type=int, default=400,
                   help="revolutions marched at most when shooting does not converge (default 400)")


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    print(f"crankgen: warning: {message}", file=sys.stderr, flush=True)


def _unrecognized(parser, args, extra):
    """Options the command does not know: the command's own one-line error (pointing to
    `crankgen COMMAND --help`), with the nearest option names it has."""
    import difflib

    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    command = sub.choices[args.command]
    known = [o for a in command._actions for o in a.option_strings]
    near = [m for o in extra if o.startswith("-")
            for m in difflib.get_close_matches(o.split("=")[0], known, n=1)]
    hint = f"; did you mean {' or '.join(dict.fromkeys(near))}?" if near else ""
    command.error(f"unrecognized arguments: {' '.join(extra)}{hint}")


class Terminated(KeyboardInterrupt):
    """SIGTERM, handled as an interruption (the run stops cleanly: pool workers ended, temporary
    files removed), exit code 143."""


def _terminate(signum, frame):
    raise Terminated()


def main(argv=None):
    """Run one command; return its exit code.  Progress, log and result lines are best effort
    (crankgen.progress.BestEffortStream): a full disk or a closed pipe behind stdout or stderr
    never stops a computation, nor turns a finished one into a failure."""
    import signal
    import threading

    from ..progress import BestEffortStream

    streams = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = BestEffortStream.wrap(sys.stdout), BestEffortStream.wrap(sys.stderr)
    previous = warnings.showwarning
    warnings.showwarning = _one_line_warning
    handler = None
    if threading.current_thread() is threading.main_thread() \
            and signal.getsignal(signal.SIGTERM) == signal.SIG_DFL:
        handler = signal.signal(signal.SIGTERM, _terminate)
    try:
        from ..notices import BeyondTheoryWarning, quiet
        with quiet(BeyondTheoryWarning):     # every command reports the range in its own lines and files
            return _main(argv)
    finally:
        if handler is not None:
            signal.signal(signal.SIGTERM, handler)
        warnings.showwarning = previous
        sys.stdout, sys.stderr = streams


def _main(argv):
    parser = build_parser()
    args, extra = parser.parse_known_args(argv)
    if extra:
        _unrecognized(parser, args, extra)
    name = f"crankgen {args.command}"
    from ..engine.cache import set_quiet
    set_quiet(getattr(args, "quiet", False))
    try:
        return args.func(args)
    except (ConvergenceError, NoResultError) as exc:         # a run that failed
        print(f"{name}: run failed: {exc}", file=sys.stderr)
        return 1
    except CrankgenError as exc:                             # parameters, --out, existing outputs
        print(f"{name}: error: {exc}", file=sys.stderr)
        return 2
    except MemoryError:
        print(f"{name}: error: out of memory (the run needs more memory than this machine "
              "gives it; ask for less)", file=sys.stderr)
        return 1
    except OSError as exc:                                   # writing an output failed mid-run
        print(f"{name}: error: {_os_error_text(exc)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as exc:
        detail = getattr(exc, "detail", "")
        print(f"{name}: {'terminated' if isinstance(exc, Terminated) else 'interrupted'}"
              + (f"; {detail}" if detail else ""), file=sys.stderr)
        return 143 if isinstance(exc, Terminated) else 130


def _os_error_text(exc):
    """FILE: what went wrong (the file crankgen was writing; never a temporary file)."""
    text = exc.strerror or str(exc)
    if exc.filename is None:
        return text
    if exc.filename2 is not None and str(exc.filename).endswith(".tmp"):
        return f"{exc.filename2}: {text}"
    return f"{exc.filename}: {text}"


if __name__ == "__main__":
    sys.exit(main())
