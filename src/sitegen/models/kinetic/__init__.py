"""The built-in model 'kinetic': Kinetic, and its figure."""
from __future__ import annotations

from ...physics.kinetic import Kinetic
from ...render.figures.kinetic import KineticFigure

MODELS = {"kinetic": Kinetic}
FIGURES = {"kinetic": KineticFigure()}
