"""Physics models (numpy/scipy only) and their registry."""
from __future__ import annotations

from .base import Model, Output, Param
from .collision import Collision
from .impulse import Impulse

MODELS: dict[str, type[Model]] = {
    "impulse": Impulse,
    "collision": Collision,
}

__all__ = ["MODELS", "Model", "Output", "Param"]
