"""`crankgen simulate`, `crankgen steady`, `crankgen sweep`: runs of the mechanism."""

import math
import sys
from pathlib import Path

from ..errors import ConvergenceError
from .options import MODELS, UsageError, _Outputs, _case, _describe, _say


SIM_COLUMNS = ["t", "theta", "v_mid", "u_end", "extension", "status"]


def _cmd_simulate(args):
    from ..validation import in_range

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

    from ..io import atomic_write, write_csv
    from ..plotting import plot_deflection
    from ..progress import Progress
    from ..simulation import simulate

    mech = case.mechanism
    steps = max(1, int(round(revolutions * case.steps_per_rev)))
    _say(args, f"simulate: {_describe(case)}, {revolutions:g} revolutions ({steps} steps)")
    failure = None
    with Progress("simulate", steps, enabled=not args.quiet) as progress:
        try:
            res = simulate(mech, omega=case.omega, approach=case.approach, formulation=case.formulation,
                           n_elements=case.n_elements, steps_per_rev=case.steps_per_rev,
                           revolutions=revolutions, integrator=case.integrator, damping=case.damping,
                           membrane=case.membrane, rotary_inertia=case.rotary_inertia,
                           store_nodes=args.nodes, tol=args.tol, progress=progress)
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


def _resolved(case, where=""):
    """Steady states need Omega* * steps_per_rev >= 1 (crankgen.steady_states refuses coarser
    steps); checked here, before any output or progress line, and said in one line."""
    if case.omega * case.steps_per_rev < 1.0:
        raise UsageError(
            f"{where}a steady state at --omega {case.omega:g} needs --steps-per-rev >= "
            f"{math.ceil(1 / case.omega)} (got {case.steps_per_rev}): a time step longer than the "
            "rod's first bending period would make the stability verdict depend on the step; "
            "`crankgen simulate` marches such slow runs")


def _cmd_steady(args):
    from ..validation import in_range, integer

    case = _case(args)
    in_range("tol", args.tol, 0, None, True)
    integer("max_revolutions", args.max_revolutions, 1)
    _resolved(case)
    out = _Outputs(args.out, STEADY_NAMES, args.force)
    try:
        return _steady(args, case, out)
    finally:
        out.abandon()


def _steady(args, case, out):
    from ..io import write_csv
    from ..plotting import plot_orbit
    from ..steady import steady_states

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

    from ..cases import Case
    from ..errors import ParameterError

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
                raise ParameterError(f"in the grid: {exc}") from None
    return list(dict.fromkeys(cases))


def _cmd_sweep(args):
    from ..validation import in_range, integer

    cases = _sweep_cases(args)
    in_range("tol", args.tol, 0, None, True)
    integer("max_revolutions", args.max_revolutions, 1)
    integer("batch_size", args.batch_size, 1)
    integer("workers", args.workers, 1)
    for c in cases:
        _resolved(c, "in the grid: ")
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

    from ..progress import Progress
    from ..sweeps import sweep

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
    from ..io import write_csv
    out.wrote(write_csv(out.path("sweep.csv"), table.columns, table.rows))
    counts = Counter(row["status"] for row in table.rows)
    print(f"wrote {out.path('sweep.csv')}: {len(table)} cases, "
          + ", ".join(f"{n} {status}" for status, n in sorted(counts.items())))
    return 0


# ---- reproduce, audit --------------------------------------------------------------------------
