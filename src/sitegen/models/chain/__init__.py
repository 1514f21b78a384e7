"""The built-in model 'chain': Chain, and its figure."""

from __future__ import annotations

from .figure import ChainFigure
from .model import Chain

MODELS = {"chain": Chain}
FIGURES = {"chain": ChainFigure()}
