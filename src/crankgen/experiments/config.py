"""What `crankgen reproduce` computes: the two models and the sweep settings (full, quick, tiny)."""

from dataclasses import asdict, dataclass, field, replace

import numpy as np

from ..declaration import schema


@dataclass(frozen=True)
class ModelSpec:
    """One of the two models every figure is computed for: a preset of the schema."""

    key: str            # the preset's name, used in CSV files and findings.md
    label: str          # for plot titles

    @property
    def options(self):
        return schema.resolve_options(self.key)

    @property
    def formulation(self):
        return self.options["formulation"]

    @property
    def damping(self):
        return self.options["damping"]

    @property
    def membrane(self):
        return self.options["membrane"]


PAPER = ModelSpec("paper", "paper model (printed form, eq. 24 damping)")
# The consistent model uses the element-mean membrane strain: the plain element locks (audit §6:
# with Kelvin-Voigt damping it needs ~128 elements for 1 % at Omega* = 0.8, the averaged one 4).
CONSISTENT = ModelSpec("consistent", "consistent model (Lagrange, Kelvin-Voigt, averaged membrane)")
MODELS = (PAPER, CONSISTENT)
# The geometrically exact rod (issue 26), set beside the two models where it changes the reading:
# the amplitude sweeps of Figures 5 and 6 (its own rows, with the consistent model's element
# count for A) and the exact-rod continuation (exact_rod.py).  Not one of MODELS: the figures'
# panels, approaches and claims stay those of the paper's two models.
EXACT = ModelSpec("exact", "exact rod (exact stretch, curvature and section rotation)")
APPROACHES = ("A", "B", "C")
FIGURES = (2, 3, 4, 5, 6, 7, 8)


def _speeds(start, stop, step):
    n = int(round((stop - start) / step))
    return tuple(float(x) for x in np.round(start + step * np.arange(n + 1), 10))


@dataclass(frozen=True)
class ReproduceConfig:
    """Every setting of a reproduction run.  `full()` is the default, `quick()` a coarse pass,
    `tiny()` a seconds-long smoke configuration (tests)."""

    preset: str = "full"
    # mechanism (the paper's common settings, unless a figure varies them)
    a: float = 0.1
    eps: float = 0.01
    ms: float = 0.5
    mu: float = 0.5
    steps_per_rev: int = 100
    dpi: int = 120                       # resolution of the PNG figures
    # the paper's element counts (Figures 4-8); a model never uses fewer than these
    paper_elements: dict = field(default_factory=lambda: {"A": 16, "B": 4, "C": 4})
    # element-count convergence check: ladder of counts, speeds, relative tolerance
    conv_ladder: tuple = (2, 4, 8, 16, 32, 64)
    conv_omegas: tuple = (0.1, 0.8)
    conv_tol: float = 0.01
    # a-posteriori refinement check: the Figure 6 cases at these speeds, with 2 n elements
    refine_omegas: tuple = (0.4, 1.2, 1.6)
    refine_fig5: bool = True             # also the Figure 5 speeds at its smallest eps
    # Figure 2: transient at low speed, element counts compared
    fig2_omega: float = 0.1
    fig2_elements: tuple = (2, 4)
    fig2_revolutions: float = 3
    # Figure 3: convergence of A (transient), and time step halved at the finest count
    fig3_omega: float = 0.8
    fig3_elements: tuple = (2, 4, 8, 16)
    fig3_steps: tuple = (100, 200)
    fig3_revolutions: float = 8
    # Figure 4: transient at high speed, and slider masses for B and C
    fig4_omega: float = 0.8
    fig4_revolutions: float = 8
    fig4_ms: tuple = (0.0, 0.5, 1.0, 2.0)
    # Figure 5: steady amplitude against eps at two speeds
    fig5_omegas: tuple = (0.1, 0.8)
    fig5_eps: tuple = (0.005, 0.0075, 0.01, 0.015, 0.02, 0.03, 0.04, 0.05, 0.07, 0.1)
    # Figure 6: steady amplitude against Omega* at two slendernesses
    fig6_omegas: tuple = _speeds(0.05, 1.6, 0.05)
    fig6_eps: tuple = (0.01, 0.1)
    fig6_inset_ylim: float = 1.4
    # Figures 7 and 8: extension over one steady revolution for several slider masses
    fig7_omega: float = 0.8
    fig8_omega: float = 0.1
    ext_ms: tuple = (0.0, 0.5, 1.0, 2.0)
    # cases without a stable periodic state (Figures 5, 6): transient from zero initial conditions,
    # max |v*| over the last `envelope_window` of `envelope_revolutions` revolutions (0: skip)
    envelope_revolutions: int = 80
    envelope_window: int = 10
    # bifurcations of approach A (bifurcations.py): crankgen.continuation over Omega* in bif_range
    # for both models at every eps of Figure 6, with bif_elements elements (None: the count the
    # run uses for A) and bif_steps_per_rev steps (None: steps_per_rev), period-doubling branches
    # followed up to bif_max_period, no step longer than bif_dp_max in Omega*, points converged to
    # bif_tol (the continuation's corrector tolerance); then a Poincare
    # sweep up over bif_beyond_values speeds above the last special point (bif_transient
    # revolutions from the previous speed's state, then bif_samples sampled ones)
    bif_range: tuple = (0.1, 1.6)
    bif_elements: object = None
    bif_steps_per_rev: object = None
    bif_max_period: int = 4
    bif_dp_max: float = 0.1
    bif_tol: float = 1e-9
    bif_beyond_values: int = 4
    bif_transient: int = 100
    bif_samples: int = 32
    # the exact rod beside the two models in Figures 5 and 6 (rows of model "exact"), with
    # exact_row_elements elements (None: the consistent model's count for A)
    exact_rows: bool = True
    exact_row_elements: object = None
    # the continuation of the exact rod and of the consistent model (exact_rod.py): the
    # slider-crank and the four-bar (a rocker of radius exact_rocker pivoted at (1, 0)) at eps =
    # exact_eps over Omega* in exact_range, exact_elements elements, exact_steps steps per
    # revolution, period doublings followed up to exact_max_period, steps of at most exact_dp_max in
    # Omega* (exact_mechanisms: which)
    exact_mechanisms: tuple = ("slider-crank", "four-bar")
    exact_eps: float = 0.01
    exact_range: tuple = (0.2, 1.6)
    exact_elements: int = 16
    exact_steps: int = 100
    exact_max_period: int = 2
    exact_dp_max: object = None          # no step longer than this in Omega* (None: the range / 50)
    exact_rocker: float = 0.5
    exact_tol: float = 1e-9
    # a consistent special point and an exact one of the same kind and period within exact_match
    # in Omega* are the same point, moved; then both models marched from rest at exact_snap_omega
    # for exact_snap_revolutions revolutions (the snap-through orbit; 0: skip)
    exact_match: float = 0.1
    exact_snap_omega: float = 1.2
    exact_snap_revolutions: int = 30
    # the exact rod's response at exact_character_omegas on each mechanism (crankgen.poincare swept
    # up, the first from rest: exact_character_transient revolutions, then exact_character_samples
    # sampled, classified with the largest Lyapunov exponent; (): skip)
    # at exact_character_steps steps per revolution (None: exact_steps; near the period doubling at
    # 1.18 the continuation's 100 steps put rest in another basin than 200 and 400 do)
    exact_character_omegas: tuple = (1.2,)
    exact_character_transient: int = 200
    exact_character_samples: int = 64
    exact_character_steps: object = 200
    # thresholds of the findings
    differ_threshold: float = 0.10       # "B or C differs from A by more than 10 %"
    crossing_rel_tol: float = 0.05       # extension spread at a common crossing / largest spread
    agree_tol: float = 0.01              # models "agree" when relative differences are below this
    # extra keyword arguments for crankgen.analyses.steady.steady_states (e.g. max_revolutions)
    steady_options: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.eps not in self.fig5_eps:
            raise ValueError("fig5_eps must contain the base eps (the ratio table reads it)")
        if len(self.conv_ladder) < 2 or list(self.conv_ladder) != sorted(set(self.conv_ladder)):
            raise ValueError("conv_ladder must hold at least two increasing element counts")
        if len(self.bif_range) != 2 or not 0 < self.bif_range[0] < self.bif_range[1]:
            raise ValueError("bif_range must be (start, stop) with 0 < start < stop")

    @classmethod
    def full(cls):
        return cls()

    @classmethod
    def quick(cls):
        """Coarse pass: fewer speeds, eps values and revolutions; ladder up to 64 elements."""
        return cls(
            preset="quick", dpi=90, conv_ladder=(2, 4, 8, 16, 32, 64), refine_omegas=(), refine_fig5=False,
            fig2_revolutions=2, fig3_revolutions=4, fig3_elements=(2, 4, 8, 16),
            fig4_revolutions=4, fig4_ms=(0.0, 0.5, 2.0),
            fig5_eps=(0.005, 0.01, 0.03, 0.1),
            fig6_omegas=_speeds(0.2, 1.6, 0.2),
            ext_ms=(0.0, 0.5, 2.0), envelope_revolutions=20, envelope_window=5,
            bif_elements=4, bif_steps_per_rev=50, bif_max_period=2, bif_tol=1e-7,
            bif_beyond_values=2, bif_transient=60, bif_samples=16,
            exact_row_elements=8, exact_elements=4, exact_steps=50, exact_tol=1e-7, exact_snap_revolutions=12,
            exact_range=(0.1, 1.6), exact_dp_max=0.1, exact_character_transient=60, exact_character_samples=32,
            exact_character_steps=None,
            steady_options={"max_revolutions": 50, "tol": 1e-6})

    @classmethod
    def tiny(cls):
        """Seconds-long smoke configuration through the same code path (tests)."""
        return cls(
            preset="tiny", paper_elements={"A": 2, "B": 1, "C": 1}, conv_ladder=(1, 2),
            conv_omegas=(0.8,), refine_omegas=(1.2,), fig2_elements=(1,), fig2_revolutions=0.5,
            fig3_elements=(1, 2), fig3_steps=(100, 200), fig3_revolutions=0.5,
            fig4_revolutions=0.5, fig4_ms=(0.0, 1.0), fig5_omegas=(0.1, 0.8),
            fig5_eps=(0.01, 0.05), fig6_omegas=(0.4, 0.8, 1.2), fig6_eps=(0.01,),
            ext_ms=(0.0, 1.0), envelope_revolutions=4, envelope_window=1,
            bif_range=(0.9, 1.3), bif_elements=4, bif_steps_per_rev=50, bif_max_period=2,
            bif_beyond_values=2, bif_transient=20, bif_samples=8,
            exact_mechanisms=("slider-crank",), exact_range=(0.9, 1.2), exact_elements=4, exact_steps=50,
            exact_tol=1e-7, exact_snap_revolutions=2, exact_character_transient=4,
            exact_character_samples=4, exact_character_steps=None, steady_options={"max_revolutions": 20})

    @classmethod
    def preset_named(cls, name):
        return {"full": cls.full, "quick": cls.quick, "tiny": cls.tiny}[name]()

    def with_(self, **changes):
        return replace(self, **changes)

    def as_dict(self):
        return asdict(self)
