"""I3: the two paths from A to B in the plane, the spring's force field and the drag along the path."""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D

from ...render import style as s
from ...render.figures.base import param_range
from ...render.layers import Layer
from .paths import CHORD, DRAG, HALF_CHORD, SPRING, arc_half_angle
from .shapes import ARROW_MAX, GRID_X, GRID_Y

CHOSEN = {"fill": "none", "stroke": s.INK, "stroke-width": "2.6"}
FAINT = {"fill": "none", "stroke": s.MUTED, "stroke-width": "1.3", "stroke-dasharray": "5 4"}
REST = {"fill": "none", "stroke": s.BLUE, "stroke-width": "1.2", "stroke-dasharray": "3 3"}


class WorkFigure:
    """A and B on a line, the chord and the arc between them, and the force acting along the way."""

    label = (
        "The plane of motion in metres. A point goes from A to B along the straight chord or along the arc "
        "over the top; the chosen path is drawn solid with an arrowhead at B, the other dashed. For the spring, "
        "blue wedges on a grid show its force at each place, pointing to the anchor and longer where the spring "
        "is stretched more. For drag there is no such field: orange wedges on the path show the drag, always "
        "against the motion, one per 0.3 m of path, so the longer path carries more of them."
    )

    def layers(self, scene):
        layers = [
            Layer(
                "field",
                "polygon",
                0,
                xs="out:field_x",
                ys="out:field_y",
                style={**_filled(s.BLUE), "fill-opacity": "0.6"},
            ),
            Layer("arc", "polyline", 0, xs="out:arc_x", ys="out:arc_y", style=FAINT),
            Layer("chosen-arc", "polyline", 0, xs="out:arc_x", ys="out:chosen_arc_y", style=CHOSEN),
            Layer("chosen-chord", "polyline", 0, xs="out:chord_x", ys=(0.0, 0.0), style=CHOSEN),
            Layer("heading", "polygon", 0, xs="out:head_x", ys="out:head_y", style=_filled(s.INK)),
            Layer("drag", "polygon", 0, xs="out:drag_x", ys="out:drag_y", style=_filled(s.ORANGE)),
            # The field arrows are drawn to one length: the note gives the spring constant they stand for.
            Layer.note("scale", "field arrows scaled to their longest; k = ", "in:k"),
        ]
        if "spring_rest_length" in scene.effects:
            layers.append(Layer("rest-length", "polyline", 0, xs="out:rest_x", ys="out:rest_y", style=REST))
        ends = ((-HALF_CHORD, 0.0), (HALF_CHORD, 0.0))
        return layers + [
            Layer("ends", "dots", 0, points=ends, style=_dots(s.INK, 9)),
            Layer("anchor", "dots", 0, xs="out:anchor_x", ys=(0.0,), style=_dots(s.BLUE, 13)),
            Layer("anchor-hole", "dots", 0, xs="out:anchor_x", ys=(0.0,), style=_dots("#ffffff", 5)),
        ]

    def draw(self, scene, tables, narrow=False):
        x_lo, x_hi, y_lo, y_hi = _limits(scene)
        # Equal scales: the axes take about 86 % of the width (80 % narrow); the rest of the height holds the
        # legend (three rows narrow, two wide) and the x label.
        height = s.width(narrow) * (0.8 if narrow else 0.86) * (y_hi - y_lo) / (x_hi - x_lo) + (1.3 if narrow else 0.9)
        fig, (ax,) = s.new_figure(height, narrow=narrow)
        ax.set_xlim(x_lo, x_hi)
        ax.set_ylim(y_lo, y_hi)
        ax.set_aspect("equal", adjustable="box")
        ax.grid(False)
        ax.set_xticks(np.arange(np.ceil(x_lo), np.floor(x_hi) + 1))
        ax.set_yticks(np.arange(np.ceil(y_lo * 2) / 2, y_hi, 0.5 if y_hi - y_lo < 4 else 1.0))
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.plot([-HALF_CHORD, HALF_CHORD], [0.0, 0.0], color=s.MUTED, lw=1.3, ls=(0, (5, 4)))
        for x, name in ((-HALF_CHORD, "A"), (HALF_CHORD, "B")):
            ax.annotate(
                name,
                (x, 0.0),
                xytext=(0, -9),
                textcoords="offset points",
                ha="center",
                va="top",
                fontsize=12,
                fontweight="bold",
                color=s.INK,
            )
        ax.legend(
            handles=_legend(scene),
            loc="lower center",
            bbox_to_anchor=(0.5, 1.0),
            ncols=2 if narrow else 3,
            frameon=False,
            handlelength=2.0,
            columnspacing=1.2,
            fontsize=9 if narrow else 10,
        )
        fig.tight_layout(pad=0.4)
        ax.apply_aspect()  # now, not at save time: the layers are placed with the axes' transform as it is here
        return fig


def _filled(colour: str) -> dict[str, str]:
    """Style of the wedge polygons: fill only, since a stroke would draw their (zero-area) joins."""
    return {"fill": colour, "stroke": "none"}


def _dots(colour: str, size: float) -> dict[str, str]:
    """Style of a dots layer: colour and diameter in pixels."""
    return {"stroke": colour, "stroke-width": f"{size:g}"}


def _limits(scene) -> tuple[float, float, float, float]:
    """Axes limits that hold the arrow grid and the tallest arc the scene can show."""
    theta = float(arc_half_angle(param_range(scene, "h")[1]))
    radius = CHORD / (2.0 * np.sin(theta)) if theta > 0 else np.inf
    widest = radius if theta > np.pi / 2 else HALF_CHORD  # past a half circle the arc bulges beyond A and B
    margin = 0.5 * ARROW_MAX + 0.03
    x_hi = max(GRID_X.max() + margin, widest + 0.1)
    y_hi = max(GRID_Y.max() + margin, param_range(scene, "h")[1] + 0.1)
    return -x_hi, x_hi, GRID_Y.min() - margin, y_hi


def _legend(scene) -> list:
    """Legend entries for what the scene can show (the wedge arrows stand in as triangles)."""
    forces = param_range(scene, "force")
    field = "spring + gravity" if "gravity" in scene.effects else "spring force"
    paths = [
        Line2D([], [], color=s.INK, lw=2.6, label="chosen path"),
        Line2D([], [], color=s.MUTED, lw=1.3, ls=(0, (5, 4)), label="other path"),
    ]
    spring = [
        Line2D([], [], ls="none", marker="o", ms=9, mfc="white", mec=s.BLUE, mew=3, label="anchor"),
        Line2D([], [], ls="none", marker=">", ms=9, color=s.BLUE, label=f"{field} ∝ |F|/k"),
    ]
    drag = [Line2D([], [], ls="none", marker=">", ms=9, color=s.ORANGE, label="drag, against motion")]
    return paths + (spring if forces[0] == SPRING else []) + (drag if forces[1] == DRAG else [])
