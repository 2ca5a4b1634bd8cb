"""Figures (matplotlib on the Agg canvas, imported when a figure is drawn): runs, steady orbits,
sweeps, mode shapes, Campbell diagrams, and the animation of the mechanism."""
