"""K1: the ossicles drawn as the lever of I4 between two pistons, and the two ledgers in dB, kept apart."""

from __future__ import annotations

import math

import matplotlib.pyplot as plt

from ...render import style as s
from ...render.figures.base import param_range, table_range
from ...render.layers import Layer

FILL_ORANGE = "#f2c2a6"  # the lever figure's light orange (render/style.py's orange, lightened like FILL_BLUE)
GROUND = -3.2  # mm: the fulcrum's feet; the bar (and the pivot) is at height 0
ARM_GAP = 1.2  # mm: from the lowest drawn part (fulcrum foot or piston edge) down to the arms' dimension lines
ARM_TICK = 0.4  # mm: half-height of their end ticks
PLATE = 0.022  # bar lengths: how far each piston's face sits outside the bar's end
PISTON_WIDTH = "9"  # px: the pistons are drawn edge-on, as thick plates
MEASURED_PEAK_DB = 23.5  # Aibara et al. 2001: measured peak middle-ear pressure gain, at 1.2 kHz
BAR_HALF = 0.3  # half-width of a bar in the level diagrams
LINES = 1.35  # line spacing of two-line labels: room for a subscript without touching the line below


class OssiclesFigure:
    """The malleus–incus lever between the eardrum and footplate pistons; pressure gain and power transmission in dB."""

    label = (
        "Top: the ossicles as a lever. A bar rests on a triangular fulcrum; its left arm (malleus) carries the "
        "eardrum, drawn edge-on with its effective diameter, and its right arm (incus) the stapes footplate; the "
        "arm lengths are in the ratio ℓ to 1. Bottom left: the ideal pressure gain 20 log10 G in dB, with the "
        "measured peak gain of 23.5 dB at 1.2 kHz dashed. Bottom right, on its own scale: the power transmitted "
        "into the load, 10 log10 T in dB, without and with the transformer. The two are never added."
    )

    def layers(self, scene):
        eardrum = "out:span_TM" if "area_ratio" in scene.effects else "out:span_FP"
        plate = {"fill": "none", "stroke-width": PISTON_WIDTH}
        bar = {"stroke-width": "1.4"}
        arm_line = _arm_line(scene)
        return [
            Layer(
                "fulcrum",
                "polygon",
                0,
                (("out:fulcrum_x0", GROUND), ("out:pivot", 0.0), ("out:fulcrum_x1", GROUND)),
                style={"fill": s.LOST, "stroke": s.INK, "stroke-width": "1.4"},
            ),
            Layer(
                "bar",
                "polyline",
                0,
                ((0.0, 0.0), (1.0, 0.0)),
                style={"fill": "none", "stroke": s.INK, "stroke-width": "5"},
            ),
            Layer("eardrum", "polyline", 0, xs=(-PLATE, -PLATE), ys=eardrum, style={**plate, "stroke": s.BLUE}),
            Layer(
                "footplate",
                "polyline",
                0,
                xs=(1.0 + PLATE, 1.0 + PLATE),
                ys="out:span_FP",
                style={**plate, "stroke": s.ORANGE},
            ),
            Layer(
                "pivot",
                "dots",
                0,
                (("out:pivot", 0.0),),
                style={"stroke": "#ffffff", "stroke-width": "2.5", "style": "stroke-linecap: round"},
            ),
            Layer(
                "arm-malleus",
                "polyline",
                0,
                _dimension(0.0, "out:pivot", arm_line),
                style={"fill": "none", "stroke": s.BLUE, "stroke-width": "1.5"},
            ),
            Layer(
                "arm-incus",
                "polyline",
                0,
                _dimension("out:pivot", 1.0, arm_line),
                style={"fill": "none", "stroke": s.ORANGE, "stroke-width": "1.5"},
            ),
            Layer("gain", "polygon", 1, _bar(0.0, "out:G_dB"), style={**bar, "fill": s.FILL_BLUE, "stroke": s.BLUE}),
            Layer("T-without", "polygon", 2, _bar(0.0, "out:T0_dB"), style={**bar, "fill": s.LOST, "stroke": s.MUTED}),
            Layer("T-with", "polygon", 2, _bar(1.0, "out:T1_dB"), style={**bar, "fill": s.FILL_BLUE, "stroke": s.BLUE}),
            # The gains drawn hold at every level: the note shows what the input level changes.
            Layer.note(
                "level",
                "at ",
                "in:SPL",
                " the gains drawn give ",
                "out:p_TM",
                " at the eardrum, ",
                "out:L_OW",
                " at the oval window",
            ),
        ]

    def draw(self, scene, tables, narrow=False):
        with plt.rc_context(s.RC):
            if narrow:  # the lever over the two ledgers, one under the other
                fig = plt.figure(figsize=(s.NARROW_WIDTH_IN, 7.2))
                grid = fig.add_gridspec(3, 1, height_ratios=[1.2, 1.0, 1.0])
                ax_lever, ax_gain, ax_power = (fig.add_subplot(grid[k, 0]) for k in range(3))
            else:
                fig = plt.figure(figsize=(s.WIDTH_IN, 4.6))
                grid = fig.add_gridspec(2, 2, height_ratios=[1.05, 1.0], width_ratios=[1.0, 1.15])
                ax_lever = fig.add_subplot(grid[0, :])
                ax_gain = fig.add_subplot(grid[1, 0])
                ax_power = fig.add_subplot(grid[1, 1])
        _draw_lever(ax_lever, scene, tables, narrow)
        _draw_gain(ax_gain, tables)
        _draw_power(ax_power, tables)
        fig.tight_layout(pad=0.4, h_pad=0.6, w_pad=1.6)
        return fig


def _draw_lever(ax, scene, tables, narrow: bool = False) -> None:
    """Axes without ticks; the ground under the fulcrum's range, the labels of pistons and arms."""
    top = _largest_radius(scene) + 0.9
    arm_line = _arm_line(scene)
    ax.set_xlim(-0.42, 1.42)
    ax.set_ylim(arm_line - 1.0, top + 1.3)
    ax.axis("off")
    low, high = table_range(tables["fulcrum_x0"])[0] - 0.04, table_range(tables["fulcrum_x1"])[1] + 0.04
    ax.plot([low, high], [GROUND, GROUND], color=s.MUTED, lw=1.2, solid_capstyle="butt")
    for k in range(int((high - low) / 0.03)):
        x = low + 0.02 + 0.03 * k
        ax.plot([x, x - 0.015], [GROUND, GROUND - 0.45], color=s.MUTED, lw=0.8)
    eardrum = "eardrum (area A$_{TM}$)" if "area_ratio" in scene.effects else "eardrum (area A$_{FP}$)"
    footplate = "footplate (area A$_{FP}$)"
    if narrow:  # two lines each, so that the names keep clear of each other and of the edges
        eardrum, footplate = (name.replace(" (", "\n(") for name in (eardrum, footplate))
    ax.text(-PLATE, top, eardrum, ha="center", va="bottom", color=s.BLUE, fontsize=10, linespacing=LINES)
    ax.text(1.0 + PLATE, top, footplate, ha="center", va="bottom", color=s.ORANGE, fontsize=10, linespacing=LINES)
    ax.text(-0.03, arm_line, "malleus ℓ", ha="right", va="center", color=s.BLUE, fontsize=10)
    ax.text(1.03, arm_line, "incus 1", ha="left", va="center", color=s.ORANGE, fontsize=10)
    ax.annotate("", xy=(-0.07, 0.0), xytext=(-0.3, 0.0), arrowprops={"arrowstyle": "-|>", "color": s.MUTED, "lw": 1.4})
    ax.text(-0.3, 0.5, "p$_{TM}$" if narrow else "sound, p$_{TM}$", ha="left", va="bottom", color=s.INK, fontsize=9)
    ax.annotate("", xy=(1.3, 0.0), xytext=(1.07, 0.0), arrowprops={"arrowstyle": "-|>", "color": s.MUTED, "lw": 1.4})
    ax.text(1.31, 0.5, "p$_{OW}$", ha="right", va="bottom", color=s.INK, fontsize=9)


def _draw_gain(ax, tables) -> None:
    """The pressure ledger (20 log): the ideal gain's bar over a fixed dB axis, the measured peak dashed."""
    top = max(1.08 * table_range(tables["G_dB"])[1], MEASURED_PEAK_DB + 7.0)  # room for the two-line label
    ax.set_xlim(-0.6, 2.2)
    ax.set_ylim(0, top)
    ax.set_xticks([0.0], ["ideal G"])
    ax.grid(axis="x", visible=False)
    ax.set_ylabel("pressure gain\n20 log$_{10}$ G (dB)", linespacing=LINES)
    ax.axhline(MEASURED_PEAK_DB, xmin=0.05, color=s.ORANGE, lw=1.4, ls=(0, (5, 3)))
    ax.text(
        0.45,
        MEASURED_PEAK_DB + 0.8,
        "measured peak\n23.5 dB at 1.2 kHz",
        ha="left",
        va="bottom",
        color=s.ORANGE,
        fontsize=8.5,
        linespacing=LINES,
    )


def _draw_power(ax, tables) -> None:
    """The power ledger (10 log): transmission into the load without and with the transformer."""
    bottom = min(table_range(tables["T0_dB"])[0], table_range(tables["T1_dB"])[0])
    ax.set_xlim(-0.6, 1.6)
    ax.set_ylim(1.1 * bottom, 0.06 * -bottom)
    ax.axhline(0, color=s.INK, lw=0.9)
    ax.set_xticks([0.0, 1.0], ["without", "with"])
    ax.set_xlabel("transformer", labelpad=2)
    ax.grid(axis="x", visible=False)
    ax.set_ylabel("power transmitted\n10 log$_{10}$ T (dB)", linespacing=LINES)
    ax.text(1.57, 0.0, "T = 1", ha="right", va="bottom", color=s.INK, fontsize=8.5)


def _largest_radius(scene) -> float:
    """The largest piston radius (mm) the scene can draw: the eardrum's, or the footplate's without the area ratio."""
    area = param_range(scene, "A_TM" if "area_ratio" in scene.effects else "A_FP")[1]
    return math.sqrt(max(area, param_range(scene, "A_FP")[1]) / math.pi)


def _arm_line(scene) -> float:
    """Height of the arms' dimension lines: just below the fulcrum's feet and the largest piston."""
    return min(GROUND, -_largest_radius(scene)) - ARM_GAP


def _bar(x: float, top):
    """A bar from 0 to `top` centred on x."""
    return ((x - BAR_HALF, 0.0), (x - BAR_HALF, top), (x + BAR_HALF, top), (x + BAR_HALF, 0.0))


def _dimension(start, end, height: float):
    """A dimension line at `height` with a tick at each end (as in the lever figure)."""
    low, high = height - ARM_TICK, height + ARM_TICK
    return ((start, high), (start, low), (start, height), (end, height), (end, high), (end, low))
