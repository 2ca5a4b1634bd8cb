"""The Sommerfeld effect of the flexible slider-crank driven by a motor of limited torque.

The slider-crank of crankgen's default mechanism (a* = 0.1, eps = 0.01, ms* = 0.5, mu* = 0.5, 4
elements) is driven by a motor T_m = T_stall (1 - thetad / Omega_nl) through a crank of inertia J.
Near the rod's resonance the rod takes the motor's power: the crank's mean speed against the motor's
no-load speed Omega_nl, from continuation of the steady motion (crankgen.continuation in
no_load_speed), is an S: two folds bound a range of Omega_nl with two stable motions, one captured
below the resonance and one beyond it.  Marching (crankgen.simulate) with Omega_nl raised slowly in
stages (each stage starting from the last one's state) follows the lower branch up to its fold and
jumps; lowered slowly it follows the upper branch down to the other fold and drops: the hysteresis.
Finally, at an Omega_nl inside the hysteresis, the continuation in the crank's inertia J shows
where a flywheel removes the captured motion (its branch folds), and run-ups from rest with
flywheels of growing inertia show which end captured.

    .venv/bin/python examples/sommerfeld.py [--out DIR] [--quick]

writes DIR/sommerfeld.png, sommerfeld_branches.csv, sommerfeld_marching.csv and
sommerfeld_flywheel.csv (default DIR: ./sommerfeld), and prints what it found.
"""

import argparse
import csv
import math
import warnings
from pathlib import Path

import numpy as np

import crankgen
from crankgen.notices import BeyondTheoryWarning

STALL, J, ELEMENTS = 0.0022, 0.05, 4
LOW, HIGH = 3.0, 12.0


def motor(no_load, inertia=J, **start):
    return crankgen.Motor(stall_torque=STALL, no_load_speed=float(no_load), inertia=inertia, **start)


def branches():
    """The continuation in no_load_speed: rows (branch, period, no_load_speed, mean_speed, stable)."""
    d = crankgen.continuation(parameter="no_load_speed", start=LOW, stop=HIGH, max_period=2,
                              crank=motor(LOW), n_elements=ELEMENTS,
                              progress=lambda text: print("  " + text) if "point" not in text else None)
    rows = []
    for k, br in enumerate(d.branches):
        for p, w, s in zip(br.parameter, br.quantities["mean_speed"], br.stable):
            rows.append((k, br.period, float(p), float(w), bool(s)))
    return d, rows


def staircase(values, duration, repeats=6):
    """March with Omega_nl stepped through `values`, each stage `duration` time units from the last
    stage's state, prolonged by `duration` at a time (up to `repeats` times) until its mean speed
    over the last third changes by less than 0.2 %: rows (no_load_speed, that mean speed)."""
    rows = []
    state, theta, speed = None, 0.0, 0.0
    for value in values:
        revolutions = duration * value / (2 * math.pi)           # the run is counted in no-load revolutions
        previous = math.inf
        for _ in range(repeats):
            r = crankgen.simulate(crank=motor(value, theta0=theta % (2 * math.pi), initial_speed=speed),
                                  n_elements=ELEMENTS, revolutions=revolutions, initial=state)
            k = len(r.t) * 2 // 3
            mean = float((r.theta[-1] - r.theta[k]) / (r.t[-1] - r.t[k]))
            state, theta, speed = (r.states[-1], r.rates[-1]), float(r.theta[-1]), float(r.crank_speed[-1])
            if abs(mean - previous) < 2e-3 * mean:
                break
            previous = mean
        rows.append((float(value), mean))
        print(f"  Omega_nl = {value:.3f}: mean speed {mean:.4f}")
    return rows


def run_up(value, inertia, duration, windows=6):
    """From rest at Omega_nl = value with a crank inertia `inertia`: (the mean speed over the last
    half of `duration`, the least and the largest mean speed of its `windows` parts: apart when the
    motion has not settled on a steady one)."""
    r = crankgen.simulate(crank=motor(value, inertia), n_elements=ELEMENTS,
                          revolutions=duration * value / (2 * math.pi), history=False)
    n = len(r.t)
    cuts = np.linspace(n // 2, n - 1, windows + 1).astype(int)
    parts = [(r.theta[b] - r.theta[a]) / (r.t[b] - r.t[a]) for a, b in zip(cuts[:-1], cuts[1:])]
    whole = (r.theta[-1] - r.theta[n // 2]) / (r.t[-1] - r.t[n // 2])
    return float(whole), float(min(parts)), float(max(parts))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="sommerfeld")
    ap.add_argument("--quick", action="store_true", help="coarser staircase and fewer flywheels")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore", BeyondTheoryWarning)

    print("continuation in no_load_speed ...")
    diagram, rows = branches()
    folds = [sp for sp in diagram.special_points if sp.kind == "fold"]
    with open(out / "sommerfeld_branches.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["branch", "period", "no_load_speed", "mean_speed", "stable"])
        w.writerows(rows)

    step = 0.5 if args.quick else 0.25
    # a stage lasts about 3 times the motor's time constant (J + the linkage's) Omega_nl / T_stall
    duration = 300.0 if args.quick else 600.0
    up_values = np.arange(LOW, HIGH + 1e-9, step)
    print("marching, Omega_nl raised in stages ...")
    up = staircase(up_values, duration)
    print("marching, Omega_nl lowered in stages ...")
    down = staircase(up_values[::-1], duration)
    with open(out / "sommerfeld_marching.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["direction", "no_load_speed", "mean_speed"])
        w.writerows([("up", *r) for r in up] + [("down", *r) for r in down])

    # the hysteresis: where the run-up and the run-down disagree
    apart = [v for (v, a), (_, b) in zip(up, down[::-1]) if abs(a - b) > 0.02 * max(a, b)]
    inside = 0.5 * (min(apart) + max(apart)) if apart else 0.5 * (LOW + HIGH)
    print(f"hysteresis: the marched speeds differ for Omega_nl in [{min(apart) if apart else float('nan'):.3f}, "
          f"{max(apart) if apart else float('nan'):.3f}]")
    inertias = (0.005, 0.05, 0.2) if args.quick else (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5)
    print(f"continuation in the crank's inertia at Omega_nl = {inside:.3f} ...")
    dj = crankgen.continuation(parameter="inertia", start=J, stop=0.5, max_period=1, crank=motor(inside),
                               n_elements=ELEMENTS)
    j_folds = [sp.parameter for sp in dj.special_points if sp.kind == "fold"]
    print("  the captured branch " + (f"ends in a fold at J = {min(j_folds):.4f}" if j_folds else
                                      "has no fold up to J = 0.5"))
    print(f"run-ups from rest at Omega_nl = {inside:.3f} ...")
    # each long enough for the motor's speed to settle: 4 (J + the linkage's ~0.005) Omega_nl / T_stall
    fly = [(J_, *run_up(inside, J_, max(duration, 8 * (J_ + 0.005) * inside / STALL))) for J_ in inertias]
    for J_, w_, lo, hi in fly:
        print(f"  J = {J_:g}: mean speed {w_:.4f} (its parts from {lo:.4f} to {hi:.4f})")
    with open(out / "sommerfeld_flywheel.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["no_load_speed", "inertia", "mean_speed", "least_part", "largest_part"])
        w.writerows([(inside, *row) for row in fly])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, fx) = plt.subplots(1, 2, figsize=(10.5, 5.0), gridspec_kw={"width_ratios": [3, 1.2]})
    for k, br in enumerate(diagram.branches):
        p, w_ = br.parameter, br.quantities["mean_speed"]
        for stable, style in ((True, "-"), (False, "--")):
            y = np.where(br.stable == stable, w_, np.nan)
            ax.plot(p, y, style, color="C0" if br.period == 1 else "C2", lw=1.6,
                    label=(f"continuation, period {br.period}, {'stable' if stable else 'unstable'}"
                           if k == [b.period for b in diagram.branches].index(br.period) else None))
    for sp in diagram.special_points:
        br = diagram.branches[sp.branch]
        i = int(np.argmin(np.abs(br.parameter - sp.parameter)))
        marker = {"fold": "o", "period-doubling": "s", "neimark-sacker": "^"}[sp.kind]
        ax.plot(sp.parameter, br.quantities["mean_speed"][i], marker, color="k", ms=6, mfc="none")
    ax.plot(*zip(*up), ">", color="C3", ms=4, label="marching, Omega_nl raised in stages")
    ax.plot(*zip(*down), "<", color="C1", ms=4, label="marching, Omega_nl lowered in stages")
    ax.plot([], [], "o", color="k", mfc="none", label="fold (o), period doubling (s)")
    ax.set_xlabel("motor's no-load speed Omega_nl* (omega_b)")
    ax.set_ylabel("mean crank speed (omega_b)")
    ax.set_title(f"Sommerfeld effect: slider-crank, eps = 0.01, T_stall* = {STALL}, J* = {J}", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    js = np.array([row[0] for row in fly])
    mid, lo, hi = (np.array([row[k] for row in fly]) for k in (1, 2, 3))
    fx.errorbar(js, mid, yerr=[mid - lo, hi - mid], fmt="o", color="C4", capsize=3)
    fx.set_xscale("log")
    for jf in j_folds[:1]:
        fx.axvline(jf, color="0.4", ls=":", lw=1)
        fx.text(jf, 0.9, f" captured branch\n ends: J* = {jf:.3g}", fontsize=7,
                va="bottom", transform=fx.get_xaxis_transform())
    fx.set_xlabel("crank inertia J* (rho A L^3)")
    fx.set_ylabel("mean crank speed after the run-up")
    fx.set_title(f"run-up from rest, Omega_nl* = {inside:.3g}", fontsize=10)
    fx.set_ylim(ax.get_ylim())
    fx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "sommerfeld.png", dpi=130)
    print(f"folds at Omega_nl = {', '.join(f'{sp.parameter:.4f}' for sp in folds)}; in J at Omega_nl = "
          f"{inside:.3f}: {', '.join(f'{j:.4f}' for j in j_folds) or 'none'}; wrote {out}/sommerfeld.png and the CSV files")


if __name__ == "__main__":
    main()
