"""The framework every model is written in (numpy/scipy only): the Model base class, parameters
and outputs, numerical settings and exact structures. The built-in models are in sitegen.models."""

from __future__ import annotations

from .base import Model, Output, Param

__all__ = ["Model", "Output", "Param"]
