"""Tabulation: each output evaluated over only the sliders it depends on, quantised for display."""
from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from ..errors import AuthorError
from .quantize import quantize
from .scenes import ResolvedScene


@dataclass(frozen=True)
class Table:
    """One output over the stops of the sliders it depends on, as integers of its last digit."""

    output: str
    axes: tuple[int, ...]  # positions in the scene's sliders, in slider order
    shape: tuple[int, ...]
    quanta: np.ndarray  # int64, C order over `axes`
    decimals: int
    labels: tuple[str, ...] = ()  # for text outputs: quanta index these phrases

    def at(self, stops: tuple[int, ...]) -> int:
        """The quantum at a full slider position (one stop per scene slider)."""
        if not self.axes:
            return int(self.quanta[0])
        return int(self.quanta[np.ravel_multi_index(tuple(stops[a] for a in self.axes), self.shape)])


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
        array = np.broadcast_to(np.asarray(values[name], dtype=float), shape)
        _require_finite(scene, axes, name, array)
        quanta = array.astype(np.int64) if output.is_text else quantize(array, output.decimals)
        kept, quanta = _drop_constant_axes(axes, quanta)
        tables[name] = Table(name, kept, quanta.shape, quanta.reshape(-1), output.decimals, output.labels)
    return tables


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


def _require_finite(scene: ResolvedScene, axes: tuple[int, ...], name: str, array: np.ndarray) -> None:
    bad = np.argwhere(~np.isfinite(array))
    if len(bad):
        stop = ", ".join(f"{scene.axes[a].param}={scene.axes[a].stop(int(k))}" for a, k in zip(axes, bad[0]))
        what = f"at {stop}" if stop else "at the scene's fixed values"
        raise AuthorError(
            scene.spec.loc,
            f"output '{name}' is not finite ({array[tuple(bad[0])]}) {what}; the model must return finite numbers",
            scene.id,
        )
