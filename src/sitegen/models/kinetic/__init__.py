"""The built-in model 'kinetic': Kinetic, and its figure."""
from __future__ import annotations

from .model import Kinetic
from .figure import KineticFigure

MODELS = {"kinetic": Kinetic}
FIGURES = {"kinetic": KineticFigure()}
