"""The built-in model 'impulse': Impulse, and its figure."""
from __future__ import annotations

from .model import Impulse
from .figure import ImpulseFigure

MODELS = {"impulse": Impulse}
FIGURES = {"impulse": ImpulseFigure()}
