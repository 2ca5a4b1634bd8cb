"""BifurcationDiagram: branches of periodic orbits and their special points; CSV and plot."""

import csv
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..io import atomic_file, save_figure

LABELS = {"fold": "F", "period-doubling": "PD", "neimark-sacker": "NS"}


def _num(x):
    """CSV cell of a number: full precision, empty when it does not exist (NaN, inf, None)."""
    if x is None:
        return ""
    x = float(x)
    return repr(x) if np.isfinite(x) else ""


@dataclass
class Branch:
    """One branch of period-`period` orbits, point by point (special points included)."""

    period: int
    parameter_name: str
    parameter: np.ndarray          # (n,)
    amplitude: np.ndarray          # (n,) max |observable| over the orbit (mechanism: max |v*|)
    stable: np.ndarray             # (n,) every multiplier inside the unit circle
    multipliers: np.ndarray        # (n, dim) complex, by decreasing modulus (of P^period)
    states: np.ndarray = field(repr=False)   # (n, dim) state at the start of the orbit
    section: np.ndarray = field(default=None, repr=False)   # (n, period) observable at the
    #                              start of each revolution of the orbit (mechanism: v* at theta = 0)
    origin: str = "start"
    stop_reason: str = ""

    def __len__(self):
        return len(self.parameter)


@dataclass
class SpecialPoint:
    kind: str                      # "fold", "period-doubling" or "neimark-sacker"
    parameter: float
    amplitude: float
    period: int                    # period of the branch it lies on
    branch: int                    # index into diagram.branches
    multiplier: complex            # the critical multiplier (+1, -1, on the unit circle)
    state: np.ndarray = field(default=None, repr=False)


@dataclass
class BifurcationDiagram:
    parameter_name: str
    branches: list
    special_points: list
    info: dict = field(default_factory=dict)   # the model and settings it was computed for

    def eps_at(self, p):
        """Slenderness of the mechanism at parameter value p (None: not a mechanism diagram)."""
        if self.parameter_name == "eps":
            return float(p)
        eps = self.info.get("eps")
        return None if eps is None else float(eps)

    def to_csv(self, folder):
        """branches.csv (one row per point; for the mechanism with deflection_over_L = eps
        amplitude and beyond_theory, crankgen.theory), special_points.csv and multipliers.csv
        (every multiplier of every point, long format) in folder; returns the paths.  A number
        that does not exist is an empty field."""
        from ..theory import DEFLECTION_LIMIT

        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        name = self.parameter_name
        paths = [folder / "branches.csv", folder / "special_points.csv", folder / "multipliers.csv"]
        flags = self.eps_at(self.branches[0].parameter[0]) is not None if self.branches else False

        def theory(p, amplitude):
            x = abs(self.eps_at(p) * float(amplitude))
            return [_num(x), "" if not np.isfinite(x) else ("yes" if x > DEFLECTION_LIMIT else "no")]
        with atomic_file(paths[0]) as fh:
            w = csv.writer(fh)
            w.writerow(["branch", "period", "point", name, "amplitude", "stable",
                        "max_abs_multiplier", "origin"]
                       + (["deflection_over_L", "beyond_theory"] if flags else []))
            for b, br in enumerate(self.branches):
                for i in range(len(br)):
                    w.writerow([b, br.period, i, _num(br.parameter[i]), _num(br.amplitude[i]),
                                int(br.stable[i]), _num(np.abs(br.multipliers[i]).max()), br.origin]
                               + (theory(br.parameter[i], br.amplitude[i]) if flags else []))
        with atomic_file(paths[1]) as fh:
            w = csv.writer(fh)
            w.writerow(["kind", name, "amplitude", "period", "branch", "multiplier_re",
                        "multiplier_im", "multiplier_abs"]
                       + (["deflection_over_L", "beyond_theory"] if flags else []))
            for s in self.special_points:
                w.writerow([s.kind, _num(s.parameter), _num(s.amplitude), s.period, s.branch,
                            _num(s.multiplier.real), _num(s.multiplier.imag), _num(abs(s.multiplier))]
                           + (theory(s.parameter, s.amplitude) if flags else []))
        with atomic_file(paths[2]) as fh:
            w = csv.writer(fh)
            w.writerow(["branch", "point", name, "index", "re", "im", "abs"])
            for b, br in enumerate(self.branches):
                for i in range(len(br)):
                    for j, m in enumerate(br.multipliers[i]):
                        w.writerow([b, i, _num(br.parameter[i]), j, _num(m.real), _num(m.imag),
                                    _num(abs(m))])
        return paths

    def plot(self, path, ax=None, title=None, ylabel="amplitude", xlabel=None):
        """Amplitude against the parameter: stable solid, unstable dashed, one colour per period,
        special points marked and labelled (F fold, PD period doubling, NS Neimark-Sacker)."""
        from ..plotting import pyplot

        plt = pyplot()
        own = ax is None
        if own:
            fig, ax = plt.subplots(figsize=(7.5, 4.5), constrained_layout=True)
        colors = {}
        for br in self.branches:
            c = colors.setdefault(br.period, f"C{len(colors)}")
            st = np.asarray(br.stable, dtype=bool)
            # draw stable and unstable runs, each run joined to the next point so no gap is left
            start = 0
            for i in range(1, len(br) + 1):
                if i == len(br) or st[i] != st[start]:
                    j = min(i + 1, len(br))
                    ax.plot(br.parameter[start:j], br.amplitude[start:j], color=c,
                            ls="-" if st[start] else "--", lw=1.6 if st[start] else 1.1)
                    start = i
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], color=c, label=f"period {k}") for k, c in colors.items()]
        handles += [Line2D([], [], color="grey", ls="-", label="stable"),
                    Line2D([], [], color="grey", ls="--", label="unstable")]
        markers = {"fold": "s", "period-doubling": "o", "neimark-sacker": "D"}
        for kind, m in markers.items():
            pts = [s for s in self.special_points if s.kind == kind]
            if not pts:
                continue
            ax.scatter([s.parameter for s in pts], [s.amplitude for s in pts], marker=m, s=36,
                       facecolor="white", edgecolor="black", zorder=5)
        # labels alternately above and below, so that neighbouring points stay readable
        for i, s in enumerate(sorted(self.special_points, key=lambda s: s.parameter)):
            ax.annotate(f"{LABELS[s.kind]} {s.parameter:.4g}", (s.parameter, s.amplitude),
                        textcoords="offset points", xytext=(5, 7 if i % 2 == 0 else -13),
                        fontsize=8, zorder=6)
        for kind, m in markers.items():
            if not any(s.kind == kind for s in self.special_points):
                continue
            handles.append(Line2D([], [], ls="none", marker=m, markerfacecolor="white",
                                  color="black", label=f"{LABELS[kind]}: {kind}"))
        ax.set_xlabel(xlabel or self.parameter_name)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(handles=handles, fontsize=8, loc="best")
        if title:
            ax.set_title(title, fontsize=9)
        if own:
            save_figure(fig, path, dpi=130)
        return path
