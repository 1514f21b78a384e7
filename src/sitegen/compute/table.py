"""A table: one output over the stops of the sliders it depends on, as integers of its last digit."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Table:
    """One output over the stops of the sliders it depends on, as integers of its last digit."""

    output: str
    axes: tuple[int, ...]  # positions in the scene's sliders, in slider order
    shape: tuple[int, ...]
    quanta: np.ndarray  # int64, C order over `axes` (a row of `width` per point for a vector)
    decimals: int
    labels: tuple[str, ...] = ()  # for text outputs: quanta index these phrases
    width: int = 0  # 0 for a scalar output, else the (longest) vector length
    lengths: np.ndarray | None = None  # for a ragged vector: the length at each point
    special: str = ""  # how to show a SPECIAL quantum
    summed_axes: bool = False  # one index, the sum of the axes' stops (a function of, e.g., m1 + m2)
    raw: bool = False  # `quanta` holds the values themselves as doubles (a coordinate of an expression)
    # Shown to significant digits: the power of ten of each entry's last digit (value = quanta × 10**exponent)
    exponents: np.ndarray | None = None
    digits: int = 0

    def flat_index(self, stops: tuple[int, ...]) -> int:
        """Row of the table at a full slider position (one stop per scene slider)."""
        return int(self.flat_indices(np.asarray([stops], dtype=np.int64))[0])

    def flat_indices(self, stops: np.ndarray) -> np.ndarray:
        """Rows of the table at many slider positions (n × sliders)."""
        if not self.axes:
            return np.zeros(len(stops), dtype=np.int64)
        if self.summed_axes:
            return stops[:, list(self.axes)].sum(axis=1)
        return np.ravel_multi_index(tuple(stops[:, a] for a in self.axes), self.shape)

    def stored_values(self) -> int:
        """How many numbers the table ships."""
        return int(self.quanta.size)

    def value_range(self) -> tuple[float, float]:
        """Smallest and largest value the table holds (for a figure's axis limits)."""
        values = self.values()
        return float(values.min()), float(values.max())

    def values(self) -> np.ndarray:
        """Every entry as the number it shows (a double as stored for a raw table)."""
        if self.raw:
            return self.quanta.astype(float)
        if self.exponents is not None:
            return self.quanta * 10.0 ** self.exponents.astype(float)
        return self.quanta * 10.0**-self.decimals

    def at(self, stops: tuple[int, ...]):
        """The quantum (or, for a vector, the quanta) at a full slider position."""
        row = self.flat_index(stops)
        if not self.width:
            return int(self.quanta[row])
        values = self.quanta.reshape(-1, self.width)[row]
        return values[: self.lengths[row]] if self.lengths is not None else values

    def rows(self) -> list:
        """Every entry in order, vectors trimmed to their length (for the page's JSON)."""
        if not self.width:
            return self.quanta.tolist()
        matrix = self.quanta.reshape(-1, self.width).tolist()
        if self.lengths is None:
            return matrix
        return [row[:n] for row, n in zip(matrix, self.lengths.tolist())]


def grid_table(name: str, axes: tuple[int, ...], quanta: np.ndarray, decimals: int) -> Table:
    """A scalar table of quanta over the stops of `axes`, without the axes it is constant along."""
    kept, quanta = drop_constant_axes(axes, quanta)
    return Table(name, kept, quanta.shape, quanta.reshape(-1), decimals)


def drop_constant_axes(axes: tuple[int, ...], quanta: np.ndarray, *others: np.ndarray) -> tuple:
    """Remove the axes along which the displayed value never changes (checked at every stop).

    A declared dependency can vanish at display precision, e.g. the momentum after a collision
    equals the momentum before whatever the restitution; the page then needs no table along it.
    `others` (a ragged table's lengths, a mantissa's exponents) share the leading axes and must be
    constant along an axis too; returns the kept axes, then each array without the dropped ones.
    """
    arrays, kept = (quanta, *others), []
    for position, axis in reversed(list(enumerate(axes))):
        firsts = [array.take([0], axis=position) for array in arrays]
        if all(_constant_along(array, first, position) for array, first in zip(arrays, firsts)):
            arrays = tuple(first.squeeze(axis=position) for first in firsts)
        else:
            kept.append(axis)
    return (tuple(reversed(kept)), *arrays)


def _constant_along(array: np.ndarray, first: np.ndarray, position: int) -> bool:
    """Whether every slice of `array` along the axis at `position` equals `first`, its first slice."""
    if array.shape[position] > 1 and not np.array_equal(array[(slice(None),) * position + (slice(1, 2),)], first):
        return False  # most axes vary from their first stop to the next: no need to compare them all
    return np.array_equal(array, np.broadcast_to(first, array.shape))
