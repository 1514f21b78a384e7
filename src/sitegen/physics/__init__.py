"""Physics models (numpy/scipy only) and their registry."""
from __future__ import annotations

from .acoustic_energy import AcousticEnergy
from .base import Model, Output, Param
from .bubble import Bubble
from .chain import Chain
from .collision import Collision
from .euler_slab import EulerSlab
from .impulse import Impulse
from .kinetic import Kinetic
from .lever import Lever
from .ossicles import Ossicles
from .work import Work

MODELS: dict[str, type[Model]] = {
    "acoustic_energy": AcousticEnergy,
    "ossicles": Ossicles,
    "lever": Lever,
    "work": Work,
    "impulse": Impulse,
    "kinetic": Kinetic,
    "collision": Collision,
    "euler_slab": EulerSlab,
    "chain": Chain,
    "bubble": Bubble,
}

__all__ = ["MODELS", "Model", "Output", "Param"]
