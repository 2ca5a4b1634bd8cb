"""Stability charts: the curves of fold, period-doubling and Neimark-Sacker points in a plane of
two parameters, the regions between them named in words (compute, regions, record, plot).

The names are loaded on first use (PEP 562), so that the command line can read the default plane
(axes.py) without importing the engine."""

from importlib import import_module

_LAZY = {"stability_chart": "compute", "ChartLine": "record", "Region": "record", "StabilityChart": "record"}

__all__ = ["ChartLine", "Region", "StabilityChart", "stability_chart"]


def __getattr__(name):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(f".{_LAZY[name]}", __name__), name)
    globals()[name] = value
    return value
