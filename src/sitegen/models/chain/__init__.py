"""The built-in model 'chain': Chain, and its figure."""
from __future__ import annotations

from ...physics.chain import Chain
from ...render.figures.chain import ChainFigure
from ...site.report.chain import ChainReport

MODELS = {"chain": Chain}
FIGURES = {"chain": ChainFigure()}
REPORTS = {"chain": ChainReport()}  # the accuracy-report parts it declares
