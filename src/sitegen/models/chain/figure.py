"""I5: the chain's masses over the continuum string, and the chain's dispersion relation against ω = ck."""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

from ...render import style as s
from ...render.figures.base import table_range
from ...render.layers import Layer
from .model import continuum_grid
from .modes import DRAWN_WALL, LENGTH, SPEED

LOG_LO, LOG_HI = 0.3, 3.0  # the dispersion panel spans 2 … 1000 in k and ω: the modes of N = 1 … 256 all fit
TALL = 1e3  # the walls drawn as layers reach beyond the panel, which clips them


class ChainFigure:
    """The masses u_j(t) as dots over the dashed string u_c(x, t); beside it ω(k) of the chain and ck."""

    label = (
        "Left: displacement of each mass of the chain (dots) and of the continuous string (dashed line) "
        "between two fixed walls. Right: on log-log axes, the frequency of each normal mode of the chain "
        "against its wavenumber, with the straight line ω = ck of "
        "the string and, shaded, the wavenumbers the pulse contains."
    )

    def describe(self, scene) -> str:
        """The label; with the boundary effect the ends may be fixed to walls or free."""
        if "boundary" not in scene.effects:
            return self.label
        return self.label.replace("between two fixed walls", "whose ends are either fixed to walls or free")

    def layers(self, scene):
        # Inline style: matplotlib's SVG sheet sets * {stroke-linecap: butt}, which would hide zero-length dots.
        dots = {"stroke": s.BLUE, "stroke-width": "5", "fill": "none", "style": "stroke-linecap: round"}
        return [
            Layer(
                "pulse-band",
                "polygon",
                1,
                ((LOG_LO, LOG_LO), (LOG_LO, LOG_HI), ("out:log_k_pulse", LOG_HI), ("out:log_k_pulse", LOG_LO)),
                style={"fill": s.FILL_BLUE, "fill-opacity": "0.35", "stroke": "none"},
            ),
            Layer("chain", "dots", 0, xs="out:x_dots", ys="out:u_dots", style=dots),
            Layer(
                "string",
                "polyline",
                0,
                xs=tuple(float(x) for x in continuum_grid()),
                ys="out:u_continuum",
                style={"stroke": s.ORANGE, "stroke-width": "1.8", "stroke-dasharray": "6 4", "fill": "none"},
            ),
            Layer("modes", "dots", 1, xs="out:log_k", ys="out:log_omega", style={**dots, "stroke-width": "4"}),
        ] + (_wall_layers() if "boundary" in scene.effects else [])

    def draw(self, scene, tables, narrow=False):
        shape = {"height_ratios": [1, 1.15]} if narrow else {"width_ratios": [2.5, 1]}
        fig, (ax, ax_w) = s.new_figure(5.6 if narrow else 2.6, ncols=2, narrow=narrow, gridspec_kw=shape)
        _draw_string_axes(ax, tables, static_walls="boundary" not in scene.effects, legend_columns=1 if narrow else 2)
        _draw_dispersion_axes(ax_w)
        fig.tight_layout(pad=0.4, w_pad=1.4)
        return fig


def _wall_layers() -> list[Layer]:
    """The walls as moving shapes: DRAWN_WALL thick with fixed ends, of zero width (unseen) with free ends."""
    wall = {"fill": s.LOST, "stroke": "none"}
    return [
        Layer(
            "left-wall",
            "polygon",
            0,
            (("out:wall_left", -TALL), (0.0, -TALL), (0.0, TALL), ("out:wall_left", TALL)),
            style=wall,
        ),
        Layer(
            "right-wall",
            "polygon",
            0,
            ((LENGTH, -TALL), ("out:wall_right", -TALL), ("out:wall_right", TALL), (LENGTH, TALL)),
            style=wall,
        ),
    ]


def _draw_string_axes(ax, tables, static_walls: bool = True, legend_columns: int = 2) -> None:
    """Fixed walls, the rest line, and u limits that fit the string and every resolved chain.

    The limits leave 20 % above the string's range: a chain with σ/a ≥ 1 overshoots it by at most
    10 %. An under-resolved chain launched moving can be kicked far higher (5.4 A at N = 2,
    σ = 0.02); those masses leave the panel, and the status readout says why.
    """
    low, high = table_range(tables["u_continuum"])
    top = 1.2 * max(1.0, -low, high)
    wall = DRAWN_WALL
    ax.set_xlim(-wall, LENGTH + wall)
    ax.set_ylim(-top, top)
    for x in (-wall, LENGTH) if static_walls else ():
        ax.add_patch(
            Rectangle(
                (x, -top), wall, 2 * top, facecolor=s.LOST, edgecolor=s.MUTED, hatch="////", linewidth=0.8, zorder=3
            )
        )
    ax.axhline(0.0, color=s.MUTED, lw=0.6)
    ax.set_xlabel("position x (m)")
    ax.set_ylabel("displacement u / A")
    ax.legend(
        handles=[
            Line2D([], [], color=s.BLUE, marker="o", ls="none", ms=5, label="chain of N masses"),
            Line2D([], [], color=s.ORANGE, lw=1.8, ls=(0, (6, 4)), label="continuous string"),
        ],
        loc="lower center",
        bbox_to_anchor=(0.5, 1.0),
        ncols=legend_columns,
        frameon=False,
        fontsize=9,
    )


def _draw_dispersion_axes(ax) -> None:
    """Log–log axes of ω against k with the string's line ω = ck; the chain's modes are a layer."""
    ax.set_xlim(LOG_LO, LOG_HI)
    ax.set_ylim(LOG_LO, LOG_HI)
    ax.plot([LOG_LO, LOG_HI], np.log10(SPEED) + np.array([LOG_LO, LOG_HI]), color=s.INK, lw=1.2, zorder=1)
    decades = [1, 2, 3]
    labels = [f"{10**d:g}" for d in decades]  # plain text: mathtext would leave "$" in the SVG
    ax.set_xticks(decades, labels)
    ax.set_yticks(decades, labels)
    ax.set_xlabel("k (rad/m)")
    ax.set_ylabel("ω (rad/s)")
    ax.text(2.45, 2.75, "ck", color=s.INK, fontsize=9, ha="right", va="center")
    ax.legend(
        handles=[
            Line2D([], [], color=s.BLUE, marker="o", ls="none", ms=4, label="modes"),
            Patch(facecolor=s.FILL_BLUE, alpha=0.6, label="pulse"),
        ],
        # above the panel: the pulse's band can shade any part of it
        loc="lower center",
        bbox_to_anchor=(0.5, 1.0),
        ncols=2,
        frameon=False,
        fontsize=9,
        handletextpad=0.3,
        columnspacing=0.8,
        handlelength=1.2,
        borderaxespad=0.2,
    )
