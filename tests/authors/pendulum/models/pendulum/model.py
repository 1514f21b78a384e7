"""A pendulum at large amplitude: its period by integrating θ'' = −(g/L) sin θ with scipy's solve_ivp, checked
against the closed form T = 4 K(m) √(L/g), m = sin²(θ0/2) (Landau and Lifshitz 1976, §11)."""

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import ellipk

from sitegen.physics import Model, Output, Param
from sitegen.physics.numerics import Measurement, Numerics


def quarter_period(theta0: float, method: str, rtol: float) -> tuple[float, int]:
    """(τ, evaluations): the time from release at rest to the bottom, in units of √(L/g), by `method`."""

    def bottom(t, y):
        return y[0]

    bottom.terminal, bottom.direction = True, -1
    run = solve_ivp(
        lambda t, y: (y[1], -np.sin(y[0])), (0.0, 100.0), (theta0, 0.0),
        method=method, rtol=rtol, atol=1e-3 * rtol, events=bottom,
    )
    return float(run.t_events[0][0]), int(run.nfev)


def exact_period(theta0_deg, length, gravity):
    """T = 4 K(sin²(θ0/2)) √(L/g), scipy's ellipk taking the parameter m = k²."""
    return 4.0 * ellipk(np.sin(np.radians(theta0_deg) / 2) ** 2) * np.sqrt(length / gravity)


class Pendulum(Model):
    """A point mass on a light rod, released from rest at θ0; its period by an ODE solver."""

    name = "pendulum"
    title = "Pendulum at large amplitude, by an ODE solver"
    params = (
        Param("theta0", "θ<sub>0</sub>", "°", 90.0, 0.0, 179.0, lo_open=True, description="amplitude"),
        Param("L", "L", "m", 1.0, 0.0, 100.0, lo_open=True, description="length"),
        Param("g", "g", "m/s²", 9.81, 0.0, 100.0, lo_open=True, description="gravity"),
    )
    outputs = (
        Output("T", "period T", "s", ("theta0", "L", "g"), decimals=4),
        Output("ratio", "T/T<sub>0</sub>", "", ("theta0",), decimals=4),
    )
    numerics = Numerics("DOP853", tolerance=1e-8, rtol=1e-10)
    methods = {name: {"rtol": 1e-8} for name in ("RK45", "DOP853", "LSODA")}
    ladders = {"rtol": (1e-4, 1e-8, 1e-12)}  # short: a test runs the bench
    error_metric = "relative error of the period"
    accuracy_stops = 3

    def _evaluate(self, x, wanted, effects):
        amplitudes, where = np.unique(x["theta0"], return_inverse=True)
        tau = np.array([quarter_period(np.radians(a), self.settings.method, self.settings.rtol)[0] for a in amplitudes])
        ratio = (4.0 * tau / (2 * np.pi))[where.reshape(x["theta0"].shape)]
        values = {"ratio": lambda: ratio, "T": lambda: ratio * 2 * np.pi * np.sqrt(x["L"] / x["g"])}
        return {name: values[name]() for name in wanted}

    def measure_error(self, values, effects) -> Measurement:
        """The period by the scene's solver at one stop against the elliptic-integral closed form."""
        x = {**self.defaults(), **values}
        tau, evaluations = quarter_period(np.radians(x["theta0"]), self.settings.method, self.settings.rtol)
        exact = exact_period(x["theta0"], x["L"], x["g"])
        error = abs(4.0 * tau * np.sqrt(x["L"] / x["g"]) - exact) / exact
        return Measurement(float(error), evaluations, self.settings.method, "4 K(sin²(θ0/2)) √(L/g)")
