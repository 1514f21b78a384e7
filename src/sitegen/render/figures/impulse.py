"""I1: the force pulse F(t) with the impulse shaded underneath."""
from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from .. import style as s
from ..layers import Layer
from .base import param_range


class ImpulseFigure:
    """F(t) of the pulse with the impulse shaded underneath."""

    label = "Force against time for a triangular pulse; the shaded area under the curve is the impulse J."

    def layers(self, scene):
        apex = ("out:t_apex", "in:F_pk")
        return [
            Layer("area", "polygon", 0, ((0.0, 0.0), apex, ("in:tau", 0.0)), style={"fill": s.FILL_BLUE, "fill-opacity": "0.75", "stroke": "none"}),
            Layer("pulse", "polyline", 0, ((0.0, 0.0), apex, ("in:tau", 0.0)), style={"fill": "none", "stroke": s.BLUE, "stroke-width": "2.2"}),
        ]

    def draw(self, scene, tables):
        fig, (ax,) = s.new_figure(2.5)
        t_max = param_range(scene, "tau")[1]
        f_max = max(param_range(scene, "F_pk")[1], 1e-9)
        ax.set_xlim(0, t_max * 1.04)
        ax.set_ylim(0, f_max * 1.08)
        ax.set_xlabel("time t (s)")
        ax.set_ylabel("force F (N)")
        ax.legend(
            handles=[Line2D([], [], color=s.BLUE, lw=2.2, label="F(t)"), Patch(color=s.FILL_BLUE, label="area = impulse J")],
            loc="upper right",
            frameon=False,
        )
        fig.tight_layout(pad=0.4)
        return fig
