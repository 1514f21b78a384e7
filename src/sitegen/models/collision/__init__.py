"""The built-in model 'collision': Collision, and its figure."""
from __future__ import annotations

from .model import Collision
from .figure import CollisionFigure

MODELS = {"collision": Collision}
FIGURES = {"collision": CollisionFigure()}
