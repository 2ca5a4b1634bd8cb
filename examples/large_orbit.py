"""The character of the exact rod's large response at eps = 0.01: periodic, quasi-periodic or chaotic.

The exact rod (model="exact") of the slider-crank, or of the four-bar with a rocker of radius 0.5
pivoted at (1, 0), is marched from rest at a crank speed Omega* (default 1.2) until its transient
is gone, then for a number of revolutions more; three tools of a dynamicist read the response:

- the Poincare section: the state once per crank revolution (the crank at theta = 0), shown as
  (v*, dv*/dt*) at mid-span: a period-P orbit is P points, a quasi-periodic one a closed curve, a
  chaotic one a cloud with structure;
- the power spectrum of v*(t) at mid-span in crank orders (multiples of the crank's frequency):
  a period-P orbit has lines at k / P only, a chaotic one a broadband floor between them;
- the largest Lyapunov exponent (Benettin's method): a second run started 1e-7 (relative) away is
  marched beside the first, the distance of the two reduced states (displacements and velocities)
  measured and the second one put back to the initial distance along the separation once per
  revolution; the mean of the log growth is the exponent per revolution (negative on a stable
  orbit, zero on a quasi-periodic one, positive in chaos);
- with --orbits K1,K2,...: the periodic orbits embedded in the response, found by Newton's method
  on P^K(x) = x (P the crank-revolution map, its exact Jacobian from the engine's linearized steps,
  as in crankgen.continuation) started from the state the transient ends in, each with its least
  period and its largest Floquet multipliers (all inside the unit circle: a stable orbit; one
  outside: an unstable orbit, a skeleton of a chaotic attractor when all are).

    .venv/bin/python examples/large_orbit.py [--mechanism slider-crank|four-bar] [--omega 1.2]
        [--transient 100] [--revolutions 200] [--lyapunov 100] [--elements 16] [--steps 200]
        [--orbits 2,4,8,16] [--out DIR]

writes DIR/large_orbit_<mechanism>_<omega>.png (per-revolution peaks, Poincare section, spectrum,
the Lyapunov estimate's running mean), DIR/large_orbit_<mechanism>_<omega>.csv (the Poincare
points: revolution, v*, dv*/dt*, the revolution's peak |v*| and its largest section rotation) and
prints what it found (default DIR: ./large_orbit).
"""

import argparse
import csv
import math
import time
from pathlib import Path

import numpy as np

import crankgen
from crankgen import notices
from crankgen._generated.classes import Circle
from crankgen.analyses import theory

DELTA = 1e-7          # the Lyapunov runs' separation, relative to the state's norm


def mechanism(name, eps=0.01):
    if name == "slider-crank":
        return crankgen.Mechanism(eps=eps)
    if name == "four-bar":
        return crankgen.Mechanism(eps=eps, guide=Circle(center=(1.0, 0.0), radius=0.5))
    raise ValueError(f"mechanism must be 'slider-crank' or 'four-bar', not {name!r}")


class Marcher:
    """Marches one mechanism at one speed in chunks of whole revolutions, each chunk starting from
    the last one's state (d, v, a): the crank is back at theta = 0 at every chunk's start."""

    def __init__(self, mech, omega, elements, steps):
        self.mech, self.omega, self.elements, self.steps = mech, float(omega), int(elements), int(steps)

    def run(self, state, revolutions, measures=False):
        with notices.quiet():
            r = crankgen.simulate(self.mech, omega=self.omega, model="exact", n_elements=self.elements,
                                  steps_per_rev=self.steps, revolutions=revolutions, initial=state, tol=1e-12)
        end = (r.states[-1].copy(), r.rates[-1].copy(), r.accelerations[-1].copy())
        rotation = theory.exact_measures(r, per_step=True)[1] if measures else None
        return r, end, rotation


def poincare(v, steps, dt):
    """(v*, dv*/dt*) at every crank angle 2 pi k of a run of whole revolutions (central differences;
    the run's first and last sample by one-sided ones)."""
    idx = np.arange(0, len(v), steps)
    rate = np.gradient(v, dt)[idx]
    return v[idx], rate


def spectrum(v, steps):
    """(orders, power): the one-sided power spectrum of v (mean removed, Hann window) against the
    frequency in crank orders."""
    x = (v - v.mean()) * np.hanning(len(v))
    p = np.abs(np.fft.rfft(x)) ** 2
    orders = np.fft.rfftfreq(len(v), d=1.0 / steps)
    return orders, p / p.max()


def lyapunov(march, state, revolutions, progress=print):
    """Benettin's estimate of the largest Lyapunov exponent per revolution: [log growth of each
    revolution] of a run beside `state` at DELTA relative distance, renormalized each revolution."""
    ref = tuple(np.array(s, dtype=float) for s in state)
    size = np.linalg.norm(np.concatenate(ref[:2]))
    rng = np.random.default_rng(1)
    direction = [rng.standard_normal(len(ref[0])), rng.standard_normal(len(ref[0]))]
    norm = np.linalg.norm(np.concatenate(direction))
    d0 = DELTA * size
    other = (ref[0] + d0 * direction[0] / norm, ref[1] + d0 * direction[1] / norm, ref[2].copy())
    logs = []
    for k in range(revolutions):
        _, ref, _ = march.run(ref, 1)
        _, other, _ = march.run(other, 1)
        diff = [o - r for o, r in zip(other, ref)]
        dist = np.linalg.norm(np.concatenate(diff[:2]))
        logs.append(math.log(dist / d0))
        other = tuple(r + d * (d0 / dist) for r, d in zip(ref, diff))
        if progress and (k + 1) % 20 == 0:
            progress(f"  Lyapunov: {k + 1}/{revolutions} revolutions, running mean {np.mean(logs):+.4f} per revolution")
    return np.array(logs)


def study(name, omega, transient, revolutions, lyap, elements, steps, out, progress=print):
    mech = mechanism(name)
    march = Marcher(mech, omega, elements, steps)
    dt = 2 * math.pi / omega / steps
    t0 = time.perf_counter()
    progress(f"{name}, Omega* = {omega:g}: transient of {transient} revolutions from rest")
    _, state, _ = march.run(None, transient)
    progress(f"  {time.perf_counter() - t0:.0f} s; then {revolutions} revolutions recorded")
    vs, peaks, rotations = [], [], []
    chunk = 25
    done = 0
    while done < revolutions:
        k = min(chunk, revolutions - done)
        r, state, rot = march.run(state, k, measures=True)
        v = np.asarray(r.v_mid, dtype=float)
        vs.append(v if not vs else v[1:])
        for i in range(k):
            peaks.append(float(np.max(np.abs(v[i * steps:(i + 1) * steps + 1]))))
            rotations.append(float(np.max(rot[i * steps:(i + 1) * steps + 1])))
        done += k
    v = np.concatenate(vs)
    pv, pr = poincare(v, steps, dt)
    orders, power = spectrum(v[:-1], steps)
    if lyap:
        progress(f"  {time.perf_counter() - t0:.0f} s; Lyapunov estimate over {lyap} revolutions")
    logs = lyapunov(march, state, lyap, progress) if lyap else np.array([])
    result = dict(name=name, omega=omega, peaks=np.array(peaks), rotations=np.array(rotations), pv=pv, pr=pr,
                  orders=orders, power=power, logs=logs, elements=elements, steps=steps,
                  transient=transient, seconds=time.perf_counter() - t0)
    result.update(classify(result))
    write(result, out)
    return result


def embedded_orbits(name, omega, transient, periods, elements, steps, progress=print):
    """[(K, least period, max |v*|, multipliers by decreasing modulus) or (K, None, residual, message)]:
    Newton's method on P^K(x) = x from the state `transient` revolutions after rest, for each K in
    periods.  P is continuation's crank-revolution map (crankgen.analyses.bifurcation.mechanism:
    the state (d, v, a) at theta = 0, scaled, with the exact Jacobian of K revolutions)."""
    from crankgen import engine
    from crankgen.analyses.bifurcation.api import make_case
    from crankgen.analyses.bifurcation.mechanism import mechanism_map
    fmap = mechanism_map(make_case(mechanism(name), "omega", omega, None, model="exact",
                                   n_elements=elements, steps_per_rev=steps), "omega")
    with notices.quiet():
        start = engine.join_state(fmap.march(fmap.rest(), omega, transient), fmap.generalized)[0] / fmap.s
    found = []
    for K in periods:
        x, res, J = start.copy(), math.inf, None
        for _ in range(12):
            try:
                P, J, _ = fmap.evaluate(x, omega, K, dp=False)
            except Exception as exc:             # a Newton iterate the engine cannot march
                res = f"{type(exc).__name__}: {exc}"
                break
            res = float(np.linalg.norm(P - x) / np.linalg.norm(x))
            if res < 1e-10:
                break
            x = x + np.linalg.solve(J - np.eye(len(x)), x - P)
        if not (isinstance(res, float) and res < 1e-10):
            found.append((K, None, res, "Newton did not converge"))
            progress(f"  period {K}: Newton did not converge ({res if isinstance(res, str) else f'residual {res:.1e}'})")
            continue
        amp, _, section = fmap.orbit(x, omega, K)
        least = next(k for k in range(1, K + 1) if K % k == 0 and
                     np.abs(section[k:] - section[:-k]).max() <= 1e-7 * max(np.abs(section).max(), 1e-12))
        mu = np.linalg.eigvals(J)
        mu = mu[np.argsort(-np.abs(mu))][:3]
        found.append((K, least, amp, mu))
        progress(f"  Newton on P^{K}: an orbit of least period {least}, max |v*| {amp:.4g}, largest multipliers of "
                 f"P^{K} " + ", ".join(f"{m.real:+.4g}" if abs(m.imag) < 1e-9 else f"{m:.4g}" for m in mu)
                 + (" (stable)" if abs(mu[0]) < 1 else " (unstable)"))
    return found


def classify(res):
    """Numbers that tell the response's character: the number of distinct Poincare points (to 1e-4
    of their spread), the spectrum's floor between the crank's half orders, the Lyapunov exponent
    and its spread over the run's halves."""
    pv = res["pv"]
    scale = max(np.ptp(pv), 1e-12)
    distinct = len({round(float(x) / (1e-4 * max(abs(pv).max(), 1e-12))) for x in pv[len(pv) // 2:]})
    orders, power = res["orders"], res["power"]
    off = (orders > 0.05) & (orders < 3.0) & (np.abs(orders * 4 - np.round(orders * 4)) > 0.05)
    floor = float(np.median(power[off])) if off.any() else math.nan
    logs = res["logs"]
    lam = float(np.mean(logs)) if len(logs) else math.nan
    halves = [float(np.mean(h)) for h in np.array_split(logs, 2)] if len(logs) > 1 else []
    return dict(distinct=distinct, spread=float(scale), floor=floor, lyapunov=lam, lyapunov_halves=halves)


def write(res, out):
    out.mkdir(parents=True, exist_ok=True)
    stem = f"large_orbit_{res['name']}_{res['omega']:g}"
    with open(out / f"{stem}.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["revolution", "v_mid", "v_mid_rate", "peak_abs_v_mid", "section_rotation_deg"])
        for k, (a, b) in enumerate(zip(res["pv"], res["pr"])):
            w.writerow([k, f"{a:.8g}", f"{b:.8g}",
                        f"{res['peaks'][k]:.6g}" if k < len(res["peaks"]) else "",
                        f"{res['rotations'][k]:.4g}" if k < len(res["rotations"]) else ""])
    plot(res, out / f"{stem}.png")


def plot(res, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    a = ax[0, 0]
    a.plot(np.arange(len(res["peaks"])), res["peaks"], ".", ms=3)
    a.set_xlabel("revolution after the transient")
    a.set_ylabel("peak |v*| in the revolution")
    a.set_title("per-revolution peaks")
    a = ax[0, 1]
    a.plot(res["pv"], res["pr"], ".", ms=3)
    a.set_xlabel("v* at mid-span, crank at 0")
    a.set_ylabel("dv*/dt*")
    a.set_title(f"Poincare section ({len(res['pv'])} revolutions)")
    a = ax[1, 0]
    a.semilogy(res["orders"], res["power"], lw=0.7)
    a.set_xlim(0, 4)
    a.set_ylim(1e-9, 2)
    a.set_xlabel("frequency (crank orders)")
    a.set_ylabel("power of v* (normalized)")
    a.set_title("power spectrum")
    a = ax[1, 1]
    logs = res["logs"]
    if len(logs):
        a.plot(np.arange(1, len(logs) + 1), np.cumsum(logs) / np.arange(1, len(logs) + 1))
        a.axhline(0, color="k", lw=0.5)
    a.set_xlabel("revolutions")
    a.set_ylabel("running mean of log growth per revolution")
    a.set_title(f"largest Lyapunov exponent: {res['lyapunov']:+.3f} per revolution" if len(logs) else
                "largest Lyapunov exponent: not estimated (--lyapunov 0)")
    fig.suptitle(f"exact rod, {res['name']}, eps = 0.01, Omega* = {res['omega']:g} ({res['elements']} elements, "
                 f"{res['steps']} steps per revolution, after {res['transient']} revolutions)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mechanism", default="slider-crank", choices=("slider-crank", "four-bar"))
    p.add_argument("--omega", type=float, default=1.2, help="crank speed Omega* (default 1.2)")
    p.add_argument("--transient", type=int, default=100, help="revolutions dropped (default 100)")
    p.add_argument("--revolutions", type=int, default=200, help="revolutions recorded (default 200)")
    p.add_argument("--lyapunov", type=int, default=100, help="revolutions of the Lyapunov estimate (0: none)")
    p.add_argument("--elements", type=int, default=16)
    p.add_argument("--steps", type=int, default=200, help="steps per revolution (default 200)")
    p.add_argument("--orbits", default="", help="periods K of the orbits sought by Newton on P^K, e.g. 2,4,8,16 "
                   "(default: none)")
    p.add_argument("--out", type=Path, default=Path("large_orbit"))
    a = p.parse_args(argv)
    try:
        periods = [int(k) for k in a.orbits.split(",") if k.strip()]
    except ValueError:
        p.error(f"--orbits must be periods separated by commas, e.g. 2,4,8, not {a.orbits!r}")
    if any(k < 1 for k in periods):
        p.error("--orbits: every period must be at least 1")
    for name, value in (("transient", a.transient), ("revolutions", a.revolutions), ("elements", a.elements),
                        ("steps", a.steps)):
        if value < 1:
            p.error(f"--{name} must be at least 1")
    if a.lyapunov < 0:
        p.error("--lyapunov must be 0 (none) or more revolutions")
    res = study(a.mechanism, a.omega, a.transient, a.revolutions, a.lyapunov, a.elements, a.steps, a.out)
    print(f"{a.mechanism}, Omega* = {a.omega:g}: {res['distinct']} distinct Poincare points in the last half; "
          f"peaks {res['peaks'].min():.2f}-{res['peaks'].max():.2f}; sections turned up to "
          f"{res['rotations'].max():.0f} degrees; spectrum floor off the quarter orders {res['floor']:.2e}; "
          + (f"largest Lyapunov exponent {res['lyapunov']:+.4f} per revolution (halves "
             + ", ".join(f"{h:+.4f}" for h in res["lyapunov_halves"]) + "); " if a.lyapunov else "")
          + f"{res['seconds']:.0f} s")
    if periods:
        print(f"periodic orbits from the state after {a.transient} revolutions:")
        embedded_orbits(a.mechanism, a.omega, a.transient, periods, a.elements, a.steps)


if __name__ == "__main__":
    main()
