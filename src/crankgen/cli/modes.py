"""`crankgen modes` and `crankgen campbell`: the natural frequencies of the mechanism frozen at a
crank angle, and their bands against crank speed with the crank orders."""

import math
import sys

from ..declaration import schema
from . import si_file
from .options import (UsageError, _Outputs, _add_mechanism_options, _add_model_options,
                      _add_output_options, _explicit, _int_list, _say)

MODES_NAMES = ("modes.csv", "shapes.csv", "modes.png")
CAMPBELL_NAMES = ("campbell.csv", "crossings.csv", "campbell.png")
# the run's parameters a frozen mechanism reads (no crank motion but its speed, no time stepping)
FROZEN_RUN = (schema.CRANK_SPEED, schema.CRANK_ANGLE, "n_elements")


def add_commands(sub):
    p = sub.add_parser("modes", help="natural frequencies and mode shapes of the mechanism frozen at a crank angle",
                       description="The lowest natural frequencies and mode shapes of the mechanism "
                                   "frozen at crank angle --theta0 (rad) turning at --omega: the rod "
                                   "straight and stretched by the axial loads of the rigid motion, the "
                                   "model's own tangent there (centrifugal and axial-load stiffening "
                                   "included, damping and Coriolis terms left out). --omega 0: the "
                                   "mechanism at rest. Writes modes.csv (mode, kind, frequency in units "
                                   "of omega_b, lambda = frequency^2 signed: negative when the frozen "
                                   "rod buckles), shapes.csv (u, v, psi of every node of every mode) and "
                                   "modes.png; with --si in rad/s and Hz.")
    _add_mechanism_options(p)
    _add_model_options(p, integrator=False, run=FROZEN_RUN, title="crank speed and angle, model")
    p.add_argument("--count", type=int, default=6, help="number of modes, >= 1 (default 6)")
    p.add_argument("--si", metavar="FILE", default=None,
                   help="the mechanism in SI from a JSON file (as `crankgen simulate --si`); its "
                        "crank_speed is the frozen speed; frequencies in rad/s and Hz")
    si_file.add_rpm_option(p)
    _add_output_options(p, "modes", ", ".join(MODES_NAMES))
    p.set_defaults(func=_cmd_modes)

    p = sub.add_parser("campbell", help="Campbell diagram: natural frequencies against crank speed with the crank orders",
                       description="The lowest natural frequencies of the mechanism frozen at --angles "
                                   "crank angles of a revolution, at --speeds crank speeds from --from to "
                                   "--to: each mode a band over the revolution (the axial force of the "
                                   "rigid motion changes over it), drawn with the crank-order lines 1x, "
                                   "2x, ...; where an order crosses a band a resonance is to be expected. "
                                   "Writes campbell.csv (per speed and mode: low, mean and high frequency, "
                                   "kind, the share of the revolution where the frozen rod buckles), "
                                   "crossings.csv (each order entering, crossing the mean of and leaving "
                                   "each band) and campbell.png, and prints the crossings of the means. "
                                   "Units: Omega* and omega_b; with --si rad/s (rpm) and Hz.")
    _add_mechanism_options(p)
    _add_model_options(p, integrator=False, run=("n_elements",), title="model")
    g = p.add_argument_group("speeds, angles and orders")
    g.add_argument("--from", dest="start", type=float, default=None,
                   help="lowest crank speed (default 0; Omega*, or rad/s with --si)")
    g.add_argument("--to", dest="stop", type=float, default=None,
                   help="highest crank speed (default 1.6 omega_b: Omega* = 1.6, or its rad/s with --si)")
    g.add_argument("--speeds", type=int, default=81, help="number of crank speeds, >= 2 (default 81)")
    g.add_argument("--angles", type=int, default=36,
                   help="crank angles per revolution the mechanism is frozen at, >= 2 (default 36)")
    g.add_argument("--modes", dest="count", type=int, default=4, help="number of modes, >= 1 (default 4)")
    g.add_argument("--orders", type=_int_list("orders", 1), default=[1, 2, 3, 4, 5, 6],
                   help="crank orders drawn and crossed (default 1,2,3,4,5,6)")
    p.add_argument("--si", metavar="FILE", default=None,
                   help="the mechanism in SI from a JSON file (as `crankgen simulate --si`; its "
                        "crank_speed is not used); speeds in rad/s, frequencies in Hz")
    si_file.add_rpm_option(p, single=False)
    _add_output_options(p, "campbell", ", ".join(CAMPBELL_NAMES))
    p.set_defaults(func=_cmd_campbell)


def _mechanism(args):
    """(mech, fields, units): the Mechanism and the command line's case fields, or with --si the
    crankgen.SIMechanism and the fields that may go with it (crankgen.cli.si_file)."""
    from ..declaration import schema
    from ..declaration.parameters import Mechanism
    from . import si_file

    si = si_file.mechanism(args)
    if si is None:
        given = _explicit(args)
        mech = Mechanism(**{n: given.pop(n) for n in schema.MECHANISM_PARAMETERS if n in given})
        return mech, given, "crankgen"
    return si, si_file.run_fields(args, si), "si"


def _cmd_modes(args):
    from ..analyses.modes import modes
    from ..declaration.validation import angle, integer

    integer("--count", args.count, 1)
    mech, fields, units = _mechanism(args)
    theta = angle(f"--{schema.PARAMETERS[schema.CRANK_ANGLE].cli}", fields.pop(schema.CRANK_ANGLE, 0.0))
    omega = fields.pop(schema.CRANK_SPEED, None)
    m = modes(mech, omega, theta, count=args.count, model=args.model, units=units, **fields)  # checks all
    out = _Outputs(args.out, MODES_NAMES, args.force)
    try:
        _write_modes(m, out)
    finally:
        out.abandon()
    si = m.scales is not None
    speed = f"{m.omega * m.scales.omega_b:g} rad/s" if si else f"Omega* = {m.omega:g}"
    print(f"modes of the mechanism frozen at crank angle {math.degrees(m.theta):g} degrees, {speed}:")
    for row in m.table():
        f = (f"{row['frequency_rad_per_s']:.6g} rad/s ({row['frequency_Hz']:.6g} Hz)" if si
             else f"{row['frequency']:.6g} omega_b")
        note = "  divergent: the frozen rod buckles (lambda < 0)" if row["omega_squared"] < 0 else ""
        print(f"  mode {row['mode']}: {row['kind']:7s} {f}{note}")
    print(f"wrote {', '.join(str(p) for p in out.written)}")
    return 0


def _write_modes(m, out):
    from ..results.io import write_csv
    from ..plots.modes import plot_modes

    rows = m.table()
    out.wrote(write_csv(out.path("modes.csv"), list(rows[0]), rows))
    n = m.shapes.shape[1] - 1
    length = "m" if m.scales is not None else "L"
    factor = m.scales.L if m.scales is not None else 1.0
    shape_rows = [{"mode": j + 1, "node": i, f"x_{length}": factor * i / n, "u": float(s[i, 0]),
                   "v": float(s[i, 1]), "psi": float(s[i, 2])}
                  for j, s in enumerate(m.shapes) for i in range(n + 1)]
    out.wrote(write_csv(out.path("shapes.csv"), list(shape_rows[0]), shape_rows))
    out.wrote(plot_modes(m, out.path("modes.png")))


def _cmd_campbell(args):
    import numpy as np

    from ..analyses.campbell import campbell
    from ..progress import Progress
    from ..analyses.limits import count
    from ..declaration.validation import in_range, integer

    count("speeds", args.speeds, "--speeds")
    count("angles", args.angles, "--angles")
    integer("--modes", args.count, 1)
    mech, fields, units = _mechanism(args)
    if args.rpm and units != "si":
        raise UsageError("--rpm (--from and --to in rpm) needs the rod in SI: --si FILE")
    unit = 1.0 if units == "crankgen" else mech.omega_b
    from ..declaration.si import rad_per_s
    per = rad_per_s if args.rpm else float                   # --from, --to in rpm: into rad/s
    start = 0.0 if args.start is None else per(in_range("--from", args.start, 0.0))
    stop = 1.6 * unit if args.stop is None else per(in_range("--to", args.stop, 0.0))
    if stop <= start:
        raise UsageError(f"--to must exceed --from, got --from {start:g} --to {stop:g}")
    from ..analyses.modes import frozen_case
    frozen_case(mech, None, model=args.model, units=units, **fields)      # the case, checked first
    out = _Outputs(args.out, CAMPBELL_NAMES, args.force)
    try:
        speeds = np.linspace(start, stop, args.speeds)
        _say(args, f"campbell: {args.speeds} crank speeds from {start:g} to {stop:g}"
                   f"{' rad/s' if units == 'si' else ''}, {args.angles} crank angles each, {args.count} modes")
        with Progress("campbell", args.speeds, enabled=not args.quiet) as progress:
            d = campbell(mech, speeds, angles=args.angles, count=args.count, orders=args.orders,
                         model=args.model, units=units, progress=progress, **fields)
        for p in d.to_csv(out.folder):
            out.wrote(p)
        out.wrote(d.plot(out.path("campbell.png")))
    finally:
        out.abandon()
    lines = d.summary()
    print("\n".join(lines) if lines else "no crank order crosses a mode's mean frequency in this speed range")
    if np.any(d.divergent > 0):
        first = d.speeds[np.argmax(np.any(d.divergent > 0, axis=1))]
        print(f"the frozen rod buckles over part of the revolution from crank speed {first:.4g}"
              f"{' rad/s' if units == 'si' else ''} on (a band down to 0)", file=sys.stdout)
    print(f"wrote {', '.join(str(p) for p in out.written)}")
    return 0
