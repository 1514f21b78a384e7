"""The built-in model 'ossicles': Ossicles, and its figure."""
from __future__ import annotations

from ...physics.ossicles import Ossicles
from ...render.figures.ossicles import OssiclesFigure

MODELS = {"ossicles": Ossicles}
FIGURES = {"ossicles": OssiclesFigure()}
