"""A simple pendulum in small swings: its period and where its bob hangs."""
from sitegen.physics import Model, Output, Param

from .swing_time import period


class Pendulum(Model):
    """T = 2π √(L/g), exact for small swings."""

    name = "pendulum"
    title = "Simple pendulum"
    params = (
        Param("L", "L", "m", 1.0, 0.0, 10.0, lo_open=True, description="length of the string"),
        Param("g", "g", "m/s²", 9.81, 0.0, 30.0, lo_open=True, description="gravitational acceleration"),
    )
    outputs = (
        Output("T", "period T", "s", ("L", "g"), decimals=4),
        Output("bob_y", "height of the bob", "m", ("L",), decimals=2),
    )

    def _evaluate(self, x, wanted, effects):
        return {"T": period(x["L"], x["g"]), "bob_y": -x["L"]}
