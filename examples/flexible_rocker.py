"""A four-bar whose rocker flexes too: the coupler's and the rocker's deflections, and where the
period doubling moves.

The four-bar of crankgen's exact-rod study (crank a* = 0.1, a rocker of length c = 0.5 pivoted at
(1, 0), the coupler at eps = 0.01 with the tip mass ms* = 0.5) is run three ways: with the usual
rigid massless rocker, with a rigid rocker of the coupler's section (a uniform bar: mass c, its
centre half-way, J_G = m c^2 / 12), and with a flexible rocker of the coupler's section (the body
"rocker": rocker_elements > 0, rocker_density = rocker_bending = rocker_axial = 1, its elements as
long as the coupler's).  The example

1. finds the steady motion at Omega* = 0.4, 0.6 and 0.8 (crankgen.steady_state): the coupler's max
   |v*| (mid-span, in the rigid linkage's frame) and, for the flexible rocker, its max deflection
   at mid-length from its chord (pivot to tip), both in units of the coupler's radius of gyration;
2. continues the three over 0.6 <= Omega* <= 1.3
   (crankgen.continuation, period-2 branches included): where the period doubling near 1.02 and
   the folds of the hysteresis loop move to.

    .venv/bin/python examples/flexible_rocker.py [--out DIR] [--elements N]

writes DIR/flexible_rocker.png (both continuations, special points marked) and
DIR/flexible_rocker.csv (the steady numbers), and prints both.  About a minute on two cores once
the engine is compiled.
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
EPS = 0.01
SPEEDS = (0.4, 0.6, 0.8)


def rockers(n_elements):
    """{name: rocker parameters}: the flexible rocker's elements as long as the coupler's."""
    return {"rigid massless rocker": {},
            "rigid rocker, coupler's section": dict(rocker_mass=C, rocker_centre=0.5, rocker_inertia=C * C**2 / 12),
            "flexible rocker, coupler's section": dict(rocker_elements=max(2, round(C * n_elements)))}


def mechanism(rocker):
    return crankgen.Mechanism(eps=EPS, ms=0.5, guide=crankgen.Circle(center=(1.0, 0.0), radius=C, **rocker))


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text}")
    return value


def steady_rows(n_elements):
    rows = []
    for name, rocker in rockers(n_elements).items():
        for omega in SPEEDS:
            s = crankgen.steady_state(mechanism(rocker), omega=omega, n_elements=n_elements, steps_per_rev=100)
            if s.v_mid is None:
                raise SystemExit(f"{name}, Omega* = {omega}: no periodic state ({s.status}: {s.message})")
            flexible = "rocker_elements" in rocker
            rows.append({"rocker": name, "omega": omega, "coupler_max_v_star": float(np.max(np.abs(s.v_mid))),
                         "rocker_max_deflection": (float(np.max(np.abs(s.rocker_deflection(0.5))))
                                                   if flexible else ""),
                         "peak_torque": float(np.max(np.abs(s.torque)))})
    return rows


def continuations(n_elements):
    out = {}
    for name, rocker in rockers(n_elements).items():
        out[name] = crankgen.continuation(mechanism(rocker), "omega", 0.6, 1.3, max_period=2,
                                          n_elements=n_elements, steps_per_rev=50)
    return out


def draw(diagrams, path, n_elements):
    fig, ax = plt.subplots(figsize=(8, 4.8), layout="constrained")
    for (name, d), colour in zip(diagrams.items(), ("0.2", "tab:red", "tab:blue")):
        for k, b in enumerate(d.branches):
            stable = np.asarray(b.stable, bool)
            ax.plot(b.parameter, np.where(stable, b.amplitude, np.nan), "-", color=colour, lw=1.4,
                    label=name if k == 0 else None)
            ax.plot(b.parameter, np.where(stable, np.nan, b.amplitude), "--", color=colour, lw=1.0)
        for s in d.special_points:
            ax.plot(s.parameter, s.amplitude, "s" if s.kind == "fold" else "o", color=colour, ms=5, mfc="none")
    ax.set_xlabel("crank speed Omega*")
    ax.set_ylabel("coupler's max |v*(1/2)| over the orbit")
    ax.axhspan(0.1 / EPS, ax.get_ylim()[1], color="0.92", zorder=0)
    ax.set_title(f"four-bar (a* = 0.1, rocker c = 0.5 pivoted at (1, 0), eps = 0.01, ms* = 0.5, coupler "
                 f"{n_elements} elements)\nstable solid, unstable dashed; period doublings o, folds square\n"
                 "shaded: |v|/L > 0.1, beyond the moderate-deflection theory (check on model='exact')", fontsize=9)
    ax.legend(loc="lower right", fontsize=9)
    ax.grid(alpha=0.3)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("."),
                        help="folder for flexible_rocker.png and .csv (default .)")
    parser.add_argument("--elements", type=positive_int, default=8,
                        help="the coupler's elements for the steady states (default 8; the continuations use 4; "
                             "the flexible rocker's elements as long as the coupler's)")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore", BeyondTheoryWarning)      # the large orbits are shaded in the figure

    rows = steady_rows(args.elements)
    with open(args.out / "flexible_rocker.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    base = {r["omega"]: r for r in rows if r["rocker"] == "rigid massless rocker"}
    print(f"steady motion, coupler {args.elements} elements (v* and the rocker's deflection in units of r = eps L; "
          "torque in rho A L^3 omega_b^2):")
    for r in rows:
        b = base[r["omega"]]
        change = "" if r is b else f" ({100 * (r['coupler_max_v_star'] / b['coupler_max_v_star'] - 1):+.1f} %)"
        rocker = "" if r["rocker_max_deflection"] == "" else f", rocker max {r['rocker_max_deflection']:.3f}"
        print(f"  {r['rocker']:36s} Omega* {r['omega']:.1f}: coupler max |v*| {r['coupler_max_v_star']:7.3f}"
              f"{change}{rocker}, peak torque {r['peak_torque']:.4f}")

    diagrams = continuations(4)
    for name, d in diagrams.items():
        points = ", ".join(f"{s.kind} {s.parameter:.4f} (period {s.period})" for s in d.special_points)
        print(f"{name}: {points}")
    draw(diagrams, args.out / "flexible_rocker.png", 4)
    print(f"wrote {args.out / 'flexible_rocker.png'} and {args.out / 'flexible_rocker.csv'}")


if __name__ == "__main__":
    main()
