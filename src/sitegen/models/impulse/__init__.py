"""The built-in model 'impulse': Impulse, and its figure."""

from __future__ import annotations

from .figure import ImpulseFigure
from .model import Impulse

MODELS = {"impulse": Impulse}
FIGURES = {"impulse": ImpulseFigure()}
