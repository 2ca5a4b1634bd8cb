"""Command-line interface: `crankgen simulate ...`, `crankgen reproduce ...`."""

import argparse
import sys
from pathlib import Path

from .audit import SECTIONS as AUDIT_SECTIONS
from .errors import CrankgenError
from .ingredients import CHOICES
from .newmark import SCHEMES


def _add_mechanism_options(p):
    g = p.add_argument_group("mechanism (dimensionless, section 5 of the paper)")
    g.add_argument("--a", type=float, default=0.1, help="crank length over rod length a* = a/L, 0 < a* < 1 (default 0.1)")
    g.add_argument("--eps", type=float, default=0.01, help="slenderness eps = r/L, r the radius of gyration, > 0 (default 0.01)")
    g.add_argument("--ms", type=float, default=0.5, help="slider mass ms* = m_s/(rho A L), >= 0 (default 0.5)")
    g.add_argument("--mu", type=float, default=0.5, help="damping mu* = omega_b mu, >= 0 (default 0.5)")


def _add_run_options(p):
    g = p.add_argument_group("model and integration")
    g.add_argument("--omega", type=float, default=0.8, help="crank speed Omega* = Omega/omega_b, > 0 (default 0.8)")
    g.add_argument("--approach", choices=CHOICES["approach"], default="A",
                   help="strain energy: A full non-linear (eq. 2), B without the quartic v_x^4 term, C linear strain (default A)")
    g.add_argument("--formulation", choices=CHOICES["formulation"], default="lagrange",
                   help="lagrange: exact Euler-Lagrange equations; paper: the printed matrix form eqs. (17)-(29) (default lagrange)")
    g.add_argument("--damping", choices=CHOICES["damping"], default="paper",
                   help="paper: C = mu (K_lin + K_non), eq. (24); kelvin-voigt: strain-rate damping of each approach's strain (default paper)")
    g.add_argument("--elements", type=int, default=16, help="number of rod elements, >= 1 (default 16)")
    g.add_argument("--steps-per-rev", type=int, default=100, help="Newmark steps per crank revolution, >= 4 (default 100)")
    g.add_argument("--revolutions", type=float, default=10, help="number of crank revolutions to simulate, > 0 (default 10)")
    g.add_argument("--integrator", choices=SCHEMES, default="newton",
                   help="newton: Newton iterations on the exact tangent, its factorization reused while they converge fast; "
                        "full-newton: the tangent refreshed at every iteration; one-pass: the paper's eqs. (34)-(39) (default newton)")
    g.add_argument("--tol", type=float, default=1e-10, help="Newton tolerance on the scaled displacement increment (default 1e-10)")


def _cmd_simulate(args):
    import numpy as np

    from .parameters import Mechanism
    from .plotting import plot_deflection
    from .progress import Progress
    from .simulation import simulate

    mech = Mechanism(a=args.a, eps=args.eps, ms=args.ms, mu=args.mu)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    steps = int(round(args.revolutions * args.steps_per_rev))
    with Progress("simulate", steps, enabled=not args.quiet) as progress:
        res = simulate(mech, omega=args.omega, approach=args.approach, formulation=args.formulation,
                       n_elements=args.elements, steps_per_rev=args.steps_per_rev,
                       revolutions=args.revolutions, integrator=args.integrator, damping=args.damping,
                       store_nodes=args.nodes, tol=args.tol, progress=progress)
    res.to_csv(out / "simulation.csv")
    if args.nodes:
        np.savetxt(out / "nodes.csv", res.nodes, delimiter=",",
                   header="full nodal vector per step: u, v, psi of nodes 0..n", comments="# ")
    plot_deflection(res, out / "v_mid.png")
    last = res.v_mid[-args.steps_per_rev:]
    print(f"wrote {out / 'simulation.csv'} and {out / 'v_mid.png'}; "
          f"max |v*| over the last revolution {np.max(np.abs(last)):.6g}")
    return 0


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


def _cmd_reproduce(args):
    from .experiments import ReproduceConfig, reproduce

    config = ReproduceConfig.quick() if args.quick else ReproduceConfig.full()
    res = reproduce(args.out, config=config, force=args.force, quiet=args.quiet,
                    figures=args.figures)
    print(f"wrote {len(res['files'])} files to {res['out']} ({res['out'] / 'findings.md'}) "
          f"in {res['wall_time']:.1f} s")
    return 0


def _cmd_audit(args):
    import time

    from .audit import SECTIONS, TITLES, write_report

    sections = args.sections or list(SECTIONS)
    start = time.perf_counter()

    def progress(k):
        if not args.quiet:
            print(f"audit: section {k}, {TITLES[k]} ({time.perf_counter() - start:.0f} s)",
                  file=sys.stderr, flush=True)
    path = write_report(args.out, sections=sections, progress=progress)
    print(f"wrote {path} in {time.perf_counter() - start:.1f} s")
    return 0


def build_parser():
    parser = argparse.ArgumentParser(
        prog="crankgen",
        description="Dynamics of flexible slider-crank mechanisms (rigid crank at constant speed, "
                    "flexible finite-element connecting rod, slider on a straight guide).")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("simulate", help="one run from zero initial conditions; writes CSV and a PNG of v*(t*)",
                       description="Integrate one mechanism from the paper's zero initial conditions and "
                                   "write simulation.csv (t*, theta, v* at x*=1/2, u*(1), extension delta*) "
                                   "and v_mid.png to the output folder.")
    _add_mechanism_options(p)
    _add_run_options(p)
    p.add_argument("--out", default="out", help="output folder (created if missing; default ./out)")
    p.add_argument("--nodes", action="store_true", help="also write the nodal history nodes.csv")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_simulate)

    p = sub.add_parser("reproduce", help="recompute the paper's Figures 2-8 and findings.md (paper and consistent models)",
                       description="Recompute Figures 2-8 of the source paper for the paper model (paper "
                                   "formulation, paper damping) and the consistent model (lagrange "
                                   "formulation, kelvin-voigt damping): one PNG and one CSV per figure, "
                                   "convergence.png/.csv (element-count check) and findings.md, whose "
                                   "numbers are all computed from the runs.")
    p.add_argument("--out", default="results",
                   help="output folder (created if missing; default ./results); files already there are "
                        "kept unless --force")
    p.add_argument("--quick", action="store_true",
                   help="coarse pass: fewer speeds, eps values, slider masses and revolutions, element "
                        "ladder up to 64")
    p.add_argument("--force", action="store_true",
                   help="overwrite output files left by an earlier run in --out")
    p.add_argument("--figures", type=_figure_list, default=[2, 3, 4, 5, 6, 7, 8], metavar="LIST",
                   help="comma-separated figures to compute, e.g. 5,6 (default: all, 2-8); the "
                        "element-count check always runs")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_reproduce)

    p = sub.add_parser("audit", help="symbolic audit report audit/report.md: what each approach and formulation keeps, and what it weighs",
                       description="Write a Markdown report (LaTeX formulas): 1 energies and dissipation "
                                   "functions by order, 2 element Euler-Lagrange equations by kind, 3 the "
                                   "printed matrix form against the derivation and ERRATA.md, 4 weights of "
                                   "the term groups along steady trajectories, 5 the quartic term, 6 element "
                                   "convergence and membrane locking. Offline; about 20 s once the engine is compiled.")
    p.add_argument("--out", default="audit", help="output folder (default ./audit); report.md is replaced")
    p.add_argument("--sections", type=_number_list("section", min(AUDIT_SECTIONS), max(AUDIT_SECTIONS)),
                   default=None, metavar="LIST",
                   help="comma-separated sections to write (default: all, 1-6)")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    p.set_defaults(func=_cmd_audit)
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except CrankgenError as exc:
        print(f"crankgen {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"crankgen {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
