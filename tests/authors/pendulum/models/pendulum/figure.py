"""The period over the small-swing period against the amplitude, with a dot at the scene's amplitude."""

import numpy as np

from sitegen.render import style as s
from sitegen.render.layers import Layer

from .model import exact_period


class SwingFigure:
    """T/T0 against θ0 (the closed form, drawn once) and the integrated value at the slider's amplitude."""

    label = "The period of the pendulum over its small-swing period against the amplitude; the dot marks the chosen one."

    def layers(self, scene):
        return [Layer("now", "dots", 0, points=(("in:theta0", "out:ratio"),), style={"stroke": s.ORANGE, "stroke-width": "9"})]

    def draw(self, scene, tables, narrow=False):
        fig, (ax,) = s.new_figure(2.6, narrow=narrow)
        amplitudes = np.linspace(1.0, 175.0, 200)
        ax.plot(amplitudes, exact_period(amplitudes, 1.0, 1.0) / (2 * np.pi), color=s.FILL_BLUE)
        ax.set_xlim(0, 180)
        ax.set_ylim(0.9, 4.0)
        ax.set_xlabel("amplitude θ₀ (°)")
        ax.set_ylabel("T/T₀")
        fig.tight_layout(pad=0.6)
        return fig
