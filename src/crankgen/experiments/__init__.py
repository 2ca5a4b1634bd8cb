"""`crankgen reproduce`: the paper's Figures 2-8 recomputed for the paper model and the consistent
model, with a findings summary computed from the runs (see runner.reproduce)."""

from .config import CONSISTENT, MODELS, PAPER, ReproduceConfig
from .runner import output_names, reproduce

__all__ = ["CONSISTENT", "MODELS", "PAPER", "ReproduceConfig", "output_names", "reproduce"]
