"""I4: the bar on its fulcrum, leaning towards the side that wins, with the balance point marked."""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ...render import style as s
from ...render.figures.base import table_range
from ...render.layers import Layer
from .mechanics import LENGTH
from .model import DRAWN_SLOPE

GROUND = -0.30  # the fulcrum stands on the ground; the pivot is at height 0
ARM_LINE = -0.42  # height of the dimension lines of the arms L_L and L_R
ARM_TICK = 0.035  # half-height of their end ticks
MARKER_HEIGHT = 0.07  # of the balance-point marker's triangle
LABEL_GAP = 0.07  # between the highest block top and the mass labels
BALANCE_LINE_TOP = DRAWN_SLOPE * LENGTH + 0.06  # the dashed line crosses the bar at every tilt
FILL_ORANGE = "#f2c2a6"  # the orange of render/style.py, lightened like FILL_BLUE


class LeverFigure:
    """The bar on its fulcrum, the two masses, their arms and the balance point."""

    label = (
        "A bar with a block at each end rests on a triangular fulcrum at the pivot position. The block sizes grow "
        "with their masses; the bar leans towards the side whose torque wins and lies level when balanced. "
        "A dashed line and a small triangle mark the balance point x*, where the pivot would balance the bar; "
        "the arms L_L and L_R are drawn below the ground."
    )

    def layers(self, scene):
        out = _output_names(scene)
        dashed = {"fill": "none", "stroke": s.MUTED, "stroke-width": "1.3", "stroke-dasharray": "5 4"}
        return [
            Layer(
                "balance-line",
                "polyline",
                0,
                ((out["x_star"], GROUND), (out["x_star"], BALANCE_LINE_TOP)),
                style=dashed,
            ),
            Layer(
                "fulcrum",
                "polygon",
                0,
                (("out:fulcrum_x0", GROUND), ("in:x_p", 0.0), ("out:fulcrum_x1", GROUND)),
                style={"fill": s.LOST, "stroke": s.INK, "stroke-width": "1.4"},
            ),
            # over the fulcrum, so it stays visible when the pivot is near the balance point
            Layer(
                "balance-marker",
                "polygon",
                0,
                ((out["marker_x0"], GROUND), (out["x_star"], GROUND + MARKER_HEIGHT), (out["marker_x1"], GROUND)),
                style={"fill": s.MUTED, "stroke": "none"},
            ),
            Layer(
                "left-block",
                "polygon",
                0,
                _block("left", out),
                style={"fill": s.FILL_BLUE, "stroke": s.BLUE, "stroke-width": "1.6"},
            ),
            Layer(
                "right-block",
                "polygon",
                0,
                _block("right", out),
                style={"fill": FILL_ORANGE, "stroke": s.ORANGE, "stroke-width": "1.6"},
            ),
            Layer(
                "bar",
                "polyline",
                0,
                ((0.0, out["y_left"]), (LENGTH, out["y_right"])),
                style={"fill": "none", "stroke": s.INK, "stroke-width": "5"},
            ),
            Layer("pivot", "dots", 0, (("in:x_p", 0.0),), style={"stroke": "#ffffff", "stroke-width": "2.5"}),
            Layer(
                "arm-left",
                "polyline",
                0,
                _dimension(0.0, "in:x_p"),
                style={"fill": "none", "stroke": s.BLUE, "stroke-width": "1.5"},
            ),
            Layer(
                "arm-right",
                "polyline",
                0,
                _dimension("in:x_p", LENGTH),
                style={"fill": "none", "stroke": s.ORANGE, "stroke-width": "1.5"},
            ),
        ]

    def draw(self, scene, tables, narrow=False):
        fig, (ax,) = s.new_figure(2.9 if narrow else 3.3, narrow=narrow)
        top = _top(scene, tables)
        bottom = ARM_LINE - 0.08
        ax.set_xlim(table_range(tables["left_block_x0"])[0] - 0.12, table_range(tables["right_block_x1"])[1] + 0.12)
        ax.set_ylim(bottom, top + 0.16)  # provisional, so that the layout sees the labels inside
        ax.grid(False)
        ax.spines["left"].set_visible(False)
        ax.set_yticks([])
        ax.set_xticks([0.0, 0.5, 1.0, 1.5, 2.0])
        ax.set_xlabel("position along the bar x (m)")
        _label_masses_and_arms(ax, top)
        _legend(ax, columns=1 if narrow else 2)
        fig.tight_layout(pad=0.4)
        _equal_aspect(ax, bottom, top + 0.16)
        _ground(ax, *ax.get_xlim())
        return fig


def _label_masses_and_arms(ax, top: float) -> None:
    """Names over the blocks (their x never changes) and beside the ends of the arms' dimension lines."""
    ax.text(0.0, top, "m$_L$", ha="center", va="bottom", color=s.BLUE, fontsize=11)
    ax.text(LENGTH, top, "m$_R$", ha="center", va="bottom", color=s.ORANGE, fontsize=11)
    ax.text(-0.04, ARM_LINE, "L$_L$", ha="right", va="center", color=s.BLUE, fontsize=10)
    ax.text(LENGTH + 0.04, ARM_LINE, "L$_R$", ha="left", va="center", color=s.ORANGE, fontsize=10)


def _legend(ax, columns: int = 2) -> None:
    """The two marks that are not self-explanatory, in a row above the picture."""
    handles = [
        Line2D(
            [],
            [],
            color=s.MUTED,
            lw=1.3,
            ls=(0, (5, 4)),
            marker="^",
            markersize=7,
            markeredgewidth=0,
            label="balance point x*",
        ),
        Patch(facecolor=s.LOST, edgecolor=s.INK, label="fulcrum (pivot at x$_p$)"),
    ]
    ax.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncols=columns, frameon=False, fontsize=9)


def _ground(ax, left: float, right: float) -> None:
    """The ground line the fulcrum stands on, hatched underneath, across the whole axes."""
    ax.plot([left, right], [GROUND, GROUND], color=s.MUTED, lw=1.2, solid_capstyle="butt")
    for x in np.arange(left + 0.05, right, 0.08):
        ax.plot([x, x - 0.05], [GROUND, GROUND - 0.05], color=s.MUTED, lw=0.8)


def _output_names(scene) -> dict[str, str]:
    """References to the outputs that follow the tilt: with the bar's mass when the scene enables it."""
    suffix = "_bar" if "bar_mass" in scene.effects else ""
    corners = [
        f"{block}_block_{end}{edge}" for block in ("left", "right") for end in ("bottom", "top") for edge in "01"
    ]
    names = ("x_star", "marker_x0", "marker_x1", "y_left", "y_right", *corners)
    return {name: f"out:{name}{suffix}" for name in names}


def _block(side: str, out: dict[str, str]):
    """A block standing on an end of the bar, its bottom along the bar (it leans with it)."""
    x0, x1 = f"out:{side}_block_x0", f"out:{side}_block_x1"
    corner = {key: out[f"{side}_block_{key}"] for key in ("bottom0", "top0", "top1", "bottom1")}
    return ((x0, corner["bottom0"]), (x0, corner["top0"]), (x1, corner["top1"]), (x1, corner["bottom1"]))


def _dimension(start, end):
    """A dimension line with a tick at each end."""
    low, high = ARM_LINE - ARM_TICK, ARM_LINE + ARM_TICK
    return ((start, high), (start, low), (start, ARM_LINE), (end, ARM_LINE), (end, high), (end, low))


def _top(scene, tables) -> float:
    """Height above every block top (the masses' labels sit there)."""
    out = _output_names(scene)
    return max(table_range(tables[out[name][4:]])[1] for name in out if "_top" in name) + LABEL_GAP


def _equal_aspect(ax, bottom: float, top: float) -> None:
    """Widen the y- or the x-limits so that a metre is as long up as across (the blocks stay square)."""
    box = ax.get_window_extent()
    x0, x1 = ax.get_xlim()
    room = (x1 - x0) * box.height / box.width  # the height that the current width allows
    if room >= top - bottom:
        pad = 0.5 * (room - (top - bottom))
        ax.set_ylim(bottom - pad, top + pad)
    else:
        pad = 0.5 * ((top - bottom) * box.width / box.height - (x1 - x0))
        ax.set_xlim(x0 - pad, x1 + pad)
        ax.set_ylim(bottom, top)
