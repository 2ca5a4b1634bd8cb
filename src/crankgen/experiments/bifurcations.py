"""The bifurcations of approach A over Omega* (the "bifurcations" step of `crankgen reproduce`).

For each model and each eps of Figure 6: crankgen.continuation of the periodic response of
approach A from bif_range[0] to bif_range[1] (branches with their stability, special points, the
period-doubling branches up to bif_max_period), then what the response is beyond the last special
point (or beyond the end of the crank-period branch, when it stopped early): a crankgen.poincare
sweep up over bif_beyond_values speeds from there to the end of the range, the first from rest,
each next from the previous speed's state.  A continuation or a sweep that fails is recorded with
its reason, never dropped.  Data only: plots.py draws it over Figure 6, report_bifurcations.py
states it in findings.md.
"""

import math

import numpy as np

from ..errors import CrankgenError
from .threads import map_in_threads
from .config import MODELS

BRANCH_COLUMNS = ["model", "formulation", "damping", "membrane", "eps", "n_elements",
                  "steps_per_rev", "branch", "period", "origin", "point", "omega", "amplitude",
                  "stable", "max_abs_multiplier"]
POINT_COLUMNS = ["model", "formulation", "damping", "membrane", "eps", "n_elements",
                 "steps_per_rev", "kind", "omega", "amplitude", "period", "branch",
                 "multiplier_re", "multiplier_im", "multiplier_abs", "message"]
BEYOND_COLUMNS = ["model", "formulation", "damping", "membrane", "eps", "n_elements",
                  "steps_per_rev", "omega", "classification", "period", "repeat_residual",
                  "lyapunov", "distinct", "message"]
_FAILURES = (CrankgenError, ArithmeticError, np.linalg.LinAlgError)


def settings_of(cfg, counts):
    """(model key, eps, n_elements, steps_per_rev) of every continuation of the step."""
    spr = cfg.bif_steps_per_rev or cfg.steps_per_rev
    return [(m.key, eps, cfg.bif_elements or counts[(m.key, "A")], spr)
            for m in MODELS for eps in cfg.fig6_eps]


def bifurcations(ctx, counts):
    """dict(range, runs): one record per model and eps (see _run)."""
    cfg = ctx.config
    runs = map_in_threads(lambda s: _run(ctx, next(m for m in MODELS if m.key == s[0]), *s[1:]),
                          settings_of(cfg, counts), stop=ctx.stop)
    return dict(range=tuple(float(x) for x in cfg.bif_range), max_period=cfg.bif_max_period,
                runs=runs)


def branch_record(br, **extra):
    """A continuation branch as the step's data: period, origin, stop reason, and per point omega,
    amplitude, stability and the largest |multiplier| (then `extra`)."""
    return dict(period=int(br.period), origin=br.origin, stop_reason=br.stop_reason,
                omega=np.asarray(br.parameter, dtype=float), amplitude=np.asarray(br.amplitude, dtype=float),
                stable=np.asarray(br.stable, dtype=bool),
                max_abs_multiplier=np.abs(np.asarray(br.multipliers)).max(axis=1), **extra)


def _model_options(m):
    return dict(approach="A", model=m.key)


def _run(ctx, m, eps, n, spr):
    """One continuation and its sweep beyond: status "ok" or "failed" (message), branches
    (period, origin, stop_reason, omega, amplitude, stable, max_abs_multiplier arrays), special
    points (kind, omega, amplitude, period, branch, multiplier) and beyond (None when there is
    nothing beyond: no special point and the crank-period branch reached the end of the range)."""
    from ..declaration.parameters import Mechanism

    cfg = ctx.config
    lo, hi = cfg.bif_range
    label = f"bifurcations, {m.key} model, eps = {eps:g}"
    rec = dict(model=m.key, formulation=m.formulation, damping=m.damping, membrane=m.membrane,
               eps=float(eps), n_elements=int(n), steps_per_rev=int(spr), status="ok", message="",
               branches=[], special_points=[], beyond=None)
    mech = Mechanism(a=cfg.a, eps=eps, ms=cfg.ms, mu=cfg.mu)
    ctx.log(f"{label}: continuation of approach A from Omega* = {lo:g} to {hi:g} "
            f"(n = {n}, {spr} steps/rev, periods up to {cfg.bif_max_period})")
    try:
        d = ctx.continuation(mech, "omega", lo, hi, n_elements=n, steps_per_rev=spr,
                         max_period=cfg.bif_max_period, dp_max=cfg.bif_dp_max, tol=cfg.bif_tol, quantities=False,
                         progress=lambda text: ctx.log(f"{label}: {text}"), **_model_options(m))
    except _FAILURES as exc:
        rec.update(status="failed", message=f"{type(exc).__name__}: {exc}")
        ctx.log(f"{label}: continuation FAILED: {exc}")
        return rec
    for br in d.branches:
        rec["branches"].append(branch_record(br))
    for s in d.special_points:
        mu = complex(s.multiplier)
        rec["special_points"].append(dict(kind=s.kind, omega=float(s.parameter),
                                          amplitude=float(s.amplitude), period=int(s.period),
                                          branch=int(s.branch), multiplier=(mu.real, mu.imag)))
    ctx.log(f"{label}: {len(d.branches)} branch(es), {len(d.special_points)} special point(s)")
    edge = beyond_edge(rec, hi)
    if edge is not None and edge < hi:
        rec["beyond"] = _beyond(ctx, mech, m, n, spr, edge, label)
    return rec


def beyond_edge(rec, hi):
    """Where the continuation stops describing the response: the largest Omega* of a special
    point, or the end of the crank-period branch when it stopped before hi; None when neither."""
    marks = [s["omega"] for s in rec["special_points"]]
    if rec["branches"]:
        b0 = rec["branches"][0]
        if not b0["stop_reason"].startswith("reached"):
            marks.append(float(np.max(b0["omega"])))
    elif rec["status"] == "ok":
        return None
    return max(marks) if marks else None


def _beyond(ctx, mech, m, n, spr, edge, label):
    """Poincare sweep up over bif_beyond_values speeds in (edge, hi]."""
    from ..analyses.bifurcation import poincare

    cfg = ctx.config
    hi = cfg.bif_range[1]
    k = cfg.bif_beyond_values
    values = [float(v) for v in np.round(edge + (hi - edge) * np.arange(1, k + 1) / k, 6)]
    out = dict(start=float(edge), values=values, transient=cfg.bif_transient,
               samples=cfg.bif_samples, status="ok", message="", points=[])
    ctx.log(f"{label}: Poincare sweep up over Omega* = {', '.join(f'{v:g}' for v in values)}")
    try:
        pc = poincare(mech, "omega", values, "up", n_elements=n, steps_per_rev=spr,
                      transient=cfg.bif_transient, samples=cfg.bif_samples, **_model_options(m))
    except _FAILURES as exc:
        out.update(status="failed", message=f"{type(exc).__name__}: {exc}")
        ctx.log(f"{label}: Poincare sweep FAILED: {exc}")
        return out
    for q in pc.points:
        out["points"].append(dict(omega=float(q.parameter), classification=q.classification,
                                  period=int(q.period), repeat_residual=_float(q.repeat_residual),
                                  lyapunov=_float(q.lyapunov), distinct=int(q.distinct),
                                  message=q.message))
    return out


def _float(x):
    """A number, or NaN for one that does not exist (None), as the recorded data hold it."""
    return math.nan if x is None else float(x)


def stability_segments(branch, specials=()):
    """[(stable, omega_from, omega_to)] along a branch, in the order of the continuation.  Where
    the stability changes between two points, the boundary is the special point of `specials`
    (those of this branch) that lies between them, else the first point of the new run."""
    st, om = branch["stable"], branch["omega"]
    out, start, begin = [], 0, float(om[0])
    for i in range(1, len(st) + 1):
        if i == len(st):
            out.append((bool(st[start]), begin, float(om[-1])))
        elif st[i] != st[start]:
            a, b = sorted((float(om[i - 1]), float(om[i])))
            hit = [s["omega"] for s in specials if a - 1e-12 <= s["omega"] <= b + 1e-12]
            end = hit[0] if hit else float(om[i])
            out.append((bool(st[start]), begin, end))
            start, begin = i, end
    return out


def multiplier_abs(sp):
    return math.hypot(*sp["multiplier"])


def tables(data):
    """{file name: (columns, rows)}: the branches point by point, the special points (a run
    without any, or that failed, has one row saying so) and the sweeps beyond."""
    branches, points, beyond = [], [], []
    for r in data["runs"]:
        base = {k: r[k] for k in ("model", "formulation", "damping", "membrane", "eps",
                                  "n_elements", "steps_per_rev")}
        for b, br in enumerate(r["branches"]):
            for i in range(len(br["omega"])):
                branches.append(dict(base, branch=b, period=br["period"], origin=br["origin"], point=i,
                                     omega=br["omega"][i], amplitude=br["amplitude"][i],
                                     stable=int(br["stable"][i]),
                                     max_abs_multiplier=br["max_abs_multiplier"][i]))
        for s in r["special_points"]:
            points.append(dict(base, kind=s["kind"], omega=s["omega"], amplitude=s["amplitude"],
                               period=s["period"], branch=s["branch"], multiplier_re=s["multiplier"][0],
                               multiplier_im=s["multiplier"][1], multiplier_abs=multiplier_abs(s)))
        if r["status"] != "ok":
            points.append(dict(base, kind="failed", message=r["message"]))
        elif not r["special_points"]:
            lo, hi = data["range"]
            points.append(dict(base, kind="none",
                               message=f"no special point for {lo:g} <= Omega* <= {hi:g}"))
        b = r["beyond"]
        if b is not None:
            if b["status"] != "ok":
                beyond.append(dict(base, classification="failed", message=b["message"]))
            for q in b["points"]:
                beyond.append(dict(base, **q))
    return {"bifurcation_branches.csv": (BRANCH_COLUMNS, branches),
            "bifurcations.csv": (POINT_COLUMNS, points),
            "bifurcation_beyond.csv": (BEYOND_COLUMNS, beyond)}
