"""Selection of the generated element kernels for a formulation, approach and damping model."""

from dataclasses import dataclass
from typing import Callable, Optional

from ._generated import damping as _damping
from ._generated import lagrange as _lagrange
from ._generated import paper as _paper
from .validation import choice

FORMULATIONS = ("lagrange", "paper")
APPROACHES = ("A", "B", "C")
DAMPING_MODELS = ("paper", "kelvin-voigt")
MEMBRANE_OPTIONS = ("pointwise", "averaged")


@dataclass(frozen=True)
class ElementKernels:
    """The generated functions that make up one model's element equations."""

    formulation: str
    approach: str
    damping: str
    membrane: str
    rod_inertia: Callable          # (q, qd, qdd, l, x0, rhoA, rhoI, a, theta, ..., phidd) -> r, K, C, M
    slider_inertia: Callable       # (qs, qsd, qsdd, ms, L, a, theta, ..., phidd) -> r, K, C, M
    rod_elastic: Callable          # (q, l, EA, EI) -> r, K[, K_sec]
    rod_damping: Callable          # kelvin-voigt: (q, qd, l, EA, EI, mu); paper: (..., rhoA, rhoI, phid, mu)
    slider_damping: Optional[Callable]   # paper damping only: (qsd, ms, phid, mu) -> r, K, C

    @property
    def has_secant(self):
        """True when the formulation prints a secant stiffness (K_lin + K_non) for eq. (37)."""
        return self.formulation == "paper"


def select_kernels(formulation, approach, damping, membrane="pointwise"):
    """The kernels of a model.  membrane="averaged" uses the element-mean membrane strain (no
    membrane locking) wherever the strain enters: the lagrange elastic force and Kelvin-Voigt
    damping of approaches A and B (the printed matrices of the paper formulation stay as printed)."""
    choice("formulation", formulation, FORMULATIONS)
    choice("approach", approach, APPROACHES)
    choice("damping", damping, DAMPING_MODELS)
    choice("membrane", membrane, MEMBRANE_OPTIONS)
    module = _lagrange if formulation == "lagrange" else _paper
    suffix = "_averaged" if membrane == "averaged" and approach != "C" else ""
    if damping == "kelvin-voigt":
        rod_damping, slider_damping = getattr(_damping, f"kelvin_voigt_{approach}{suffix}"), None
    else:
        rod_damping, slider_damping = getattr(_damping, f"paper_{approach}"), _damping.paper_slider
    elastic_suffix = suffix if formulation == "lagrange" else ""
    return ElementKernels(
        formulation, approach, damping, membrane,
        rod_inertia=module.rod_inertia, slider_inertia=module.slider_inertia,
        rod_elastic=getattr(module, f"rod_elastic_{approach}{elastic_suffix}"),
        rod_damping=rod_damping, slider_damping=slider_damping,
    )
