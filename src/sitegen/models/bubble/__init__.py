"""The built-in model 'bubble': Bubble, and its figures."""

from __future__ import annotations

from .figure import BubbleEventsFigure, BubbleFigure
from .model import Bubble

MODELS = {"bubble": Bubble}
FIGURES = {"bubble": BubbleFigure(), "bubble_events": BubbleEventsFigure()}
