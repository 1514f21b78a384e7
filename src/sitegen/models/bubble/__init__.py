"""The built-in model 'bubble': Bubble, and its figures."""

from __future__ import annotations

from .figure import BubbleEventsFigure, BubbleFigure
from .model import Bubble
from .report import BubbleReport

MODELS = {"bubble": Bubble}
FIGURES = {"bubble": BubbleFigure(), "bubble_events": BubbleEventsFigure()}
REPORTS = {"bubble": BubbleReport()}  # the accuracy-report parts it declares
