"""The built-in model 'bubble': Bubble, and its figures."""

from __future__ import annotations

from .. import figures_when_asked
from .model import Bubble

MODELS = {"bubble": Bubble}
# FIGURES, made when first asked for: a worker that only tabulates imports no figure
__getattr__ = figures_when_asked(__name__, bubble="BubbleFigure", bubble_events="BubbleEventsFigure")
