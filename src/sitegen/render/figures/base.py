"""What every figure view provides, and helpers for the ranges of its axes."""
from __future__ import annotations

from typing import Protocol

from ...compute.scenes import ResolvedScene
from ...compute.table import Table
from ..layers import Layer


class FigureView(Protocol):
    """What a figure provides: a description, its layers, and its static background."""

    label: str

    def layers(self, scene: ResolvedScene) -> list[Layer]: ...

    def draw(self, scene: ResolvedScene, tables: dict[str, Table]): ...


def figure_label(view: FigureView, scene: ResolvedScene) -> str:
    """The figure's description for screen readers: per scene when the view says what the scene's
    effects add (`describe(scene)`), else the view's label."""
    describe = getattr(view, "describe", None)
    return describe(scene) if describe else view.label


def param_range(scene: ResolvedScene, name: str) -> tuple[float, float]:
    """The smallest and largest value a parameter takes in the scene."""
    index = scene.axis_index(name)
    if index is None:
        value = scene.base_values()[name]
        return value, value
    axis = scene.axes[index]
    return float(axis.lo), float(axis.hi)


def table_range(table: Table) -> tuple[float, float]:
    """The smallest and largest value in a table, in display units."""
    return table.value_range()
