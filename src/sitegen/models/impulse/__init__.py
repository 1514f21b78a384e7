"""The built-in model 'impulse': Impulse, and its figure."""
from __future__ import annotations

from ...physics.impulse import Impulse
from ...render.figures.impulse import ImpulseFigure

MODELS = {"impulse": Impulse}
FIGURES = {"impulse": ImpulseFigure()}
