"""The built-in model 'lever': Lever, and its figure."""
from __future__ import annotations

from ...physics.lever import Lever
from ...render.figures.lever import LeverFigure

MODELS = {"lever": Lever}
FIGURES = {"lever": LeverFigure()}
