"""Figures: a static matplotlib SVG background plus moving layers stored as data."""
