"""The built-in model 'work': Work, and its figure."""

from __future__ import annotations

from .figure import WorkFigure
from .model import Work

MODELS = {"work": Work}
FIGURES = {"work": WorkFigure()}
