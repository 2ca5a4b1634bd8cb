"""`crankgen simulate`, `crankgen steady`, `crankgen sweep`: runs of the mechanism.

Everything a command can check is checked before anything is computed or created: the
parameters, the memory the run would need (crankgen.analyses.limits: steps x degrees of freedom, elements,
the size of a sweep's grid before it is built), the output folder and the checkpoint."""

import itertools
import math
import os
import sys
from pathlib import Path

from ..declaration import schema
from ..errors import ConvergenceError, ParameterError
from ..discrete.kinematics import step_period
from ..analyses.limits import check_run_size, count
from . import si_file
from .options import CASE_FIELDS, UsageError, _Outputs, _case, _describe, _flag, _say



def _failure_text(failure, approach):
    """A failed run's reason; for an ill-posed approach, what that means (not an instability)."""
    from ..analyses.theory import ill_posed

    text = str(failure)
    if ill_posed(approach):
        text += (f" (approach {approach} is ill-posed: its strain energy is unbounded below, so a "
                 "run can diverge; this is not an instability)")
    return text


def _theory_note(deflection, strain, result=None):
    """'; beyond the theory (...)' when a response leaves the range of the theory (the paper's, and
    what to use beyond it; an exact-model result's by the exact rod's own limits)."""
    from ..analyses.theory import CRITERION, REMEDY, is_exact, reasons

    if getattr(result, "case", None) is not None and is_exact(result.case):
        flag = result.beyond_theory
        return f"; {flag}" if flag else ""
    why = reasons(deflection, strain)
    return f"; BEYOND THE THEORY ({why}; criterion {CRITERION}); {REMEDY}" if why else ""


def _cmd_simulate(args):
    from ..declaration.validation import in_range

    si = si_file.mechanism(args)
    case = _case(args) if si is None else si_file.case(args, si)    # validates every parameter ...
    section = _section(args, si)
    revolutions = in_range("revolutions", args.revolutions, 0, None, True)
    in_range("tol", args.tol, 0, None, True)
    from ..discrete.kinematics import check_crank_steps
    from ..analyses.simulation import run_length

    dt, steps = run_length(case, revolutions)
    check_crank_steps(case, dt, steps * dt)
    check_run_size(case.n_elements, steps, stored="nodes" if args.nodes else "states",
                   names={"n_steps": "--revolutions", "n_elements": "--elements"})
    names = ["simulation.csv", "summary.csv", "v_mid.png"] + (["nodes.csv"] if args.nodes else [])
    out = _Outputs(args.out, names, args.force)             # ... and the output folder, first
    try:
        return _simulate(args, case, revolutions, steps, out, si, section)
    finally:
        out.abandon()


def _section(args, si):
    """The --section of the command line, checked against the SI rod (None: not given)."""
    if getattr(args, "section", None) is None:
        return None
    from ..declaration.sections import parse
    from ..analyses.stresses import check_section
    section = parse(args.section)
    check_section(section, si)
    return section


def _loads_and_stress(result, section, si, stress=True):
    """The summary lines of the peak loads and (stress=True) the outer-fibre stresses of a result."""
    from ..analyses.stresses import peak_loads
    from ..analyses.stresses import stress as stress_of
    from ..declaration.si import scales_of
    scales = None if si is None else scales_of(si)
    from ..analyses.stresses import crank_degrees
    loads = "; ".join(f"{p.name} {p.value:.4g} {p.units}"
                      + ("" if p.direction is None else f" towards {p.direction:.1f} deg")
                      + f" (t{'' if scales else '*'} = {p.t:.4g}"
                      f"{' s' if scales else ''}, crank angle {crank_degrees(p.theta):.1f} deg)"
                      for p in peak_loads(result, scales))
    if not stress:
        return [f"peak loads: {loads}"]
    return [f"peak loads: {loads}", stress_of(result, section, si=si).summary()
            + ("" if si is not None else " (units of E: the fibre's strain)")]


def _simulate(args, case, revolutions, steps, out, si=None, section=None):
    import numpy as np

    from ..results.io import write_csv
    from ..plots.figures import plot_deflection
    from ..progress import Progress
    from ..analyses.simulation import simulate

    kind = "no-load revolutions" if case.motion_record.driven else "revolutions"     # a driven crank's run
    _say(args, f"simulate: {_describe(case)}, {revolutions:g} {kind} ({steps} steps)")
    transient = case.motion_record.transient
    if transient and revolutions < getattr(case, transient):
        ramp, speed = getattr(case, transient), schema.PARAMETERS[schema.CRANK_SPEED]
        _say(args, f"simulate: note: the run ends after {revolutions:g} revolutions, before the ramp of "
                   f"{ramp:g} revolutions completes (the crank does not reach {speed.axis} = "
                   f"{getattr(case, speed.name):g}); --revolutions {ramp:g} or more runs the whole ramp")
    failure = None
    with Progress("simulate", steps, enabled=not args.quiet) as progress:
        try:
            res = simulate(case=case, revolutions=revolutions, store_nodes=args.nodes, tol=args.tol,
                           progress=progress)
        except ConvergenceError as exc:
            if exc.partial is None:
                raise
            failure, res = exc, exc.partial
    view = None if si is None else res.si_view(si)
    columns, values = (res if view is None else view).table(along=True, section=section)  # every output, per step
    strain, defl = values[columns.index("axial_strain")], values[columns.index("deflection_over_L")]
    rows = (dict(zip(columns, row), status="ok") for row in zip(*values))                 # streamed
    columns = columns + ["status"]
    if failure is not None:
        t_fail = failure.time if view is None else failure.time * view.scales.factor("1/omega_b")
        theta = float(_theta_at(case, failure.time))
        last = {columns[0]: t_fail, columns[1]: math.degrees(theta) if view is None else theta,
                "status": f"failed: {_failure_text(failure, case.approach)}"}
        rows = itertools.chain(rows, [last])
    out.wrote(write_csv(out.path("simulation.csv"), columns, rows))
    from ..analyses.rod_loads import summary_line
    from ..results.tables import flat_table
    peaks = _load_summary(res, section, si) if len(res.t) > 1 else {}
    if peaks:
        out.wrote(write_csv(out.path("summary.csv"), *flat_table(list(peaks), [peaks])))
    if args.nodes and res.nodes is not None:
        nodes = res.nodes if view is None else view.nodes
        from ..discrete.mesh import COMPONENTS, NODE_DOFS, components_of
        n = nodes.shape[1] // NODE_DOFS
        # node i at x* = i / n: u, v (along and across the rigid rod; units of L, or m with --si)
        # and the slope psi = dv/dx (rad), on the exact rod also chi = du/dx (dimensionless)
        # then every node's inertial position X, Y (crankgen.plots.animation.inertial_nodes)
        from ..plots.animation import inertial_nodes
        length = "L" if view is None else "m"
        units = {"u": length, "v": length, "psi": "rad", "chi": "1"}
        present = components_of(case.options)
        keep = [i * NODE_DOFS + COMPONENTS.index(q) for i in range(n) for q in present]
        nodes = np.asarray(nodes)[:, keep]
        node_columns = columns[:2] + [f"{q}{i}_{units[q]}" for i in range(n) for q in present]
        node_columns += [f"{q}{i}_{length}" for i in range(n) for q in ("X", "Y")]
        where = inertial_nodes(res).reshape(len(res.t), -1) * (1.0 if view is None else view.scales.L)
        node_rows = (dict(zip(node_columns, (t, th, *row, *xy)))                     # streamed
                     for t, th, row, xy in zip(values[0], values[1], nodes, where))
        out.wrote(write_csv(out.path("nodes.csv"), node_columns, node_rows))
    # a motion whose speed changes over its first revolutions (a run-up) is drawn against the crank
    # speed it passes (its resonances) and against the revolutions, other runs against time
    transient = case.motion_record.transient
    if transient and getattr(res, "states", None) is not None:
        from ..discrete.kinematics import time_of_revolutions
        from ..plots.figures import plot_runup
        out.wrote(plot_runup(res, out.path("v_mid.png"), time_of_revolutions(case, getattr(case, transient)),
                             failure=failure, si=view, strain=strain))
    else:
        out.wrote(plot_deflection(res, out.path("v_mid.png"), failure=failure, si=view, strain=strain))
    note = _theory_note(float(np.max(defl)) if len(defl) else math.nan,
                        float(np.max(strain)) if len(strain) else math.nan, res)
    if failure is not None:
        print(f"crankgen simulate: run failed: {_failure_text(failure, case.approach)}; wrote the "
              f"history up to the failure ({len(res.t)} points, marked in the status column) to "
              f"{out.path('simulation.csv')}", file=sys.stderr)
        return 1
    last = (res.v_mid if view is None else view.v_mid)[-case.steps_per_rev:]
    print(f"wrote {', '.join(str(p) for p in out.written)}; max |v{'*' if view is None else ''}| "
          f"over the last revolution {np.max(np.abs(last)):.6g}{'' if view is None else ' m'}{note}")
    if section is not None:
        print("\n".join(_loads_and_stress(res, section, si)))
    if peaks:
        print(summary_line(peaks, si is not None))
        print(f"model: {res.verdict}")
    return 0


def _theta_at(case, t):
    from ..discrete.kinematics import case_state
    return case_state(case, t).theta


# ---- steady ------------------------------------------------------------------------------------
STEADY_NAMES = ["steady.csv", "orbit.csv", "orbit.png"]


def _load_summary(result, section=None, si=None):
    """simulate's summary.csv, one row of what sizes the rod and its bearings over a result: the
    peaks in crankgen's units (crankgen.analyses.rod_loads.peaks), the model's verdict (model_error,
    verdict: crankgen.analyses.model_error), and with si (the crankgen.SIMechanism of the run) their
    SI columns (crankgen.results.si_row.row_in_si), with a section the stress peaks (in Pa with si)."""
    from ..analyses.rod_loads import peaks, stress_peaks
    out = dict(peaks(result))
    judged = result.verdict
    out.update(model_error=judged.error, verdict=judged.words or None)
    if si is not None:
        from ..results.si_row import row_in_si
        extra = row_in_si(out, si)
        out.update({k: v for k, v in extra.items() if k not in out})
    if section is not None:
        out.update(stress_peaks(result, section, si))
    return out


def _resolved(case, where="", speed=None):
    """Steady states need a crank motion periodic in the crank angle, a turning crank and
    Omega* * steps_per_rev >= 1 (crankgen.steady_states refuses coarser steps); checked here,
    before any output or progress line, and said in one line.  A driven crank's motion is
    autonomous: shot on the section of its crank angle (crankgen.analyses.section).  speed: how the
    user gave the crank speed when not by its flag (an --si file's field, --rpm), named in the
    messages."""
    if case.motion_record.driven:
        from ..discrete.system import check_coordinates
        try:
            check_coordinates(case)
        except ParameterError as exc:
            raise UsageError(str(exc)) from None
        return
    if not case.periodic:
        raise UsageError(
            f"{where}a steady state needs a crank motion periodic in the crank angle; --crank "
            f"{case.motion_record.name} is not (a transient: `crankgen simulate` runs it)")
    given_speed, speed = speed, schema.PARAMETERS[schema.CRANK_SPEED]
    omega = getattr(case, speed.name)
    given = f"--{speed.cli} {omega:g}" if given_speed is None else given_speed
    if omega == 0:
        raise UsageError(
            f"{where}a steady state needs a turning crank: {given} is a crank at rest, which has "
            f"no revolution to repeat; give a crank speed > 0 (`crankgen modes` at speed 0 gives the "
            "natural frequencies of the mechanism at rest)")
    if omega * case.steps_per_rev < 1.0:
        raise UsageError(
            f"{where}a steady state at {given} (Omega* = {omega:g}) needs --steps-per-rev >= "
            f"{math.ceil(1 / omega)} (got {case.steps_per_rev}): a time step longer than the "
            "rod's first bending period would make the stability verdict depend on the step; "
            "`crankgen simulate` marches such slow runs")


def _cmd_steady(args):
    from ..declaration.validation import in_range

    si = si_file.mechanism(args)
    case = _case(args) if si is None else si_file.case(args, si)
    section = _section(args, si)
    in_range("tol", args.tol, 0, None, True)
    count("max_revolutions", args.max_revolutions, "--max-revolutions")
    check_run_size(case.n_elements, case.steps_per_rev, stored="steady",
                   names={"n_elements": "--elements", "n_steps": "--steps-per-rev"})
    _resolved(case, speed=si_file.speed_words(args, None if si is None else si.crank_speed))
    out = _Outputs(args.out, STEADY_NAMES, args.force)
    try:
        return _steady(args, case, out, section, si)
    finally:
        out.abandon()


def _method_text(args, case):
    """How the periodic state is sought: shooting differentiates the converged Newton step map,
    so any other integrator marches."""
    if case.motion_record.driven:
        return (f"shooting on the section theta = theta0 (an autonomous motion: the revolution time is "
                f"unknown), tolerance {args.tol:g}")
    if args.method == "shooting" and case.integrator == "newton":
        return f"shooting (Newton on the revolution map), tolerance {args.tol:g}"
    why = "" if args.method == "march" else \
        f" (shooting needs --integrator newton; the {case.integrator} step map is not differentiated)"
    return (f"marching revolution by revolution until the state changes by less than {args.tol:g} "
            f"per revolution{why}")


def _steady(args, case, out, section=None, si=None):
    from dataclasses import replace

    from ..analyses import theory
    from ..results.io import write_csv
    from ..plots.figures import plot_orbit
    from ..analyses.steady import steady_states
    from ..results.tables import flat_table

    _say(args, f"steady: {_describe(case)}; {_method_text(args, case)}")
    st = steady_states([case], tol=args.tol, max_revolutions=args.max_revolutions,
                       method=args.method)[0]
    if si is not None:
        st = replace(st, scales=si.scales)
    row = st.row()
    row["strain_energy_bound"] = theory.strain_energy(case.approach)
    if st.status == "failed":
        row["message"] = _failure_text(st.message, case.approach)
    if si is not None:
        from ..results.si_row import row_in_si
        row.update(row_in_si(row, si))
    if section is not None and st.states is not None:        # the peak stresses, where and when
        from ..analyses.rod_loads import stress_peaks
        row.update(stress_peaks(st, section, si))
    out.wrote(write_csv(out.path("steady.csv"), *flat_table(list(row), [row])))
    if st.v_mid is not None:
        columns, values = (st if si is None else st.si).table(along=True, section=section)
        steps = values[columns.index("axial_strain")]
        out.wrote(write_csv(out.path("orbit.csv"), columns, (dict(zip(columns, r)) for r in zip(*values))))
        out.wrote(plot_orbit(st, out.path("orbit.png"), strain=steps, si=None if si is None else st.si))
    else:                                    # no orbit: leave no orbit of an earlier run beside it
        for name in ("orbit.csv", "orbit.png"):
            out.path(name).unlink(missing_ok=True)

    def num(x, fmt):
        return "—" if x is None or not math.isfinite(x) else fmt.format(x)
    amplitude = (f"max|v*| {num(st.amplitude, '{:.6g}')}, half peak-to-peak {num(st.half_peak_to_peak, '{:.6g}')}"
                 if si is None else
                 f"max|v| {num(row.get('amplitude_m'), '{:.6g}')} m, half peak-to-peak "
                 f"{num(row.get('half_peak_to_peak_m'), '{:.6g}')} m")
    nan = math.nan
    print(f"status {st.status}; amplitude {amplitude}; largest |Floquet multiplier| "
          f"{num(st.multiplier, '{:.4g}')}; {st.iterations} shooting iterations, {st.periods} "
          f"revolutions marched, residual {num(st.residual, '{:.2e}')}"
          + (f"; {row['message']}" if row["message"] else "")
          + _theory_note(nan if row["deflection_over_L"] is None else row["deflection_over_L"],
                         nan if row["axial_strain"] is None else row["axial_strain"], st))
    if st.period is not None:
        no_load = 2 * math.pi / step_period(case)
        speeds = (f"revolution time T* = {st.period:.6g}, mean speed {st.mean_speed:.6g} (no-load {no_load:g})"
                  if si is None else
                  f"revolution time {row['revolution_time_s']:.6g} s, mean speed {row['mean_speed_rad_per_s']:.6g} "
                  f"rad/s (no-load {si.no_load_speed:g} rad/s)")
        print(f"the motor-driven crank: {speeds}, speed fluctuation {st.speed_fluctuation:.4g} of the mean; "
              "the multipliers are the section map's (the flow's trivial multiplier 1 is not among them)")
        if st.motor_duty is not None:                # what sizes the motor
            names, units = (("peak_motor_torque", "rms_motor_torque", "mean_motor_power"),
                            ("rhoA L^3 omega_b^2", "rhoA L^3 omega_b^3"))
            if si is not None:
                names, units = ("peak_motor_torque_N_m", "rms_motor_torque_N_m", "mean_motor_power_W"), ("N m", "W")
            peak, rms, power = (row[n] for n in names)
            print(f"the motor: peak torque {peak:.4g} {units[0]}, RMS torque {rms:.4g} {units[0]}, mean power "
                  f"{power:.4g} {units[1]} over the revolution")
    if section is not None and st.states is not None:
        print("\n".join(_loads_and_stress(st, section, si)))
    elif st.states is not None:                  # the loads a motor and its bearings are sized from
        print(_loads_and_stress(st, None, si, stress=False)[0])
    if st.states is not None:
        from ..analyses.rod_loads import summary_line
        print(summary_line(row, si is not None))
        print(f"model: {st.verdict}")
    print(f"wrote {', '.join(str(p) for p in out.written)}")
    if st.status == "failed":
        print(f"crankgen steady: run failed: {row['message']}", file=sys.stderr)
        return 1
    return 0


# ---- sweep -------------------------------------------------------------------------------------
def _listed(value):
    return value if isinstance(value, list) else [value]


def _sweep_grid(args):
    """(models, axes) of the grid: the presets listed (None: the default model) and the value
    lists of every case field given; nothing is built yet."""
    models = _listed(args.model) if args.model else [None]
    axes = [[(name, v) for v in _listed(getattr(args, name))] for name in CASE_FIELDS
            if getattr(args, name, None) is not None]
    if getattr(args, "rpm", None) is not None:             # crank speeds in rpm (with --si: _si_grid)
        axes.append([(RPM_AXIS, v) for v in args.rpm])
    return models, axes


RPM_AXIS = "rpm"        # the sweep's grid of crank speeds in rpm (--rpm, with --si)


def _sweep_cases(args, models, axes, si=None):
    """The grid: every combination of the listed values and models, validated.  With --si (si: the
    file's crankgen.SIMechanism) a value of a parameter the file can hold is in SI and replaces the
    file's field; the others are the run's settings."""
    from dataclasses import replace

    from ..declaration.cases import make_case
    from ..errors import ParameterError
    from ..declaration.si import SI_NAME

    cases = []
    for model in models:
        for combo in itertools.product(*axes):
            values = dict(combo)
            try:
                if si is None:
                    cases.append(make_case(model=model, **values))
                else:
                    fields = {SI_NAME[n]: values.pop(n) for n in list(values) if n in SI_NAME}
                    if RPM_AXIS in values:               # the crank speed in rpm, in place of the file's
                        speed = SI_NAME[schema.CRANK_SPEED]
                        fields.update({speed: None, f"{speed}_rpm": values.pop(RPM_AXIS)})
                    cases.append(replace(si, **fields).case(model=model, **values))
            except ParameterError as exc:
                where = dict(combo, model=model) if model else dict(combo)
                raise ParameterError(f"{exc} (in the grid: {where})") from None
    return list(dict.fromkeys(cases))


def _si_grid(args):
    """The --si file of a sweep, its grid flags checked: each of a parameter the file can hold is in
    SI (the file's unit for it), a unit that is a parameter (the slenderness: the section's) is
    refused."""
    if args.si is None:
        if args.rpm is not None:
            raise UsageError("--rpm is a crank speed in SI: it needs the rod in SI, --si FILE (without it "
                             f"--{schema.PARAMETERS[schema.CRANK_SPEED].cli} takes Omega*)")
        return None
    if args.rpm is not None and getattr(args, schema.CRANK_SPEED, None) is not None:
        raise UsageError(f"--rpm and --{schema.PARAMETERS[schema.CRANK_SPEED].cli} are both crank speeds: give one")
    si = si_file.read(args.si, None if args.rpm is None else args.rpm[0], replace_speed=True)
    for name in schema.UNIT_PARAMETERS.values():
        if getattr(args, name, None) is not None:
            raise UsageError(f"with --si, {schema.PARAMETERS[name].label} is the rod's section (sqrt(I/A)/L): "
                             f"leave out --{schema.PARAMETERS[name].cli} (give I and A in the file)")
    return si


SWEEP_NAMES = ["sweep.csv", "sweep_columns.csv", "sweep.png"]


def _cmd_sweep(args):
    from ..declaration.validation import in_range, integer

    in_range("tol", args.tol, 0, None, True)
    count("max_revolutions", args.max_revolutions, "--max-revolutions")
    batch_size = integer("batch_size", args.batch_size, 1)
    count("workers", args.workers, "--workers")
    si = _si_grid(args)
    models, axes = _sweep_grid(args)
    size = len(models) * math.prod(len(axis) for axis in axes)
    given = [f"--{_flag(axis[0][0])} ({len(axis)})" for axis in axes
             if len(axis) > 1] + ([f"models ({len(models)})"] if len(models) > 1 else [])
    from ..declaration import schema
    elements = _listed(args.n_elements) if args.n_elements is not None else [schema.PARAMETERS["n_elements"].default]
    steps = _listed(args.steps_per_rev) if args.steps_per_rev is not None else [schema.PARAMETERS["steps_per_rev"].default]
    check_run_size(max(elements), max(steps), size, "steady",
                   batch=batch_size * args.workers,
                   names={"n_cases": "the grid " + " x ".join(given) if given else "the grid",
                          "n_elements": "--elements (with --batch-size and --workers)",
                          "n_steps": "--steps-per-rev"})
    if size > 10000:
        _say(args, f"sweep: building the grid of {size} cases")
    cases = _sweep_cases(args, models, axes, si)
    for c in cases:
        _resolved(c, "in the grid: ")
    if args.checkpoint is not None and not args.checkpoint.strip():
        raise UsageError("--checkpoint is an empty name; give a file")
    checkpoint = Path(args.checkpoint) if args.checkpoint else Path(args.out) / "sweep.jsonl"
    _check_checkpoint(checkpoint, Path(args.out))
    out = _Outputs(args.out, SWEEP_NAMES, args.force)
    try:
        return _sweep(args, cases, checkpoint, out, si)
    finally:
        out.abandon()


def _check_checkpoint(path, out):
    """Refuse, before anything is created, a checkpoint that is not a regular file (a folder, a
    device, a FIFO, a socket, a link out of its folder), has no folder, or is not a crankgen sweep
    checkpoint of this format version.  Nothing is opened but a regular file."""
    from ..results.io import NotRegularFileError, check_target
    from ..analyses.sweeps import check_checkpoint_file

    try:
        target = check_target(path)
    except NotRegularFileError as exc:
        raise UsageError(f"checkpoint {exc}") from None
    if target.parent != out and not target.parent.is_dir():
        raise UsageError(f"checkpoint {path}: its folder {target.parent} does not exist")
    if target.exists():
        try:
            check_checkpoint_file(target)
        except NotRegularFileError as exc:          # changed since check_target looked
            raise UsageError(f"checkpoint {exc}") from None


def _sweep(args, cases, checkpoint, out, si=None):
    from collections import Counter

    from ..progress import Progress
    from ..analyses.sweeps import sweep, worker_init

    if args.fresh and checkpoint.exists():
        _say(args, f"sweep: --fresh: the records of {checkpoint} are discarded, every case is "
                   "computed again")
    elif checkpoint.exists():
        _say(args, f"sweep: resuming from {checkpoint}: cases recorded there are not recomputed"
                   + ("" if args.retry_failed else " (failed ones included; --retry-failed reruns them)"))
    _say(args, f"sweep: {len(cases)} cases in batches of {args.batch_size}; checkpoint {checkpoint}")
    executor = None
    if args.workers > 1:
        import concurrent.futures as cf
        executor = cf.ProcessPoolExecutor(args.workers, initializer=worker_init,
                                          initargs=(os.getpid(),))
    recorded, finished = {"done": None}, False
    try:
        with Progress("sweep (cases)", len(cases), enabled=not args.quiet, interval=30) as bar:
            def progress(done, total):
                recorded["done"] = done
                bar(done, total)
            table = sweep(cases, executor=executor, checkpoint=checkpoint, batch_size=args.batch_size,
                          tol=args.tol, max_revolutions=args.max_revolutions,
                          retry_failed=args.retry_failed, progress=progress, fresh=args.fresh)
        finished = True
    except KeyboardInterrupt as exc:
        done = recorded["done"]
        exc.detail = (f"{done} of {len(cases)} cases are recorded in {checkpoint}: the same command "
                      "resumes from them" if done else
                      f"no case of this sweep had finished; nothing new was recorded in {checkpoint}")
        raise
    finally:
        if executor is not None:
            _stop_pool(executor, now=not finished)
    from ..results.io import write_csv
    from ..results.tables import flat_table
    shown = table if si is None else table.si_view(si)
    columns, rows = flat_table(shown.columns, shown.rows)
    out.wrote(write_csv(out.path("sweep.csv"), columns, rows))
    out.wrote(write_csv(out.path("sweep_columns.csv"), ["column", "units", "meaning"], shown.describe(columns)))
    from ..plots.sweep import plot_sweep, varying
    drawn = [c for c in varying(table.rows, table.columns)
             if c in schema.PARAMETERS and schema.PARAMETERS[c].kind in ("real", "count")]
    if drawn:
        out.wrote(plot_sweep(table, out.path("sweep.png"), si=si))
    else:                                    # nothing numeric swept: no curve to draw
        out.path("sweep.png").unlink(missing_ok=True)
    counts = Counter(row["status"] for row in table.rows)
    print(f"wrote {', '.join(str(p) for p in out.written)}: {len(table)} cases, "
          + ", ".join(f"{n} {status}" for status, n in sorted(counts.items()))
          + ("" if drawn else " (no numeric parameter swept: no sweep.png)"))
    return 0


def _stop_pool(executor, now):
    """Shut the pool down; `now` (the sweep stopped: an interruption, an error) without waiting for
    work nobody will read: what has not started is cancelled and the workers are ended."""
    if now:
        for process in list((getattr(executor, "_processes", None) or {}).values()):
            try:
                process.kill()
            except (OSError, AttributeError, ValueError):
                pass
    executor.shutdown(wait=True, cancel_futures=True)


# ---- reproduce, audit --------------------------------------------------------------------------
