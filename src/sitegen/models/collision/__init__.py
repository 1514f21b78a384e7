"""The built-in model 'collision': Collision, and its figure."""

from __future__ import annotations

from .figure import CollisionFigure
from .model import Collision

MODELS = {"collision": Collision}
FIGURES = {"collision": CollisionFigure()}
