"""A pendulum at any amplitude: its period from the complete elliptic integral, and where the bob is.

Physics only (numpy and scipy): no plotting, no formatting. `_evaluate` gets every parameter as a
broadcast numpy array and returns the outputs asked for."""
import numpy as np
from scipy.special import ellipk

from sitegen.physics import Model, Output, Param

ARC_POINTS = 41  # vertices of the drawn arc of the swing


def small_swing_period(length, gravity):
    """T0 = 2π √(L/g), the period in the limit of small swings."""
    return 2 * np.pi * np.sqrt(length / gravity)


def period_ratio(amplitude_deg):
    """T/T0 = (2/π) K(m) with m = sin²(θ0/2): the exact period over the small-swing period."""
    half = np.radians(amplitude_deg) / 2
    return 2 / np.pi * ellipk(np.sin(half) ** 2)


class Pendulum(Model):
    """A point mass on a light rigid rod, released from rest at the angle θ0."""

    name = "pendulum"
    title = "Pendulum at any amplitude"
    params = (
        Param("theta0", "θ<sub>0</sub>", "°", 60.0, 0.0, 179.0, lo_open=True, description="amplitude of the swing"),
        Param("L", "L", "m", 1.0, 0.0, 100.0, lo_open=True, description="length of the rod"),
        Param("g", "g", "m/s²", 9.81, 0.0, 100.0, lo_open=True, description="gravitational acceleration"),
    )
    outputs = (
        Output("T", "period T", "s", ("theta0", "L", "g"), decimals=3),
        Output("T0", "small-swing period T<sub>0</sub>", "s", ("L", "g"), decimals=3),
        Output("ratio", "T/T<sub>0</sub>", "", ("theta0",), decimals=3),
        Output("bob_x", "bob's x at the end of the swing", "m", ("theta0", "L"), decimals=3),
        Output("bob_y", "bob's y at the end of the swing", "m", ("theta0", "L"), decimals=3),
        Output("arc_x", "x along the swing", "m", ("theta0", "L"), decimals=3, size=ARC_POINTS),
        Output("arc_y", "y along the swing", "m", ("theta0", "L"), decimals=3, size=ARC_POINTS),
    )

    def _evaluate(self, x, wanted, effects):
        theta, length = np.radians(x["theta0"]), x["L"]
        sweep = theta[..., None] * np.linspace(-1.0, 1.0, ARC_POINTS)  # from one end of the swing to the other
        values = {
            "T0": lambda: small_swing_period(length, x["g"]),
            "ratio": lambda: period_ratio(x["theta0"]),
            "T": lambda: small_swing_period(length, x["g"]) * period_ratio(x["theta0"]),
            "bob_x": lambda: length * np.sin(theta),
            "bob_y": lambda: -length * np.cos(theta),
            "arc_x": lambda: length[..., None] * np.sin(sweep),
            "arc_y": lambda: -length[..., None] * np.cos(sweep),
        }
        return {name: values[name]() for name in wanted}
