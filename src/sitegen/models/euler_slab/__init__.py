"""The built-in model 'euler_slab': EulerSlab, and its figure."""

from __future__ import annotations

from .figure import EulerSlabFigure
from .model import EulerSlab

MODELS = {"euler_slab": EulerSlab}
FIGURES = {"euler_slab": EulerSlabFigure()}
