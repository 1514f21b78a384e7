"""The built-in model 'acoustic_energy': AcousticEnergy, and its figure."""

from __future__ import annotations

from .. import figures_when_asked
from .model import AcousticEnergy

MODELS = {"acoustic_energy": AcousticEnergy}
# FIGURES, made when first asked for: a worker that only tabulates imports no figure
__getattr__ = figures_when_asked(__name__, acoustic_energy="AcousticEnergyFigure")
