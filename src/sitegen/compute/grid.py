"""Slider grids with exact decimal stops."""
from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal

import numpy as np


@dataclass(frozen=True)
class Axis:
    """One slider's grid: `count` stops lo, lo + step, ... held exactly as decimals."""

    param: str
    lo: Decimal
    step: Decimal
    count: int

    @property
    def hi(self) -> Decimal:
        """The last stop."""
        return self.lo + self.step * (self.count - 1)

    @property
    def decimals(self) -> int:
        """Digits after the point needed to write every stop exactly."""
        return max(_decimals(self.lo), _decimals(self.step))

    def stop(self, index: int) -> Decimal:
        """The exact value of stop `index`."""
        return self.lo + self.step * index

    def values(self) -> np.ndarray:
        """Every stop as the nearest float (the same float an author's literal would give)."""
        return np.array([float(self.stop(i)) for i in range(self.count)])

    def index_of(self, value: Decimal) -> int | None:
        """The index of the stop equal to `value`, or None when it is off the grid."""
        k = (value - self.lo) / self.step
        return int(k) if k == k.to_integral_value() and 0 <= k < self.count else None


def _decimals(value: Decimal) -> int:
    return max(0, -value.normalize().as_tuple().exponent)
