"""Steady midspan amplitude: Exudyn (geometrically exact ANCF cable rod) against crankgen.

For eps in EPS and Omega* in SPEEDS (a* = 0.1, ms* = 0.5, mu* = 0.5, strain-rate damping):
- Exudyn: validate/exudyn_slider_crank.py, marched from the rigid mechanism's state, amplitude
  max |v*(1/2)| over the last revolution, with convergence checks at every point (half the
  elements, half the time step) and the periodicity of the last revolutions;
- crankgen, consistent model: steady_state(approach="A", formulation="lagrange",
  damping="kelvin-voigt", membrane="averaged", n_elements=16), same time step as Exudyn;
- crankgen, paper model: formulation="paper", damping="paper" (for context only: another
  damping model, so not expected to match);
- crankgen, the geometrically exact rod without rotary inertia (model="exact",
  rotary_inertia=False): the cable's own physics, so the two should agree to discretization error.
Diagnostics that explain the differences:
- crankgen without rotary inertia (rho I = 0; ANCF cable elements have none) for eps = 0.1;
- smaller cranks (a* = 0.01, 0.03) at Omega* = 0.8: the differences vanish with the amplitude.

Then the time per step of both codes on one case, measured in the same run (validate/peer_timing.py):
`--timing` runs that part alone (about a minute) and updates its section of results.md.

Writes validate/results.md, validate/results.csv and validate/timing.json.
`python validate/compare.py --help`.
"""

import argparse
import csv
import math
import multiprocessing as mp
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import crankgen                                # noqa: E402
try:
    import exudyn_slider_crank as exs          # noqa: E402
except ModuleNotFoundError as _missing:        # --help works without Exudyn; a run says what to install
    if _missing.name != "exudyn":
        raise
    exs = None
import peer_timing                             # noqa: E402

EPS = (0.01, 0.1)
SPEEDS = (0.2, 0.4, 0.6, 0.8, 1.0, 1.2)
A, MS, MU = 0.1, 0.5, 0.5
N_EL = 16                 # ANCF elements (and crankgen elements)
SPR = 400                 # time steps per crank revolution (both codes)
REVS = 24                 # revolutions marched in Exudyn
RHO = 0.9                 # generalized-alpha spectral radius (Exudyn default; 1.0 lets the
                          # index-3 multipliers oscillate undamped and Newton degrade)
CHECK_EL = 8              # convergence check: half the elements
CHECK_SPR = 2 * SPR       # convergence check: half the time step
CHECK_RHO = 0.8           # convergence check: more numerical damping (at Omega* = 0.8 only)
CHECK_REVS = 36           # convergence check: more revolutions (at Omega* = 0.8 only)
SMALL_A = (0.001, 0.01, 0.03)   # diagnostic: smaller cranks at Omega* = 0.8
NOROT_SPR, NOROT_REVS = 200, 30     # diagnostic rho I = 0 (crankgen's NumPy engine, marched)


# ---------------------------------------------------------------------------------------------
# work items (run in worker processes)

def exudyn_job(eps, omega, a=A, n_elements=N_EL, steps_per_rev=SPR, revolutions=REVS,
               spectral_radius=RHO):
    try:
        r = exs.run(eps, omega, a=a, ms=MS, mu=MU, n_elements=n_elements,
                    steps_per_rev=steps_per_rev, revolutions=revolutions,
                    spectral_radius=spectral_radius)
        r.theta = r.v_mid = None
        return r
    except Exception as exc:                   # report, never hide
        return f"failed: {type(exc).__name__}: {exc}"


def norot_job(eps, omega, a=A, steps_per_rev=NOROT_SPR, revolutions=NOROT_REVS):
    """crankgen consistent model with and without rotary inertia, both marched the same way from
    zero initial conditions; amplitude over the last revolution and its change per revolution."""
    out = {}
    mech = crankgen.Mechanism(a, eps, MS, MU)
    for label, rotary in (("rot", True), ("norot", False)):
        try:
            r = crankgen.simulate(mech, omega=omega, model="consistent", approach="A", n_elements=N_EL,
                                  steps_per_rev=steps_per_rev, revolutions=revolutions,
                                  rotary_inertia=rotary)
            v = r.v_mid
            n = steps_per_rev
            last, prev, prev2 = v[-n - 1:], v[-2 * n - 1:-n], v[-3 * n - 1:-2 * n]
            amp = float(np.max(np.abs(last)))
            out[label] = (amp, float(np.max(np.abs(last - prev)) / amp),
                          float(np.max(np.abs(last - prev2)) / amp))
        except Exception as exc:
            out[label] = (math.nan, f"failed: {type(exc).__name__}: {exc}", math.nan)
    return out


def crankgen_steady(eps, omega, model, a=A):
    """Approach A of one of crankgen's models ("consistent" or "paper")."""
    return crankgen.steady_state(crankgen.Mechanism(a=a, eps=eps, ms=MS, mu=MU), omega=omega, model=model,
                                 approach="A", n_elements=N_EL, steps_per_rev=SPR)


def crankgen_exact(eps, omega):
    """crankgen's geometrically exact rod without rotary inertia (the ANCF cable has none): the
    same kinematics and strain measures as Exudyn's cable, so the two should agree."""
    try:
        return crankgen.steady_state(crankgen.Mechanism(a=A, eps=eps, ms=MS, mu=MU), omega=omega, model="exact",
                                     n_elements=N_EL, steps_per_rev=SPR, rotary_inertia=False)
    except Exception as exc:                   # report, never hide
        return f"failed: {type(exc).__name__}: {exc}"


def exact_section(rows, cgx):
    """The exact rod against Exudyn: a table and its largest difference where both are periodic."""
    L = ["## The geometrically exact rod against Exudyn\n",
         "*crankgen exact* = `steady_state(model=\"exact\", rotary_inertia=False, "
         f"n_elements={N_EL}, steps_per_rev={SPR})`: the same rod as the ANCF cable (exact stretch "
         "and curvature, no rotary inertia), so the difference measures the two codes' "
         "discretizations and nothing of the physics.\n",
         "| eps | Omega* | Exudyn | crankgen exact | difference |", "|---:|---:|---:|---:|---:|"]
    diffs = []
    for r in rows:
        x = cgx[r["eps"], r["omega"]]
        if isinstance(x, str):
            L.append(f"| {r['eps']:g} | {r['omega']:g} | {fnum(r['exudyn_amplitude'])} | {x} | - |")
            continue
        both = r["exudyn_status"] == "periodic" and x.status == "periodic"
        d = rel(x.amplitude, r["exudyn_amplitude"]) if both else math.nan
        if both:
            diffs.append(abs(d))
        ex = fnum(r["exudyn_amplitude"]) if r["exudyn_status"] == "periodic" else \
            f"{fnum(r['exudyn_amplitude'])} ({r['exudyn_status']})"
        L.append(f"| {r['eps']:g} | {r['omega']:g} | {ex} | {cg_cell(x)} | {fpct(d)} |")
    L.append("")
    if diffs:
        L.append(f"Where both are periodic the exact rod and the ANCF cable differ by at most "
                 f"{100 * max(diffs):.2f} %.\n")
    return "\n".join(L)


# ---------------------------------------------------------------------------------------------
# formatting

def fnum(x, digits=4):
    if isinstance(x, str) or x is None or not math.isfinite(x):
        return "-"
    return f"{x:.{digits}f}"


def fpct(x):
    return "-" if x is None or not math.isfinite(x) else f"{100 * x:+.2f} %"


def rel(x, ref):
    return x / ref - 1.0 if math.isfinite(x) and math.isfinite(ref) and ref != 0 else math.nan


def marched_status(v):
    """Status of a crankgen march (amplitude, change/rev, change/2 revs), like Exudyn's."""
    amp, chg, chg2 = v
    if isinstance(chg, str):
        return chg
    return ("periodic" if chg < exs.PERIODIC_TOL else
            "period-2" if chg2 < exs.PERIODIC_TOL else "not-periodic")


def exu_amp(r):
    return r.amplitude if not isinstance(r, str) else math.nan


def exu_status(r):
    return r if isinstance(r, str) else r.status


def cg_cell(res):
    """Amplitude with the status shown when it is not periodic."""
    if res.status == "periodic":
        return fnum(res.amplitude)
    return f"{fnum(res.amplitude)} ({res.status})"


def exu_cell(r):
    if isinstance(r, str):
        return r
    return fnum(r.amplitude) if r.status == "periodic" else f"{fnum(r.amplitude)} ({r.status})"


# ---------------------------------------------------------------------------------------------

def main():
    p = argparse.ArgumentParser(
        description="Exudyn vs crankgen: steady midspan amplitude (about 4 minutes on 2 cores), then "
                    "the time per step of both codes on one case, in the same run")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                   help="worker processes for the amplitude runs (default: all cores)")
    p.add_argument("--out", default=HERE, help="directory for results.md, results.csv and timing.json")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--timing", action="store_true",
                       help="only the time per step (about a minute): writes timing.json and replaces "
                            "the timing section of an existing results.md")
    which.add_argument("--no-timing", action="store_true", help="only the amplitudes")
    args = p.parse_args()
    if exs is None:
        sys.exit("validate/compare.py needs Exudyn: pip install exudyn (make validate installs it)")
    if args.jobs < 1:
        p.error(f"--jobs must be at least 1, got {args.jobs}")
    os.makedirs(args.out, exist_ok=True)
    if args.timing:
        write_timing(args.out)
        return
    t_start = time.perf_counter()
    import exudyn

    # 1. Exudyn runs and the diagnostics, in worker processes
    jobs = {}
    ctx = mp.get_context("spawn")
    with ProcessPoolExecutor(max_workers=max(1, args.jobs), mp_context=ctx) as pool:
        for eps in EPS:
            for w in SPEEDS:
                jobs[("main", eps, w)] = pool.submit(exudyn_job, eps, w)
                jobs[("el", eps, w)] = pool.submit(exudyn_job, eps, w, n_elements=CHECK_EL)
                jobs[("dt", eps, w)] = pool.submit(exudyn_job, eps, w, steps_per_rev=CHECK_SPR)
            jobs[("rho", eps, 0.8)] = pool.submit(exudyn_job, eps, 0.8, spectral_radius=CHECK_RHO)
            jobs[("revs", eps, 0.8)] = pool.submit(exudyn_job, eps, 0.8, revolutions=CHECK_REVS)
            for a in SMALL_A:
                jobs[("small", eps, a)] = pool.submit(exudyn_job, eps, 0.8, a=a)
        for w in SPEEDS:
            jobs[("norot", 0.1, w)] = pool.submit(norot_job, 0.1, w)
        for a in SMALL_A:
            jobs[("norot-small", 0.1, a)] = pool.submit(norot_job, 0.1, 0.8, a=a)

        # 2. crankgen steady states (in this process, meanwhile)
        cg, cgp, cg_small, cgx = {}, {}, {}, {}
        for eps in EPS:
            for w in SPEEDS:
                cg[eps, w] = crankgen_steady(eps, w, "consistent")
                cgp[eps, w] = crankgen_steady(eps, w, "paper")
                cgx[eps, w] = crankgen_exact(eps, w)
            for a in SMALL_A:
                cg_small[eps, a] = crankgen_steady(eps, 0.8, "consistent", a=a)
        res = {k: f.result() for k, f in jobs.items()}
    wall = time.perf_counter() - t_start

    # 3. table rows
    rows = []
    for eps in EPS:
        for w in SPEEDS:
            ex, c, cp = res[("main", eps, w)], cg[eps, w], cgp[eps, w]
            both = exu_status(ex) == "periodic" and c.status == "periodic"
            nr = res.get(("norot", eps, w))
            rows.append(dict(
                eps=eps, omega=w,
                exudyn_amplitude=exu_amp(ex), exudyn_status=exu_status(ex),
                exudyn_change_per_rev=ex.periodicity if not isinstance(ex, str) else math.nan,
                exudyn_amplitude_8el=exu_amp(res[("el", eps, w)]),
                exudyn_amplitude_half_dt=exu_amp(res[("dt", eps, w)]),
                crankgen_amplitude=c.amplitude, crankgen_status=c.status,
                rel_diff=rel(c.amplitude, exu_amp(ex)) if both else math.nan,
                crankgen_exact_amplitude=(cgx[eps, w].amplitude if not isinstance(cgx[eps, w], str) else math.nan),
                crankgen_exact_status=(cgx[eps, w].status if not isinstance(cgx[eps, w], str) else cgx[eps, w]),
                crankgen_paper_amplitude=cp.amplitude, crankgen_paper_status=cp.status,
                crankgen_norot_amplitude=nr["norot"][0] if nr else math.nan,
                crankgen_norot_status=marched_status(nr["norot"]) if nr else "",
                crankgen_marched_amplitude=nr["rot"][0] if nr else math.nan,
                crankgen_marched_status=marched_status(nr["rot"]) if nr else "",
                exudyn_wall_time=ex.wall_time if not isinstance(ex, str) else math.nan))

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as fh:
        wr = csv.DictWriter(fh, fieldnames=list(rows[0]))
        wr.writeheader()
        for r in rows:
            wr.writerow({k: (repr(float(v)) if isinstance(v, float) else v) for k, v in r.items()})

    md = render(rows, res, cg, cgp, cg_small, wall, exudyn.__version__, exact_section(rows, cgx))
    with open(os.path.join(args.out, "results.md"), "w") as fh:
        fh.write(md)
    print(md)
    if not args.no_timing:          # after the pool has closed: nothing else runs meanwhile
        write_timing(args.out)


TIMING_BEGIN, TIMING_END = "<!-- timing: written by compare.py --timing -->", "<!-- end of timing -->"


def write_timing(out):
    """Measure the time per step (peer_timing.measure), write timing.json and the timing section of
    results.md (replaced where it is, appended otherwise; results.md is created if missing)."""
    import json
    result = peer_timing.measure()
    with open(os.path.join(out, "timing.json"), "w") as fh:
        fh.write(json.dumps(result, indent=2) + "\n")
    section = timing_section(result)
    path = os.path.join(out, "results.md")
    md = open(path).read() if os.path.exists(path) else ""
    if TIMING_BEGIN in md and TIMING_END in md:
        head, rest = md.split(TIMING_BEGIN, 1)
        md = head + section + rest.split(TIMING_END, 1)[1]
    else:
        md = md + ("\n" if md and not md.endswith("\n\n") else "") + section + "\n"
    with open(path, "w") as fh:
        fh.write(md)
    print(section)


def timing_section(result):
    """The markdown section of results.md with the time per step of both codes."""
    c, rows = result["case"], result["rows"]
    ex = rows[0]
    load = result["machine"].get("load_average")
    L = [TIMING_BEGIN, "## Time per step, both codes on the same march\n",
         f"Measured {result['date']} by `validate/compare.py --timing` (Exudyn {result['exudyn']}, "
         f"crankgen {result['crankgen']}) on {result['machine']['cpus']} cores"
         + (f", load average {load[0]:.1f} at the end" if load else "") + ". "
         f"Case: eps = {c['eps']:g}, Omega* = {c['omega']:g}, a* = {c['a']:g}, ms* = {c['ms']:g}, "
         f"mu* = {c['mu']:g}, {c['n_elements']} elements in both codes, {c['steps_per_rev']} steps "
         f"per revolution, {c['revolutions']} revolutions from the rigid mechanism's state "
         f"({c['steps_per_rev'] * c['revolutions']} steps), each code loaded by a short run first; "
         f"best of {c['repeats']} interleaved repeats. Exudyn: `SolveDynamic` alone (model built "
         "before the clock starts), no sensors and no solution file, the solver settings above "
         "(generalized-alpha, full Newton: the Jacobian computed and factorized at every "
         "iteration, Exudyn's default dense LU, relative tolerance 1e-8). crankgen: its defaults "
         "for each model, through `simulate(..., history=False)` and through its engine alone "
         "(`engine.march`, one thread). *v\\* at the end*: the midspan deflection at the last "
         "step, to show that the codes march the same problem (the exact rod and the ANCF cable "
         "agree; the consistent model differs as in the table above).\n",
         peer_timing.table(result), ""]
    share = ex.get("profile_share")
    if share:
        L.append("Exudyn's own timer on one more run: " + ", ".join(
            f"{k} {100 * v:.0f} %" for k, v in share.items()) + f"; {ex['jacobians_per_step']:.2f} "
            "Jacobians per step.\n")
    L.append("Wall times on a shared machine: the ratios, measured in the same run, are the result; "
             "the absolute times depend on the machine and its load.")
    L.append(TIMING_END)
    return "\n".join(L)


def findings(rows, res, cg, cg_small):
    """Summary paragraph; the numbers come from this run, the reading is the author's (it was
    written for the settings at the top of this file)."""
    per = [r for r in rows if r["exudyn_status"] == "periodic"]
    conv = max((max(abs(rel(r["exudyn_amplitude_8el"], r["exudyn_amplitude"])),
                    abs(rel(r["exudyn_amplitude_half_dt"], r["exudyn_amplitude"]))) for r in per),
               default=math.nan)
    a0 = min(SMALL_A)
    nonper = sorted({r["omega"] for r in rows if r["exudyn_status"] != "periodic"})

    def small(eps, a, which):
        ex = exu_amp(res[("small", eps, a)])
        if which == "cg":
            return fpct(rel(cg_small[eps, a].amplitude, ex))
        return fpct(rel(res[("norot-small", eps, a)]["norot"][0], ex))

    low = [r for r in per if r["omega"] <= 0.6 and r["eps"] == 0.01]
    T = []
    T.append("## Findings\n")
    T.append(f"- Exudyn's amplitudes are converged: halving the elements or the time step changes "
             f"them by at most {100 * conv:.2f} % wherever the response is periodic (Exudyn is not "
             f"periodic at Omega* = {', '.join(f'{x:g}' for x in nonper) or '-'}), and there the last "
             f"two revolutions agree to within {max((r['exudyn_change_per_rev'] for r in per), default=math.nan):.1e} "
             "of the amplitude.")
    T.append(f"- eps = 0.01, Omega* <= 0.6: crankgen's consistent model and Exudyn agree within "
             f"{100 * max((abs(r['rel_diff']) for r in low), default=math.nan):.2f} %.")
    T.append(f"- Small-amplitude limit (a* = {a0:g}, Omega* = 0.8): crankgen - Exudyn = "
             f"{small(0.01, a0, 'cg')} at eps = 0.01 and {small(0.1, a0, 'cg')} at eps = 0.1; with "
             f"crankgen's rotary inertia removed the eps = 0.1 difference is {small(0.1, a0, 'norot')}. "
             "The linear difference is therefore the rotary inertia rho I = eps^2 that crankgen's "
             "rod has and the ANCF cable lacks (it scales with eps^2: 100 times smaller at "
             "eps = 0.01). At eps = 0.1 it is not slight near resonance: it lowers the rod's "
             "bending frequency by about 5 % (omega^2 ~ 1/(1 + pi^2 eps^2)).")
    T.append("- At finite amplitude the differences grow with the deflection (table *Amplitude "
             "dependence*) and are largest where the amplitude rises steeply with the speed "
             "(Omega* = 0.8, between the quasi-static range and the resonance): "
             f"{fpct(rel(cg[0.01, 0.8].amplitude, exu_amp(res[('main', 0.01, 0.8)])))} at eps = 0.01 "
             f"(v = {0.01 * cg[0.01, 0.8].amplitude:.3f} L) and "
             f"{fpct(rel(res[('norot', 0.1, 0.8)]['norot'][0], exu_amp(res[('main', 0.1, 0.8)])))} "
             "at eps = 0.1 even without rotary inertia. They vanish as the crank (and with it "
             "the deflection) shrinks, so they come from terms beyond crankgen's strain energy "
             "(eq. 2: curvature v'' and membrane strain u' + v'^2/2 in the rigid rod's frame, "
             "moderate rotations), which the geometrically exact cable keeps (exact curvature, "
             "strain |r'| - 1). This is our reading, not a proof: the term responsible was not "
             "isolated.")
    w = max(SPEEDS)
    st = {eps: exu_status(res[("main", eps, w)]) for eps in EPS}
    nr = res[("norot", 0.1, w)]
    T.append(f"- Omega* = {w:g}: crankgen's shooting returns a period-1 orbit with status "
             + ", ".join(f"{cg[eps, w].status} (largest Floquet multiplier {cg[eps, w].multiplier:.2f}) "
                         f"at eps = {eps:g}" for eps in EPS)
             + "; Exudyn, marched from the rigid start, is "
             + " and ".join(f"{st[eps]} at eps = {eps:g}" for eps in EPS)
             + f". crankgen marched the same way is {marched_status(nr['rot'])} at eps = 0.1 with "
             f"rotary inertia but {marched_status(nr['norot'])} (amplitude {fnum(nr['norot'][0])}) "
             f"without it, whereas Exudyn (no rotary inertia either) is {st[0.1]} at amplitude "
             f"{fnum(exu_amp(res[('main', 0.1, w)]))}: a qualitative difference that is not explained "
             "here (coexisting responses, reached from the same start by one model and not the "
             "other, are possible in this range). Amplitudes at this speed are not compared.")
    T.append("- The paper-model column uses stiffness-proportional damping C = mu (K_lin + K_non) "
             "(eq. 24), a different dissipation; it is context, not a validation target.\n")
    return "\n".join(T)


def render(rows, res, cg, cgp, cg_small, wall, exu_version, exact=""):
    L = []
    add = L.append
    add("# Exudyn (ANCF cable) vs crankgen: steady midspan amplitude\n")
    add(f"Generated by `validate/compare.py` (Exudyn {exu_version}, crankgen "
        f"{getattr(crankgen, '__version__', '?')}); total wall time {wall:.0f} s on "
        f"{os.cpu_count()} cores.\n")
    add(f"Mechanism: a* = {A}, ms* = {MS}, mu* = {MU}, strain-rate (Kelvin-Voigt) damping on axial "
        "strain and curvature. Amplitude: max |v*(1/2)| over one steady revolution, v* measured "
        "from the crank pin along e_j = (sin phi, cos phi) of the rigid rod, divided by eps.\n")
    add("Columns: *Exudyn* = ANCF cable model; *crankgen* = `steady_state(approach=\"A\", "
        "formulation=\"lagrange\", damping=\"kelvin-voigt\", membrane=\"averaged\", "
        f"n_elements={N_EL}, steps_per_rev={SPR})`; *difference* = crankgen / Exudyn - 1 (only "
        "when both are periodic); *crankgen paper* = `formulation=\"paper\", damping=\"paper\"` "
        "(printed model, stiffness-proportional damping: context only, not the same damping); "
        "*crankgen, rho I = 0* = the consistent model without rotary inertia (diagnostic, see "
        "below). A status other than periodic is shown in brackets.\n")
    add("| eps | Omega* | Exudyn | crankgen | difference | crankgen paper | crankgen, rho I = 0 | difference (rho I = 0) |")
    add("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        ex = res[("main", r["eps"], r["omega"])]
        c, cp = cg[r["eps"], r["omega"]], cgp[r["eps"], r["omega"]]
        nr = res.get(("norot", r["eps"], r["omega"]))
        if nr:
            amp, st = nr["norot"][0], marched_status(nr["norot"])
            per = st == "periodic"
            nr_cell = fnum(amp) if per else (f"{fnum(amp)} ({st})" if math.isfinite(amp) else st)
            nr_diff = fpct(rel(amp, r["exudyn_amplitude"])) if per and r["exudyn_status"] == "periodic" else "-"
        else:
            nr_cell, nr_diff = "n/a", "-"
        add(f"| {r['eps']:g} | {r['omega']:g} | {exu_cell(ex)} | {cg_cell(c)} | {fpct(r['rel_diff'])} "
            f"| {cg_cell(cp)} | {nr_cell} | {nr_diff} |")
    add("")

    add(findings(rows, res, cg, cg_small))
    if exact:
        add(exact)
    add("## Exudyn model and settings\n")
    add("- Rod: ObjectANCFCable2D elements (NodePoint2DSlope1 nodes), L = 1, rho A = 1, "
        "EI = 1/pi^4, EA = 1/(pi^4 eps^2); damping parameters bendingDamping = mu* EI and "
        "axialDamping = mu* EA (Exudyn's viscous virtual work "
        "int (d_eps epsdot delta eps + d_K Kdot delta K) dx). No rotary inertia.")
    add("- Crank pin: position of the first node prescribed, a*(cos Omega* t, sin Omega* t), by two "
        "CoordinateConstraints with time-dependent offsets; slope free.")
    add("- Slider: MassPoint2D (ms*) on the last node, Y = 0 by a CoordinateConstraint; slope free.")
    add("- Start: straight, stress-free rod at theta = 0 with the rigid mechanism's velocities.")
    add(f"- Solver: generalized-alpha (index 3), spectral radius {RHO:g}, full Newton (relative "
        f"tolerance 1e-8), fixed step; {N_EL} elements, {SPR} steps per revolution "
        f"(dt* = 2 pi / ({SPR} Omega*)), {REVS} revolutions; amplitude from the last one.\n")

    add("## Convergence checks (Exudyn)\n")
    add(f"At every point: {CHECK_EL} instead of {N_EL} elements, and {CHECK_SPR} instead of {SPR} "
        "steps per revolution (half the time step); change of v* between the last two "
        "revolutions, relative to the amplitude.\n")
    add(f"| eps | Omega* | amplitude ({N_EL} el, {SPR}/rev) | {CHECK_EL} elements | half time step | change per revolution | wall time (s) |")
    add("|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        ex = res[("main", r["eps"], r["omega"])]
        e8, edt = res[("el", r["eps"], r["omega"])], res[("dt", r["eps"], r["omega"])]
        add(f"| {r['eps']:g} | {r['omega']:g} | {exu_cell(ex)} "
            f"| {fnum(exu_amp(e8), 6)} ({fpct(rel(exu_amp(e8), r['exudyn_amplitude']))}) "
            f"| {fnum(exu_amp(edt), 6)} ({fpct(rel(exu_amp(edt), r['exudyn_amplitude']))}) "
            f"| {r['exudyn_change_per_rev']:.1e} | {r['exudyn_wall_time']:.1f} |")
    add("")
    add(f"At Omega* = 0.8: spectral radius {CHECK_RHO:g} instead of {RHO:g}, and {CHECK_REVS} instead "
        f"of {REVS} revolutions:\n")
    add("| eps | amplitude | spectral radius " + f"{CHECK_RHO:g} | {CHECK_REVS} revolutions |")
    add("|---:|---:|---:|---:|")
    for eps in EPS:
        m, rr, rv = res[("main", eps, 0.8)], res[("rho", eps, 0.8)], res[("revs", eps, 0.8)]
        add(f"| {eps:g} | {fnum(exu_amp(m), 6)} | {fnum(exu_amp(rr), 6)} ({fpct(rel(exu_amp(rr), exu_amp(m)))}) "
            f"| {fnum(exu_amp(rv), 6)} ({fpct(rel(exu_amp(rv), exu_amp(m)))}) |")
    add("")

    add("## Diagnostics\n")
    add("**Rotary inertia.** crankgen's rod has rho I = eps^2 (eq. B1); the ANCF cable has none. "
        "*crankgen, rho I = 0* is crankgen's consistent model with rho I set to 0 (a `Mechanism` "
        "subclass read by crankgen's NumPy engine), marched "
        f"{NOROT_REVS} revolutions from rest at {NOROT_SPR} steps per revolution; the same march "
        "with rho I = eps^2 (compiled engine) is shown beside it, and its change between the last "
        "two revolutions tells whether marching from rest settles on the orbit `steady_state` "
        "found. Computed for eps = 0.1 only (at eps = 0.01, rho I = 1e-4).\n")
    add("| eps | Omega* | crankgen steady_state | marched, rho I = eps^2 (change/rev) "
        "| marched, rho I = 0 (change/rev) | Exudyn |")
    add("|---:|---:|---:|---:|---:|---:|")

    def marched(v):
        amp, chg, chg2 = v
        if isinstance(chg, str):
            return chg
        kind = "" if chg < exs.PERIODIC_TOL else (", period-2" if chg2 < exs.PERIODIC_TOL
                                                   else ", not periodic")
        return f"{fnum(amp)} ({chg:.0e}{kind})"

    for w in SPEEDS:
        nr = res[("norot", 0.1, w)]
        add(f"| 0.1 | {w:g} | {cg_cell(cg[0.1, w])} | {marched(nr['rot'])} | {marched(nr['norot'])} "
            f"| {exu_cell(res[('main', 0.1, w)])} |")
    add("")
    add("**Amplitude dependence.** The comparison at Omega* = 0.8 with smaller cranks (the "
        "deflection, the rod's rotations and its axial strain all scale roughly with a*):\n")
    add("| eps | a* | Exudyn | crankgen | difference | crankgen, rho I = 0 | difference (rho I = 0) |")
    add("|---:|---:|---:|---:|---:|---:|---:|")
    for eps in EPS:
        for a in SMALL_A + (A,):
            ex = res[("small", eps, a)] if a != A else res[("main", eps, 0.8)]
            c = cg_small[eps, a] if a != A else cg[eps, 0.8]
            both = exu_status(ex) == "periodic" and c.status == "periodic"
            nr = res.get(("norot-small", eps, a)) if a != A else res.get(("norot", eps, 0.8))
            if nr and marched_status(nr["norot"]) == "periodic":
                nr_amp = nr["norot"][0]
                nr_cells = f"{fnum(nr_amp, 5)} | {fpct(rel(nr_amp, exu_amp(ex))) if both else '-'}"
            else:
                nr_cells = "n/a | -"
            add(f"| {eps:g} | {a:g} | {fnum(exu_amp(ex), 5) if both else exu_cell(ex)} "
                f"| {fnum(c.amplitude, 5) if both else cg_cell(c)} "
                f"| {fpct(rel(c.amplitude, exu_amp(ex))) if both else '-'} | {nr_cells} |")
    add("")
    return "\n".join(L) + "\n"


if __name__ == "__main__":
    main()
