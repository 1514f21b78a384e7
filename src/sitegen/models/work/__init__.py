"""The built-in model 'work': Work, and its figure."""
from __future__ import annotations

from ...physics.work import Work
from ...render.figures.work import WorkFigure

MODELS = {"work": Work}
FIGURES = {"work": WorkFigure()}
