"""The book's own model: a pendulum swinging at any amplitude (model.py) and its figure (figure.py).

sitegen finds this plugin because it is a folder in the book's models/: it reads the two dicts below."""
from .figure import PendulumFigure
from .model import Pendulum

MODELS = {"pendulum": Pendulum}
FIGURES = {"pendulum": PendulumFigure()}
