"""The built-in model 'collision': Collision, and its figure."""
from __future__ import annotations

from ...physics.collision import Collision
from ...render.figures.collision import CollisionFigure

MODELS = {"collision": Collision}
FIGURES = {"collision": CollisionFigure()}
