"""Stability charts: the curves of fold, period-doubling and Neimark-Sacker points in a plane of
two parameters, the regions between them named in words (compute, regions, record, plot)."""

from .compute import stability_chart
from .record import ChartLine, Region, StabilityChart

__all__ = ["ChartLine", "Region", "StabilityChart", "stability_chart"]
