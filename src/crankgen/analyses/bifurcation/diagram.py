"""BifurcationDiagram: branches of periodic orbits and their special points; CSV and plot."""

import csv
import math
import textwrap
from dataclasses import dataclass, field

import numpy as np

from ...declaration import schema
from ...results.io import atomic_file, save_figure
from ...declaration.units import in_L
from ...errors import ParameterError
from . import diagram_files
from .diagram_files import cell

LABELS = {"fold": "F", "period-doubling": "PD", "neimark-sacker": "NS"}


# branch colours by period (the reproduce figures use the same): black, purple, green, olive,
# none near the approaches' blue, orange and red (crankgen.plots.figures.APPROACH_COLORS)
PERIOD_COLORS = {1: "black", 2: "#7b2d8e", 4: "#2ca02c", 8: "#6b6b00"}


def axis(parameter):
    """The axis text of a parameter: its record's axis (the name itself otherwise)."""
    p = schema.PARAMETERS.get(parameter)
    return parameter if p is None else p.axis


TITLE_WIDTH = 120                # characters of a figure title's line of parameters


def describe(info, what, parameter, width=None):
    """A two-line title from a diagram's info (the model and settings it was computed for): what
    and the parameter varied, the model; then every fixed parameter that sets the response (the
    crank speed, eps, ms*, mu*, a*) and the linkage (a four-bar's rocker and ground pivot, a
    guide offset, gravity, a fluctuating crank), the varied parameter left out.  width: the
    second line wrapped at that many characters, between items (a figure's title)."""
    if not info:
        return f"{what} in {parameter}"
    from ...plots.figures import model_parts
    parts = model_parts(info)
    main, other = schema.describe({k: v for k, v in info.items() if k in schema.PARAMETERS}, skip=(parameter,))
    head = f"{what} in {axis(parameter)}: " + ", ".join(p for p in parts if p)
    if width is None:
        return head + "\n" + ", ".join(main + other)
    from ...plots.figures import listed
    lines = textwrap.fill(listed(main + other), width, break_on_hyphens=False)
    return head + "\n" + lines.replace("\u00a0", " ")         # broken between items only


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
    # the range of the theory point by point (crankgen.analyses.theory; the mechanism's diagrams): |v|/L =
    # eps amplitude, and whether it exceeds theory.DEFLECTION_LIMIT (None for another map)
    deflection_over_L: np.ndarray = field(default=None, repr=False)
    beyond_theory: np.ndarray = field(default=None, repr=False)
    quantities: dict = field(default_factory=dict)   # name -> (n,): the orbits' physical quantities
    quantity_units: dict = field(default_factory=dict)   # name -> units (bifurcation/quantities.py)
    quantity_notes: list = field(default_factory=list)   # points whose quantities failed, and why

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
    multipliers: np.ndarray = field(default=None, repr=False)   # all of them (of P^period)
    parameter_name: str = ""       # the parameter continued
    case: object = field(default=None, repr=False)   # the mechanism's Case at the point (crankgen.follow)
    range: tuple = None            # the continuation's range of the parameter


@dataclass
class BifurcationDiagram:
    parameter_name: str
    branches: list
    special_points: list
    info: dict = field(default_factory=dict)   # the model and settings it was computed for

    @property
    def si(self):
        """The diagram in SI (bifurcation/si_view.py) of a continuation made with units="si"."""
        from .si_view import si_of
        return si_of(self)

    def si_view(self, si_mechanism):
        """The diagram in SI for the crankgen.SIMechanism whose dimensionless form it was computed for."""
        from .si_view import DiagramSI
        return DiagramSI(self, si_mechanism)

    @property
    def exact(self):
        """Whether the diagram is of the exact rod (its own limits, crankgen.analyses.theory)."""
        return (self.info or {}).get("approach") == "exact"

    def flag_range(self):
        """Set every branch's deflection_over_L and beyond_theory (a mechanism's diagram: eps known);
        for the exact rod beyond_theory by its own limits: eps, and the orbits' outer-fibre strain
        (the peak_strain quantity, when computed; the section rotation is not computed along
        branches)."""
        from ..theory import DEFLECTION_LIMIT, FIBRE_STRAIN_LIMIT, SLENDERNESS_LIMIT
        for br in self.branches:
            if len(br) and self.eps_at(br.parameter[0]) is not None:
                eps = np.array([self.eps_at(p) for p in br.parameter])
                br.deflection_over_L = np.abs(eps * br.amplitude)
                if self.exact:
                    strain = np.asarray((br.quantities or {}).get("peak_strain", np.full(len(br), np.nan)), float)
                    with np.errstate(invalid="ignore"):
                        br.beyond_theory = (eps > SLENDERNESS_LIMIT) | (strain > FIBRE_STRAIN_LIMIT)
                else:
                    br.beyond_theory = br.deflection_over_L > DEFLECTION_LIMIT

    @property
    def beyond_theory(self):
        """The RangeFlag (crankgen.analyses.theory) of the whole diagram: its largest |v|/L over every branch
        point (the axial strain is not computed along branches); for the exact rod its largest eps
        and outer-fibre strain (peak_strain) by its own limits; each branch's beyond_theory gives
        the points."""
        from ..theory import exact_range_flag, range_flag

        def largest(arrays):
            values = [float(np.nanmax(a)) for a in arrays if a is not None and len(a) and np.isfinite(a).any()]
            return max(values) if values else math.nan
        if self.exact:
            eps = largest([np.array([self.eps_at(p) for p in br.parameter]) for br in self.branches
                           if len(br) and self.eps_at(br.parameter[0]) is not None])
            strain = largest([np.asarray(br.quantities["peak_strain"], float) for br in self.branches
                              if "peak_strain" in (br.quantities or {})])
            return exact_range_flag(eps, strain)
        values = [np.max(br.deflection_over_L) for br in self.branches
                  if br.deflection_over_L is not None and len(br)]
        return range_flag(max(values) if values else math.nan)

    def eps_at(self, p):
        """The amplitude's unit (v* = v / r: the radius of gyration r) in L at parameter value p, the
        slenderness (None: not a mechanism diagram)."""
        values = dict(self.info, **{self.parameter_name: float(p)})
        return in_L("r", values) if schema.UNIT_PARAMETERS["r"] in values else None

    def orbit(self, branch, point):
        """The orbit of point `point` of branch `branch` of a mechanism's diagram, marched for its
        period from its stored state: a SimulationResult whose `animate` shows it.  A driven crank's
        point starts on the section of its crank angle (the DOF map's state there) and runs for its
        period's revolution times (to the nearest step)."""
        from dataclasses import replace

        from ...declaration.cases import Case
        from ...declaration.validation import integer
        from ...discrete.kinematics import step_period
        from ..section import CrankSection
        from ..simulation import simulate
        branch = integer("branch", branch, 0)
        if branch >= len(self.branches):
            raise ParameterError(f"branch must be below {len(self.branches)}, got {branch}")
        br = self.branches[branch]
        point = integer("point", point, 0)
        if point >= len(br):
            raise ParameterError(f"point must be below {len(br)} (the branch's points), got {point}")
        info = {k: v for k, v in self.info.items() if k in Case.__dataclass_fields__}
        case = replace(Case.from_dict(info), **{self.parameter_name: float(br.parameter[point])})
        state = np.asarray(br.states[point], dtype=float)     # (d, v), or (d, v, a) for generalized-alpha,
        if case.motion_record.coordinates:                    # a driven crank: its state on the section
            X, V, _ = CrankSection(case).full(state)
            period = br.period * float(br.quantities["revolution_time"][point])
            return simulate(case=case, initial=(X[0], V[0]), revolutions=period / step_period(case))
        parts = np.split(state, len(state) // (3 * case.n_elements))   # at theta0, crankgen's units
        return simulate(case=case, initial=parts, revolutions=br.period)

    def as_dict(self):
        """Everything the diagram holds, as JSON-ready data (diagram_files.py)."""
        return diagram_files.as_dict(self)

    @classmethod
    def from_dict(cls, data):
        return diagram_files.from_dict(data, (cls, Branch, SpecialPoint))

    def to_json(self, path):
        """The whole diagram (every point's parameter, amplitude, stability, multipliers, state,
        section samples and physical quantities; the special points; the model) as JSON;
        BifurcationDiagram.from_json reads it back."""
        return diagram_files.write_json(self, path)

    @classmethod
    def from_json(cls, path):
        return diagram_files.read_json(path, (cls, Branch, SpecialPoint))

    @classmethod
    def read_csv(cls, folder, info=None):
        """The diagram of the CSV files to_csv wrote in folder (info: the model, for the special
        points' Case; the CSV files do not hold it)."""
        return diagram_files.read_csv(folder, info, (cls, Branch, SpecialPoint))

    def to_csv(self, folder):
        """branches.csv (one row per point, with its branch's origin and stop_reason, why the
        branch ends; for the mechanism with deflection_over_L = eps
        amplitude and beyond_theory, crankgen.analyses.theory, and the orbits' physical quantities,
        bifurcation/quantities.py), special_points.csv, multipliers.csv (every multiplier of every
        point, long format) and states.csv (every point's section samples and state) in folder;
        returns the paths.  A number that does not exist is an empty field.
        BifurcationDiagram.read_csv reads them back."""
        from ..theory import beyond

        from ...results.io import output_folder
        paths = output_folder(folder, ["branches.csv", "special_points.csv", "multipliers.csv", "states.csv"])
        folder, paths = paths[0].parent, paths[:3]
        name = self.parameter_name
        flags = self.eps_at(self.branches[0].parameter[0]) is not None if self.branches else False
        quantities = list(dict.fromkeys(q for br in self.branches for q in br.quantities))

        def theory(p, amplitude, flag=None):
            x = abs(self.eps_at(p) * float(amplitude))
            if self.exact:                  # the exact rod's own limits (flag_range)
                return [cell(x), "" if flag is None else ("yes" if flag else "no")]
            return [cell(x), beyond(deflection=x)]
        with atomic_file(paths[0]) as fh:
            w = csv.writer(fh)
            w.writerow(["branch", "period", "point", name, "amplitude", "stable",
                        "max_abs_multiplier", "origin", "stop_reason"]
                       + (["deflection_over_L", "beyond_theory"] if flags else []) + quantities)
            for b, br in enumerate(self.branches):
                for i in range(len(br)):
                    w.writerow([b, br.period, i, cell(br.parameter[i]), cell(br.amplitude[i]),
                                int(br.stable[i]), cell(np.abs(br.multipliers[i]).max()), br.origin,
                                br.stop_reason]
                               + (theory(br.parameter[i], br.amplitude[i],
                                         None if br.beyond_theory is None else br.beyond_theory[i])
                                  if flags else [])
                               + [cell(br.quantities[q][i]) if q in br.quantities else "" for q in quantities])
        with atomic_file(paths[1]) as fh:
            w = csv.writer(fh)
            w.writerow(["kind", name, "amplitude", "period", "branch", "multiplier_re",
                        "multiplier_im", "multiplier_abs"]
                       + (["deflection_over_L", "beyond_theory"] if flags else []))
            for s in self.special_points:
                w.writerow([s.kind, cell(s.parameter), cell(s.amplitude), s.period, s.branch,
                            cell(s.multiplier.real), cell(s.multiplier.imag), cell(abs(s.multiplier))]
                           + (theory(s.parameter, s.amplitude) if flags else []))
        with atomic_file(paths[2]) as fh:
            w = csv.writer(fh)
            w.writerow(["branch", "point", name, "index", "re", "im", "abs"])
            for b, br in enumerate(self.branches):
                for i in range(len(br)):
                    for j, m in enumerate(br.multipliers[i]):
                        w.writerow([b, i, cell(br.parameter[i]), j, cell(m.real), cell(m.imag),
                                    cell(abs(m))])
        paths.append(diagram_files.write_states(self, folder / "states.csv"))
        return paths

    def plot(self, path, ax=None, title=None, ylabel=None, xlabel=None, sweep=None):
        """Amplitude against the parameter: stable solid, unstable dashed, one colour per period,
        special points marked and labelled (F fold, PD period doubling, NS Neimark-Sacker) where
        the label covers no curve; for the mechanism, the range beyond the theory (|v|/L > 0.1)
        shaded.  sweep: a PoincareDiagram (crankgen.poincare, up and down) whose marched
        amplitudes are drawn over the branches (the hysteresis a run-up and a run-down show).
        Axis labels and title default to what the diagram holds; the legend sits below the axes."""
        from matplotlib.lines import Line2D

        from ...plots.figures import beyond_patch, fit_panels, panels, place_labels
        from ..theory import DEFLECTION_LIMIT

        own = ax is None
        if own:
            from ...results.io import output_path
            path = output_path(path)
            fig, axes = panels(1, 1, width=7.5, height=4.2)
            ax = axes[0, 0]
        colors = {}
        for br in self.branches:
            c = colors.setdefault(br.period, PERIOD_COLORS.get(br.period, "0.4"))
            st = np.asarray(br.stable, dtype=bool)
            # draw stable and unstable runs, each run joined to the next point so no gap is left
            start = 0
            for i in range(1, len(br) + 1):
                if i == len(br) or st[i] != st[start]:
                    j = min(i + 1, len(br))
                    ax.plot(br.parameter[start:j], br.amplitude[start:j], color=c,
                            ls="-" if st[start] else "--", lw=1.6 if st[start] else 1.1)
                    start = i
        handles = [Line2D([], [], color=c, label=f"period {k}") for k, c in sorted(colors.items())]
        handles += [Line2D([], [], color="grey", ls="-", label="stable"),
                    Line2D([], [], color="grey", ls="--", label="unstable")]
        if sweep is not None:
            style = {"up": ("C0", "^", 18), "down": ("C3", "v", 18)}
            for d, (c, m, size) in style.items():
                pts = [q for q in sweep.points if q.direction == d and q.amplitude is not None]
                if pts:
                    ax.scatter([q.parameter for q in pts], [q.amplitude for q in pts], marker=m, s=size,
                               color=c, alpha=0.75, lw=0, zorder=4)
                    handles.append(Line2D([], [], ls="none", marker=m, color=c,
                                          label=f"marched, sweep {d}"))
        markers = {"fold": "s", "period-doubling": "o", "neimark-sacker": "D"}
        for kind, m in markers.items():
            pts = [s for s in self.special_points if s.kind == kind]
            if not pts:
                continue
            ax.scatter([s.parameter for s in pts], [s.amplitude for s in pts], marker=m, s=36,
                       facecolor="white", edgecolor="black", zorder=5)
            handles.append(Line2D([], [], ls="none", marker=m, markerfacecolor="white",
                                  color="black", label=f"{LABELS[kind]}: {kind}"))
        eps = self.eps_at(0.0) if self.parameter_name != schema.UNIT_PARAMETERS["r"] else None
        amps = [a for br in self.branches for a in np.asarray(br.amplitude, dtype=float) if np.isfinite(a)]
        if eps and amps and max(amps) * eps > DEFLECTION_LIMIT:
            lo, hi = ax.get_ylim()
            ax.axhspan(DEFLECTION_LIMIT / eps, max(hi, DEFLECTION_LIMIT / eps), color="0.88", lw=0, zorder=0)
            ax.set_ylim(lo, hi)
            handles.append(beyond_patch("0.88"))
        place_labels(ax, [(s.parameter, s.amplitude, f"{LABELS[s.kind]} {s.parameter:.4g}", "black")
                          for s in sorted(self.special_points, key=lambda s: s.parameter)])
        mech = self.eps_at(0.0) is not None
        ax.set_xlabel(xlabel or axis(self.parameter_name))
        ax.set_ylabel(ylabel or ("max |v*(1/2)| over the orbit" if mech else "amplitude"))
        ax.grid(alpha=0.3)
        leg = ax.legend(handles=handles, fontsize=8, loc="upper center", ncol=3, frameon=False,
                        bbox_to_anchor=(0.5, -0.16))
        leg._crankgen_outside = True
        ax.set_title(title or describe(self.info, "continuation", self.parameter_name, TITLE_WIDTH), fontsize=9)
        if own:
            save_figure(fit_panels(fig), path, dpi=130)
        return path
