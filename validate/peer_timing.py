"""Time per step of crankgen and Exudyn on the same slider-crank march, measured in one run.

The case (CASE): the slider-crank of validate/compare.py at eps = 0.01, Omega* = 0.8, a* = 0.1,
ms* = 0.5, mu* = 0.5 (strain-rate damping), 16 elements in both codes, STEPS_PER_REV steps per
crank revolution, REVOLUTIONS revolutions marched from the rigid mechanism's state (the same start
in both codes).  Every code is loaded and run once on a short march first (compilation, imports),
then each timing is the best of REPEATS wall times of the whole march:
- crankgen through `crankgen.simulate(..., history=False)` (what a user calls; it includes
  building the case and the run's outputs) and through its engine alone (`engine.march` on an
  `engine.Batch`, as bench/run.py's step_times does), for the default consistent model and the
  exact rod (model="exact"), each with its default time scheme and Newton settings;
- Exudyn's ANCF cable model (exudyn_slider_crank.timed_solve): `exu.SolveDynamic` alone, the
  model built before the clock starts, no sensors and no solution file, with the solver settings
  of validate/compare.py (generalized-alpha rho_inf 0.9, full Newton, dense LU).
Each row also gives v* at the midpoint at the last step: the codes must march the same problem
for the times to compare (they differ by the modelling differences of results.md, a few percent
at this speed).  Times are measured on whatever machine runs this; read ratios, not absolutes.

Used by `python validate/compare.py --timing` and bench/run.py's peer_step_times().
"""

import math
import os
import platform
import time

import numpy as np

import crankgen
from crankgen import engine
from crankgen.declaration.cases import Case

CASE = dict(eps=0.01, omega=0.8, a=0.1, ms=0.5, mu=0.5, n_elements=16)
STEPS_PER_REV = 200       # issue 40's case for one step as simulate delivers it
REVOLUTIONS = 20
REPEATS = 3
CRANKGEN_MODELS = ("consistent", "exact")
NEWTON = {"newton": "Newton, tangent reused while it converges fast",
          "full-newton": "full Newton"}


def _mechanism():
    return crankgen.Mechanism(a=CASE["a"], eps=CASE["eps"], ms=CASE["ms"], mu=CASE["mu"])


def crankgen_runs(steps_per_rev=STEPS_PER_REV, revolutions=REVOLUTIONS):
    """crankgen's timed runs, loaded: {(model, path): callable returning a row}; per model, through
    simulate(history=False) and through engine.march (one case, one thread)."""
    import warnings
    from crankgen.notices import BeyondTheoryWarning
    mech, n_steps = _mechanism(), steps_per_rev * revolutions
    settings = dict(omega=CASE["omega"], n_elements=CASE["n_elements"], steps_per_rev=steps_per_rev)
    runs = {}

    def quiet(fn):
        def run():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", BeyondTheoryWarning)     # the deflection at this speed
                return fn()
        return run

    for model in CRANKGEN_MODELS:
        case = Case.from_mechanism(mech, model=model, **settings)
        common = dict(code="crankgen", model=model, integrator=case.integrator, rho_inf=case.rho_inf,
                      steps=n_steps)

        def simulate(model=model, common=common):
            t = time.perf_counter()
            r = crankgen.simulate(mech, model=model, revolutions=revolutions, history=False, **settings)
            seconds = time.perf_counter() - t
            return dict(common, path="simulate(history=False)", seconds=seconds,
                        newton_iterations_per_step=float(np.mean(r.iterations[1:])),
                        vstar_end=float(r.v_mid[-1]))

        batch = engine.Batch([case])

        def march(batch=batch, common=common):
            t = time.perf_counter()
            m = engine.march(batch, n_steps, parallel=False)
            seconds = time.perf_counter() - t
            if int(m.status[0]) != engine.OK:
                raise RuntimeError(f"crankgen's engine failed: {engine.STATUS_TEXT[int(m.status[0])]}")
            return dict(common, path="engine.march", seconds=seconds,
                        newton_iterations_per_step=float(m.iterations[0].mean()),
                        vstar_end=float(m.y[0, -1, 0]))

        quiet(lambda: crankgen.simulate(mech, model=model, revolutions=1, history=False, **settings))()
        engine.march(batch, 5, parallel=False)                                  # load compiled code
        runs[model, "simulate"] = quiet(simulate)
        runs[model, "engine"] = march
    return runs


def exudyn_run(steps_per_rev=STEPS_PER_REV, revolutions=REVOLUTIONS):
    """Exudyn's timed run (SolveDynamic alone), loaded; and the keywords of timed_solve."""
    import exudyn_slider_crank as exs
    kw = dict(eps=CASE["eps"], omega=CASE["omega"], a=CASE["a"], ms=CASE["ms"], mu=CASE["mu"],
              n_elements=CASE["n_elements"], steps_per_rev=steps_per_rev)
    exs.timed_solve(**kw, revolutions=1)                                        # load

    def run():
        r = exs.timed_solve(**kw, revolutions=revolutions)
        return dict(code="Exudyn", model="ANCF cable", path="SolveDynamic (no sensors, no file)",
                    integrator="full Newton, dense LU", rho_inf=0.9, seconds=r["seconds"],
                    steps=r["steps"], newton_iterations_per_step=r["newton_iterations"] / r["steps"],
                    jacobians_per_step=r["jacobians"] / r["steps"], vstar_end=r["vstar_end"])
    return run, kw


def measure(steps_per_rev=STEPS_PER_REV, revolutions=REVOLUTIONS, repeats=REPEATS, profile=True,
            progress=print):
    """The whole comparison: a dict ready for JSON (rows, ratios Exudyn / each crankgen row,
    settings).  The repeats are interleaved (every run once, then again), so that a change of the
    machine's load during the measurement reaches every row alike; each row keeps its fastest."""
    import exudyn
    import exudyn_slider_crank as exs
    progress(f"timing Exudyn and crankgen on the same march ({revolutions} revolutions of "
             f"{steps_per_rev} steps, best of {repeats}) ...")
    peer, kw = exudyn_run(steps_per_rev, revolutions)
    runs = dict([(("Exudyn", "solve"), peer)] + list(crankgen_runs(steps_per_rev, revolutions).items()))
    best = {}
    for _ in range(repeats):
        for key, run in runs.items():
            r = run()
            if key not in best or r["seconds"] < best[key]["seconds"]:
                best[key] = r
    rows = list(best.values())
    for r in rows:
        r["us_per_step"] = 1e6 * r["seconds"] / r["steps"]
    for r in rows[1:]:
        r["exudyn_over_this"] = rows[0]["us_per_step"] / r["us_per_step"]
    if profile:             # Exudyn's own timer, one more run (the timer itself costs a little)
        timer = exs.timed_solve(**kw, revolutions=revolutions, profile=True)["timer"]
        total = timer.get("total") or math.nan
        rows[0]["profile_share"] = {k: v / total for k, v in sorted(timer.items(), key=lambda kv: -kv[1])
                                    if k not in ("total", "useTimer", "totalJacobian") and v / total >= 0.01}
    return dict(date=time.strftime("%Y-%m-%d %H:%M:%S"),
                machine=dict(platform=platform.platform(), python=platform.python_version(),
                             cpus=os.cpu_count(), load_average=list(os.getloadavg())),
                exudyn=exudyn.__version__, crankgen=getattr(crankgen, "__version__", "?"),
                case=dict(CASE, steps_per_rev=steps_per_rev, revolutions=revolutions, repeats=repeats),
                rows=rows)


def table(result):
    """Markdown table of measure()'s result."""
    L = ["| code | model | timed | time scheme / Newton | us per step | Newton iterations per step "
         "| Exudyn / this | v* at the end |",
         "|---|---|---|---|---:|---:|---:|---:|"]
    for r in result["rows"]:
        scheme = ("Newmark (trapezoidal)" if r["rho_inf"] == 1 else f"generalized-alpha {r['rho_inf']:g}")
        scheme += ", " + NEWTON.get(r["integrator"], r["integrator"])
        ratio = f"{r['exudyn_over_this']:.1f}" if "exudyn_over_this" in r else "1"
        L.append(f"| {r['code']} | {r['model']} | {r['path']} | {scheme} | {r['us_per_step']:.1f} "
                 f"| {r['newton_iterations_per_step']:.2f} | {ratio} | {r['vstar_end']:.4f} |")
    return "\n".join(L)
