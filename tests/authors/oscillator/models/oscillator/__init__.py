"""One point of the basilar membrane: a driven, damped oscillator (model.py) and its figure (figure.py)."""

from .figure import OscillatorFigure
from .model import Oscillator

MODELS = {"oscillator": Oscillator}
FIGURES = {"oscillator": OscillatorFigure()}
