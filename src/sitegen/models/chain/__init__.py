"""The built-in model 'chain': Chain, and its figure."""

from __future__ import annotations

from .figure import ChainFigure
from .model import Chain
from .report import ChainReport

MODELS = {"chain": Chain}
FIGURES = {"chain": ChainFigure()}
REPORTS = {"chain": ChainReport()}  # the accuracy-report parts it declares
