"""The oscillator drawn: its amplitude curve with the chosen frequency on it, and its motion from rest."""

from sitegen.render import style as s
from sitegen.render.figures.base import param_range, table_range
from sitegen.render.layers import Layer

from .model import CURVE_F, RING_T


class OscillatorFigure:
    """Left: X against f, a dot at the slider's f. Right: x(t) from rest, a dot at the slider's t."""

    label = ("Left: the steady amplitude against the drive frequency, a peak at the natural frequency; the dot "
             "marks the chosen frequency. Right: the motion from rest, growing to the steady amplitude.")

    def layers(self, scene):
        return [
            Layer("curve", "polyline", 0, xs=CURVE_F, ys="out:gain_curve", style={"stroke": s.BLUE, "stroke-width": "2"}),
            Layer("here", "dots", 0, points=(("in:f", "out:X"),), style={"stroke": s.ORANGE, "stroke-width": "9"}),
            Layer("motion", "polyline", 1, xs=RING_T, ys="out:ring", style={"stroke": s.BLUE, "stroke-width": "1.5"}),
            Layer("now", "dots", 1, points=(("in:t", "out:x_now"),), style={"stroke": s.ORANGE, "stroke-width": "9"}),
        ]

    def draw(self, scene, tables, narrow=False):
        fig, (curve, motion) = s.new_figure(6.2 if narrow else 2.8, ncols=2, narrow=narrow)
        peak = table_range(tables["gain_curve"])[1]
        curve.set_xlim(0, CURVE_F[-1])
        curve.set_ylim(0, peak * 1.08)
        curve.set_xlabel("drive frequency f (kHz)")
        curve.set_ylabel("amplitude X (nm)")
        reach = max(abs(v) for v in table_range(tables["ring"])) * 1.08
        motion.set_xlim(0, max(RING_T[-1], param_range(scene, "t")[1]))
        motion.set_ylim(-reach, reach)
        motion.set_xlabel("time t (ms)")
        motion.set_ylabel("x (nm)")
        fig.tight_layout(pad=0.6)
        return fig
