"""Options shared by the commands, made from the schema (derive/declaration.py): a flag per parameter of
a case (its kind, range, units and help; --model and the options' flags from the presets and
options), the output folder; argument types; the Case a command line describes."""

import argparse
import math
import re
import sys
from pathlib import Path

from ..declaration import schema
from ..errors import CrankgenError, ParameterError
from ..declaration import values as _values

# The named models (presets of the schema): --model sets their options; an explicit --formulation,
# --damping or --membrane overrides the model's value for that option.
MODELS = {name: dict(p.options) for name, p in schema.PRESETS.items()}
MODEL_HELP = ("; ".join(f"{name}: {p.doc}" for name, p in schema.PRESETS.items())
              + f" (default {schema.DEFAULT_PRESET}). An explicit option flag overrides the model's value")
_ON_OFF = {"on": True, "off": False}


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


# ---- flags from the schema ---------------------------------------------------------------------
def _default_text(p):
    default = p.default
    if p.kind == "pair":
        return ",".join(f"{x:g}" for x in default)
    if p.kind == "curve":
        return _values.text(p, default)
    return f"{default:g}" if isinstance(default, float) else str(default)


def _help(p, many):
    where = ""
    every = schema.GUIDES if p.owner == "guide" else schema.MOTIONS
    if p.owner in ("guide", "motion") and set(p.readers) != set(every):
        where = f" [{' and '.join(p.readers)} {p.owner}]"
    rng = f", {_values.range_text(p)}" if (p.kind == "real" and (p.low, p.high) != (None, None)) or p.kind == "count" else ""
    by_model = "".join(f"; with --model {name}: {preset.settings[p.name]:g}"
                       for name, preset in schema.PRESETS.items() if p.name in preset.settings)
    return f"{p.doc}{rng}{where} (default {_default_text(p)}{by_model})" + many


def _parameter_type(p, grid):
    if p.kind == "real":
        return _float_grid if grid else _number
    if p.kind == "pair":
        return _pair
    if p.kind == "curve":
        return _curve(p)
    if p.kind == "count":
        return _int_list(p.cli, p.low) if grid else int
    if p.kind == "sign":
        return _choices(p.cli, ("1", "-1", "+1"), grid, cast=int)
    return _choices(p.cli, p.choices, grid)


def _add_parameter(g, p, grid):
    many = " (a list of them allowed)" if grid and p.kind in ("count", "sign", "choice") else ""
    metavar = p.metavar or ("{" + ",".join(p.choices) + "}" if p.kind == "choice" else
                             "{1,-1}" if p.kind == "sign" else p.cli.upper().replace("-", "_"))
    g.add_argument(f"--{p.cli}", dest=p.name, type=_parameter_type(p, grid), default=None,
                   metavar=metavar, help=_help(p, many))


def _add_mechanism_options(p, grid=False):
    g = p.add_argument_group("mechanism (dimensionless, section 5 of the paper)"
                             + (": each takes a value, a list 0.1,0.2 or a range START:STOP:STEP" if grid else ""))
    for name in schema.MECHANISM_PARAMETERS:
        _add_parameter(g, schema.PARAMETERS[name], grid)


def _add_model_options(p, grid=False, integrator=True, run=None, title=None):
    """The run's parameters (run: the names to offer; default all, the integrator only when
    `integrator`), --model and the options' flags."""
    g = p.add_argument_group(title or ("crank motion, model and integration"
                                       + (" (lists allowed: A,B or 8,16)" if grid else "")))
    many = " (a list of them allowed)" if grid else ""
    for name in schema.RUN_PARAMETERS:
        if (name == "integrator" and not integrator) or (run is not None and name not in run):
            continue
        _add_parameter(g, schema.PARAMETERS[name], grid)
    g.add_argument("--model", type=_choices("model", tuple(schema.PRESETS), grid), default=None,
                   metavar="{" + ",".join(schema.PRESETS) + "}", help=MODEL_HELP + many)
    for o in schema.OPTIONS.values():
        choices = tuple(_ON_OFF) if isinstance(o.default, bool) else o.choices
        shown = ({v: k for k, v in _ON_OFF.items()}[o.default] if isinstance(o.default, bool) else o.default)
        g.add_argument(f"--{o.cli}", dest=o.name, default=None, metavar="{" + ",".join(map(str, choices)) + "}",
                       type=_choices(o.cli, choices, grid, cast=_ON_OFF.get if isinstance(o.default, bool) else None),
                       help=f"{o.doc} (default: the model's; without a model {shown})" + many)
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


def _curve(p):
    """argparse type: a torque curve's per-unit pairs 'S:F,S:F,...' (crankgen.torque_curve)."""
    def parse(text):
        try:
            return _values.canonical(p, text)
        except ParameterError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    return parse


def _number(text):
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None


def _decimals(text):
    """Decimal places a number is written with ('0.05' -> 2, '1e-3' -> 3, '2' -> 0)."""
    from decimal import Decimal, InvalidOperation
    try:
        return max(0, -Decimal(text.strip()).as_tuple().exponent)
    except (InvalidOperation, TypeError):
        return 12


def _clean(x, decimals=12):
    """A grid value without floating-point noise: rounded to the decimal places its range is
    written with (-0.3 + 3 x 0.1 -> 0.0, not 5.55e-17), one canonical zero."""
    return round(x, decimals) + 0.0


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
            places = max(_decimals(parts[0]), _decimals(parts[2]))
            values += [_clean(start + k * step, places) for k in range(n + 1)]
        else:
            values.append(_number(item) + 0.0)
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


def _choices(what, allowed, many, cast=None):
    def parse(text):
        values = [s.strip() for s in text.split(",") if s.strip()] if many else [text]
        for v in values or [text]:
            if v not in allowed:
                raise argparse.ArgumentTypeError(
                    f"{what} must be {' or '.join(allowed) if len(allowed) < 3 else 'one of ' + ', '.join(allowed)}"
                    f", got {v!r}")
        if cast is not None:
            values = [cast(v) for v in values]
        return list(dict.fromkeys(values)) if many else values[0]
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
CASE_FIELDS = tuple(schema.PARAMETERS) + tuple(schema.OPTIONS)


def _flag(name):
    """The command-line flag (without --) of a case field."""
    from ..declaration import schema
    spec = schema.PARAMETERS.get(name) or schema.OPTIONS.get(name)
    return name if spec is None else spec.cli          # a flag of its own name (--rpm)


def _explicit(args):
    """{field: value} of every case field the command line gives (None: not given)."""
    return {name: getattr(args, name) for name in CASE_FIELDS if getattr(args, name, None) is not None}


def _model_options(args):
    """The model options of the command line: the model's (default consistent), explicit options
    winning."""
    return schema.resolve_options(args.model, **{n: getattr(args, n, None) for n in schema.OPTIONS})


def _case(args):
    from ..declaration.cases import make_case
    return make_case(model=args.model, **_explicit(args))


def _describe(case):
    main, other = schema.describe(case.parameters())
    extra = "" if case.rotary_inertia else ", no rotary inertia"
    from ..discrete.time_scheme import label
    from ..plots.figures import membrane_words
    return (f"approach {case.approach}, {case.formulation} formulation, {case.damping} damping"
            f"{membrane_words(case.as_dict())}, {label(case.rho_inf)}, "
            + ", ".join(main + [f"n = {case.n_elements}"] + other) + extra)


def _say(args, text):
    if not args.quiet:
        print(text, file=sys.stderr, flush=True)


class _Outputs:
    """The output folder of a command: checked (and created) before computing; if the command
    stops before writing anything, the folders it created are removed again."""

    def __init__(self, folder, names, force, subfolders=()):
        from ..engine.cache import announce
        from ..results.io import prepare_folder
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
        from ..results.io import remove_if_empty
        if not self.written:
            remove_if_empty(self.created)


# ---- simulate ----------------------------------------------------------------------------------
