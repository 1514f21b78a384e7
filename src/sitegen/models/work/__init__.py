"""The built-in model 'work': Work, and its figure."""
from __future__ import annotations

from .model import Work
from .figure import WorkFigure

MODELS = {"work": Work}
FIGURES = {"work": WorkFigure()}
