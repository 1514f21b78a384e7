"""The built-in model 'lever': Lever, and its figure."""
from __future__ import annotations

from .model import Lever
from .figure import LeverFigure

MODELS = {"lever": Lever}
FIGURES = {"lever": LeverFigure()}
