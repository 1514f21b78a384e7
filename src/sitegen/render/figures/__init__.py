"""What a figure view provides (base.py); the built-in views live with their models in sitegen.models."""

from __future__ import annotations

from .base import FigureView

__all__ = ["FigureView"]
