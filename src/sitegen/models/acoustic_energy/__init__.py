"""The built-in model 'acoustic_energy': AcousticEnergy, and its figure."""

from __future__ import annotations

from .figure import AcousticEnergyFigure
from .model import AcousticEnergy

MODELS = {"acoustic_energy": AcousticEnergy}
FIGURES = {"acoustic_energy": AcousticEnergyFigure()}
