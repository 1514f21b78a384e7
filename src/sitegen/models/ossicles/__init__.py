"""The built-in model 'ossicles': Ossicles, and its figure."""

from __future__ import annotations

from .figure import OssiclesFigure
from .model import Ossicles

MODELS = {"ossicles": Ossicles}
FIGURES = {"ossicles": OssiclesFigure()}
