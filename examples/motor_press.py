"""A motor sized for a small press: the run-up from rest and the steady motion, in SI, in under a minute.

A steel connecting rod (0.25 m, 10 x 10 mm) on a 50 mm crank drives a 0.5 kg ram at a nominal 3000
rpm.  The crank is driven by a motor (its stall torque, no-load speed and the inertia of its rotor,
the crank and a flywheel, in SI) instead of turning at a prescribed speed: crankgen.Motor, here as
the fields of a crankgen.SIMechanism.  The example

1. runs the press up from rest (crankgen.simulate): how long until it reaches 95 % of its final
   mean speed;
2. finds its steady motion (crankgen.steady_state: shooting on the crank's section, the revolution
   time unknown): mean speed, speed fluctuation, peak and RMS motor torque, mean power (the load's
   20 N m and the rod's damping), the peak crank torque and pin force, the rod's buckling margin,
   and which model to trust there;
3. does the same with a flywheel five times heavier: the speed fluctuation falls about as the
   inertia grows, the motor's peak torque with it.

    .venv/bin/python examples/motor_press.py [--out DIR]

writes DIR/motor_press.png (the run-up's crank speed against time; the steady revolution's crank
speed and motor torque against the crank angle, both flywheels) and DIR/motor_press.csv (one row
per flywheel), and prints the numbers.  About 30-60 s on two cores once the engine is compiled.
"""

import argparse
import csv
import math
import warnings
from pathlib import Path

import numpy as np

import crankgen
from crankgen import torque_curve
from crankgen.notices import BeyondTheoryWarning

ROD = dict(L=0.25, E=2.1e11, rho=7850.0, A=1e-4, I=0.01 ** 4 / 12)      # m, Pa, kg/m^3, m^2, m^4
PRESS = dict(ROD, a=0.05, slider_mass=0.5, damping=2e-4)                  # m, kg, s
# a motor whose no-load speed is 3000 rpm, its stall torque 400 N m (at the crank), against the
# press's work: a constant 20 N m (6.3 kW at 3000 rpm)
MOTOR = dict(motion="motor", stall_torque=400.0, no_load_speed_rpm=3000.0, load_torque=20.0)
FLYWHEELS = (0.02, 0.1)                          # kg m^2: the rotor, crank and flywheel about the crank
SETTINGS = dict(n_elements=4)                    # the rod's first bending mode is at 7.9 times the speed


def run(inertia):
    si = crankgen.SIMechanism(**PRESS, **MOTOR, inertia=inertia)
    # five of the motor's time constants J Omega_nl / T_stall, in no-load revolutions
    omega = si.no_load_speed
    revolutions = max(10, math.ceil(5 * inertia * omega / MOTOR["stall_torque"] * omega / (2 * math.pi)))
    start = crankgen.simulate(si, units="si", revolutions=revolutions, **SETTINGS)        # from rest
    speed = start.si.crank_speed
    t = start.si.t
    steady = crankgen.steady_state(si, units="si", **SETTINGS)
    row = steady.row()
    from crankgen.results.si_row import row_in_si
    row.update(row_in_si(row, si))
    mean = row["mean_speed_rad_per_s"]
    reached = float(t[np.argmax(speed >= 0.95 * mean)])
    return si, start, steady, dict(
        inertia_kg_m2=inertia, time_to_95_percent_s=reached, mean_speed_rpm=mean * 30 / math.pi,
        speed_fluctuation=row["speed_fluctuation"], peak_motor_torque_N_m=row["peak_motor_torque_N_m"],
        rms_motor_torque_N_m=row["rms_motor_torque_N_m"], mean_motor_power_W=row["mean_motor_power_W"],
        peak_crank_torque_N_m=row["peak_torque_N_m"], peak_pin_force_A_N=row["peak_crank_on_rod_N"],
        buckling_margin=row["buckling_margin"], verdict=str(steady.verdict))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="motor_press")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore", BeyondTheoryWarning)

    results = [run(J) for J in FLYWHEELS]
    for _, _, _, r in results:
        print(f"flywheel J = {r['inertia_kg_m2']:g} kg m^2: 95 % of the speed after {r['time_to_95_percent_s']:.3f} s; "
              f"steady {r['mean_speed_rpm']:.0f} rpm, fluctuation {100 * r['speed_fluctuation']:.2f} %; motor "
              f"torque peak {r['peak_motor_torque_N_m']:.1f} N m, RMS {r['rms_motor_torque_N_m']:.1f} N m, mean "
              f"power {r['mean_motor_power_W']:.1f} W; crank torque peak {r['peak_crank_torque_N_m']:.1f} N m, pin "
              f"force at A {r['peak_pin_force_A_N']:.0f} N, buckling margin {r['buckling_margin']:.1f}")
    print(f"model: {results[0][3]['verdict']}")
    with open(out / "motor_press.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(results[0][3]))
        w.writeheader()
        w.writerows(r for _, _, _, r in results)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(13.5, 4.2))
    for (si, start, steady, r), color in zip(results, ("C0", "C3")):
        label = f"J = {r['inertia_kg_m2']:g} kg m^2"
        a1.plot(start.si.t, start.si.crank_speed * 30 / math.pi, color=color, label=label)
        deg = np.degrees(steady.theta - steady.theta[0])
        a2.plot(deg, steady.si.crank_speed * 30 / math.pi, color=color, label=label)
        motor = torque_curve.motor_torque(steady.case, steady.crank_speed)           # T_m(thetad) on its curve
        a3.plot(deg, motor * si.scales.factor("rhoA L^3 omega_b^2"), color=color, label=f"motor, {label}")
        a3.plot(deg, steady.si.torque, color=color, ls=":", lw=1, label=f"the rod's demand, {label}")
    a1.set(xlabel="time (s)", ylabel="crank speed (rpm)", title="run-up from rest")
    a2.set(xlabel="crank angle (degrees)", ylabel="crank speed (rpm)", title="steady revolution: speed")
    a3.set(xlabel="crank angle (degrees)", ylabel="torque (N m)", title="steady revolution: torque")
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    a3.grid(alpha=0.3)
    a3.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2, frameon=False)
    fig.suptitle("a press (steel rod 0.25 m, 10 x 10 mm; crank 50 mm; ram 0.5 kg) driven by a motor of 400 N m "
                 "stall torque and 3000 rpm no-load speed, a 20 N m load", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "motor_press.png", dpi=120)
    print(f"wrote {out}/motor_press.png and {out}/motor_press.csv")


if __name__ == "__main__":
    main()
