"""Slider grids: the exact stops of each control."""
from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal

import numpy as np

RANGE, LIST, CHOICE = "range", "list", "choice"


@dataclass(frozen=True)
class Axis:
    """One control's grid: its stops held exactly as decimals.

    kind "range": evenly spaced stops lo, lo + step, ...; "list": stops the author listed;
    "choice": a radio group, whose stops are codes of the model's choices and `labels` their names.
    """

    param: str
    stops: tuple[Decimal, ...]
    kind: str = RANGE
    labels: tuple[str, ...] = ()

    @classmethod
    def evenly(cls, param: str, lo: Decimal, step: Decimal, count: int) -> "Axis":
        """An evenly spaced grid of `count` stops."""
        return cls(param, tuple(lo + step * k for k in range(count)))

    @property
    def count(self) -> int:
        """Number of stops."""
        return len(self.stops)

    @property
    def lo(self) -> Decimal:
        """The first stop."""
        return self.stops[0]

    @property
    def hi(self) -> Decimal:
        """The last stop."""
        return self.stops[-1]

    @property
    def step(self) -> Decimal:
        """The spacing of an evenly spaced grid (1 for a list or choice, which step by index)."""
        return self.stops[1] - self.stops[0] if self.kind == RANGE and self.count > 1 else Decimal(1)

    @property
    def decimals(self) -> int:
        """Digits after the point needed to write every stop exactly."""
        return max(_decimals(s) for s in self.stops)

    def stop(self, index: int) -> Decimal:
        """The exact value of stop `index`."""
        return self.stops[index]

    def values(self) -> np.ndarray:
        """Every stop as the nearest float (the same float an author's literal would give)."""
        return np.array([float(s) for s in self.stops])

    def index_of(self, value: Decimal) -> int | None:
        """The index of the stop equal to `value`, or None when it is off the grid."""
        return next((i for i, s in enumerate(self.stops) if s == value), None)


def _decimals(value: Decimal) -> int:
    return max(0, -value.normalize().as_tuple().exponent)
