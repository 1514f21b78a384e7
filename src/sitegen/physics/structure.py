"""How an output is built from a few exact pieces instead of a value per slider stop.

A model declares, next to an output, the mathematical form it has (docs/physics/README.md): a
polynomial of known degree in some coordinates, a branch chosen by a threshold, a ratio. The
build turns the declaration into small tables (polynomial nodes, one coordinate table) and
verifies it against the model at sampled stops (in the check phase). These classes are pure mathematics: nothing here
knows about pages, tables or scripts.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

Kernel = Callable[[Mapping[str, np.ndarray]], np.ndarray]


@dataclass(frozen=True)
class Coord:
    """An interpolation coordinate: a parameter itself, or a function of parameters (e.g. 1/m,
    1/(m1 + m2)) whose value at each slider stop the build tabulates (as exact doubles, or
    rounded to `decimals` digits when given)."""

    name: str
    of: tuple[str, ...]
    fn: Callable[..., np.ndarray] | None = None  # fn(**params) -> values; None: the parameter itself
    decimals: int | None = None

    @property
    def is_param(self) -> bool:
        """Whether the coordinate is one parameter's own value."""
        return self.fn is None


def param(name: str) -> Coord:
    """The coordinate that is parameter `name` itself."""
    return Coord(name, (name,))


@dataclass(frozen=True)
class Poly:
    """A polynomial with the given degree in each coordinate (1 for each: multilinear).

    `kernel(values)` evaluates the same formula at any coordinate values (the nodes need not be
    physical states: w1 = 0 with m1 = 5 is fine for a polynomial identity); `values` holds the
    coordinates by name plus every other parameter at the scene's fixed value.
    """

    kernel: Kernel
    degrees: tuple[tuple[Coord, int], ...]
    size: int = 0  # a vector output's length (every component the same polynomial form)


@dataclass(frozen=True)
class Choose:
    """The value of one of `branches`, picked by an integer-valued piece (a choice parameter's
    index, a threshold, or another output's label)."""

    by: Piece
    branches: tuple[Piece, ...]


@dataclass(frozen=True)
class Threshold:
    """An index from comparing a value with increasing `edges`: the number of edges the value
    exceeds, mapped through `labels` (so a value equal to an edge counts as not above it)."""

    value: Piece
    edges: tuple[float, ...]
    labels: tuple[int, ...]


@dataclass(frozen=True)
class Ratio:
    """scale * numerator / denominator, and `when_zero` where the denominator is exactly 0."""

    numerator: Piece
    denominator: Piece
    scale: float = 1.0
    when_zero: float = 0.0


@dataclass(frozen=True)
class Log10:
    """scale * log10(value), e.g. a level in decibels of a ratio the other pieces give exactly."""

    value: Piece
    scale: float = 1.0


@dataclass(frozen=True)
class ChoiceOf:
    """The index of a choice parameter (e.g. force: spring = 0, drag = 1)."""

    name: str


@dataclass(frozen=True)
class OutputOf:
    """Another output of the same model, tabulated at every stop of its own dependencies (a pole or
    a branch that must not be interpolated)."""

    name: str


Piece = Poly | Choose | Threshold | Ratio | Log10 | ChoiceOf | OutputOf


def outputs_read(piece) -> set[str]:
    """The other outputs a piece reads at every stop (its OutputOf leaves)."""
    if isinstance(piece, OutputOf):
        return {piece.name}
    children = {
        Choose: lambda p: [p.by, *p.branches],
        Threshold: lambda p: [p.value],
        Log10: lambda p: [p.value],
        Ratio: lambda p: [p.numerator, p.denominator],
    }.get(type(piece), lambda p: [])(piece)
    return set().union(*(outputs_read(c) for c in children))
