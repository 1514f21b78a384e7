"""The built-in model 'acoustic_energy': AcousticEnergy, and its figure."""
from __future__ import annotations

from ...physics.acoustic_energy import AcousticEnergy
from ...render.figures.acoustic_energy import AcousticEnergyFigure

MODELS = {"acoustic_energy": AcousticEnergy}
FIGURES = {"acoustic_energy": AcousticEnergyFigure()}
