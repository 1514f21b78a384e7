"""The built-in model 'euler_slab': EulerSlab, and its figure."""
from __future__ import annotations

from .model import EulerSlab
from .figure import EulerSlabFigure

MODELS = {"euler_slab": EulerSlab}
FIGURES = {"euler_slab": EulerSlabFigure()}
