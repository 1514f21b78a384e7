"""The pendulum drawn: a pivot, and a string that ends at the bob."""
from sitegen.render.layers import Layer
from sitegen.render.style import new_figure


class PendulumFigure:
    """A string hanging from a pivot; its length follows the slider."""

    label = "A pendulum: a string hanging from a pivot, its bob at the end."

    def layers(self, scene):
        return [Layer("string", "polyline", 0, ((0.0, 0.0), (0.0, "out:bob_y")), style={"stroke": "#1f63b5"}),
                Layer("bob", "dots", 0, ((0.0, "out:bob_y"),), style={"stroke": "#1f63b5", "stroke-width": "8"})]

    def draw(self, scene, tables):
        fig, (ax,) = new_figure(2.0)
        ax.set_xlim(-1.5, 1.5)
        ax.set_ylim(-2.2, 0.2)
        ax.plot([-0.3, 0.3], [0, 0], color="black")
        return fig
