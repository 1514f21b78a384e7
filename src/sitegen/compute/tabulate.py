"""Tabulation: each output evaluated over only the sliders it depends on, quantised for display."""
from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from ..errors import AuthorError
from .quantize import SPECIAL, quantize
from .scenes import ResolvedScene


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

    def flat_index(self, stops: tuple[int, ...]) -> int:
        """Row of the table at a full slider position (one stop per scene slider)."""
        return int(np.ravel_multi_index(tuple(stops[a] for a in self.axes), self.shape)) if self.axes else 0

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


def tabulate_scene(scene: ResolvedScene, names: list[str]) -> dict[str, Table]:
    """Evaluate the named outputs over their slider grids; fail on any non-finite value."""
    groups: dict[tuple[int, ...], list[str]] = defaultdict(list)
    for name in names:
        deps = scene.model.output(name).deps
        groups[tuple(i for i, a in enumerate(scene.axes) if a.param in deps)].append(name)
    tables: dict[str, Table] = {}
    for axes, group in sorted(groups.items()):
        tables.update(_tabulate_group(scene, axes, group))
    return {name: tables[name] for name in names}


def _tabulate_group(scene: ResolvedScene, axes: tuple[int, ...], names: list[str]) -> dict[str, Table]:
    inputs = scene.base_values()
    grids = np.meshgrid(*(scene.axes[i].values() for i in axes), indexing="ij")
    for i, grid in zip(axes, grids):
        inputs[scene.axes[i].param] = grid
    shape = tuple(scene.axes[i].count for i in axes)
    try:
        values = scene.model.evaluate(inputs, names, scene.effects)
    except (ValueError, ArithmeticError) as error:
        raise AuthorError(scene.spec.loc, f"model '{scene.model.name}' failed: {error}", scene.id) from None
    tables = {}
    for name in names:
        output = scene.model.output(name)
        array = np.broadcast_to(np.asarray(values[name], dtype=float), shape + ((output.size,) if output.size else ()))
        lengths = _ragged_lengths(scene, axes, output, array) if output.ragged else None
        if lengths is not None:
            array = np.nan_to_num(array, nan=0.0)  # the padding; the lengths say where rows end
        _require_finite(scene, axes, output, array)
        quanta = array.astype(np.int64) if output.is_text else quantize(array, output.decimals, special=bool(output.special))
        if lengths is not None:  # drop axes only where the lengths are constant too
            quanta = np.concatenate([quanta, lengths[..., None]], axis=-1)
        kept, quanta = _drop_constant_axes(axes, quanta)
        if lengths is not None:
            quanta, lengths = quanta[..., :-1], quanta[..., -1]
        grid = quanta.shape[: len(kept)]
        tables[name] = Table(
            name, kept, grid, quanta.reshape(-1), output.decimals, output.labels, output.size,
            None if lengths is None else lengths.reshape(-1), output.special,
        )
    return tables


def _ragged_lengths(scene: ResolvedScene, axes, output, array: np.ndarray) -> np.ndarray:
    """Length of each vector: its elements up to the first NaN, which must be padding to the end."""
    finite = ~np.isnan(array)
    lengths = finite.sum(axis=-1)
    padded_at_end = np.arange(output.size) < lengths[..., None]
    if not np.array_equal(finite, padded_at_end):
        bad = np.argwhere(~np.all(finite == padded_at_end, axis=-1))[0]
        raise AuthorError(scene.spec.loc, f"output '{output.name}' has NaN inside its values {_stop_text(scene, axes, bad)}", scene.id)
    return lengths


def _drop_constant_axes(axes: tuple[int, ...], quanta: np.ndarray) -> tuple[tuple[int, ...], np.ndarray]:
    """Remove the axes along which the displayed value never changes (checked at every stop).

    A declared dependency can vanish at display precision, e.g. the momentum after a collision
    equals the momentum before whatever the restitution; the page then needs no table along it.
    """
    kept = []
    for position, axis in reversed(list(enumerate(axes))):
        first = quanta.take([0], axis=position)
        if np.array_equal(quanta, np.broadcast_to(first, quanta.shape)):
            quanta = first.squeeze(axis=position)
        else:
            kept.append(axis)
    return tuple(reversed(kept)), quanta


def _require_finite(scene: ResolvedScene, axes: tuple[int, ...], output, array: np.ndarray) -> None:
    """Fail on a non-finite value, unless the output declares how the page shows it (not NaN)."""
    allowed = np.isinf(array) if output.special else np.zeros(array.shape, bool)
    bad = np.argwhere(~(np.isfinite(array) | allowed))
    if len(bad):
        raise AuthorError(
            scene.spec.loc,
            f"output '{output.name}' is not finite ({array[tuple(bad[0])]}) {_stop_text(scene, axes, bad[0])}; "
            "the model must return finite numbers",
            scene.id,
        )


def _stop_text(scene: ResolvedScene, axes: tuple[int, ...], index) -> str:
    stop = ", ".join(f"{scene.axes[a].param}={scene.axes[a].stop(int(k))}" for a, k in zip(axes, index))
    return f"at {stop}" if stop else "at the scene's fixed values"
