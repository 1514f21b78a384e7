"""The book's own model: a pendulum whose period comes from an ODE solver (model.py), and its figure."""

from .figure import SwingFigure
from .model import Pendulum

MODELS = {"pendulum": Pendulum}
FIGURES = {"pendulum": SwingFigure()}
