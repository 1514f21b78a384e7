"""The built-in model 'kinetic': Kinetic, and its figure."""

from __future__ import annotations

from .figure import KineticFigure
from .model import Kinetic

MODELS = {"kinetic": Kinetic}
FIGURES = {"kinetic": KineticFigure()}
