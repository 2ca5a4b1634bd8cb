"""`crankgen compare`: the rigid mechanism beside the flexible one (crankgen.analyses.rigid.compare)."""

from . import si_file
from .options import (_Outputs, _add_mechanism_options, _add_model_options, _add_output_options, _case,
                      _describe, _say)

NAMES = ("compare.csv", "compare.png")


def add_command(sub):
    p = sub.add_parser("compare", help="rigid against flexible: crank torque, pin forces and stress, one table",
                       description="How much the rod's flexibility changes what a mechanism is sized by: "
                                   "the rigid mechanism (kineto-static: its rigid motion's loads carried by "
                                   "the rod quasi-statically, crankgen.analyses.rigid) beside the flexible one (its "
                                   "steady periodic state) at the same crank angles. Prints and writes "
                                   "compare.csv (quantity, units, rigid, flexible, flexible/rigid: peak and "
                                   "RMS crank torque, peak pin forces at A and B, peak compression, tension "
                                   "and bending moment, with --section the peak outer-fibre stress) and "
                                   "compare.png (torque, pin forces and the mid-span bending moment over the "
                                   "revolution). A crank at a constant speed.")
    _add_mechanism_options(p)
    _add_model_options(p)
    p.add_argument("--section", metavar="SPEC", default=None,
                   help="the rod's cross-section for the peak stress: rectangle:B,H, circle:D, tube:D,T or "
                        "A,I,C (in m with --si, the file's rod; otherwise only its shape counts, the stress "
                        "in units of E)")
    si_file.add_option(p, "the table in SI (N m, N, Pa)")
    si_file.add_rpm_option(p)
    _add_output_options(p, "compare", ", ".join(NAMES))
    p.set_defaults(func=_cmd_compare)


def _cmd_compare(args):
    from ..analyses.rigid import compare
    from .runs import _resolved, _section

    si = si_file.mechanism(args)
    case = _case(args) if si is None else si_file.case(args, si)
    section = _section(args, si)
    _resolved(case, speed=si_file.speed_words(args, None))
    out = _Outputs(args.out, NAMES, args.force)
    try:
        _say(args, f"compare: {_describe(case)}; the steady state, then the rigid mechanism at its angles")
        if si is None:
            c = compare(case=case, section=section)
        else:
            settings = si_file.run_fields(args, si)
            c = compare(si, section=section, units="si", model=args.model, **settings)
        out.wrote(c.to_csv(out.path("compare.csv")))
        out.wrote(c.plot(out.path("compare.png")))
    finally:
        out.abandon()
    print("\n".join(c.summary()))
    print(f"model: {c.flexible.verdict}")
    print(f"wrote {', '.join(str(p) for p in out.written)}")
    return 0
