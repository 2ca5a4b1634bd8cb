"""A four-bar's rocker with its own mass: how far the massless rocker's answers move.

The four-bar of crankgen's exact-rod study (crank a* = 0.1, a rocker of length c = 0.5 pivoted at
(1, 0), the coupler at eps = 0.01 with the tip mass ms* = 0.5) is run twice: with the usual rigid
massless rocker, and with a rigid rocker of the coupler's own section (a uniform bar: mass
m_r* = c, its centre of mass half-way, J_G* = m_r c^2 / 12 about it).  The example

1. finds the steady motion at Omega* = 0.4, 0.6 and 0.8 (crankgen.steady_state): the coupler's
   max |v*|, the peak crank torque and the peak force on the rocker's ground pivot (its bearing);
2. continues both over 0.6 <= Omega* <= 1.3 (crankgen.continuation, period-2 branches included):
   where the period doubling near 1.02 and the folds of the hysteresis loop move to.

    .venv/bin/python examples/heavy_rocker.py [--out DIR] [--elements N]

writes DIR/heavy_rocker.png (both continuations, special points marked) and DIR/heavy_rocker.csv
(the steady numbers), and prints both.  About a minute on two cores once the engine is compiled.
"""

import argparse
import csv
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import crankgen
from crankgen.notices import BeyondTheoryWarning

C = 0.5
FOUR_BAR = dict(guide=crankgen.Circle(center=(1.0, 0.0), radius=C), eps=0.01, ms=0.5)
ROCKERS = {"massless rocker": {},
           "rocker of the coupler's section": dict(rocker_mass=C, rocker_centre=0.5, rocker_inertia=C * C**2 / 12)}
SPEEDS = (0.4, 0.6, 0.8)


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text}")
    return value


def steady_rows(n_elements):
    rows = []
    for name, rocker in ROCKERS.items():
        mech = crankgen.Mechanism(**FOUR_BAR, **rocker)
        for omega in SPEEDS:
            s = crankgen.steady_state(mech, omega=omega, n_elements=n_elements, steps_per_rev=100)
            if s.v_mid is None:
                raise SystemExit(f"{name}, Omega* = {omega}: no periodic state ({s.status}: {s.message})")
            pivot = np.hypot(s.ground_on_rocker_x, s.ground_on_rocker_y)
            rows.append({"rocker": name, "omega": omega, "max_v_star": float(np.max(np.abs(s.v_mid))),
                         "peak_torque": float(np.max(np.abs(s.torque))), "peak_pivot_force": float(np.max(pivot))})
    return rows


def continuations(n_elements):
    out = {}
    for name, rocker in ROCKERS.items():
        out[name] = crankgen.continuation(crankgen.Mechanism(**FOUR_BAR, **rocker), "omega", 0.6, 1.3,
                                          max_period=2, n_elements=n_elements, steps_per_rev=50)
    return out


def draw(diagrams, path):
    fig, ax = plt.subplots(figsize=(8, 4.8), layout="constrained")
    for (name, d), colour in zip(diagrams.items(), ("0.2", "tab:red")):
        for k, b in enumerate(d.branches):
            stable = np.asarray(b.stable, bool)
            amp = np.where(stable, b.amplitude, np.nan)
            ax.plot(b.parameter, amp, "-", color=colour, lw=1.4, label=name if k == 0 else None)
            ax.plot(b.parameter, np.where(stable, np.nan, b.amplitude), "--", color=colour, lw=1.0)
        for s in d.special_points:
            ax.plot(s.parameter, s.amplitude, "s" if s.kind == "fold" else "o", color=colour, ms=5, mfc="none")
    ax.set_xlabel("crank speed Omega*")
    ax.set_ylabel("max |v*(1/2)| over the orbit")
    ax.axhspan(0.1 / FOUR_BAR["eps"], ax.get_ylim()[1], color="0.92", zorder=0)
    ax.set_title("four-bar (a* = 0.1, rocker c = 0.5 pivoted at (1, 0), eps = 0.01, ms* = 0.5, 4 elements)\n"
                 "stable solid, unstable dashed; period doublings o, folds square\n"
                 "shaded: |v|/L > 0.1, beyond the moderate-deflection theory (check on model='exact')", fontsize=9)
    ax.legend(loc="lower right", fontsize=9)
    ax.grid(alpha=0.3)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("."), help="folder for heavy_rocker.png and .csv (default .)")
    parser.add_argument("--elements", type=positive_int, default=8,
                        help="the coupler's elements for the steady states (default 8; the continuations use 4)")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore", BeyondTheoryWarning)      # the large orbits are shaded in the figure

    rows = steady_rows(args.elements)
    with open(args.out / "heavy_rocker.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    base = {r["omega"]: r for r in rows if r["rocker"] == "massless rocker"}
    print(f"steady motion, {args.elements} elements (units rho A L^3 omega_b^2 and rho A L^2 omega_b^2):")
    for r in rows:
        b = base[r["omega"]]
        change = "" if r is b else (f"   ({100 * (r['max_v_star'] / b['max_v_star'] - 1):+.0f} %, "
                                    f"{100 * (r['peak_torque'] / b['peak_torque'] - 1):+.0f} %, "
                                    f"{100 * (r['peak_pivot_force'] / b['peak_pivot_force'] - 1):+.0f} %)")
        print(f"  {r['rocker']:32s} Omega* {r['omega']:.1f}: max |v*| {r['max_v_star']:7.3f}, peak torque "
              f"{r['peak_torque']:.4f}, peak pivot force {r['peak_pivot_force']:.4f}{change}")

    diagrams = continuations(4)
    for name, d in diagrams.items():
        points = ", ".join(f"{s.kind} {s.parameter:.4f} (period {s.period})" for s in d.special_points)
        print(f"{name}: {points}")
    draw(diagrams, args.out / "heavy_rocker.png")
    print(f"wrote {args.out / 'heavy_rocker.png'} and {args.out / 'heavy_rocker.csv'}")


if __name__ == "__main__":
    main()
