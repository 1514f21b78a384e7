"""The built-in model 'impulse': Impulse, and its figure."""

from __future__ import annotations

from .. import figures_when_asked
from .model import Impulse

MODELS = {"impulse": Impulse}
# FIGURES, made when first asked for: a worker that only tabulates imports no figure
__getattr__ = figures_when_asked(__name__, impulse="ImpulseFigure")
