"""What every figure view provides, and helpers for the ranges of its axes."""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from typing import Protocol

from ...compute.scenes import ResolvedScene
from ...compute.table import Table
from ...errors import did_you_mean
from ...physics.base import UnknownName
from ..layers import Layer
from ..style import laid_out
from ..svg import figure_svg


class FigureView(Protocol):
    """What a figure provides: a description, its layers, and its static background.

    `draw` makes the wide figure for a text column, and with `narrow=True` the one for a phone: the same axes
    in the same order (the layers are placed on them by number) at style.NARROW_WIDTH_IN, panels stacked.
    """

    label: str

    def layers(self, scene: ResolvedScene) -> list[Layer]: ...

    def draw(self, scene: ResolvedScene, tables: dict[str, Table], narrow: bool = False): ...


def figure_label(view: FigureView, scene: ResolvedScene) -> str:
    """The figure's description for screen readers: per scene when the view says what the scene's
    effects add (`describe(scene)`), else the view's label."""
    describe = getattr(view, "describe", None)
    return describe(scene) if describe else view.label


class SceneTables(Mapping):
    """The tables a figure's `draw` reads, by output: a name the scene has no table of is an error saying which
    it has (the outputs the scene shows: its readouts and what its layers read), not a bare KeyError."""

    def __init__(self, tables: Mapping[str, Table]):
        self._tables = tables

    def __getitem__(self, name: str) -> Table:
        if name not in self._tables:
            shown = sorted(n for n in self._tables if not n.startswith("~"))
            raise UnknownName(
                f"the scene has no table '{name}'{did_you_mean(name, shown)} Its tables (the outputs it shows: its "
                f"readouts and what its layers read): {', '.join(shown)}"
            )
        return self._tables[name]

    def __iter__(self):
        return iter(self._tables)

    def __len__(self) -> int:
        return len(self._tables)


def scene_figures(
    view: FigureView, scene: ResolvedScene, tables: dict[str, Table], layers: list[Layer], points: list, prefix: str
) -> list[str]:
    """The scene's figure as inline SVG: wide, then narrow (ids prefixed "<prefix>-narrow") when the view draws one."""
    label = figure_label(view, scene)
    tables = SceneTables(tables)
    svgs = [figure_svg(laid_out(view.draw(scene, tables)), layers, points, prefix, label)]
    if "narrow" in inspect.signature(view.draw).parameters:
        svgs.append(
            figure_svg(
                laid_out(view.draw(scene, tables, narrow=True)), layers, points, f"{prefix}-narrow", label, "narrow"
            )
        )
    return svgs


def param_range(scene: ResolvedScene, name: str) -> tuple[float, float]:
    """The smallest and largest value a parameter takes in the scene."""
    index = scene.axis_index(name)
    if index is None:
        values = scene.base_values()
        if name not in values:
            raise UnknownName(
                f"model '{scene.model.name}' has no parameter '{name}'{did_you_mean(name, values)} "
                f"Its parameters: {', '.join(values)}"
            )
        return values[name], values[name]
    axis = scene.axes[index]
    return float(axis.lo), float(axis.hi)


def table_range(table: Table) -> tuple[float, float]:
    """The smallest and largest value in a table, in display units."""
    return table.value_range()
