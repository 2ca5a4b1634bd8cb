"""The flexible slider crank of the Test Set for IVP Solvers, computed with crankgen.

The Test Set for IVP Solvers (release 2.3, problem 'crank'; B. Simeon's model) publishes reference
values of a real steel slider crank: a rigid crank turning at 150 rad/s, an elastic steel rod, a
sliding block, no damping, linear strain, started from a given elastic state and read at
t = 0.1 s.  Its numbers (mechanism, initial state, reference values) are written below as data,
with their origin.  The published values belong to the test set's own discretisation of the rod
(two sine modes for the deflection, one quadratic axial element); crankgen discretises the rod with
finite elements, so this script refines crankgen's mesh and time step and sets the converged
values beside the published ones.

What it does:
1. builds the mechanism from the published SI data (crankgen.SIMechanism);
2. maps the published initial state (Ritz co-ordinates and the chord frame's rates) onto
   crankgen's moving frame and mesh (`published_initial_state`, the algebra in comments);
3. runs crankgen's linear-strain model (approach C, exact Lagrange equations, no damping, no
   rotary inertia of the sections) on a ladder of meshes and time steps, and prints the slider
   position, the chord angle and the rod's midpoint deflection from its chord at t = 0.1 s beside
   the published values, with Richardson-extrapolated values;
4. plots the midpoint deflection and the chord's elongation over 0 <= t <= 0.1 s;
5. runs the non-linear strain models (approaches A and B) on the same mechanism and reports what
   they change.

    python examples/ivp_testset_slider_crank.py            # full ladder, 2 to 3 minutes on 2 cores
    python examples/ivp_testset_slider_crank.py --quick    # coarse ladder, seconds
    python examples/ivp_testset_slider_crank.py --out DIR  # where the PNG and CSV go (default ./ivp_testset)

Units: SI throughout (m, s, rad, kg).  Conventions: X along the guide from the crank pivot towards
the slider, Y a quarter turn counter-clockwise; angles counter-clockwise from X.
"""

import argparse
import csv
import math
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

import crankgen

# ---- the published data: Test Set for IVP Solvers, release 2.3, problem 'crank' ---------------------
# mechanism (SI): crank 0.15 m at 150 rad/s; steel rod 0.30 m, square section 8 mm x 8 mm,
# E = 2.0e11 Pa, rho = 7870 kg/m^3; slider mass 0.075552 kg (half the rod's mass); guide through the
# crank pivot; no gravity, no damping.
CRANK, ROD, SIDE = 0.15, 0.30, 0.008
E, RHO, SLIDER_MASS, CRANK_SPEED = 2.0e11, 7870.0, 0.075552, 150.0

# initial state at t = 0 ("init 1" of the test set): crank angle phi1, chord angle phi2 (the rod's
# chord, from the crank pin to the rod's end, counter-clockwise from X), slider position x3, the
# Ritz co-ordinates q1..q4 (m) and their rates (m/s), the chord's angular rate phi2' (rad/s)
PHI1, PHI2, X3 = 0.0, 0.0, 0.450016933
Q = (0.0, 0.0, 1.03339863e-5, 1.69327969e-5)
QD = (0.4448961125815990, 4.634339319238670e-3, -1.785910760000550e-6, -2.689386719979040e-6)
PHI2_RATE, X3_RATE = -74.99576703969453, -2.689386719979040e-6

# reference values at t = 0.1 s
T_END = 0.1
PUBLISHED = {"slider_position": 0.1697373328427860,      # x3 (m)
             "chord_angle": -0.3311734988256260,         # phi2 (rad)
             "midpoint_deflection": 1.893192899613509e-4,  # q1: the rod's midpoint off its chord (m)
             "chord_elongation": -8.363313279112129e-6,  # q4: the end's axial displacement (m)
             "chord_rate": 60.25346755138369,            # phi2' (rad/s)
             "slider_velocity": -8.753116326670527}      # x3' (m/s)
LABELS = {"slider_position": "slider position x3 (m)", "chord_angle": "chord angle phi2 (rad)",
          "midpoint_deflection": "midpoint deflection q1 (m)", "chord_elongation": "chord elongation q4 (m)",
          "chord_rate": "chord rate phi2' (rad/s)", "slider_velocity": "slider velocity x3' (m/s)"}
PRIMARY = ("slider_position", "chord_angle", "midpoint_deflection")
COLUMN_UNITS = {"slider_position": "m", "chord_angle": "rad", "midpoint_deflection": "m",
                "chord_elongation": "m", "chord_rate": "rad_per_s", "slider_velocity": "m_per_s"}

# crankgen's model of the benchmark: linear strain (approach C), the exact Lagrange equations, no
# rotary inertia of the cross-sections (the test set's rod has none), and no damping: the
# SIMechanism's damping = 0 gives mu* = 0, so the damping family (Kelvin-Voigt by default) adds
# nothing.  The membrane option acts on approaches A and B only.  The time scheme is the trapezoidal
# rule (rho_inf = 1: no numerical damping): the steps resolve every mode that matters here (the
# first axial mode at omega dt = 0.015), and an undamped benchmark is integrated without dissipation.
MODEL = dict(approach="C", formulation="lagrange", rotary_inertia=False, rho_inf=1.0)


def mechanism():
    return crankgen.SIMechanism(L=ROD, a=CRANK, E=E, rho=RHO, A=SIDE**2, I=SIDE**4 / 12,
                                slider_mass=SLIDER_MASS, crank_speed=CRANK_SPEED, damping=0.0)


def published_initial_state():
    """The published initial state as a crankgen.InitialState in SI (fields of x in metres).

    The test set describes the rod in a frame attached at the crank pin and turning with the rod's
    ACTUAL chord (angle phi2 counter-clockwise from X).  With xi = x / L, a material point x of the
    rod sits, in that frame, at (x + uS(x), w(x)) with

        uS = q3 4 xi (1 - xi) + q4 xi (2 xi - 1)        (one quadratic axial element)
        w  = q1 sin(pi xi) + q2 sin(2 pi xi)             (two sine modes; zero at both ends)

    crankgen describes it in the frame of the RIGID mechanism's chord (e_i from the pin to the rigid
    end, e_j a quarter turn counter-clockwise), at (x + u(x), v(x)).  e_i points at the angle -phi,
    phi the rigid rod angle measured clockwise, sin phi = (a / L) sin theta (derive/guides.py).  The
    angle from e_i to the actual chord is therefore

        delta = phi2 - (-phi) = phi2 + phi,

    and the same point in both frames gives (a rotation by delta):

        x + u = cos(delta) (x + uS) - sin(delta) w
        v     = sin(delta) (x + uS) + cos(delta) w

    Differentiating in time (delta' = phi2' + phi', and d/dt of the rotation is delta' times the
    rotation by delta + pi/2):

        u_t = cos(delta) uS' - sin(delta) w' - delta' v
        v_t = sin(delta) uS' + cos(delta) w' + delta' (x + u)

    with the rigid rate phi' = (a / L) theta' cos(theta) / cos(phi).  At the published start,
    theta = phi1 = 0 and phi2 = 0: both frames lie along X (delta = 0), so u = uS, v = w = 0,
    u_t = uS', and v_t = w' + delta' (x + uS): the actual chord turns at phi2' = -74.9958 rad/s, the
    rigid one at -75 rad/s (phi' = 75 clockwise), and the 0.0042 rad/s between them is a
    transverse velocity growing along the rod.  crankgen projects these fields on its mesh by
    nodal interpolation (crankgen.discrete.initial) and checks the pin and the guide: here the end moves
    along the guide because the published phi2' satisfies (L + q4) phi2' = -L phi', the test set's
    own consistency condition.
    """
    a_over_L = CRANK / ROD
    phi = math.asin(a_over_L * math.sin(PHI1))                      # rigid rod angle (clockwise)
    phi_rate = a_over_L * CRANK_SPEED * math.cos(PHI1) / math.cos(phi)
    delta, delta_rate = PHI2 + phi, PHI2_RATE + phi_rate
    c, s = math.cos(delta), math.sin(delta)
    q1, q2, q3, q4 = Q
    q1d, q2d, q3d, q4d = QD

    def uS(x):
        xi = x / ROD
        return q3 * 4 * xi * (1 - xi) + q4 * xi * (2 * xi - 1)

    def uS_t(x):
        xi = x / ROD
        return q3d * 4 * xi * (1 - xi) + q4d * xi * (2 * xi - 1)

    def w(x):
        xi = x / ROD
        return q1 * np.sin(np.pi * xi) + q2 * np.sin(2 * np.pi * xi)

    def w_t(x):
        xi = x / ROD
        return q1d * np.sin(np.pi * xi) + q2d * np.sin(2 * np.pi * xi)

    def u(x):
        return c * (x + uS(x)) - s * w(x) - x

    def v(x):
        return s * (x + uS(x)) + c * w(x)

    def u_t(x):
        return c * uS_t(x) - s * w_t(x) - delta_rate * v(x)

    def v_t(x):
        return s * uS_t(x) + c * w_t(x) + delta_rate * (x + u(x))

    return crankgen.InitialState(u=u, v=v, u_t=u_t, v_t=v_t)


def check_published_state():
    """The published slider position and rate follow from the rest of the published state."""
    x3 = CRANK * math.cos(PHI1) + (ROD + Q[3]) * math.cos(PHI2)
    x3_rate = (-CRANK * CRANK_SPEED * math.sin(PHI1) + QD[3] * math.cos(PHI2)
               - (ROD + Q[3]) * PHI2_RATE * math.sin(PHI2))
    assert abs(x3 - X3) < 1e-9 and abs(x3_rate - X3_RATE) < 1e-15, (x3, x3_rate)


# ---- runs ----------------------------------------------------------------------------------------
def at_end(n, steps_per_rev, approach="C", membrane=None):
    """The published quantities at t = 0.1 s from crankgen (SI)."""
    model = dict(MODEL, approach=approach)
    if membrane is not None:
        model["membrane"] = membrane
    start = time.perf_counter()
    r = crankgen.simulate(mechanism(), units="si", times=[T_END], initial=published_initial_state(),
                          history=False, n_elements=n, steps_per_rev=steps_per_rev, **model)
    s = r.si.at_times
    out = {"slider_position": s.slider_position[0], "chord_angle": s.chord_angle[0],
           "midpoint_deflection": s.chord_deflection(ROD / 2)[0], "chord_elongation": s.chord_elongation[0],
           "chord_rate": s.chord_rate[0], "slider_velocity": s.slider_velocity[0]}
    out.update(n=n, steps_per_rev=steps_per_rev, dt=r.t[1] * r.si.scales.factor("1/omega_b"),
               seconds=time.perf_counter() - start)
    return out


def history(n, steps_per_rev, approach="C", membrane=None):
    """The midpoint deflection and the chord elongation over 0 <= t <= 0.1 s (SI)."""
    model = dict(MODEL, approach=approach)
    if membrane is not None:
        model["membrane"] = membrane
    r = crankgen.simulate(mechanism(), units="si", times=[T_END], initial=published_initial_state(),
                          n_elements=n, steps_per_rev=steps_per_rev, **model)
    keep = r.si.t <= T_END
    return (r.si.t[keep], r.si.chord_deflection(ROD / 2)[keep], r.si.chord_elongation[keep],
            r.si.at_times.chord_deflection(ROD / 2)[0])


def first_axial_frequency():
    """The first axial frequency of the rod pinned at the crank with the slider at its end (rad/s):
    beta L tan(beta L) = m_rod / m_slider, omega = beta sqrt(E / rho) (bisection on (0, pi/2))."""
    ratio = RHO * SIDE**2 * ROD / SLIDER_MASS
    lo, hi = 1e-9, math.pi / 2 - 1e-12
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mid * math.tan(mid) < ratio else (lo, mid)
    return lo / ROD * math.sqrt(E / RHO)


def axial_vibration(t, elongation):
    """(times, part): the chord elongation less its running mean over one period of the first axial
    mode: the rod's undamped axial vibration."""
    period = 2 * math.pi / first_axial_frequency()
    width = max(3, int(round(period / (t[1] - t[0]))))
    mean = np.convolve(elongation, np.ones(width) / width, mode="valid")
    lead = (width - 1) // 2
    return t[lead:lead + mean.size], elongation[lead:lead + mean.size] - mean


def richardson(coarse, fine, order=2):
    """Extrapolation of values at step h (coarse) and h / 2 (fine), error ~ h^order."""
    return fine + (fine - coarse) / (2**order - 1)


def observed_order(v1, v2, v3):
    """log2 of the ratio of successive differences of values at h, h/2, h/4 (None if not monotone)."""
    d1, d2 = v2 - v1, v3 - v2
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        return None
    return math.log2(abs(d1 / d2))


# ---- report --------------------------------------------------------------------------------------
def rel(x, ref):
    return (x - ref) / abs(ref)


def show_ladder(rows, meshes, steps):
    print("\nt = 0.1 s, crankgen approach C (linear strain), lagrange, no damping, no rotary inertia")
    header = f"{'n':>3} {'steps/rev':>9} {'dt (s)':>9}   " + "   ".join(f"{LABELS[k]:>27}" for k in PRIMARY)
    print(header)
    by = {(r["n"], r["steps_per_rev"]): r for r in rows}
    for n in meshes:
        for spr in steps:
            r = by[(n, spr)]
            print(f"{n:>3} {spr:>9} {r['dt']:9.2e}   " + "   ".join(f"{r[k]:27.12g}" for k in PRIMARY))
        vals = [[by[(n, spr)][k] for spr in steps] for k in PRIMARY]
        orders = [observed_order(*v[-3:]) if len(v) >= 3 else None for v in vals]
        extra = [richardson(v[-2], v[-1]) for v in vals]
        print(f"{n:>3} {'Richardson':>9} {'(h^2)':>9}   " + "   ".join(f"{x:27.12g}" for x in extra))
        print(f"{'':>3} {'observed':>9} {'order':>9}   " + "   ".join(
            f"{('%.2f' % p) if p is not None else 'not monotone':>27}" for p in orders))
    print(f"{'':>3} {'published':>9} {'':>9}   " + "   ".join(f"{PUBLISHED[k]:27.12g}" for k in PRIMARY))


def show_meshes(rows, meshes, steps):
    """Mesh convergence: the values at the coarsest step of the ladder and the Richardson values in
    the step, mesh by mesh, with the change from the previous mesh."""
    by = {(r["n"], r["steps_per_rev"]): r for r in rows}
    for title, value in ((f"{steps[0]} steps/rev", lambda n, k: by[(n, steps[0])][k]),
                         ("Richardson in the step",
                          lambda n, k: richardson(by[(n, steps[-2])][k], by[(n, steps[-1])][k]))):
        print(f"\nmesh convergence, {title}: value (change from the previous mesh)")
        for i, n in enumerate(meshes):
            cells = []
            for k in PRIMARY:
                change = "" if i == 0 else f"({value(n, k) - value(meshes[i - 1], k):+.1e})"
                cells.append(f"{value(n, k):20.12g} {change:>9}")
            print(f"{n:>3}   " + "   ".join(cells))


def converged(rows, meshes, steps):
    """Converged values: Richardson in the step on the finest mesh.  Their uncertainty: the larger of
    its change from the next coarser mesh and of the last step refinement on the finest mesh (the
    positions and the deflection carry the rod's undamped axial vibration, whose phase at 0.1 s
    converges slowly: see the README)."""
    by = {(r["n"], r["steps_per_rev"]): r for r in rows}
    out = {}
    for k in PRIMARY:
        per_mesh = [richardson(by[(n, steps[-2])][k], by[(n, steps[-1])][k]) for n in meshes]
        last_step = abs(by[(meshes[-1], steps[-1])][k] - by[(meshes[-1], steps[-2])][k])
        out[k] = (per_mesh[-1], max(abs(per_mesh[-1] - per_mesh[-2]), last_step), per_mesh)
    return out


def plot(path, t, deflection, elongation, t_a, deflection_a, value_at_end, spr, n):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2, a3) = plt.subplots(3, 1, figsize=(8, 8.4), sharex=True, constrained_layout=True,
                                     gridspec_kw=dict(height_ratios=(3, 2, 1.4)))
    a1.plot(t, deflection * 1e3, lw=0.9, color="C0", label=f"crankgen, approach C ({n} elements, {spr} steps/rev)")
    a1.plot(t_a, deflection_a * 1e3, lw=0.8, ls="--", color="C3", label="crankgen, approach A (non-linear strain)")
    a1.plot([T_END], [PUBLISHED["midpoint_deflection"] * 1e3], "kx", ms=9, mew=2, label="published q1(0.1 s)")
    a1.plot([T_END], [value_at_end * 1e3], "o", mfc="none", color="C0", ms=8, label="crankgen at 0.1 s")
    a1.axhline(0.0, color="0.6", lw=0.6)
    a1.set_ylabel("midpoint deflection\nfrom the chord (mm)")
    a1.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
    a1.grid(alpha=0.3)
    fig.suptitle("Slider crank of the Test Set for IVP Solvers (problem 'crank'): crankgen", fontsize=10)
    a2.plot(t, elongation * 1e6, lw=0.7, color="C2", label="crankgen, approach C")
    a2.plot([T_END], [PUBLISHED["chord_elongation"] * 1e6], "kx", ms=9, mew=2, label="published q4(0.1 s)")
    a2.set_ylabel("chord elongation (µm)")
    a2.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
    a2.grid(alpha=0.3)
    tv, vib = axial_vibration(t, elongation)
    a3.plot(tv, vib * 1e9, lw=0.5, color="C4")
    a3.set_ylabel("axial vibration (nm)")
    a3.set_xlabel("t (s)")
    a3.grid(alpha=0.3)
    a3.set_title("chord elongation less its running mean over one period of the first axial mode", fontsize=8)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _cell(x):
    """A CSV cell: a number at full precision as plain text (repr of a Python float: NumPy 2's
    repr of its own scalars is "np.float64(...)", which no CSV reader takes for a number), else
    the value as text."""
    if isinstance(x, (float, np.floating)):
        return repr(float(x))
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    return x


def write_table(path, rows):
    """crank.csv: one row per run (source "crankgen": elements, steps per revolution, time step in
    s and the values at t = 0.1 s in SI), then the published values (source "published"; no
    elements, steps or time step).  Every column holds numbers (or empty fields) or words only."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        keys = ["n", "steps_per_rev", "dt", *LABELS]
        w.writerow(["source", "n", "steps_per_rev", "dt_s", *[f"{k}_{COLUMN_UNITS[k]}" for k in LABELS]])
        for r in sorted(rows, key=lambda r: (r["n"], r["steps_per_rev"])):
            w.writerow(["crankgen", *[_cell(r[k]) for k in keys]])
        w.writerow(["published", "", "", "", *[_cell(PUBLISHED[k]) for k in LABELS]])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="coarse ladder (4, 8 elements; 6400-25600 steps/rev)")
    parser.add_argument("--out", default="ivp_testset",
                        help="folder for crank.png and crank.csv (default ./ivp_testset)")
    args = parser.parse_args(argv)
    out = Path(args.out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        parser.error(f"--out {out}: cannot create the folder ({exc.strerror or exc})")
    check_published_state()
    si = mechanism()
    print(f"mechanism: omega_b = {si.omega_b:.2f} rad/s (first pinned-pinned bending frequency), "
          f"Omega* = {si.omega:.6f}, eps = r/L = {si.radius_of_gyration / ROD:.6f}, "
          f"ms* = {si.mechanism.ms:.4f}, mu* = {si.mechanism.mu:g}")
    if args.quick:
        meshes, steps = (4, 8), (6400, 12800, 25600)
    else:
        meshes, steps = (4, 8, 16, 32, 64), (51200, 102400, 204800)
    jobs = [(n, spr) for n in meshes for spr in steps]
    workers = max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)
    print(f"{len(jobs)} runs to t = 0.1 s on {workers} threads ...", flush=True)
    start = time.perf_counter()
    with ThreadPoolExecutor(workers) as pool:           # the compiled engine releases the GIL
        rows = list(pool.map(lambda job: at_end(*job), sorted(jobs, key=lambda j: -j[0] * j[1])))
    print(f"done in {time.perf_counter() - start:.0f} s")
    show_ladder(rows, meshes, steps)
    show_meshes(rows, meshes, steps)

    conv = converged(rows, meshes, steps)
    print("\nconverged (Richardson in the step, finest mesh) beside the published values:")
    print(f"{'quantity':>30} {'crankgen':>20} {'+-':>9} {'published':>20} {'relative difference':>20}")
    for k in PRIMARY:
        value, spread, _ = conv[k]
        print(f"{LABELS[k]:>30} {value:20.12g} {spread:9.1e} {PUBLISHED[k]:20.12g} {rel(value, PUBLISHED[k]):20.2e}")
    finest = max(rows, key=lambda r: (r["n"], r["steps_per_rev"]))
    print(f"\nrates and the chord's elongation at the finest settings ({finest['n']} elements, "
          f"{finest['steps_per_rev']} steps/rev; they carry the rod's undamped axial vibration, see the README):")
    for k in ("chord_elongation", "chord_rate", "slider_velocity"):
        print(f"{LABELS[k]:>30} {finest[k]:20.12g} {'':>9} {PUBLISHED[k]:20.12g} {rel(finest[k], PUBLISHED[k]):20.2e}")

    write_table(out / "crank.csv", rows)

    # the non-linear strain: approaches A and B on the same mechanism and initial state
    n_nl, spr_nl = (8, 12800) if args.quick else (16, 51200)
    print(f"\nnon-linear strain ({n_nl} elements, {spr_nl} steps/rev; A and B with the element-mean membrane "
          "strain, free of membrane locking):")

    def attempt(ap):
        try:
            return at_end(n_nl, spr_nl, ap, "averaged")
        except crankgen.ConvergenceError as exc:
            return exc

    with ThreadPoolExecutor(workers) as pool:
        nl = dict(zip(("C", "A", "B"), pool.map(attempt, ("C", "A", "B"))))
    for ap in ("A", "B"):
        if isinstance(nl[ap], crankgen.ConvergenceError):
            seconds = nl[ap].time / si.omega_b
            print(f"  approach {ap}: the run stops at t = {seconds * 1e3:.2f} ms ({nl[ap]}): its strain energy "
                  f"lacks the quartic term, so it is unbounded below once the rod's slopes are a few times "
                  f"r/L = {si.radius_of_gyration / ROD:.4f}, as they are here")
            continue
        print(f"  approach {ap} - C at t = 0.1 s: " + ", ".join(
            f"{k.replace('_', ' ')} {nl[ap][k] - nl['C'][k]:+.3e} ({rel(nl[ap][k], nl['C'][k]):+.1e} relative)"
            for k in PRIMARY))
    t_c, defl_c, elong_c, at_c = history(n_nl, spr_nl // 2)
    t_a, defl_a, _, _ = history(n_nl, spr_nl // 2, "A", "averaged")
    peak = np.max(np.abs(defl_c))
    diff = np.abs(defl_a - defl_c)
    early = t_c <= 0.02
    print(f"  over 0 <= t <= 0.1 s ({n_nl} elements, {spr_nl // 2} steps/rev): max |q1| (C) {peak:.4e} m "
          f"(q1 / L = {peak / ROD:.1e}); max |q1(A) - q1(C)| {np.max(diff):.2e} m ({np.max(diff) / peak:.0%} "
          f"of max |q1|), {np.max(diff[early]):.2e} m over the first 20 ms")
    print(f"\naxial vibration ({n_nl} elements, {spr_nl // 2} steps/rev): the chord elongation oscillates about "
          f"its running mean over one period of the first axial mode ({first_axial_frequency():.0f} rad/s) by up to "
          f"{np.max(np.abs(axial_vibration(t_c, elong_c)[1])):.1e} m")
    plot(out / "crank.png", t_c, defl_c, elong_c, t_a, defl_a, at_c, spr_nl // 2, n_nl)
    print(f"\nwrote {out / 'crank.png'} and {out / 'crank.csv'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
