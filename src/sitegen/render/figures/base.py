"""What every figure view provides, and helpers for the ranges of its axes."""

from __future__ import annotations

import inspect
from typing import Protocol

from ...compute.scenes import ResolvedScene
from ...compute.table import Table
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


def scene_figures(
    view: FigureView, scene: ResolvedScene, tables: dict[str, Table], layers: list[Layer], points: list, prefix: str
) -> list[str]:
    """The scene's figure as inline SVG: wide, then narrow (ids prefixed "<prefix>-narrow") when the view draws one."""
    label = figure_label(view, scene)
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
        value = scene.base_values()[name]
        return value, value
    axis = scene.axes[index]
    return float(axis.lo), float(axis.hi)


def table_range(table: Table) -> tuple[float, float]:
    """The smallest and largest value in a table, in display units."""
    return table.value_range()
