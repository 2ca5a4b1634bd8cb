"""Options shared by the commands: the mechanism, the model (--model paper|consistent and its
overrides) and the output folder; argument types; the Case a command line describes."""

import argparse
import math
import re
import sys
from pathlib import Path

from ..errors import CrankgenError
from ..ingredients import CHOICES
from ..newmark import SCHEMES

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
    """argparse with a one-line error message (and exit code 2), pointing to --help.

    A value that starts with a minus sign followed by a digit, a point or inf / nan is a value,
    not an option: `--offset -0.05`, `--gravity -1e-3,0`, `--offset -0.05,0.05` and ranges
    `-0.1:0.1:0.05` (argparse alone takes only plain negative numbers such as -1 or -.5 as
    values).  No option of crankgen looks like that, so real option names keep working."""

    NEGATIVE_VALUE = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = self.NEGATIVE_VALUE

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
    from ..cases import Case
    return Case(a=args.a, eps=args.eps, ms=args.ms, mu=args.mu, omega=args.omega,
                gravity=args.gravity, offset=args.offset, approach=args.approach,
                n_elements=args.elements, steps_per_rev=args.steps_per_rev,
                integrator=args.integrator, **_model_options(args))


def _describe(case):
    extra = "" if case.rotary_inertia else ", no rotary inertia"
    if any(case.gravity):
        extra += f", gravity ({case.gravity[0]:g}, {case.gravity[1]:g})"
    if case.offset:
        extra += f", offset {case.offset:g}"
    return (f"approach {case.approach}, {case.formulation} formulation, {case.damping} damping, "
            f"{case.membrane} membrane, Omega* = {case.omega:g}, eps = {case.eps:g}, "
            f"n = {case.n_elements}{extra}")


def _say(args, text):
    if not args.quiet:
        print(text, file=sys.stderr, flush=True)


class _Outputs:
    """The output folder of a command: checked (and created) before computing; if the command
    stops before writing anything, the folders it created are removed again."""

    def __init__(self, folder, names, force, subfolders=()):
        from ..compile_cache import announce
        from ..io import prepare_folder
        self.folder = Path(folder)
        self.created = prepare_folder(folder, names, force, subfolders)
        self.written = []
        announce()                  # arguments and folder are fine: computing starts now

    def path(self, name):
        return self.folder / name

    def wrote(self, path):
        self.written.append(Path(path))
        return path

    def abandon(self):
        from ..io import remove_if_empty
        if not self.written:
            remove_if_empty(self.created)


# ---- simulate ----------------------------------------------------------------------------------
