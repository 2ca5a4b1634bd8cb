"""The consistent model's special points re-read on the geometrically exact rod (the "exact rod"
step of `crankgen reproduce`, issue 26).

For each mechanism of exact_mechanisms (the slider-crank; the four-bar with a rocker of radius
exact_rocker pivoted at (1, 0)) at eps = exact_eps: crankgen.continuation over Omega* in
exact_range of the consistent model and of the exact rod (model="consistent" / "exact", the same
mesh, steps and corrector tolerance, period doublings followed up to exact_max_period).  Where a
branch of the exact rod stops before the end of the range, the orbit at its last point is marched
and its section rotation and outer-fibre strain read (crankgen.analyses.theory.exact_measures): the
element has no rotation limit, so such an end is the continuation's (its corrector, its step bound),
not the rod's.  Then both models are marched from rest at
Omega* = exact_snap_omega for exact_snap_revolutions revolutions (the consistent model's
snap-through orbit), and the exact rod's response at exact_character_omegas is classified on each
mechanism (crankgen.poincare from rest: exact_character_transient revolutions, then
exact_character_samples sampled once per revolution; period-k, quasi-periodic or irregular, with
the largest Lyapunov exponent of the revolution map).  `compare` pairs the special points (same kind and period, nearest in
Omega* within exact_match) into survive / move / vanish / new.  Data only: plot_exact_rod.py
draws it, report_exact_rod.py states it in findings.md.
"""

import math

import numpy as np

from ..errors import CrankgenError
from .bifurcations import branch_record
from .config import CONSISTENT, EXACT
from .threads import map_in_threads

MODELS = (CONSISTENT, EXACT)
MOVED = 0.005            # |Delta Omega*| below this: the point survives where it was
_FAILURES = (CrankgenError, ArithmeticError, np.linalg.LinAlgError)
BRANCH_COLUMNS = ["mechanism", "model", "eps", "n_elements", "steps_per_rev", "branch", "period", "origin",
                  "stop_reason", "point", "omega", "amplitude", "stable", "max_abs_multiplier"]
CHARACTER_COLUMNS = ["mechanism", "model", "eps", "n_elements", "steps_per_rev", "transient", "samples", "omega",
                     "classification", "period", "lyapunov", "distinct", "amplitude", "sample_min", "sample_max",
                     "message"]
POINT_COLUMNS = ["mechanism", "model", "eps", "n_elements", "steps_per_rev", "kind", "omega", "amplitude",
                 "period", "branch", "multiplier_abs", "fate", "exact_omega", "shift", "message"]


def mechanism(cfg, name):
    """The crankgen.Mechanism of a mechanism's name at the step's eps."""
    from ..declaration.parameters import Mechanism
    from .._generated.classes import Circle
    guide = {} if name == "slider-crank" else dict(guide=Circle(center=(1.0, 0.0), radius=cfg.exact_rocker))
    return Mechanism(a=cfg.a, eps=cfg.exact_eps, ms=cfg.ms, mu=cfg.mu, **guide)


def settings_of(cfg):
    return dict(mechanisms=list(cfg.exact_mechanisms), eps=cfg.exact_eps, range=list(cfg.exact_range),
                n_elements=cfg.exact_elements, steps_per_rev=cfg.exact_steps, max_period=cfg.exact_max_period,
                dp_max=cfg.exact_dp_max, rocker=cfg.exact_rocker, tol=cfg.exact_tol, snap_omega=cfg.exact_snap_omega,
                snap_revolutions=cfg.exact_snap_revolutions, match=cfg.exact_match,
                character_omegas=list(cfg.exact_character_omegas), character_transient=cfg.exact_character_transient,
                character_samples=cfg.exact_character_samples, character_steps=character_steps(cfg))


def character_steps(cfg):
    """The steps per revolution of the character step: exact_character_steps, or exact_steps."""
    return int(cfg.exact_character_steps or cfg.exact_steps)


def exact_rod(ctx):
    """dict(settings, runs, snaps, comparisons)."""
    cfg = ctx.config
    runs = map_in_threads(lambda pair: _run(ctx, *pair), [(name, m) for name in cfg.exact_mechanisms for m in MODELS],
                          stop=ctx.stop)
    snaps = [_snap(ctx, m) for m in MODELS] if cfg.exact_snap_revolutions > 0 else []
    characters = (map_in_threads(lambda name: _character(ctx, name), list(cfg.exact_mechanisms), stop=ctx.stop)
                  if cfg.exact_character_omegas else [])
    comparisons = {name: compare(*[r for r in runs if r["mechanism"] == name], cfg.exact_match)
                   for name in cfg.exact_mechanisms}
    return dict(settings=settings_of(cfg), runs=runs, snaps=snaps, characters=characters, comparisons=comparisons)


def _run(ctx, name, m):
    cfg = ctx.config
    lo, hi = cfg.exact_range
    label = f"exact rod, {name}, {m.key} model"
    rec = dict(mechanism=name, model=m.key, eps=float(cfg.exact_eps), n_elements=int(cfg.exact_elements),
               steps_per_rev=int(cfg.exact_steps), status="ok", message="", branches=[], special_points=[])
    ctx.log(f"{label}: continuation from Omega* = {lo:g} to {hi:g} (n = {cfg.exact_elements}, "
            f"{cfg.exact_steps} steps/rev, periods up to {cfg.exact_max_period})")
    mech = mechanism(cfg, name)
    try:
        d = ctx.continuation(mech, "omega", lo, hi, model=m.key, n_elements=cfg.exact_elements,
                             steps_per_rev=cfg.exact_steps, max_period=cfg.exact_max_period, tol=cfg.exact_tol,
                             dp_max=cfg.exact_dp_max, quantities=False,
                             progress=lambda text: ctx.log(f"{label}: {text}"))
    except _FAILURES as exc:
        rec.update(status="failed", message=f"{type(exc).__name__}: {exc}")
        ctx.log(f"{label}: continuation FAILED: {exc}")
        return rec
    for br in d.branches:
        rec["branches"].append(branch_record(br, end=(_end_measures(mech, m, cfg, br, hi) if m is EXACT else None)))
    for s in d.special_points:
        rec["special_points"].append(dict(kind=s.kind, omega=float(s.parameter), amplitude=float(s.amplitude),
                                          period=int(s.period), branch=int(s.branch),
                                          multiplier_abs=float(abs(complex(s.multiplier)))))
    ctx.log(f"{label}: {len(d.branches)} branch(es), {len(d.special_points)} special point(s)")
    return rec


def _end_measures(mech, m, cfg, br, hi):
    """For an exact-rod branch that stops before the end of the range: the orbit at its last point
    marched for its period, its largest section rotation (degrees) and outer-fibre strain."""
    if str(br.stop_reason).startswith("reached") or not len(br):
        return None
    from .. import notices
    from ..analyses import theory
    from ..analyses.simulation import simulate
    from ..declaration.schema import resolve_options
    from ..discrete.mesh import Mesh, components_of
    state = np.asarray(br.states[-1], dtype=float)
    mesh = Mesh(cfg.exact_elements, components=components_of(resolve_options(model=m.key)))
    parts = tuple(state.reshape(-1, mesh.n_dofs))      # (d, v) or (d, v, a), the model's node layout
    out = dict(omega=float(br.parameter[-1]), amplitude=float(br.amplitude[-1]))
    try:
        with notices.quiet():
            r = simulate(mech, omega=float(br.parameter[-1]), model=m.key, n_elements=cfg.exact_elements,
                         steps_per_rev=cfg.exact_steps, revolutions=int(br.period), initial=parts)
        fibre, rotation = theory.exact_measures(r)
        out.update(section_rotation_deg=rotation, fibre_strain=fibre, max_abs_v=float(np.max(np.abs(r.v_mid))))
    except _FAILURES as exc:
        out.update(message=f"{type(exc).__name__}: {exc}")
    return out


def _snap(ctx, m):
    """A march from rest at exact_snap_omega: the per-revolution peaks of |v*| (the last ones), or
    where it stopped and why."""
    from .. import notices
    from ..analyses import theory
    from ..analyses.simulation import simulate
    cfg = ctx.config
    mech = mechanism(cfg, "slider-crank")
    om, revs = cfg.exact_snap_omega, cfg.exact_snap_revolutions
    ctx.log(f"exact rod, slider-crank, {m.key} model: march from rest at Omega* = {om:g}, {revs} revolutions")
    rec = dict(model=m.key, omega=float(om), revolutions=int(revs), status="ok", message="")
    try:
        with notices.quiet():
            r = simulate(mech, omega=om, model=m.key, n_elements=cfg.exact_elements,
                         steps_per_rev=cfg.exact_steps, revolutions=revs)
    except _FAILURES as exc:
        part = getattr(exc, "partial", None)
        rec.update(status="stopped", message=str(exc).split(";")[0],
                   time=float(getattr(exc, "time", math.nan) or math.nan),
                   reason=str(exc))
        r = part
    if r is not None and len(r.v_mid):
        v = np.abs(np.asarray(r.v_mid, dtype=float))
        k = cfg.exact_steps
        peaks = [float(np.max(v[i * k:(i + 1) * k + 1])) for i in range(max(1, (len(v) - 1) // k))]
        rec.update(peaks=peaks, max_abs_v=float(np.nanmax(v)), t_end=float(r.t[-1]))
        if m is EXACT and r.states is not None:
            rec["section_rotation_deg"] = float(theory.exact_measures(r)[1])
    return rec


def _character(ctx, name):
    """The exact rod's response at exact_character_omegas on one mechanism: crankgen.poincare swept
    up (the first speed from rest), each speed's classification with its evidence (the largest
    Lyapunov exponent per revolution from the exact Jacobians of the revolution map, the distinct
    samples of v* at theta = 0, their range) and the amplitude max |v*|."""
    from .. import notices
    from ..analyses.bifurcation import poincare
    cfg = ctx.config
    omegas = [float(w) for w in cfg.exact_character_omegas]
    label = f"exact rod, {name}"
    ctx.log(f"{label}: Poincare sampling at Omega* = {', '.join(f'{w:g}' for w in omegas)} "
            f"({character_steps(cfg)} steps per revolution; {cfg.exact_character_transient} revolutions, then "
            f"{cfg.exact_character_samples} sampled)")
    rec = dict(mechanism=name, status="ok", message="", points=[])
    try:
        with notices.quiet():
            d = poincare(mechanism(cfg, name), "omega", omegas, "up", model=EXACT.key,
                         n_elements=cfg.exact_elements, steps_per_rev=character_steps(cfg),
                         transient=cfg.exact_character_transient, samples=cfg.exact_character_samples)
    except _FAILURES as exc:
        rec.update(status="failed", message=f"{type(exc).__name__}: {exc}")
        ctx.log(f"{label}: Poincare sampling FAILED: {exc}")
        return rec
    for q in d.points:
        s = np.asarray(q.samples, dtype=float)
        rec["points"].append(dict(omega=float(q.parameter), classification=q.classification, period=int(q.period),
                                  lyapunov=None if q.lyapunov is None else float(q.lyapunov),
                                  distinct=int(q.distinct), amplitude=None if q.amplitude is None else float(q.amplitude),
                                  sample_min=float(s.min()) if s.size else None,
                                  sample_max=float(s.max()) if s.size else None, message=q.message))
        ctx.log(f"{label}: Omega* = {q.parameter:g}: {q.classification}"
                + (f", largest Lyapunov exponent {q.lyapunov:+.3f} per revolution" if q.lyapunov is not None else ""))
    return rec


def compare(consistent, exact, window):
    """[(consistent special point, exact special point or None, fate)] and the exact points with no
    consistent counterpart: fate "survives" (|shift| < MOVED), "moves" (within window) or
    "vanishes"; the exact rod's unmatched points "new".  Pairs are made nearest first."""
    if consistent["status"] != "ok" or exact["status"] != "ok":
        return dict(pairs=[], new=[], status="failed")
    candidates = sorted(((abs(c["omega"] - e["omega"]), i, j)
                         for i, c in enumerate(consistent["special_points"])
                         for j, e in enumerate(exact["special_points"])
                         if c["kind"] == e["kind"] and c["period"] == e["period"]
                         and abs(c["omega"] - e["omega"]) <= window))
    taken_c, taken_e, match = set(), set(), {}
    for _, i, j in candidates:
        if i not in taken_c and j not in taken_e:
            taken_c.add(i)
            taken_e.add(j)
            match[i] = j
    pairs = []
    for i, c in enumerate(consistent["special_points"]):
        e = exact["special_points"][match[i]] if i in match else None
        fate = ("vanishes" if e is None else "survives" if abs(e["omega"] - c["omega"]) < MOVED else "moves")
        pairs.append(dict(consistent=c, exact=e, fate=fate))
    new = [e for j, e in enumerate(exact["special_points"]) if j not in taken_e]
    return dict(pairs=pairs, new=new, status="ok")


def hysteresis(run):
    """(lo, hi) of the hysteresis loop of the period-2 branch: from its lowest fold in Omega* (where
    the large orbit ends, sweeping down) to its fold of smallest amplitude (where the small period-2
    orbit born at the period doubling turns, sweeping up: the jump); None without two such folds."""
    folds = [s for s in run.get("special_points", []) if s["kind"] == "fold" and s["period"] == 2]
    if len(folds) < 2:
        return None
    lo = min(folds, key=lambda s: s["omega"])
    hi = min(folds, key=lambda s: s["amplitude"])
    return (lo["omega"], hi["omega"]) if lo is not hi and lo["omega"] < hi["omega"] else None


def largest(run, period):
    """(max amplitude, its Omega*) over the branches of a period, or None."""
    best = None
    for br in run.get("branches", []):
        if br["period"] == period and len(br["amplitude"]):
            k = int(np.argmax(br["amplitude"]))
            if best is None or br["amplitude"][k] > best[0]:
                best = (float(br["amplitude"][k]), float(br["omega"][k]))
    return best


def tables(data):
    """{file name: (columns, rows)}: every point of every branch; every special point with its
    fate on the exact rod (a consistent point: survives / moves / vanishes and the exact Omega*;
    an exact point without a counterpart: new)."""
    branches, points = [], []
    for r in data["runs"]:
        base = {k: r[k] for k in ("mechanism", "model", "eps", "n_elements", "steps_per_rev")}
        for b, br in enumerate(r["branches"]):
            for i in range(len(br["omega"])):
                branches.append(dict(base, branch=b, period=br["period"], origin=br["origin"],
                                     stop_reason=br["stop_reason"], point=i, omega=br["omega"][i],
                                     amplitude=br["amplitude"][i], stable=int(br["stable"][i]),
                                     max_abs_multiplier=br["max_abs_multiplier"][i]))
        if r["status"] != "ok":
            points.append(dict(base, kind="failed", message=r["message"]))
            continue
        comp = data["comparisons"].get(r["mechanism"], {})
        fates = {}
        for p in comp.get("pairs", []):
            fates[id_of(p["consistent"])] = p
        new = {id_of(e) for e in comp.get("new", [])}
        for s in r["special_points"]:
            row = dict(base, kind=s["kind"], omega=s["omega"], amplitude=s["amplitude"], period=s["period"],
                       branch=s["branch"], multiplier_abs=s["multiplier_abs"])
            if r["model"] == CONSISTENT.key and id_of(s) in fates:
                p = fates[id_of(s)]
                row["fate"] = p["fate"]
                if p["exact"] is not None:
                    row.update(exact_omega=p["exact"]["omega"], shift=p["exact"]["omega"] - s["omega"])
            elif r["model"] == EXACT.key and id_of(s) in new:
                row["fate"] = "new"
            points.append(row)
    st = data["settings"]
    character = [dict(mechanism=c["mechanism"], model=EXACT.key, eps=st["eps"], n_elements=st["n_elements"],
                      steps_per_rev=st["character_steps"], transient=st["character_transient"],
                      samples=st["character_samples"], **q)
                 for c in data.get("characters", []) for q in (c["points"] if c["status"] == "ok" else
                                                              [dict(classification="failed", message=c["message"])])]
    return {"exact_rod_branches.csv": (BRANCH_COLUMNS, branches),
            "exact_rod_points.csv": (POINT_COLUMNS, points),
            "exact_rod_character.csv": (CHARACTER_COLUMNS, character)}


def id_of(point):
    """A special point's key (kind, period, Omega*, branch) to find it again after a JSON round trip."""
    return (point["kind"], int(point["period"]), round(float(point["omega"]), 12), int(point["branch"]))
