"""The built-in model 'bubble': Bubble, and its figures."""
from __future__ import annotations

from ...physics.bubble import Bubble
from ...render.figures.bubble import BubbleEventsFigure, BubbleFigure
from ...site.report.bubble import BubbleReport

MODELS = {"bubble": Bubble}
FIGURES = {"bubble": BubbleFigure(), "bubble_events": BubbleEventsFigure()}
REPORTS = {"bubble": BubbleReport()}  # the accuracy-report parts it declares
