"""`crankgen simulate`, `crankgen steady`, `crankgen sweep`: runs of the mechanism."""

import math
import sys
from pathlib import Path

from ..errors import ConvergenceError
from .options import MODELS, UsageError, _Outputs, _case, _describe, _say


SIM_COLUMNS = ["t", "theta_deg", "v_mid", "u_end", "extension", "deflection_over_L", "axial_strain",
               "beyond_theory", "status"]


def _failure_text(failure, approach):
    """A failed run's reason; for an ill-posed approach, what that means (not an instability)."""
    from ..theory import ill_posed

    text = str(failure)
    if ill_posed(approach):
        text += (f" (approach {approach} is ill-posed: its strain energy is unbounded below, so a "
                 "run can diverge; this is not an instability)")
    return text


def _theory_note(deflection, strain):
    """'; beyond the theory (...)' when a response leaves the range of the theory."""
    from ..theory import CRITERION, reasons

    why = reasons(deflection, strain)
    return f"; BEYOND THE THEORY ({why}; criterion {CRITERION})" if why else ""


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

    from ..io import write_csv
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
    from .. import theory

    strain = theory.axial_strain(res, per_step=True)
    rows = [dict(t=t, theta_deg=math.degrees(th), v_mid=v, u_end=u, extension=e,
                 deflection_over_L=theory.deflection_over_L(case.eps, v), axial_strain=st,
                 beyond_theory=theory.beyond(theory.deflection_over_L(case.eps, v), st), status="ok")
            for t, th, v, u, e, st in zip(res.t, res.theta, res.v_mid, res.u_end, res.extension, strain)]
    if failure is not None:
        rows.append(dict(t=failure.time, theta_deg=math.degrees(case.omega * failure.time),
                         status=f"failed: {_failure_text(failure, case.approach)}"))
    out.wrote(write_csv(out.path("simulation.csv"), SIM_COLUMNS, rows))
    if args.nodes and res.nodes is not None:
        n = res.nodes.shape[1] // 3
        # node i at x* = i / n: u, v (units of L, along and across the rigid rod) and the slope
        # psi = dv/dx (rad)
        columns = ["t", "theta_deg"] + [f"{q}{i}_{unit}" for i in range(n)
                                        for q, unit in (("u", "L"), ("v", "L"), ("psi", "rad"))]
        node_rows = [dict(zip(columns, (t, math.degrees(th), *values)))
                     for t, th, values in zip(res.t, res.theta, res.nodes)]
        out.wrote(write_csv(out.path("nodes.csv"), columns, node_rows))
    out.wrote(plot_deflection(res, out.path("v_mid.png"), failure=failure))
    defl = max((r["deflection_over_L"] for r in rows[:len(res.t)]), default=math.nan)
    note = _theory_note(defl, float(np.max(strain)) if len(strain) else math.nan)
    if failure is not None:
        print(f"crankgen simulate: run failed: {_failure_text(failure, case.approach)}; wrote the "
              f"history up to the failure ({len(res.t)} points, marked in the status column) to "
              f"{out.path('simulation.csv')}", file=sys.stderr)
        return 1
    last = res.v_mid[-case.steps_per_rev:]
    print(f"wrote {', '.join(str(p) for p in out.written)}; max |v*| over the last revolution "
          f"{np.max(np.abs(last)):.6g}{note}")
    return 0


# ---- steady ------------------------------------------------------------------------------------
STEADY_NAMES = ["steady.csv", "orbit.csv", "orbit.png"]
ORBIT_COLUMNS = ["theta_deg", "t", "v_mid", "u_end", "extension", "deflection_over_L", "axial_strain"]
THEORY_COLUMNS = ["deflection_over_L", "axial_strain", "beyond_theory", "strain_energy"]


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


def _method_text(args, case):
    """How the periodic state is sought: shooting differentiates the converged Newton step map,
    so any other integrator marches."""
    if args.method == "shooting" and case.integrator == "newton":
        return f"shooting (Newton on the revolution map), tolerance {args.tol:g}"
    why = "" if args.method == "march" else \
        f" (shooting needs --integrator newton; the {case.integrator} step map is not differentiated)"
    return (f"marching revolution by revolution until the state changes by less than {args.tol:g} "
            f"per revolution{why}")


def _steady(args, case, out):
    import numpy as np

    from .. import theory
    from ..io import write_csv
    from ..plotting import plot_orbit
    from ..steady import steady_states
    from ..tables import flat_table

    _say(args, f"steady: {_describe(case)}; {_method_text(args, case)}")
    st = steady_states([case], tol=args.tol, max_revolutions=args.max_revolutions,
                       method=args.method)[0]
    row = st.row()
    defl = theory.deflection_over_L(case.eps, st.amplitude)
    strain = theory.axial_strain(st) if st.v_mid is not None else math.nan
    row.update(deflection_over_L=defl, axial_strain=strain, beyond_theory=theory.beyond(defl, strain),
               strain_energy=theory.strain_energy(case.approach))
    if st.status == "failed":
        row["message"] = _failure_text(st.message, case.approach)
    out.wrote(write_csv(out.path("steady.csv"), *flat_table(list(row), [row])))
    if st.v_mid is not None:
        steps = theory.axial_strain(st, per_step=True)
        rows = [dict(zip(ORBIT_COLUMNS, (np.degrees(th), t, v, u, e, theory.deflection_over_L(case.eps, v), a)))
                for th, t, v, u, e, a in zip(st.theta, st.t, st.v_mid, st.u_end, st.extension, steps)]
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
          + (f"; {row['message']}" if row["message"] else "") + _theory_note(defl, strain))
    print(f"wrote {', '.join(str(p) for p in out.written)}")
    if st.status == "failed":
        print(f"crankgen steady: run failed: {row['message']}", file=sys.stderr)
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
    from ..tables import flat_table
    out.wrote(write_csv(out.path("sweep.csv"), *flat_table(table.columns, table.rows)))
    counts = Counter(row["status"] for row in table.rows)
    print(f"wrote {out.path('sweep.csv')}: {len(table)} cases, "
          + ", ".join(f"{n} {status}" for status, n in sorted(counts.items())))
    return 0


# ---- reproduce, audit --------------------------------------------------------------------------
