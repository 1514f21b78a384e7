"""Figure views, one per file, and their registry."""
from __future__ import annotations

from .acoustic_energy import AcousticEnergyFigure
from .base import FigureView
from .bubble import BubbleEventsFigure, BubbleFigure
from .chain import ChainFigure
from .collision import CollisionFigure
from .euler_slab import EulerSlabFigure
from .impulse import ImpulseFigure
from .kinetic import KineticFigure
from .lever import LeverFigure
from .ossicles import OssiclesFigure
from .work import WorkFigure

FIGURES: dict[str, FigureView] = {
    "acoustic_energy": AcousticEnergyFigure(),
    "ossicles": OssiclesFigure(),
    "lever": LeverFigure(),
    "work": WorkFigure(),
    "impulse": ImpulseFigure(),
    "kinetic": KineticFigure(),
    "collision": CollisionFigure(),
    "euler_slab": EulerSlabFigure(),
    "chain": ChainFigure(),
    "bubble": BubbleFigure(),
    "bubble_events": BubbleEventsFigure(),
}

__all__ = ["FIGURES", "FigureView"]
