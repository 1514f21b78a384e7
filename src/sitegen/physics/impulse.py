"""I1: the impulse of a symmetric triangular force pulse, J = F_pk tau / 2 (closed form)."""
from __future__ import annotations

import numpy as np

from .base import Model, Output, Param


class Impulse(Model):
    """A triangular pulse F(t) = F_pk max(0, 1 - |2t/tau - 1|) acting on a mass m."""

    name = "impulse"
    title = "Impulse of a force pulse"
    params = (
        Param("F_pk", "F<sub>pk</sub>", "N", 12.0, lo=0.0, description="peak force"),
        Param("tau", "τ", "s", 0.20, lo=0.0, lo_open=True, description="pulse duration"),
        Param("m", "m", "kg", 2.0, lo=0.0, lo_open=True, description="mass"),
    )
    outputs = (
        Output("J", "impulse J", "N·s", ("F_pk", "tau")),
        Output("dp", "Δp = J", "kg·m/s", ("F_pk", "tau")),
        Output("dv", "Δv = J/m", "m/s", ("F_pk", "tau", "m")),
        # The apex time of the pulse, a vertex of the F(t) figure (exact: tau is on a 0.01 grid).
        Output("t_apex", "apex time τ/2", "s", ("tau",), decimals=4),
    )

    def _evaluate(self, x, wanted, effects):
        impulse = 0.5 * x["F_pk"] * x["tau"]
        formulas = {
            "J": lambda: impulse,
            "dp": lambda: impulse,  # Newton's second law, integrated: the momentum change is J
            "dv": lambda: impulse / x["m"],
            "t_apex": lambda: 0.5 * x["tau"],
        }
        return {name: formulas[name]() for name in wanted}


def force(t: np.ndarray, F_pk: float, tau: float) -> np.ndarray:
    """The force of the pulse at times `t` (zero outside 0 <= t <= tau)."""
    return F_pk * np.maximum(0.0, 1.0 - np.abs(2.0 * np.asarray(t) / tau - 1.0))


def velocity(t: np.ndarray, F_pk: float, tau: float, m: float, v0: float = 0.0) -> np.ndarray:
    """The velocity of the mass during and after the pulse (piecewise quadratic in t)."""
    t = np.clip(np.asarray(t, float), 0.0, tau)
    rising = F_pk * t**2 / (m * tau)
    falling = (0.5 * F_pk * tau - F_pk * (tau - t) ** 2 / tau) / m
    return v0 + np.where(t <= 0.5 * tau, rising, falling)

