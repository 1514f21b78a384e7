"""Figure views, one per file, and their registry."""
from __future__ import annotations

from .base import FigureView
from .collision import CollisionFigure
from .impulse import ImpulseFigure

FIGURES: dict[str, FigureView] = {
    "impulse": ImpulseFigure(),
    "collision": CollisionFigure(),
}

__all__ = ["FIGURES", "FigureView"]
