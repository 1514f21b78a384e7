"""The period of a pendulum's small swings."""
import numpy as np


def period(length, gravity):
    """T = 2π √(L/g)."""
    return 2 * np.pi * np.sqrt(length / gravity)
