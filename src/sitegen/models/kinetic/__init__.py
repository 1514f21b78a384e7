"""The built-in model 'kinetic': Kinetic, and its figure."""

from __future__ import annotations

from .. import figures_when_asked
from .model import Kinetic

MODELS = {"kinetic": Kinetic}
# FIGURES, made when first asked for: a worker that only tabulates imports no figure
__getattr__ = figures_when_asked(__name__, kinetic="KineticFigure")
