"""Slider grids: the exact stops of each control."""

from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction
from functools import cached_property

import numpy as np

RANGE, LIST, CHOICE = "range", "list", "choice"


@dataclass(frozen=True)
class Axis:
    """One control's grid: its stops held exactly, as decimals (or fractions, for a step like 1/60).

    kind "range": evenly spaced stops lo, lo + step, ...; "list": stops the author listed, or evenly
    spaced by a fraction no decimal holds (the page steps through both by index); "choice": a radio
    group, whose stops are codes of the model's choices and `labels` their names.
    """

    param: str
    stops: tuple[Decimal | Fraction, ...]
    kind: str = RANGE
    labels: tuple[str, ...] = ()

    @classmethod
    def evenly(cls, param: str, lo: Decimal, step: Decimal | Fraction, count: int) -> Axis:
        """An evenly spaced grid of `count` stops (listed when the step is a fraction such as 1/60)."""
        if isinstance(step, Fraction) and isinstance(as_decimal(step), Fraction):
            return cls(param, tuple(as_decimal(Fraction(lo) + step * k) for k in range(count)), LIST)
        step = as_decimal(step)
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

    @cached_property
    def decimals(self) -> int:
        """Digits after the point needed to write every stop exactly, or, when a stop such as 1/60
        has no finite decimal, the fewest that still tell every stop apart."""
        exact = max((_decimals(s) for s in self.stops if isinstance(s, Decimal)), default=0)
        if not self.has_fractions:
            return exact
        digits = exact
        while len({self._rounded(k, digits) for k in range(self.count)}) < self.count:
            digits += 1
        return digits

    @property
    def has_fractions(self) -> bool:
        """Whether some stop has no finite decimal (a step such as 1/60): the stops are then shown rounded."""
        return any(isinstance(s, Fraction) for s in self.stops)

    def quantum(self, index: int) -> int:
        """Stop `index` in units of its last shown digit, rounded half away from zero."""
        return self._rounded(index, self.decimals)

    def _rounded(self, index: int, digits: int) -> int:
        scaled = Fraction(self.stops[index]) * 10**digits
        magnitude = int(abs(scaled) + Fraction(1, 2))
        return -magnitude if scaled < 0 else magnitude

    def stop(self, index: int) -> Decimal:
        """The exact value of stop `index`."""
        return self.stops[index]

    def values(self) -> np.ndarray:
        """Every stop as the nearest float (the same float an author's literal would give)."""
        return np.array([float(s) for s in self.stops])

    def index_of(self, value: Decimal) -> int | None:
        """The index of the stop equal to `value`, or None when it is off the grid."""
        return next((i for i, s in enumerate(self.stops) if s == value), None)


def as_decimal(value: Decimal | Fraction) -> Decimal | Fraction:
    """A fraction as a decimal when one holds it exactly (so 1/2 reads 0.5 and keys stay as before)."""
    if isinstance(value, Decimal):
        return value
    denominator = value.denominator
    for prime in (2, 5):
        while denominator % prime == 0:
            denominator //= prime
    return Decimal(value.numerator) / Decimal(value.denominator) if denominator == 1 else value


def _decimals(value: Decimal) -> int:
    return max(0, -value.normalize().as_tuple().exponent)
