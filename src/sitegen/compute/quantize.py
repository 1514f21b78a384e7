"""Numbers as the page shows them: integers counting units of the last displayed digit."""
from __future__ import annotations

import numpy as np

MINUS = "\u2212"
SPECIAL = np.iinfo(np.int64).min  # marks a value the page shows in words (e.g. "∞"); null in JSON


def quantize(values, decimals: int, special: bool = False) -> np.ndarray:
    """Round to `decimals` digits and return the integer count of 10**-decimals units.

    A value that rounds to zero becomes plain 0, so a page never shows "-0.000". With `special`,
    non-finite values (a singularity, or a quantity that does not exist there) become the SPECIAL marker.
    """
    values = np.asarray(values, dtype=float)
    infinite = ~np.isfinite(values) if special else np.zeros(values.shape, bool)
    scaled = np.rint(np.where(infinite, 0.0, values) * 10.0**decimals)
    quanta = scaled.astype(np.int64) + 0  # + 0 folds -0 into 0 (integers carry no sign of zero)
    return np.where(infinite, SPECIAL, quanta)


def format_quantum(quantum: int, decimals: int) -> str:
    """Write an integer count of 10**-decimals units as a decimal string, e.g. (-2333, 3) -> '−2.333'."""
    digits = str(abs(int(quantum))).rjust(decimals + 1, "0")
    body = f"{digits[:-decimals]}.{digits[-decimals:]}" if decimals else digits
    return (MINUS if quantum < 0 else "") + body


def fmt(value: float, decimals: int) -> str:
    """Format one number exactly as the page does."""
    return format_quantum(int(quantize(value, decimals)), decimals)
