"""The built-in model 'euler_slab': EulerSlab, and its figure."""
from __future__ import annotations

from ...physics.euler_slab import EulerSlab
from ...render.figures.euler_slab import EulerSlabFigure

MODELS = {"euler_slab": EulerSlab}
FIGURES = {"euler_slab": EulerSlabFigure()}
