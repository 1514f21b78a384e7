"""The built-in model 'acoustic_energy': AcousticEnergy, and its figure."""
from __future__ import annotations

from .model import AcousticEnergy
from .figure import AcousticEnergyFigure

MODELS = {"acoustic_energy": AcousticEnergy}
FIGURES = {"acoustic_energy": AcousticEnergyFigure()}
