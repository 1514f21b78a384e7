"""A mass on a spring: its angular frequency and period (the model), and a bar of its period (the figure)."""
import numpy as np

from sitegen.physics import Model, Output, Param
from sitegen.render.layers import Layer
from sitegen.render.style import new_figure


class Swing(Model):
    """ω = √(k/m), T = 2π/ω."""

    name = "swing"
    title = "Mass on a spring"
    params = (
        Param("m", "m", "kg", 1.0, 0.0, 100.0, lo_open=True, description="mass"),
        Param("k", "k", "N/m", 4.0, 0.0, 1000.0, lo_open=True, description="spring constant"),
    )
    outputs = (
        Output("omega", "angular frequency ω", "rad/s", ("m", "k"), decimals=3),
        Output("period", "period T", "s", ("m", "k"), decimals=3),
    )

    def _evaluate(self, x, wanted, effects):
        omega = np.sqrt(x["k"] / x["m"])
        return {"omega": omega, "period": 2 * np.pi / omega}


class SwingFigure:
    """A bar as long as the period."""

    label = "A bar whose length is the period."

    def layers(self, scene):
        return [Layer("bar", "polyline", 0, ((0.0, 0.0), ("out:period", 0.0)), style={"stroke": "#c8541c", "stroke-width": "6"})]

    def draw(self, scene, tables):
        fig, (ax,) = new_figure(1.0)
        ax.set_xlim(0, 10)
        ax.set_ylim(-1, 1)
        return fig


MODELS = {"swing": Swing}
FIGURES = {"swing": SwingFigure()}
