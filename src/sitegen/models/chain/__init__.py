"""The built-in model 'chain': Chain, and its figure."""

from __future__ import annotations

from .. import figures_when_asked
from .model import Chain

MODELS = {"chain": Chain}
# FIGURES, made when first asked for: a worker that only tabulates imports no figure
__getattr__ = figures_when_asked(__name__, chain="ChainFigure")
