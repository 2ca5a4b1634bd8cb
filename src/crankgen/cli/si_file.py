"""`--si FILE`: the mechanism and its crank motion in SI from a JSON file, for every command that
runs a mechanism (simulate, steady, sweep, continue, poincare, modes, campbell, animate).

The file holds the fields of a crankgen.SIMechanism (crankgen.declaration.si): the rod's L, E, rho, A, I and
every parameter of the mechanism, its guide and its crank motion by its SI name, in the SI unit of
its declared units.  With --si a parameter with a unit (the crank length, the end mass, the
damping, gravity, the offset, a four-bar's c and d, the crank speeds) and the choice of guide and
crank motion come from the file only; a dimensionless one (the start angle, a run-up's ramp in
revolutions, a fluctuation's amplitude and order, a four-bar's branch) from the file or its flag,
not both; the slenderness is the section's.  The run's settings (elements, steps, model options)
stay flags."""

import json

from ..declaration import schema
from .options import UsageError, _explicit


def fields_text():
    """The file's fields with their units, for --help: {"L": m, ..., "crank_speed": rad/s, ...}."""
    from ..declaration.units import ROD, Scales

    def what(p):
        if p.kind == "choice":
            return "|".join(f'"{c}"' for c in p.choices)
        if p.kind == "sign":
            return "1|-1"
        if p.kind == "count":
            return "integer"
        if p.kind == "curve":
            return 'per-unit pairs [[S, F], ...] or "S:F,..."'
        unit = Scales.si_name(p.units)
        return ("number" if unit == "1" else unit) + (" (two)" if p.kind == "pair" else "")
    parts = [f'"{n}": {u}' for n, u, _ in ROD] + [f'"{si}": {what(p)}' for si, p in schema.SI_FIELDS.items()]
    from ..declaration.plausibility import CHECKS
    from ..declaration.si import RPM_FIELDS
    parts += [f'"{name}": rpm' for name in RPM_FIELDS]
    parts.append('"unchecked": [the plausibility checks to skip, of ' + ", ".join(CHECKS) + "]")
    return "{" + ", ".join(parts) + "}"


def add_option(p, what):
    """--si FILE, its help naming every field with its unit and `what` the command does with it."""
    p.add_argument("--si", metavar="FILE", default=None,
                   help=f"the mechanism and its crank motion in SI from a JSON file, {fields_text()} (the "
                        "rod's L, E, rho, A, I and the fields its guide and crank motion need are required; "
                        "damping, the time constant mu of the model's damping (Kelvin-Voigt strain-rate "
                        "damping by default, eq. 24 with --damping paper), defaults to 0; a left-out "
                        "dimensionless field takes its flag's default); it replaces the mechanism and "
                        f"crank-motion flags with units; {what}")


def range_text():
    """The SI unit of each parameter a continuation can vary with --si, from the declaration
    ("crank_speed (omega) in rad/s, a in m, ..."); the slenderness left out (the rod's section)."""
    from ..declaration.si import si_unit
    out = []
    for name in schema.CONTINUABLE:
        if name in schema.UNIT_PARAMETERS.values():
            continue
        p, unit = schema.PARAMETERS[name], si_unit(name)
        label = f"{p.si} ({name})" if p.si else name
        out.append(f"{label} in {unit}" if unit != "1" else f"{label} as a number")
    return ", ".join(out)


def add_rpm_option(p, single=True):
    """--rpm: the crank speed in rpm (single: a value, with --si in place of the file's crank speed),
    or (single=False) a switch: --from and --to are crank speeds in rpm."""
    if single:
        p.add_argument("--rpm", type=float, default=None, metavar="RPM",
                       help="the crank speed in rpm (rpm = rad/s x 60 / (2 pi)), with --si: the file then "
                            "gives no crank speed (one file for the rod, the speed here)")
    else:
        p.add_argument("--rpm", action="store_true",
                       help="with --si and the crank speed varied: --from and --to in rpm (rpm = rad/s x 60 "
                            "/ (2 pi)); the files stay in rad/s")


def _crank_field():
    from ..declaration.si import SI_NAME
    return SI_NAME[schema.CRANK_SPEED]


def mechanism(args):
    """The crankgen.SIMechanism of --si (None without it), with --rpm VALUE as its crank speed;
    --rpm without --si is refused (a speed in rpm needs the rod in SI)."""
    rpm = getattr(args, "rpm", None)
    rpm = None if isinstance(rpm, bool) else rpm
    if args.si is None:
        if rpm is not None:
            raise UsageError(f"--rpm is a crank speed in SI: it needs the rod in SI, --si FILE (without it "
                             f"--{schema.PARAMETERS[schema.CRANK_SPEED].cli} takes Omega*, the crank speed over "
                             "the rod's first bending frequency)")
        return None
    return read(args.si, rpm)


def speed_words(args, value):
    """How the user gave the crank speed whose value (rad/s) is `value`: '--rpm 0', '"crank_speed": 0
    in FILE' (or its _rpm field), or None without --si."""
    if args.si is None:
        return None
    rpm = getattr(args, "rpm", None)
    if rpm is not None and not isinstance(rpm, bool):
        return f"--rpm {rpm:g}"
    field = _crank_field()
    try:
        data = json.loads(open(args.si, encoding="utf-8").read())
    except (OSError, ValueError):
        data = {}
    if f"{field}_rpm" in data:
        return f'"{field}_rpm": {data[f"{field}_rpm"]!r} in {args.si}'
    return f'"{field}": {data.get(field, value)!r} in {args.si}'


def read(path, rpm=None, replace_speed=False):
    """The crankgen.SIMechanism of a JSON file (UsageError naming what is wrong); rpm: the crank
    speed in rpm from the command line (the file must then give none, unless replace_speed: a
    sweep's grid replaces the file's)."""
    from ..results.io import read_regular
    from ..declaration.si import SIMechanism
    names = SIMechanism.field_names()

    def unique(pairs):                 # a field given twice is a mistake, not the last one's value
        seen = set()
        for key, _ in pairs:
            if key in seen:
                raise UsageError(f"--si {path}: the field {key!r} is given twice; give it once")
            seen.add(key)
        return dict(pairs)
    try:
        data = json.loads(read_regular(path), object_pairs_hook=unique)
    except OSError as exc:
        raise UsageError(f"--si {path}: {exc.strerror or exc}; give the path of a JSON file") from None
    except ValueError as exc:
        raise UsageError(f"--si {path}: not valid JSON ({exc})") from None
    if not isinstance(data, dict):
        raise UsageError(f"--si {path}: expected a JSON object with the fields {', '.join(names)}")
    unknown = sorted(set(data) - set(names))
    if unknown:
        import difflib
        near = difflib.get_close_matches(unknown[0], names, n=1)
        hint = f"; did you mean {near[0]!r}?" if near else ""
        raise UsageError(f"--si {path}: unknown field {unknown[0]!r}{hint} (the fields are {', '.join(names)})")
    if rpm is not None:
        field = _crank_field()
        given = [k for k in (field, f"{field}_rpm") if k in data]
        if replace_speed:
            for k in given:
                data.pop(k)
        elif given:
            raise UsageError(f"--rpm {rpm:g} and {path}'s \"{given[0]}\" are the same crank speed: give one")
        data[f"{field}_rpm"] = rpm
    return SIMechanism(**data)


def run_fields(args, si, keep=()):
    """The command line's case fields that may go with the SI file: the run's settings, the model
    options and the dimensionless parameters the file leaves out.  A flag for a parameter the
    file gives, for one with a unit, or choosing the guide or crank motion is refused (UsageError
    naming the file's field).  keep: names the command reads itself, passed on unchecked."""
    from ..declaration.si import SI_NAME, dimensioned
    given = _explicit(args)
    in_file = si.values()
    for name in given:
        p = schema.PARAMETERS.get(name)
        if name in keep:
            continue
        if p is None or not (p.slots or p.selects):
            continue
        field = SI_NAME.get(name)
        if name in in_file:
            where = f"as {field}" if field else "from the rod's section"
            raise UsageError(f"--si gives {p.label} ({where}): leave out --{p.cli}")
        if dimensioned(p) or p.selects:
            raise UsageError(f"with --si, {p.label} comes from the file: give \"{field}\" there "
                             f"(in {'SI' if dimensioned(p) else 'the file'}) and leave out --{p.cli}")
    return given


def case(args, si, keep=()):
    """The Case of the SI file and the command line's run settings (run_fields)."""
    return si.case(model=args.model, **run_fields(args, si, keep))
