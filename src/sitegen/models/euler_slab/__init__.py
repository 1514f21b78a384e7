"""The built-in model 'euler_slab': EulerSlab, and its figure."""

from __future__ import annotations

from .. import figures_when_asked
from .model import EulerSlab

MODELS = {"euler_slab": EulerSlab}
# FIGURES, made when first asked for: a worker that only tabulates imports no figure
__getattr__ = figures_when_asked(__name__, euler_slab="EulerSlabFigure")
