"""Brute-force bifurcation diagrams: march the map value by value and sample it once per period.

Each parameter value starts from the last state of the previous one (so sweeps up and down show
hysteresis), iterates `transient` times, then `samples` times, recording the observable (the
mechanism: v*(1/2) at theta = 0, once per crank revolution).  Classification, with its evidence:
- "period-k" (k <= max_period): the smallest k with max_j |x_{j+k} - x_j| / (1 + max |x|) < tol
  over the sampled states (repeat_residual); while a divisor of k nearly repeats (to 1e-4), up to
  four more rounds of samples are taken first (a slowly decaying alternation mimics period 2k);
- otherwise the largest Lyapunov exponent per application, from the product of the exact
  Jacobians along `samples` further applications (renormalized each time: the first column of a
  QR iteration; the first quarter aligns the vector and is not averaged): > lyapunov_tol "irregular", within +-lyapunov_tol "quasi-periodic", below
  -lyapunov_tol "unsettled" (still converging after the transient);
- "failed" when the map cannot be evaluated (message says why; the next value restarts from the
  last good state).  When the transient from the previous value's state fails, the value is
  approached once more from that state in four parameter steps of transient / 4 iterations each.
distinct counts the sampled values that differ by more than 1e-6 (1 + |sample|); amplitude is the
largest |observable| along the orbit marched once more from the last state (for the mechanism max
|v*(1/2)| over every step: what a diagram's branches show), over the period found, or
AMPLITUDE_REVOLUTIONS applications when none.
"""

import csv
import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ...declaration import schema
from ...errors import CrankgenError, ParameterError
from ..blas import single_thread
from .maps import MapError

from ...results.io import atomic_file, save_figure
from .diagram_files import cell

DIRECTIONS = ("up", "down", "both")
AMPLITUDE_REVOLUTIONS = 8      # applications over which a response that does not repeat is measured


@dataclass
class PoincarePoint:
    direction: str                 # "up" or "down"
    parameter: float
    classification: str            # "period-k", "quasi-periodic", "irregular", "unsettled", "failed"
    period: int                    # k of "period-k", else 0
    repeat_residual: Optional[float]   # scaled max |x_{j+k} - x_j| for that k (smallest over k
    #                                    otherwise); None when the march failed
    lyapunov: Optional[float]      # largest Lyapunov exponent per application; None when periodic
    #                                (not computed) or failed
    distinct: int                  # distinct sampled values
    samples: np.ndarray = field(repr=False)   # the observable once per application
    message: str = ""
    amplitude: Optional[float] = None    # max |observable| along the last revolutions marched (the
    #                                      orbit's period, or AMPLITUDE_REVOLUTIONS when not periodic)


@dataclass
class PoincareDiagram:
    parameter_name: str
    points: list
    info: dict = field(default_factory=dict)

    @property
    def si(self):
        """The diagram in SI (bifurcation/si_view.py) of a sweep made with units="si"."""
        from .si_view import si_of
        return si_of(self)

    def si_view(self, si_mechanism):
        """The diagram in SI for the crankgen.SIMechanism whose dimensionless form it was computed for."""
        from .si_view import DiagramSI
        return DiagramSI(self, si_mechanism)

    def to_csv(self, folder):
        """poincare_summary.csv (one row per value and direction) and poincare_samples.csv (every
        sample) in folder; returns the paths."""
        from ...results.io import output_folder
        paths = output_folder(folder, ["poincare_summary.csv", "poincare_samples.csv"])
        name = self.parameter_name
        with atomic_file(paths[0]) as fh:
            w = csv.writer(fh)
            w.writerow(["direction", name, "classification", "period", "repeat_residual",
                        "lyapunov", "distinct", "amplitude", "message"])
            for q in self.points:
                w.writerow([q.direction, cell(q.parameter), q.classification, q.period,
                            cell(q.repeat_residual), cell(q.lyapunov), q.distinct, cell(q.amplitude),
                            q.message])
        with atomic_file(paths[1]) as fh:
            w = csv.writer(fh)
            w.writerow(["direction", name, "sample", "value"])
            for q in self.points:
                for j, v in enumerate(q.samples):
                    w.writerow([q.direction, cell(q.parameter), j, cell(v)])
        return paths

    def plot(self, path, diagram=None, title=None, ylabel=None, xlabel=None):
        """Samples against the parameter (sweeps up and down in two colours); with a
        BifurcationDiagram, its branches' section points are drawn over them (stable solid,
        unstable dashed, one colour per period) and its special points marked, labelled where
        the label covers no data.  Axis labels and title default to what the sweep holds; the
        legend sits below the axes."""
        from matplotlib.lines import Line2D

        from ...plots.figures import beyond_patch, fit_panels, panels, place_labels, shade_beyond
        from ..theory import DEFLECTION_LIMIT
        from .diagram import LABELS, PERIOD_COLORS, TITLE_WIDTH, axis, describe

        from ...results.io import output_path
        path = output_path(path)
        fig, axes = panels(1, 1, width=7.5, height=4.2)
        ax = axes[0, 0]
        handles = []
        style = {"up": ("C0", "o", 7), "down": ("C3", "x", 12)}
        for d in ("up", "down"):
            pts = [q for q in self.points if q.direction == d and len(q.samples)]
            if not pts:
                continue
            c, m, s = style[d]
            xs = np.concatenate([np.full(len(q.samples), q.parameter) for q in pts])
            ys = np.concatenate([q.samples for q in pts])
            ax.scatter(xs, ys, s=s, marker=m, color=c, lw=0.6, alpha=0.7, zorder=3)
            handles.append(Line2D([], [], ls="none", marker=m, color=c, label=f"sweep {d}"))
        failed = [q.parameter for q in self.points if q.classification == "failed"]
        if failed:
            ax.scatter(failed, np.full(len(failed), 0.04), transform=ax.get_xaxis_transform(),
                       marker="+", color="k", s=40, zorder=5)
            handles.append(Line2D([], [], ls="none", marker="+", color="k",
                                  label="+ at the bottom: the march failed there (see CSV)"))
        if diagram is not None:
            periods = set()
            for br in diagram.branches:
                if br.section is None:
                    continue
                color = PERIOD_COLORS.get(br.period, "0.4")
                periods.add(br.period)
                st = np.asarray(br.stable, dtype=bool)
                for j in range(br.period):
                    y = br.section[:, j]
                    start = 0
                    for i in range(1, len(br) + 1):
                        if i == len(br) or st[i] != st[start]:
                            e = min(i + 1, len(br))
                            ax.plot(br.parameter[start:e], y[start:e], color=color,
                                    ls="-" if st[start] else "--", lw=0.9 if st[start] else 0.7,
                                    zorder=4)
                            start = i
            handles += [Line2D([], [], color=PERIOD_COLORS.get(k, "0.4"), label=f"continuation, period {k}")
                        for k in sorted(periods)]
            handles += [Line2D([], [], color="grey", ls="-", label="continuation, stable"),
                        Line2D([], [], color="grey", ls="--", label="continuation, unstable")]
            for sp in diagram.special_points:
                ax.axvline(sp.parameter, color="grey", lw=0.6, ls=":", zorder=1)
            place_labels(ax, [(sp.parameter, float(diagram.branches[sp.branch].section[
                np.argmin(np.abs(diagram.branches[sp.branch].parameter - sp.parameter)), 0])
                if diagram.branches[sp.branch].section is not None else 0.0,
                f"{LABELS[sp.kind]} {sp.parameter:.4g}", "dimgrey")
                for sp in sorted(diagram.special_points, key=lambda s: s.parameter)])
            handles.append(Line2D([], [], color="grey", lw=0.6, ls=":",
                                  label="dotted: special points of the continuation"))
        r_unit = schema.UNIT_PARAMETERS["r"]          # v* is in units of r: the slenderness gives it in L
        mech = r_unit in self.info or self.parameter_name == r_unit
        # the range beyond the theory, |v|/L > 0.1, shaded as in every other figure (over a sweep
        # of the slenderness the limit changes along the axis: drawn for its largest value, the
        # smallest band)
        eps = (self.info.get(r_unit) if self.parameter_name != r_unit
               else max((q.parameter for q in self.points), default=None))
        samples = [abs(float(v)) for q in self.points for v in q.samples if np.isfinite(v)]
        if mech and eps and samples and max(samples) * eps > DEFLECTION_LIMIT:
            shade_beyond(ax, DEFLECTION_LIMIT / eps, "0.88")
            handles.append(beyond_patch("0.88"))
        ax.set_xlabel(xlabel or axis(self.parameter_name))
        ax.set_ylabel(ylabel or ("v*(1/2) at theta = 0, once per revolution" if mech
                                 else "observable, once per application of the map"))
        ax.grid(alpha=0.3)
        if handles:
            leg = ax.legend(handles=handles, fontsize=8, loc="upper center", ncol=3, frameon=False,
                            bbox_to_anchor=(0.5, -0.16))
            leg._crankgen_outside = True
        ax.set_title(title or describe(self.info, "Poincare sweep", self.parameter_name, TITLE_WIDTH), fontsize=9)
        save_figure(fit_panels(fig), path, dpi=130)
        return path


def _classify(states, tol, max_period):
    scale = 1.0 + float(np.max(np.abs(states)))
    best = (math.inf, 0)
    n = len(states)
    for k in range(1, max_period + 1):
        if n - k < 2:
            break
        r = float(np.max(np.abs(states[k:] - states[:-k]))) / scale
        if r < tol:
            return k, r
        best = min(best, (r, k))
    return 0, best[0]


def _lyapunov(jacs, seed=0):
    """Mean log growth of a renormalized tangent vector over the last 3/4 of the Jacobians (the
    first quarter aligns it with the most expanding direction)."""
    w = np.random.default_rng(seed).standard_normal(jacs.shape[1])
    w /= np.linalg.norm(w)
    skip = len(jacs) // 4
    total = 0.0
    for i, J in enumerate(jacs):
        w = J @ w
        g = float(np.linalg.norm(w))
        if not (g > 0 and math.isfinite(g)):
            return math.inf if not math.isfinite(g) else -math.inf
        if i >= skip:
            total += math.log(g)
        w /= g
    return total / (len(jacs) - skip)


def _distinct(samples):
    s = np.sort(np.asarray(samples, dtype=float))
    if s.size == 0:
        return 0
    gaps = np.diff(s) > 1e-6 * (1.0 + np.abs(s[1:]))
    return int(1 + np.sum(gaps))


def sweep_map(fmap, values, x0, direction="up", transient=100, samples=64, max_period=8, tol=1e-8,
              lyapunov_tol=0.01, progress=None):
    """PoincareDiagram of fmap over values (see module docstring); x0 the state the first value
    starts from.  progress(done, total) after each value."""
    if direction not in DIRECTIONS:
        raise ParameterError(f"direction must be one of {', '.join(map(repr, DIRECTIONS))}, got {direction!r}")
    values = sorted(float(v) for v in values)
    if not values:
        raise ParameterError("values must hold at least one parameter value")
    passes = {"up": [("up", values)], "down": [("down", values[::-1])],
              "both": [("up", values), ("down", values[::-1])]}[direction]
    with single_thread():
        return _sweep(fmap, passes, x0, transient, samples, max_period, tol, lyapunov_tol, progress)


def _sweep(fmap, passes, x0, transient, samples, max_period, tol, lyapunov_tol, progress):
    total = sum(len(v) for _, v in passes)
    x = np.asarray(x0, dtype=float)
    points, done, p_last = [], 0, None
    for d, vals in passes:
        for p in vals:
            try:
                try:
                    states, _, _ = fmap.iterate(x, p, transient)
                except (MapError, CrankgenError):
                    if p_last is None:
                        raise
                    # the jump from the last state failed: ramp the parameter in four steps
                    for q in np.linspace(p_last, p, 5)[1:]:
                        x = fmap.iterate(x, q, max(transient // 4, 1))[0][-1]
                    states, _, _ = fmap.iterate(x, p, transient)
                states, smp, _ = fmap.iterate(states[-1], p, samples)
                k, r = _classify(states, tol, max_period)
                for _ in range(4):
                    # a slowly decaying alternation (multiplier near -1) can pass the test at 2k
                    # before it does at k: sample again while a divisor of k nearly repeats
                    near = _classify(states, 1e-4, k - 1)[0] if k > 1 else 0
                    if not near or k % near:
                        break
                    states, smp, _ = fmap.iterate(states[-1], p, samples)
                    k, r = _classify(states, tol, max_period)
                lyap = None
                if k:
                    cls = f"period-{k}"
                else:
                    _, _, jacs = fmap.iterate(states[-1], p, samples, jacobian=True)
                    lyap = _lyapunov(jacs)
                    cls = ("irregular" if lyap > lyapunov_tol else
                           "quasi-periodic" if lyap >= -lyapunov_tol else "unsettled")
                amplitude = float(fmap.orbit(states[-1], p, k or AMPLITUDE_REVOLUTIONS)[0])
                points.append(PoincarePoint(d, p, cls, k, r if math.isfinite(r) else None, lyap,
                                            _distinct(smp[1:]), smp[1:], amplitude=amplitude))
                x, p_last = states[-1], p
            except (MapError, CrankgenError) as exc:
                points.append(PoincarePoint(d, p, "failed", 0, None, None, 0,
                                            np.zeros(0), str(exc)))
            done += 1
            if progress is not None:
                progress(done, total)
    return PoincareDiagram(fmap.parameter, points)
