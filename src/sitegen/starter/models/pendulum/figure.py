"""The pendulum drawn: at the end of its swing (left), and its period against the amplitude (right).

`draw` makes the static figure once (matplotlib); `layers` lists the parts that move with the
sliders, whose vertices are numbers, "in:<parameter>" or "out:<output>" of the model."""
import numpy as np

from sitegen.render import style as s
from sitegen.render.figures.base import param_range, table_range
from sitegen.render.layers import Layer

from .model import period_ratio


class PendulumFigure:
    """The rod, the bob and the arc it swings through; the period ratio as a curve with a dot on it."""

    label = ("Left: the pendulum at the end of its swing, with the arc it swings through. Right: its period "
             "over the small-swing period against the amplitude, a curve that rises steeply towards 180°; "
             "the dot marks the chosen amplitude.")

    def layers(self, scene):
        return [
            Layer("arc", "polyline", 0, xs="out:arc_x", ys="out:arc_y",
                  style={"fill": "none", "stroke": s.MUTED, "stroke-width": "1.3", "stroke-dasharray": "4 3"}),
            Layer("rod", "polyline", 0, points=((0.0, 0.0), ("out:bob_x", "out:bob_y")),
                  style={"fill": "none", "stroke": s.INK, "stroke-width": "2"}),
            # A dot takes its colour from the stroke and its diameter from the stroke's width.
            Layer("bob", "dots", 0, points=(("out:bob_x", "out:bob_y"),), style={"stroke": s.BLUE, "stroke-width": "14"}),
            Layer("now", "dots", 1, points=(("in:theta0", "out:ratio"),), style={"stroke": s.ORANGE, "stroke-width": "9"}),
        ]

    def draw(self, scene, tables, narrow=False):
        fig, (swing, period) = s.new_figure(6.2 if narrow else 2.9, ncols=2, narrow=narrow)
        reach = param_range(scene, "L")[1] * 1.08
        swing.set_xlim(-reach, reach)
        swing.set_ylim(-reach, reach)
        swing.set_aspect("equal")
        swing.set_xlabel("x (m)")
        swing.set_ylabel("y (m)")
        swing.plot([0.0], [0.0], marker="o", color=s.INK, markersize=5)
        amplitudes = np.linspace(0.5, 179.0, 400)
        period.plot(amplitudes, period_ratio(amplitudes), color=s.FILL_BLUE)
        period.set_xlim(0, 180)
        period.set_xticks(range(0, 181, 45))
        period.set_ylim(0.9, table_range(tables["ratio"])[1] * 1.08)
        period.set_xlabel("amplitude θ₀ (°)")
        period.set_ylabel("T/T₀")
        fig.tight_layout(pad=0.6)
        swing.apply_aspect()  # now, not when saved: the layers are placed with the axes' transform as it is here
        return fig
