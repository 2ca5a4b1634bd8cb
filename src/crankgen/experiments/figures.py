"""The data of Figures 2-8 (one function per figure) and of the element-count convergence check.

Every function takes a run context `ctx` (config, `ctx.steady(cases, label)` -> SteadyStates,
`ctx.transients(specs, label)` -> TransientCurves, `ctx.log`) and returns a dict of rows and
arrays; plotting (plots.py) and CSV tables (`csv_table`) are separate.  Each function sends all the
steady-state cases of its figure to the engine in one call.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from ..analyses import theory
from ..declaration.cases import Case
from . import findings as fd
from .config import APPROACHES, EXACT, MODELS

STABLE = "periodic"
# A run of an approach whose strain energy is unbounded below (crankgen.analyses.theory: approach B) that
# fails has diverged: its status is DIVERGED (the word every table, figure and CSV uses), never an
# amplitude or a stability result.  A failure of another approach stays "failed".
DIVERGED = "diverged"
# Range of the theory (crankgen.analyses.theory): |v| / L = eps |v*| above THEORY_LIMIT or an axial strain of
# the neutral axis above STRAIN_LIMIT is "beyond the theory".
THEORY_LIMIT = theory.DEFLECTION_LIMIT
STRAIN_LIMIT = theory.STRAIN_LIMIT
# a transient from rest whose max |v*| over its last window is more than this factor times the
# window before is still growing (a run-off, not an irregular response, whose window maxima
# differ by tens of per cent): it gives no envelope
GROWTH = 2.0
# the findings note of a transient whose max |v*| over its last revolution exceeds the one before by this factor
STILL_GROWING = 1.05


def failure_status(approach):
    """Status of a run that failed: DIVERGED for an ill-posed approach, "failed" otherwise."""
    return DIVERGED if theory.ill_posed(approach) else "failed"


def beyond_theory(eps, v_star, strain=math.nan):
    """(|v|/L, flag) for a deflection v* (scaled by r) at slenderness eps and an axial strain;
    flag "" when neither is known."""
    x = theory.deflection_over_L(eps, v_star) if v_star is not None else math.nan
    return x, theory.beyond(x, strain)


# ----------------------------------------------------------------------------- basic records

@dataclass(frozen=True)
class TransientSpec:
    model: str
    approach: str
    n_elements: int
    omega: float
    revolutions: float
    steps_per_rev: int = 100
    eps: float = 0.01
    ms: float = 0.5


@dataclass
class TransientCurve:
    """One run from zero initial conditions; status "ok" or "failed" (message, fail_time).  A
    failed run keeps its history up to the last good step in t, v_mid (possibly empty)."""

    spec: TransientSpec
    status: str = "ok"             # "ok", DIVERGED (an ill-posed approach failed) or "failed"
    message: str = ""
    fail_time: float = math.nan
    t: np.ndarray = field(default=None, repr=False)
    v_mid: np.ndarray = field(default=None, repr=False)
    axial_strain: np.ndarray = field(default=None, repr=False)   # per step (crankgen.analyses.theory)

    @property
    def ok(self):
        return self.status == "ok"

    @property
    def diverged(self):
        return self.status == DIVERGED

    @property
    def max_strain(self):
        """Largest axial strain of the run (of its history up to the failure); nan if unknown."""
        s = self.axial_strain
        return float(np.max(s)) if s is not None and len(s) else math.nan

    @property
    def has_history(self):
        return self.v_mid is not None and len(self.v_mid) > 0

    @property
    def max_abs(self):
        """max |v*| of the run (of its history up to the failure for a failed run)."""
        return float(np.max(np.abs(self.v_mid))) if self.has_history else math.nan

    @property
    def still_growing(self):
        """(max |v*| over the revolution before the last, over the last) when the last is more than
        STILL_GROWING times the one before (the findings say so of a transient from rest); None
        otherwise, and for a run without two whole revolutions of history."""
        k = self.spec.steps_per_rev
        if not (self.has_history and len(self.v_mid) > 2 * k):
            return None
        last, before = np.max(np.abs(self.v_mid[-k:])), np.max(np.abs(self.v_mid[-2 * k:-k]))
        return (before, last) if last > STILL_GROWING * before else None

    def label(self):
        return f"{self.spec.approach}, n = {self.spec.n_elements}"

    def to_record(self):
        return dict(spec=self.spec.__dict__.copy(), status=self.status, message=self.message,
                    fail_time=self.fail_time, t=self.t, v_mid=self.v_mid, axial_strain=self.axial_strain)

    @classmethod
    def from_record(cls, r):
        return cls(TransientSpec(**r["spec"]), status=r["status"], message=r["message"],
                   fail_time=r["fail_time"], t=r["t"], v_mid=r["v_mid"],
                   axial_strain=r.get("axial_strain"))


def model_spec(key):
    return next(m for m in MODELS + (EXACT,) if m.key == key)


def make_case(cfg, model_key, approach, n, omega, eps=None, ms=None, steps=None):
    return Case(a=cfg.a, eps=cfg.eps if eps is None else eps, ms=cfg.ms if ms is None else ms,
                mu=cfg.mu, omega=omega, approach=approach, model=model_spec(model_key).key, n_elements=n,
                steps_per_rev=cfg.steps_per_rev if steps is None else steps, integrator="newton")


def _num(x):
    """A SteadyState number for this module's arithmetic: None (missing) -> NaN, which the CSV
    tables write as an empty field."""
    return math.nan if x is None else x


def steady_row(model_key, s, **extra):
    """Flat record of a SteadyState (numbers as floats; NaN where there is no periodic state).  A
    failure of an ill-posed approach is DIVERGED; axial_strain is the orbit's (periodic or
    unstable), or a non-periodic response's from its transient (_envelopes)."""
    c = s.case
    orbit = s.status in (STABLE, "unstable") and getattr(s, "states", None) is not None
    row = dict(model=model_key, formulation=c.formulation, damping=c.damping, membrane=c.membrane,
               approach=c.approach,
               n_elements=c.n_elements, steps_per_rev=c.steps_per_rev, omega=c.omega, eps=c.eps,
               ms=c.ms, status=failure_status(c.approach) if s.status == "failed" else s.status,
               amplitude=_num(s.amplitude) if s.status == STABLE else math.nan,
               orbit_amplitude=_num(s.amplitude), half_peak_to_peak=_num(s.half_peak_to_peak),
               iterations=s.iterations, periods=s.periods, residual=_num(s.residual),
               multiplier=_num(getattr(s, "multiplier", None)), message=s.message,
               envelope=math.nan, envelope_note="",
               axial_strain=theory.axial_strain(s) if orbit else math.nan,
               strain_energy_bound=theory.strain_energy(c.approach))
    if c.approach == EXACT.key:       # the exact rod's own limits (crankgen.analyses.theory)
        row["fibre_strain"], row["section_rotation_deg"] = (theory.exact_measures(s) if orbit
                                                            else (math.nan, math.nan))
    row.update(extra)
    flag_theory(row)
    return row


def response_of(row):
    """max |v*| of the response a row stands for: the periodic orbit, the unstable orbit (the
    status is about it), or for a non-periodic response the envelope of its transient from rest;
    nan when there is none (a diverged or failed case)."""
    key = {STABLE: "amplitude", "unstable": "orbit_amplitude"}.get(row["status"], "envelope")
    value = row.get(key, math.nan)
    return math.nan if value is None else value


def flag_theory(row):
    """deflection_over_L (|v|/L of the row's response, response_of) and beyond_theory ("yes" when
    it or the row's axial strain exceeds the limits of crankgen.analyses.theory; an exact-rod row by the
    exact rod's own limits: its eps, outer-fibre strain and section rotation)."""
    row["deflection_over_L"], row["beyond_theory"] = beyond_theory(
        row["eps"], response_of(row), row.get("axial_strain", math.nan))
    if row.get("approach") == EXACT.key:
        flag = theory.exact_range_flag(row["eps"], row.get("fibre_strain", math.nan),
                                       row.get("section_rotation_deg", math.nan))
        row["beyond_theory"] = flag.label if math.isfinite(response_of(row)) else ""


# ----------------------------------------------------------------------------- convergence

def _series_summary(ns, rows, tol):
    """Converged count of one ladder series and a one-line reason."""
    amps = [r["amplitude"] for r in rows]
    n = fd.converged_count(ns, amps, tol)
    if n is not None:
        return dict(kind="converged", n=n, note=f"converged to {100 * tol:g} % at n = {n}")
    finite = [r for r in rows if math.isfinite(r["amplitude"])]
    if not finite:
        bad = rows[0]
        if all(r["status"] == DIVERGED for r in rows):
            return dict(kind="diverged", n=None,
                        note=f"diverged at every n ({theory.ILL_POSED}; {bad['message']})")
        return dict(kind="no-result", n=None,
                    note=f"no periodic state at any n ({bad['status']}: {bad['message']})")
    ch = fd.successive_changes(amps)
    last = ch[np.isfinite(ch)]
    text = f"last change {100 * last[-1]:.2g} %" if last.size else "no two periodic counts"
    return dict(kind="not-converged", n=int(ns[-1]),
                note=f"not converged to {100 * tol:g} % up to n = {ns[-1]} ({text})")


def convergence_study(ctx):
    """Steady amplitude of every model and approach at conv_omegas (base eps) on the element ladder;
    a series stops once two successive counts agree to conv_tol, or after two counts without a
    periodic state.  One engine call per ladder level.  Returns rows, series summaries and the
    element count used for each (model, approach)."""
    cfg = ctx.config
    keys = [(m.key, ap, om) for m in MODELS for ap in APPROACHES for om in cfg.conv_omegas]
    ladder = list(cfg.conv_ladder)
    results = {k: {} for k in keys}
    active = set(keys)
    for level, n in enumerate(ladder):
        todo = []
        for k in keys:
            if k not in active:
                continue
            done = [m for m in ladder[:level] if m in results[k]]
            rows = [results[k][m] for m in done]
            if len(rows) >= 2:
                if fd.converged_count(done, [r["amplitude"] for r in rows], cfg.conv_tol) is not None:
                    active.discard(k)
                    continue
                if not any(math.isfinite(r["amplitude"]) for r in rows[-2:]):
                    active.discard(k)
                    continue
            todo.append(k)
        if not todo:
            break
        cases = [make_case(cfg, mk, ap, n, om) for mk, ap, om in todo]
        states = ctx.steady(cases, f"convergence n = {n}")
        for k, s in zip(todo, states):
            results[k][n] = steady_row(k[0], s)
    rows, series = [], {}
    for k in keys:
        ns = sorted(results[k])
        srows = [results[k][n] for n in ns]
        ch = list(fd.successive_changes([r["amplitude"] for r in srows])) + [math.nan]
        for r, c in zip(srows, ch):
            r["change_to_next"] = c
            rows.append(r)
        series[k] = dict(ns=ns, amplitudes=[r["amplitude"] for r in srows],
                         **_series_summary(ns, srows, cfg.conv_tol))
    counts, count_notes = {}, {}
    for m in MODELS:
        for ap in APPROACHES:
            ss = [series[(m.key, ap, om)] for om in cfg.conv_omegas]
            floor = cfg.paper_elements[ap]
            checked = [s["n"] for s in ss if s["kind"] in ("converged", "not-converged")]
            if checked:
                n = max(max(checked), floor)
            else:
                n = floor
            counts[(m.key, ap)] = n
            parts = [f"Omega* = {om:g}: {s['note']}" for om, s in zip(cfg.conv_omegas, ss)]
            if not checked:
                parts.append(f"could not be checked; the paper's count {floor} is used")
            elif n == floor and max(checked) < floor:
                parts.append(f"the paper's count {floor} (larger) is used")
            count_notes[(m.key, ap)] = "; ".join(parts)
    return dict(rows=rows, series=series, counts=counts, notes=count_notes)


def refinement_points(cfg):
    """(Omega*, eps) of the refinement check: the Figure 6 slendernesses at refine_omegas, and (if
    refine_fig5) the Figure 5 speeds at its smallest eps."""
    pts = [(om, eps) for eps in cfg.fig6_eps for om in cfg.refine_omegas]
    if cfg.refine_fig5:
        pts += [(om, min(cfg.fig5_eps)) for om in cfg.fig5_omegas]
    return list(dict.fromkeys(pts))


def refinement_check(ctx, counts, fig6=None, fig5=None):
    """Cases of Figures 5 and 6 (refinement_points) with n and 2 n elements (n the count used): how
    much the amplitude still changes away from the speeds and eps of the convergence check.
    Reuses the figures' results for n when available."""
    cfg = ctx.config
    have = {}
    for fig in (fig5, fig6):
        for r in (fig or {}).get("rows", []):
            have[(r["model"], r["approach"], r["eps"], r["omega"], r["n_elements"])] = r
    points = refinement_points(cfg)
    specs, cases = [], []
    for m in MODELS:
        for ap in APPROACHES:
            n = counts[(m.key, ap)]
            for om, eps in points:
                for nn in (n, 2 * n):
                    if (m.key, ap, eps, om, nn) in have:
                        continue
                    specs.append((m.key, ap, eps, om, nn))
                    cases.append(make_case(cfg, m.key, ap, nn, om, eps=eps))
    if cases:
        for spec, s in zip(specs, ctx.steady(cases, "refinement check (2 n elements)")):
            have[spec] = steady_row(spec[0], s)
    rows = []
    for m in MODELS:
        for ap in APPROACHES:
            n = counts[(m.key, ap)]
            for om, eps in points:
                r1, r2 = have[(m.key, ap, eps, om, n)], have[(m.key, ap, eps, om, 2 * n)]
                rows.append(dict(model=m.key, approach=ap, eps=eps, omega=om, n_elements=n,
                                 amplitude=r1["amplitude"], status=r1["status"],
                                 n_refined=2 * n, amplitude_refined=r2["amplitude"],
                                 status_refined=r2["status"],
                                 change=float(fd.relative_difference(r1["amplitude"], r2["amplitude"])),
                                 message=r1["message"] or r2["message"]))
    return dict(rows=rows)


# ----------------------------------------------------------------------------- transients

def figure2(ctx, counts):
    """v* against t* at the low speed: approaches A, B, C, element counts compared."""
    cfg = ctx.config
    specs = []
    for m in MODELS:
        for ap in APPROACHES:
            for n in sorted(set(cfg.fig2_elements) | {counts[(m.key, ap)]}):
                specs.append(TransientSpec(m.key, ap, n, cfg.fig2_omega, cfg.fig2_revolutions,
                                           cfg.steps_per_rev, cfg.eps, cfg.ms))
    return dict(figure=2, curves=ctx.transients(specs, "figure 2 (transients)"))


def figure3(ctx, counts):
    """Convergence of approach A (transient v* at the high speed) with the element count; the
    finest count also with the time step halved."""
    cfg = ctx.config
    specs = []
    for m in MODELS:
        ns = sorted(set(cfg.fig3_elements) | {counts[(m.key, "A")]})
        for n in ns:
            specs.append(TransientSpec(m.key, "A", n, cfg.fig3_omega, cfg.fig3_revolutions,
                                       cfg.fig3_steps[0], cfg.eps, cfg.ms))
        for steps in cfg.fig3_steps[1:]:
            specs.append(TransientSpec(m.key, "A", ns[-1], cfg.fig3_omega, cfg.fig3_revolutions,
                                       steps, cfg.eps, cfg.ms))
    return dict(figure=3, curves=ctx.transients(specs, "figure 3 (transients)"))


def figure4(ctx, counts):
    """Transient v* at the high speed: A, B, C; and B and C for several slider masses."""
    cfg = ctx.config
    specs = []
    for m in MODELS:
        for ap in APPROACHES:
            masses = sorted(set(cfg.fig4_ms) | {cfg.ms}) if ap != "A" else [cfg.ms]
            for ms in masses:
                specs.append(TransientSpec(m.key, ap, counts[(m.key, ap)], cfg.fig4_omega,
                                           cfg.fig4_revolutions, cfg.steps_per_rev, cfg.eps, ms))
    return dict(figure=4, curves=ctx.transients(specs, "figure 4 (transients)"))


def transient_summary(curves):
    """Rows: per curve its status, max |v*| and failure time."""
    return [dict(model=c.spec.model, approach=c.spec.approach, n_elements=c.spec.n_elements,
                 steps_per_rev=c.spec.steps_per_rev, omega=c.spec.omega, eps=c.spec.eps,
                 ms=c.spec.ms, status=c.status, max_abs=c.max_abs, fail_time=c.fail_time,
                 message=c.message) for c in curves]


def transient_difference(a, b):
    """max |v_a - v_b| / max |v_b| over the common time points of two transient curves (the finer
    time step subsampled); None if either failed or their time grids do not nest."""
    if not (a.ok and b.ok):
        return None
    ka, kb = a.spec.steps_per_rev, b.spec.steps_per_rev
    if kb % ka == 0:
        va, vb = a.v_mid, b.v_mid[:: kb // ka]
    elif ka % kb == 0:
        va, vb = a.v_mid[:: ka // kb], b.v_mid
    else:
        return None
    k = min(len(va), len(vb))
    scale = np.max(np.abs(vb[:k]))
    return float(np.max(np.abs(va[:k] - vb[:k])) / scale) if scale > 0 else None


# ----------------------------------------------------------------------------- sweeps

def _add_ratios(rows):
    """ratio_to_A on each row: amplitude over approach A's amplitude at the same model and point."""
    ref = {(r["model"], r["omega"], r["eps"], r["ms"]): r["amplitude"]
           for r in rows if r["approach"] == "A"}
    for r in rows:
        base = ref.get((r["model"], r["omega"], r["eps"], r["ms"]), math.nan)
        r["ratio_to_A"] = float(fd.ratio(r["amplitude"], base))


def _envelopes(ctx, rows, label):
    """For cases without a stable periodic state whose integration did not fail: a transient from
    zero initial conditions of envelope_revolutions; its max |v*| over the last envelope_window
    revolutions is the envelope, unless it still grows (more than GROWTH times the window
    before): then there is no settled response and no envelope.  A transient that fails has none
    either: DIVERGED for an ill-posed approach (its numbers before it stopped are no amplitude)."""
    cfg = ctx.config
    if cfg.envelope_revolutions <= 0:
        return
    todo = [r for r in rows if r["status"] in ("unstable", "not-periodic")]
    if not todo:
        return
    specs = [TransientSpec(r["model"], r["approach"], r["n_elements"], r["omega"],
                           cfg.envelope_revolutions, r["steps_per_rev"], r["eps"], r["ms"])
             for r in todo]
    curves = ctx.transients(specs, f"{label}: response of cases without a stable periodic state")
    total, w = cfg.envelope_revolutions, cfg.envelope_window
    for r, c in zip(todo, curves):
        if c.ok:
            k = c.spec.steps_per_rev
            last = float(np.max(np.abs(c.v_mid[-(w * k + 1):])))
            before = c.v_mid[-(2 * w * k + 1):-(w * k)]
            prev = float(np.max(np.abs(before))) if 2 * w <= total and len(before) else math.nan
            if math.isfinite(prev) and last > GROWTH * prev:
                r["envelope_note"] = (f"the transient from rest is still growing after {total} revolutions "
                                      f"(max |v*| {prev:.4g} over revolutions {total - 2 * w}-{total - w}, "
                                      f"{last:.4g} over {total - w}-{total}): no settled response")
            else:
                r["envelope"] = last
                note = f"max |v*| over revolutions {total - w}-{total} from zero initial conditions"
                strain = (float(np.max(c.axial_strain[-(w * k + 1):]))
                          if c.axial_strain is not None else math.nan)
                if r["status"] == "not-periodic":
                    r["axial_strain"] = strain
                else:        # an unstable orbit: the row is about the orbit, the note about this
                    why = ("" if r["approach"] == EXACT.key else    # its own limits: the row's flag
                           theory.reasons(theory.deflection_over_L(r["eps"], last), strain))
                    note += ("; it settles away from the unstable orbit" if last > 1.05 * r["orbit_amplitude"]
                             else "") + (f"; beyond the theory ({why})" if why else "")
                r["envelope_note"] = note
        else:
            word = "diverged" if c.diverged else "failed"
            ill = f" ({theory.ILL_POSED})" if c.diverged else ""
            r["envelope_note"] = (f"the transient from rest {word}{ill} at t* = {c.fail_time:.4g} "
                                  f"(|v*| had reached {c.max_abs:.3g}; no amplitude): {c.message}")
        flag_theory(r)


def _sweep(ctx, counts, points, label):
    cfg = ctx.config
    keys, cases = [], []
    for m in MODELS:
        for ap in APPROACHES:
            for om, eps in points:
                keys.append(m.key)
                cases.append(make_case(cfg, m.key, ap, counts[(m.key, ap)], om, eps=eps))
    rows = [steady_row(k, s) for k, s in zip(keys, ctx.steady(cases, label))]
    _add_ratios(rows)
    _envelopes(ctx, rows, label)
    if cfg.exact_rows:               # the exact rod beside them, in its own call: the rows above unchanged
        n = cfg.exact_row_elements or counts[(MODELS[1].key, "A")]
        cases = [make_case(cfg, EXACT.key, EXACT.key, n, om, eps=eps) for om, eps in points]
        exact = [steady_row(EXACT.key, s) for s in ctx.steady(cases, f"{label}, the exact rod")]
        _envelopes(ctx, exact, f"{label}, the exact rod")
        rows += exact
    return rows


def figure5(ctx, counts):
    """Steady amplitude of v* against eps at fig5_omegas, approaches A, B, C."""
    cfg = ctx.config
    pts = [(om, eps) for om in cfg.fig5_omegas for eps in cfg.fig5_eps]
    return dict(figure=5, rows=_sweep(ctx, counts, pts, "figure 5 (steady states)"))


def figure6(ctx, counts):
    """Steady amplitude of v* against Omega* at fig6_eps, approaches A, B, C."""
    cfg = ctx.config
    pts = [(om, eps) for eps in cfg.fig6_eps for om in cfg.fig6_omegas]
    return dict(figure=6, rows=_sweep(ctx, counts, pts, "figure 6 (steady states)"))


def _extension(ctx, counts, figure, omega):
    cfg = ctx.config
    keys, cases = [], []
    for m in MODELS:
        for ms in cfg.ext_ms:
            keys.append(m.key)
            cases.append(make_case(cfg, m.key, "A", counts[(m.key, "A")], omega, ms=ms))
    curves = []
    for k, s in zip(keys, ctx.steady(cases, f"figure {figure} (steady states)")):
        row = steady_row(k, s)
        if s.status in ("periodic", "unstable") and s.extension is not None:
            row["theta_deg"] = np.degrees(np.asarray(s.theta, dtype=float))
            row["extension"] = np.asarray(s.extension, dtype=float)
            row["u_end"] = None if s.u_end is None else np.asarray(s.u_end, dtype=float)
        else:
            row["theta_deg"], row["extension"], row["u_end"] = None, None, None
        curves.append(row)
    return dict(figure=figure, omega=omega, curves=curves)


def figure7(ctx, counts):
    """Extension delta* over one steady revolution, approach A, slider masses ext_ms, fig7_omega."""
    return _extension(ctx, counts, 7, ctx.config.fig7_omega)


def figure8(ctx, counts):
    """As figure 7 at fig8_omega."""
    return _extension(ctx, counts, 8, ctx.config.fig8_omega)


def extension_crossings_of(data, model_key, rel_tol):
    """Common crossing angles of the stable extension curves of one model (None if < 2 curves)."""
    cs = [c for c in data["curves"] if c["model"] == model_key and c["status"] == STABLE]
    if len(cs) < 2:
        return None
    return fd.extension_crossings(cs[0]["theta_deg"], np.stack([c["extension"] for c in cs]), rel_tol)


# ----------------------------------------------------------------------------- CSV tables

STEADY_COLUMNS = ["model", "formulation", "damping", "approach", "strain_energy_bound", "n_elements",
                  "steps_per_rev", "omega", "eps", "ms", "status", "amplitude", "ratio_to_A",
                  "orbit_amplitude", "half_peak_to_peak", "envelope", "envelope_note",
                  "deflection_over_L", "axial_strain", "beyond_theory", "iterations", "periods",
                  "residual", "multiplier", "message", "fibre_strain", "section_rotation_deg"]
TRANSIENT_COLUMNS = ["model", "formulation", "damping", "approach", "strain_energy_bound", "n_elements",
                     "steps_per_rev", "omega", "eps", "ms", "status", "message", "t", "theta_deg",
                     "v_mid", "deflection_over_L", "axial_strain", "beyond_theory"]
EXTENSION_COLUMNS = ["model", "formulation", "damping", "approach", "strain_energy_bound", "n_elements",
                     "steps_per_rev", "omega", "eps", "ms", "status", "message", "deflection_over_L",
                     "axial_strain", "beyond_theory", "theta_deg", "extension", "u_end"]
CONVERGENCE_COLUMNS = ["check", "model", "approach", "omega", "eps", "n_elements", "status",
                       "amplitude", "change_to_next", "n_refined", "amplitude_refined",
                       "status_refined", "change", "message"]


def csv_table(data):
    """(columns, rows) of the plotted data of a figure."""
    fig = data["figure"]
    if fig in (2, 3, 4):
        rows = []
        for c in data["curves"]:
            s, m = c.spec, model_spec(c.spec.model)
            base = dict(model=s.model, formulation=m.formulation, damping=m.damping, membrane=m.membrane,
                        approach=s.approach, strain_energy_bound=theory.strain_energy(s.approach),
                        n_elements=s.n_elements, steps_per_rev=s.steps_per_rev,
                        omega=s.omega, eps=s.eps, ms=s.ms, status=c.status, message=c.message)
            if c.has_history:     # a failed run: its rows up to the last good step
                theta = np.degrees(s.omega * c.t)
                strain = c.axial_strain if c.axial_strain is not None else np.full(len(c.t), math.nan)
                for t, th, v, e in zip(c.t, theta, c.v_mid, strain):
                    x, flag = beyond_theory(s.eps, v, e)
                    rows.append(dict(base, t=t, theta_deg=th, v_mid=v, deflection_over_L=x,
                                     axial_strain=e, beyond_theory=flag))
            if not c.ok:    # and one row where it failed (no v*)
                rows.append(dict(base, t=c.fail_time, theta_deg=math.degrees(s.omega * c.fail_time)
                                 if math.isfinite(c.fail_time) else math.nan))
        return TRANSIENT_COLUMNS, rows
    if fig in (5, 6):
        return STEADY_COLUMNS, data["rows"]
    if fig in (7, 8):
        rows = []
        for c in data["curves"]:
            base = {k: c[k] for k in EXTENSION_COLUMNS if k in c and k not in ("theta_deg", "extension")}
            if c["theta_deg"] is not None:
                u = c.get("u_end")
                u = [math.nan] * len(c["theta_deg"]) if u is None else u
                rows.extend(dict(base, theta_deg=th, extension=e, u_end=ue)
                            for th, e, ue in zip(c["theta_deg"], c["extension"], u))
            else:
                rows.append(base)
        return EXTENSION_COLUMNS, rows
    raise ValueError(f"no table for figure {fig}")


def convergence_table(conv, refine=None):
    rows = [dict(r, check="ladder") for r in conv["rows"]]
    if refine is not None:
        rows += [dict(r, check="refinement") for r in refine["rows"]]
    return CONVERGENCE_COLUMNS, rows
