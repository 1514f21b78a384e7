"""Axes, tabulation of model outputs over slider grids, and display quantisation."""
