"""The built-in model 'lever': Lever, and its figure."""

from __future__ import annotations

from .figure import LeverFigure
from .model import Lever

MODELS = {"lever": Lever}
FIGURES = {"lever": LeverFigure()}
