"""The built-in model 'ossicles': Ossicles, and its figure."""
from __future__ import annotations

from .model import Ossicles
from .figure import OssiclesFigure

MODELS = {"ossicles": Ossicles}
FIGURES = {"ossicles": OssiclesFigure()}
