"""I2: a 1-D collision with restitution, in the cancellation-safe centre-of-mass form."""
from __future__ import annotations

import numpy as np

from .base import Model, Output, Param

COLLISION, SEPARATING = 0, 1


class Collision(Model):
    """Body 1 starts left of body 2; they collide only if v1i > v2i (approaching)."""

    name = "collision"
    title = "Collision with restitution"
    params = (
        Param("m1", "m<sub>1</sub>", "kg", 1.0, lo=0.0, lo_open=True, description="mass of body 1"),
        Param("m2", "m<sub>2</sub>", "kg", 2.0, lo=0.0, lo_open=True, description="mass of body 2"),
        Param("v1i", "v<sub>1i</sub>", "m/s", 3.0, description="initial velocity of body 1"),
        Param("v2i", "v<sub>2i</sub>", "m/s", -1.0, description="initial velocity of body 2"),
        Param("e", "e", "", 1.0, lo=0.0, hi=1.0, description="coefficient of restitution"),
    )
    _all = ("m1", "m2", "v1i", "v2i", "e")
    _initial = ("m1", "m2", "v1i", "v2i")
    outputs = (
        Output("v1f", "v<sub>1f</sub>", "m/s", _all),
        Output("v2f", "v<sub>2f</sub>", "m/s", _all),
        Output("v_cm", "V (centre of mass)", "m/s", _initial),
        Output("p_before", "p before", "kg·m/s", _initial, decimals=2),
        Output("p_after", "p after", "kg·m/s", _all, decimals=2),
        Output("K_before", "K before", "J", _initial, decimals=2),
        Output("K_after", "K after", "J", _all, decimals=2),
        Output("K_lost", "K lost", "J", _all, decimals=2),
        Output("K_kept_pct", "K kept", "%", _all, decimals=1),
        Output(
            "status",
            "status",
            "",
            ("v1i", "v2i"),
            labels=("collision", "no collision — bodies separating (or at rest relative to each other)"),
        ),
    )
    effects = ("restitution_law",)

    def _evaluate(self, x, wanted, effects):
        m1, m2, v1i, v2i, e = (x[k] for k in self._all)
        total = m1 + m2
        w1, w2 = m1 / total, m2 / total  # w2 directly, never 1 - w1 (cancellation at extreme ratios)
        delta = v1i - v2i
        approaching = delta > 0
        com = w1 * v1i + w2 * v2i
        # Separating or equal velocities: no contact, so no impulse (v_f is v_i bitwise).
        v1f = np.where(approaching, com - e * w2 * delta, v1i)
        v2f = np.where(approaching, com + e * w1 * delta, v2i)
        formulas = {
            "v1f": lambda: v1f,
            "v2f": lambda: v2f,
            "v_cm": lambda: com,
            "p_before": lambda: m1 * v1i + m2 * v2i,
            "p_after": lambda: m1 * v1f + m2 * v2f,  # computed from v_f: shows conservation
            "K_before": lambda: 0.5 * m1 * v1i**2 + 0.5 * m2 * v2i**2,
            "K_after": lambda: 0.5 * m1 * v1f**2 + 0.5 * m2 * v2f**2,
            # Closed form, not K_before - K_after, which loses all digits when the loss is tiny.
            "K_lost": lambda: np.where(approaching, 0.5 * (m1 * w2) * (1 - e) * (1 + e) * delta**2, 0.0),
            "K_kept_pct": lambda: _kept_percent(m1, m2, v1i, v2i, e, w2, delta, approaching),
            "status": lambda: np.where(approaching, COLLISION, SEPARATING),
        }
        return {name: formulas[name]() for name in wanted}


def _kept_percent(m1, m2, v1i, v2i, e, w2, delta, approaching):
    """Percentage of the kinetic energy that survives; 100 when nothing moves (nothing is lost)."""
    before = 0.5 * m1 * v1i**2 + 0.5 * m2 * v2i**2
    lost = np.where(approaching, 0.5 * (m1 * w2) * (1 - e) * (1 + e) * delta**2, 0.0)
    fraction_lost = np.divide(lost, before, out=np.zeros_like(before), where=before > 0)
    return 100.0 * (1.0 - fraction_lost)
