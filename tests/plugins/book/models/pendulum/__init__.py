"""The book's own model: a simple pendulum (model.py), its figure (figure.py) and a helper (swing_time.py)."""
from .figure import PendulumFigure
from .model import Pendulum

MODELS = {"pendulum": Pendulum}
FIGURES = {"pendulum": PendulumFigure()}
