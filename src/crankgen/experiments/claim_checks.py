"""How each of the paper's claims (claims.py) is computed from a model's runs: one function per
claim returning an Outcome (verdict, the computed value in words, the reason), from the measures
of claim_measures.py.  A quantity a check needs that the runs do not hold raises Missing (the
claim is then "not computable", with the message)."""

import math

import numpy as np

from ..analyses import theory
from . import findings as fd
from .claim_measures import (ANGLE, CLOSE, FACTOR, ILL, Missing, NOTICEABLE, NOT_COMPUTABLE,
                             NOT_REPRODUCED, Outcome, PARTLY, REPRODUCED, SAME, SLOPE, SPEED, STABLE,
                             _amp, _angle_match, _at_speed, _by_parts, _compare_points, _conv_series,
                             _crossings, _curves, _diff, _ext_curves, _fig, _first_divergence, _fold,
                             _held_text, _held_verdict, _limit_speed, _near, _num, _offsets_text, _pct,
                             _pct_or, _rows, _status)
from .figures import DIVERGED    # a run of an ill-posed approach that failed


# ----------------------------------------------------------------------------- claims

def c2a(run, m):
    cfg = run.cfg
    out = {}
    for ap in "ABC":
        c2 = _curves(run, 2, m, approach=ap, n_elements=2)
        c4 = _curves(run, 2, m, approach=ap, n_elements=4)
        if not (c2 and c4):
            raise Missing("Figure 2 was not run with 2 and 4 elements")
        out[ap] = _diff(c2[0], c4[0])
    known = [d for d in out.values() if d is not None]
    value = ", ".join(f"{ap} {_pct_or(d, ILL)}" for ap, d in out.items())
    return Outcome(_by_parts([None if d is None else d <= CLOSE for d in out.values()]),
                   f"2 vs 4 elements: {value}",
                   f"largest {_pct(max(known)) if known else 'n/a'} (tolerance {_pct(CLOSE)}) at "
                   f"Omega* = {cfg.fig2_omega:g}")


def _fig2_count(run, m):
    ns = {c.spec.n_elements for c in _fig(run, 2)["curves"] if c.spec.model == m}
    return 4 if 4 in ns else max(ns)


def c2b(run, m):
    n = _fig2_count(run, m)
    a = _curves(run, 2, m, approach="A", n_elements=n)
    out = {}
    for ap in "BC":
        c = _curves(run, 2, m, approach=ap, n_elements=n)
        if not (a and c):
            raise Missing(f"Figure 2 has no A and {ap} run with the same count")
        out[ap] = _diff(c[0], a[0])
    return Outcome(_by_parts([None if d is None else d <= CLOSE for d in out.values()]),
                   f"vs A (n = {n}): " + ", ".join(f"{ap} {_pct_or(d, ILL)}" for ap, d in out.items()),
                   f"tolerance {_pct(CLOSE)} of max |v*_A|")


def c3a(run, m):
    s = _conv_series(run, m, "A", run.cfg.fig3_omega)
    if s["kind"] != "converged":
        return Outcome(NOT_REPRODUCED, s["kind"], s["note"])
    n = s["n"]
    v = REPRODUCED if n == 16 else (PARTLY if n in (8, 32) else NOT_REPRODUCED)
    return Outcome(v, f"converged at n = {n}", f"smallest n whose steady amplitude is within "
                   f"{_pct(run.cfg.conv_tol)} of the next count's: 16 reproduces, 8 or 32 partly")


def c3b(run, m):
    cs = _curves(run, 3, m)
    finest = max(c.spec.n_elements for c in cs)
    pair = sorted([c for c in cs if c.spec.n_elements == finest], key=lambda c: c.spec.steps_per_rev)
    if len(pair) < 2:
        raise Missing("Figure 3 has no run with a second time step")
    d = _diff(pair[0], pair[-1])
    if d is None:
        return Outcome(NOT_COMPUTABLE, ILL, "the runs of approach A diverged")
    v = REPRODUCED if d <= SAME else (PARTLY if d <= NOTICEABLE else NOT_REPRODUCED)
    return Outcome(v, f"{_pct(d)} (n = {finest}, {pair[0].spec.steps_per_rev} vs "
                   f"{pair[-1].spec.steps_per_rev} steps)",
                   f"same within {_pct(SAME)}, partly within {_pct(NOTICEABLE)}")


def c3c(run, m):
    om = run.cfg.fig3_omega
    res = {ap: _conv_series(run, m, ap, om) for ap in "BC"}
    ok = [None if s["kind"] == "diverged" else (s["kind"] == "converged" and s["n"] <= 4)
          for s in res.values()]
    words = {"diverged": ILL, "no-result": "no periodic state at any count",
             "not-converged": f"not converged up to n = {max(run.cfg.conv_ladder)}"}
    value = "; ".join(f"{ap} {'converges at n = ' + str(s['n']) if s['kind'] == 'converged' else words[s['kind']]}"
                      for ap, s in res.items())
    return Outcome(_by_parts(ok), value,
                   f"converged count at Omega* = {om:g} at most 4" +
                   ("; a series that diverged has no count" if None in ok else ""))


def c4a(run, m):
    cfg = run.cfg
    base = {ap: _curves(run, 4, m, approach=ap, ms=cfg.ms) for ap in "BC"}
    heavy_ms = max(c.spec.ms for c in _curves(run, 4, m, approach="B"))
    heavy = {ap: _curves(run, 4, m, approach=ap, ms=heavy_ms) for ap in "BC"}
    if not all(base.values()) or not all(heavy.values()) or heavy_ms <= cfg.ms:
        raise Missing("Figure 4 has no B and C runs with a larger slider mass")
    d0, d1 = _diff(base["C"][0], base["B"][0]), _diff(heavy["C"][0], heavy["B"][0])
    parts = [None if d0 is None else d0 > NOTICEABLE,
             None if d0 is None or d1 is None else (d1 > NOTICEABLE and d1 > d0)]
    return Outcome(_by_parts(parts),
                   f"|C - B| / max |B|: {_pct_or(d0, 'B ' + ILL)} at ms* = {cfg.ms:g}, "
                   f"{_pct_or(d1, 'B ' + ILL)} at ms* = {heavy_ms:g}",
                   f"noticeable above {_pct(NOTICEABLE)}, and larger with the larger mass; a B run "
                   "that diverged has no deflection to compare")


def c4b(run, m):
    cfg = run.cfg
    cs = _curves(run, 4, m, approach="C")
    ref = [c for c in cs if c.spec.ms == cfg.ms]
    if len(cs) < 2 or not ref:
        raise Missing("Figure 4 has no C runs with several slider masses")
    ds = [_diff(c, ref[0]) for c in cs if c is not ref[0]]
    if any(d is None for d in ds):
        return Outcome(NOT_COMPUTABLE, ILL, "a C run diverged")
    d = max(ds)
    v = REPRODUCED if d <= SAME else (PARTLY if d <= NOTICEABLE else NOT_REPRODUCED)
    return Outcome(v, f"largest change of C with ms*: {_pct(d)}",
                   f"no effect within {_pct(SAME)}, partly within {_pct(NOTICEABLE)}")


def c4c(run, m):
    cfg = run.cfg
    a = _curves(run, 4, m, approach="A", ms=cfg.ms)
    out = {}
    for ap in "BC":
        c = _curves(run, 4, m, approach=ap, ms=cfg.ms)
        if not (a and c):
            raise Missing("Figure 4 lacks A, B or C at the base slider mass")
        if a[0].diverged or c[0].diverged:
            out[ap] = None
        elif not (a[0].ok and c[0].ok):
            out[ap] = math.nan
        else:
            out[ap] = a[0].max_abs / c[0].max_abs
    ok = [None if r is None else (_fold(r, 0.1) == REPRODUCED if math.isfinite(r) else False)
          for r in out.values()]
    return Outcome(_by_parts(ok), "max|A| / max|X|: " + ", ".join(
        f"{ap} {ILL if r is None else _num(r)}" for ap, r in out.items()),
        f"within a factor {FACTOR:g} of 0.1; a run that diverged has no deflection")


def c5a(run, m):
    om = min(run.cfg.fig5_omegas, key=lambda o: abs(o - 0.1))
    if abs(om - 0.1) > 1e-9:
        raise Missing("Figure 5 was not run at Omega* = 0.1")
    diffs, diverged = {}, []
    for eps in run.cfg.fig5_eps:          # at each eps, the larger of |B/A - 1| and |C/A - 1|
        a = dict(model=m, approach="A", omega=om, eps=eps)
        d, div = _compare_points([(ap, _amp(run, 5, **a), _amp(run, 5, **dict(a, approach=ap)),
                                   _status(run, 5, **a), _status(run, 5, **dict(a, approach=ap)))
                                  for ap in "BC"])
        if div:
            diverged.append(f"eps = {eps:g}")
        else:
            diffs[f"eps = {eps:g}"] = max(d.values())
    return Outcome(_held_verdict(diffs, diverged), _held_text(diffs, diverged, "|X/A - 1|"),
                   f"within {_pct(CLOSE)} at every eps, for B and C")


def c5b(run, m):
    cfg = run.cfg
    if 0.8 not in cfg.fig5_omegas or 0.01 not in cfg.fig5_eps:
        raise Missing("Figure 5 was not run at Omega* = 0.8, eps = 0.01")
    if _status(run, 5, model=m, approach="B", omega=0.8, eps=0.01) == DIVERGED:
        return Outcome(NOT_COMPUTABLE, f"B {ILL}", "B has no amplitude at Omega* = 0.8, eps = 0.01")
    r = _amp(run, 5, model=m, approach="B", omega=0.8, eps=0.01) / _amp(run, 5, model=m, approach="A", omega=0.8, eps=0.01)
    return Outcome(_fold(r, 10.0), f"B/A = {_num(r)}",
                   f"within a factor {FACTOR:g} of 10; partly if at least 2" +
                   ("" if math.isfinite(r) else " (B or A has no stable periodic state)"))


def c5c(run, m):
    pairs = []
    for om in run.cfg.fig5_omegas:
        for eps in run.cfg.fig5_eps:
            b = dict(model=m, approach="B", omega=om, eps=eps)
            c = dict(b, approach="C")
            pairs.append((f"Omega* = {om:g}, eps = {eps:g}", _amp(run, 5, **b), _amp(run, 5, **c),
                          _status(run, 5, **b), _status(run, 5, **c)))
    diffs, diverged = _compare_points(pairs)
    return Outcome(_held_verdict(diffs, diverged), _held_text(diffs, diverged, "|C/B - 1|"),
                   f"within {_pct(CLOSE)} where both have a stable periodic state (no stable state in "
                   "one of them counts against the claim; a B run that diverged has no amplitude)")


def c5d(run, m):
    parts, texts = [], []
    for om in run.cfg.fig5_omegas:
        for ap in "ABC":
            rr = sorted(_rows(run, 5, model=m, approach=ap, omega=om), key=lambda r: r["eps"])
            f = fd.loglog_slope([r["eps"] for r in rr], [r["amplitude"] for r in rr])
            if not f and rr and all(r["status"] == DIVERGED for r in rr):
                parts.append(None)
                texts.append(f"{ap}@{om:g}: {ILL}")
                continue
            ok = bool(f) and f["points"] >= 3 and abs(f["slope"] + 1) <= SLOPE and f["max_residual"] <= 0.1
            parts.append(ok)
            texts.append(f"{ap}@{om:g}: {_num(f['slope']) if f else 'n/a'}")
    return Outcome(_by_parts(parts), "slopes " + ", ".join(texts),
                   f"slope -1 +- {SLOPE:g} with max residual 0.1 in log v*, every approach and speed")


def c6a(run, m):
    rows_b = {r["omega"]: r for r in _rows(run, 6, model=m, approach="B", eps=0.01)}
    rows_c = {r["omega"]: r for r in _rows(run, 6, model=m, approach="C", eps=0.01)}
    oms = sorted(o for o in rows_b if o < 0.7 and o in rows_c)
    if not oms:
        raise Missing("Figure 6 has no eps = 0.01 points below Omega* = 0.7")
    diffs, diverged = _compare_points(
        [(f"Omega* = {o:g}", rows_b[o]["amplitude"], rows_c[o]["amplitude"], rows_b[o]["status"],
          rows_c[o]["status"]) for o in oms])
    return Outcome(_held_verdict(diffs, diverged), _held_text(diffs, diverged, "|C/B - 1|"),
                   f"within {_pct(CLOSE)} at every Omega* < 0.7 where both can be compared")


def c6b(run, m):
    s = _limit_speed(run, m, 0.01)
    div = _first_divergence(run, m, 0.01)
    how = (f" (where the run from rest of B diverges; B is {theory.ILL_POSED})"
           if div is not None and div == s else "")
    return Outcome(_near(s, 0.2, SPEED, 2 * SPEED) if s is not None else NOT_REPRODUCED,
                   f"Omega* = {_num(s)}{how}" if s is not None else "never over the sweep",
                   f"speed where B or C first differs from A by more than "
                   f"{_pct(run.cfg.differ_threshold)}; 0.2 +- {SPEED:g}, partly +- {2 * SPEED:g}")


def c6c(run, m):
    rs = {ap: _at_speed(run, 6, m, ap, 0.01, 1.0) for ap in "ABC"}
    if any(r is None for r in rs.values()):
        raise Missing("Figure 6 has no eps = 0.01 point at Omega* = 1")
    ratios = {ap: None if rs[ap]["status"] == DIVERGED else rs[ap]["ratio_to_A"] for ap in "BC"}
    vs = [None if x is None else _fold(x, 10.0) for x in ratios.values()]
    known = [v for v in vs if v is not None]
    v = NOT_COMPUTABLE if not known else (known[0] if len(set(known)) == 1 and len(known) == len(vs)
                                          else PARTLY)
    return Outcome(v, "at Omega* = 1: " + ", ".join(
        f"{ap}/A {ILL if x is None else _num(x)}" for ap, x in ratios.items()),
        f"within a factor {FACTOR:g} of 10" +
        ("; A has no stable periodic state there" if rs["A"]["status"] != STABLE else ""))


def c6d(run, m):
    parts, texts = [], []
    for ap in "BC":
        rows = _rows(run, 6, model=m, approach=ap, eps=0.01)
        rr = [r for r in rows if r["status"] == STABLE]
        div = [r["omega"] for r in rows if r["status"] == DIVERGED]
        if not rr:
            parts.append(None if div else False)
            texts.append(f"{ap}: {ILL} at every speed" if div else f"{ap}: no stable points")
            continue
        top = max(rr, key=lambda r: r["amplitude"])
        if div and min(div) > top["omega"] and not any(r["omega"] > top["omega"] and r["status"] == STABLE
                                                       for r in rows):
            # the largest stable point is the last one before the runs diverge: not a peak
            parts.append(None)
            texts.append(f"{ap}: no peak can be read (its runs from rest diverge from Omega* = "
                         f"{min(div):g}; {ap} is {theory.ILL_POSED})")
            continue
        hi = max(r["omega"] for r in rows)
        parts.append(abs(top["omega"] - 1.0) <= 2 * SPEED and top["omega"] < hi)
        texts.append(f"{ap} max at {top['omega']:g}")
    ra = sorted([r for r in _rows(run, 6, model=m, approach="A", eps=0.01)
                 if r["omega"] >= 1.0 - 1e-9], key=lambda r: r["omega"])
    amps = [r["amplitude"] for r in ra]
    grows = len(amps) >= 2 and all(math.isfinite(x) for x in amps) and all(np.diff(amps) > 0)
    parts.append(grows)
    texts.append("A " + ("grows" if grows else "does not grow") + " beyond 1"
                 + ("" if all(math.isfinite(x) for x in amps) else " (no stable state at some speeds)"))
    return Outcome(_by_parts(parts), "; ".join(texts),
                   f"B and C peak within 1 +- {2 * SPEED:g} inside the sweep; A increasing at every "
                   "sweep speed from 1 on")


def c6e(run, m):
    if 0.1 not in run.cfg.fig6_eps or 0.01 not in run.cfg.fig6_eps:
        raise Missing("Figure 6 was not run at eps = 0.01 and 0.1")
    ratios = []
    for ap in "ABC":
        lo = {r["omega"]: r["amplitude"] for r in _rows(run, 6, model=m, approach=ap, eps=0.01)}
        hi = {r["omega"]: r["amplitude"] for r in _rows(run, 6, model=m, approach=ap, eps=0.1)}
        ratios += [hi[o] / lo[o] for o in lo if o in hi and math.isfinite(hi[o]) and math.isfinite(lo[o])
                   and lo[o] > 0]
    med = float(np.median(ratios)) if ratios else math.nan
    s = _limit_speed(run, m, 0.1)
    parts = [_fold(med, 0.1) == REPRODUCED, _near(s, 0.4, SPEED) == REPRODUCED if s is not None else False]
    return Outcome(_by_parts(parts), f"median amplitude ratio eps 0.1 / 0.01: {_num(med)}; B or C "
                   f"leaves A at Omega* = {_num(s) if s is not None else 'never'}",
                   f"ratio within a factor {FACTOR:g} of 0.1; limit speed 0.4 +- {SPEED:g}")


def c7a(run, m):
    cs = _ext_curves(run, 7, m)
    if len(cs) < 2:
        raise Missing("Figure 7 has fewer than two stable curves")
    mx = [float(np.max(c["extension"])) for c in cs]
    mn = [float(np.min(c["extension"])) for c in cs]
    parts = [all(np.diff(mx) > 0), all(np.diff(mn) < 0)]
    return Outcome(_by_parts(parts), "max delta* " + ", ".join(f"{x:.3g}" for x in mx) + "; min delta* "
                   + ", ".join(f"{x:.3g}" for x in mn) + " (ms* " + ", ".join(f"{c['ms']:g}" for c in cs) + ")",
                   "extension and contraction both grow with ms*")


def _crossing_claim(run, f, m, expected):
    xs = _crossings(run, f, m)
    d = _angle_match(xs, expected)
    ok = [x <= ANGLE for x in d]
    v = _by_parts(ok) if len(xs) == 2 or not all(ok) else PARTLY
    return xs, d, v


def c7b(run, m):
    xs, d, v = _crossing_claim(run, 7, m, (106.4, 295.2))
    return Outcome(v, ", ".join(f"{x:.1f}" for x in xs) + " deg" if xs else "no common crossing",
                   f"two crossings, each within {ANGLE:g} deg of the paper's ({_offsets_text(xs, (106.4, 295.2), d)})")


def c7c(run, m):
    xs = _crossings(run, 7, m)
    if not xs:
        return Outcome(NOT_REPRODUCED, "no common crossing", "no crossing to check")
    cs = _ext_curves(run, 7, m)
    eps2 = run.cfg.eps ** 2
    worst = 0.0
    for c in cs:
        if c.get("u_end") is None:
            raise Missing("Figure 7 data has no u*(1)")
        first = eps2 * np.asarray(c["u_end"])
        scale = float(np.max(np.abs(first)))
        for x in xs:
            val = float(np.interp(x, c["theta_deg"], first))
            worst = max(worst, abs(val) / scale if scale > 0 else 0.0)
    v = REPRODUCED if worst <= CLOSE else (PARTLY if worst <= 4 * CLOSE else NOT_REPRODUCED)
    return Outcome(v, f"|eps^2 u*(1)| at the crossings: up to {_pct(worst)} of its largest value",
                   f"u*(1) zero within {_pct(CLOSE)} of its range (partly {_pct(4 * CLOSE)}); v*(1) is "
                   "zero by the slider constraint")


def c8a(run, m):
    cs = _ext_curves(run, 8, m)
    c = min(cs, key=lambda c: abs(c["ms"] - run.cfg.ms))
    if c.get("u_end") is None:
        raise Missing("Figure 8 data has no u*(1)")
    first = run.cfg.eps ** 2 * np.asarray(c["u_end"])
    second = np.asarray(c["extension"]) - first
    share = float(np.max(np.abs(second)) / np.max(np.abs(first)))
    th, e = np.asarray(c["theta_deg"]), np.asarray(c["extension"])
    mirror = np.interp((360.0 - th) % 360.0, th, e)
    asym = float(np.max(np.abs(e - mirror)) / np.ptp(e)) if np.ptp(e) > 0 else math.nan
    return Outcome(_by_parts([share <= NOTICEABLE, asym <= CLOSE]),
                   f"max|2nd term| / max|1st term| = {_pct(share)}; asymmetry about 180 deg {_pct(asym)} of the range",
                   f"second term below {_pct(NOTICEABLE)} of the first; symmetric within {_pct(CLOSE)} (ms* = {c['ms']:g})")


def _crank_rod_angle(a, theta_deg):
    """Angle (degrees) between the crank and the (rigid) rod at crank angle theta."""
    th = math.radians(theta_deg)
    crank = np.array([math.cos(th), math.sin(th)])
    rod = np.array([math.sqrt(1 - (a * math.sin(th)) ** 2), -a * math.sin(th)])
    return math.degrees(math.acos(float(crank @ rod) / float(np.linalg.norm(rod))))


def c8b(run, m):
    xs, d, v = _crossing_claim(run, 8, m, (86.4, 279.0))
    angles = [_crank_rod_angle(run.cfg.a, x) for x in xs]
    near90 = bool(angles) and all(abs(x - 90) <= 10 for x in angles)
    if v == REPRODUCED and not near90:
        v = PARTLY
    return Outcome(v, (", ".join(f"{x:.1f}" for x in xs) + " deg; crank-rod angle there "
                       + ", ".join(f"{x:.0f}" for x in angles) + " deg") if xs else "no common crossing",
                   f"crossings within {ANGLE:g} deg of the paper's ({_offsets_text(xs, (86.4, 279.0), d)}), "
                   "angle between crank and rod within 90 +- 10 deg")


def k1(run, m):
    cfg = run.cfg
    s = {ap: _conv_series(run, m, ap, 0.1) for ap in "ABC"}
    n = {ap: s[ap]["n"] if s[ap]["kind"] == "converged" else math.inf for ap in "ABC"}
    fast = n["A"] <= max(n["B"], n["C"])
    errs = []
    for ap in "BC":
        for r in _rows(run, 6, model=m, approach=ap, eps=0.01):
            if r["omega"] <= 0.2 + 1e-9:
                errs.append(abs(r["ratio_to_A"] - 1) if math.isfinite(r["ratio_to_A"]) else math.inf)
    if not errs:
        raise Missing("Figure 6 has no eps = 0.01 point at or below Omega* = 0.2")
    err = max(errs)
    return Outcome(_by_parts([fast, err <= cfg.differ_threshold]),
                   "converged n at Omega* = 0.1: " + ", ".join(f"{ap} {n[ap]}" for ap in "ABC")
                   + f"; max |X/A - 1| for Omega* <= 0.2: {_pct(err)}",
                   f"A needs no more elements than B or C; error within {_pct(cfg.differ_threshold)}")


def k2(run, m):
    cfg = run.cfg
    thr = cfg.differ_threshold
    errs = {}
    for eps in (0.01, 0.1):
        e = {}
        for ap in "BC":
            for r in _rows(run, 6, model=m, approach=ap, eps=eps):
                if r["omega"] > 0.2 + 1e-9 and math.isfinite(r["ratio_to_A"]):
                    e.setdefault(r["omega"], []).append(abs(r["ratio_to_A"] - 1))
        errs[eps] = {o: max(v) for o, v in e.items()}
    if not errs[0.01]:
        raise Missing("Figure 6 has no eps = 0.01 point above Omega* = 0.2")
    noticeable = max(errs[0.01].values()) > thr
    common = [o for o in errs[0.01] if o in errs[0.1]]
    larger = bool(common) and np.median([errs[0.01][o] - errs[0.1][o] for o in common]) > 0
    lo, hi = _conv_series(run, m, "A", 0.1), _conv_series(run, m, "A", 0.8)
    na = [s["n"] if s["kind"] not in ("no-result", "diverged") else None for s in (lo, hi)]
    more = None not in na and na[1] > na[0]
    return Outcome(_by_parts([noticeable, larger, more]),
                   f"max error above 0.2: {_pct(max(errs[0.01].values()))} (eps 0.01); larger for eps 0.01 than 0.1: "
                   f"{'yes' if larger else 'no'}; A converged n {na[0]} -> {na[1]} (Omega* 0.1 -> 0.8)",
                   f"errors above {_pct(thr)}, larger at the smaller eps (median over common speeds), "
                   "A's count growing with speed")


def k3(run, m):
    c7 = min(_ext_curves(run, 7, m), key=lambda c: abs(c["ms"] - run.cfg.ms))
    c8 = min(_ext_curves(run, 8, m), key=lambda c: abs(c["ms"] - run.cfg.ms))
    r = float(np.ptp(c7["extension"]) / np.ptp(c8["extension"]))
    x7, x8 = _crossings(run, 7, m), _crossings(run, 8, m)
    return Outcome(_by_parts([r >= 2.0, len(x7) == 2, len(x8) == 2]),
                   f"range of delta* at 0.8 / at 0.1 = {_num(r)}; crossings {len(x7)} (Fig. 7), {len(x8)} (Fig. 8)",
                   "much larger: at least twice the range; exactly two crossings in each figure")


def k4(run, m):
    s = _limit_speed(run, m, 0.01)
    rs = {ap: _at_speed(run, 6, m, ap, 0.01, 1.0) for ap in "BC"}
    if any(r is None for r in rs.values()):
        raise Missing("Figure 6 has no eps = 0.01 point at Omega* = 1")
    ratios = [None if rs[ap]["status"] == DIVERGED else rs[ap]["ratio_to_A"] for ap in "BC"]
    parts = [s is not None and abs(s - 0.2) <= SPEED,
             *[None if x is None else _fold(x, 10.0) == REPRODUCED for x in ratios]]
    txt = [ILL if x is None else _num(x) for x in ratios]
    return Outcome(_by_parts(parts), f"errors from Omega* = {_num(s) if s is not None else 'never'}; at 1: B/A "
                   f"{txt[0]}, C/A {txt[1]}",
                   f"onset 0.2 +- {SPEED:g}; ratios within a factor {FACTOR:g} of 10")
