"""A driven, damped oscillator: x'' + 2ζω₀x' + ω₀²x = ω₀² x_st cos(ωt), released from rest at t = 0.

Steady state (e.g. French, Vibrations and Waves, 1971, ch. 4): X = x_st / √((1 − r²)² + (2ζr)²) and
tan φ = 2ζr / (1 − r²) with r = f/f₀. From rest, the motion is the steady one plus a transient that
dies as exp(−ζω₀t) (underdamped, ζ < 1). Frequencies in kHz, times in ms, lengths in nm.
"""

import numpy as np

from sitegen.physics import Model, Output, Param

CURVE_F = tuple(round(0.05 * k, 2) for k in range(1, 61))  # kHz: the amplitude curve's frequencies
RING_T = tuple(0.25 * k for k in range(81))  # ms: the ring-up's times


def steady(f0, zeta, f, x_st):
    """The steady amplitude X (nm) and phase lag φ (rad)."""
    r = f / f0
    return x_st / np.hypot(1.0 - r**2, 2.0 * zeta * r), np.arctan2(2.0 * zeta * r, 1.0 - r**2)


def from_rest(f0, zeta, f, x_st, t):
    """x(t) released from rest: the steady motion plus the transient that makes x(0) = x'(0) = 0."""
    amplitude, lag = steady(f0, zeta, f, x_st)
    w0, w = 2 * np.pi * f0, 2 * np.pi * f
    wd = w0 * np.sqrt(1.0 - zeta**2)
    a = -amplitude * np.cos(lag)
    b = (zeta * w0 * a - amplitude * w * np.sin(lag)) / wd
    transient = np.exp(-zeta * w0 * t) * (a * np.cos(wd * t) + b * np.sin(wd * t))
    return amplitude * np.cos(w * t - lag) + transient


class Oscillator(Model):
    """One point of the membrane as a driven, damped oscillator."""

    name = "oscillator"
    title = "Driven, damped oscillator"
    params = (
        Param("f0", "f<sub>0</sub>", "kHz", 1.0, 0.0, 20.0, lo_open=True, description="natural frequency"),
        Param("zeta", "ζ", "", 0.1, 0.0, 0.95, lo_open=True, description="damping ratio"),
        Param("f", "f", "kHz", 1.0, 0.0, 20.0, lo_open=True, description="drive frequency"),
        Param("x_st", "x<sub>st</sub>", "nm", 25.0, 0.0, 1000.0, lo_open=True, description="static deflection"),
        Param("t", "t", "ms", 0.0, 0.0, 100.0, description="time since the sound began"),
    )
    outputs = (
        Output("X", "amplitude X", "nm", ("f0", "zeta", "f", "x_st"), decimals=2),
        Output("phase", "phase lag φ", "°", ("f0", "zeta", "f"), decimals=1),
        Output("x_now", "displacement x(t)", "nm", ("f0", "zeta", "f", "x_st", "t"), decimals=2),
        Output("gain_curve", "amplitude against frequency", "nm", ("f0", "zeta", "x_st"), decimals=2,
               size=len(CURVE_F)),
        Output("ring", "motion from rest", "nm", ("f0", "zeta", "f", "x_st"), decimals=2, size=len(RING_T)),
    )

    def _evaluate(self, x, wanted, effects):
        f0, zeta, f, x_st = x["f0"], x["zeta"], x["f"], x["x_st"]
        grid = lambda values: np.asarray(values)  # noqa: E731 - a trailing axis for the vector outputs
        values = {
            "X": lambda: steady(f0, zeta, f, x_st)[0],
            "phase": lambda: np.degrees(steady(f0, zeta, f, x_st)[1]),
            "x_now": lambda: from_rest(f0, zeta, f, x_st, x["t"]),
            "gain_curve": lambda: steady(f0[..., None], zeta[..., None], grid(CURVE_F), x_st[..., None])[0],
            "ring": lambda: from_rest(f0[..., None], zeta[..., None], f[..., None], x_st[..., None], grid(RING_T)),
        }
        return {name: values[name]() for name in wanted}
