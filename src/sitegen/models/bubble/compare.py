"""The bubble's run against its reference: the largest difference in R/R0, and the outputs whose
shown digits differ (wrong, or near a rounding boundary the run's error may cross).
"""

from __future__ import annotations

import numpy as np

from ...compute.quantize import shown_integers
from ...physics.base import Output
from .point import read_run
from .run import Run
from .terms import Problem


def shown_difference(
    mine: dict, theirs: dict, prefix: str, error: float, outputs: tuple[Output, ...]
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The `outputs` (`prefix`_key) whose displayed values differ between two read runs: those that are wrong,
    and those where the reference lies within the run's measured `error` (relative, at least 1e-12) of a
    rounding boundary, where the run cannot be expected to show the reference's digit.

    Labels must match exactly (the solver's label names the method, so it is left out); a number is
    compared at its displayed digits, element by element for the figure's arrays. `outputs` are the model's
    declared outputs, passed in because the model imports this module.
    """
    wrong, near = [], []
    for key, theirs_value in theirs.items():
        name = f"{prefix}_{key}"
        output = next((o for o in outputs if o.name == name), None) if key != "solver" else None
        if output is None:
            continue
        a, b = np.atleast_1d(np.asarray(mine[key], float)), np.atleast_1d(np.asarray(theirs_value, float))
        if output.labels:
            if not np.array_equal(a, b):
                wrong.append(name)
            continue
        unit = _last_digit(b, output)
        differs = _shown(a, unit) != _shown(b, unit)
        if len(a) != len(b) or np.any(differs & ~(np.isfinite(a) & np.isfinite(b))):
            wrong.append(name)
            continue
        # distance of the reference from the nearest rounding boundary (in the displayed unit's halves)
        with np.errstate(invalid="ignore"):  # inf and NaN entries are equal here (differs is False)
            boundary = np.abs(np.abs(b / unit - np.floor(b / unit)) - 0.5) * unit
        close = boundary <= max(error, 1e-12) * np.maximum(np.abs(b), 1.0)
        if np.any(differs & ~close):
            wrong.append(name)
        elif np.any(differs):
            near.append(name)
    return tuple(wrong), tuple(near)


def _last_digit(values: np.ndarray, output: Output):
    """The unit of the last displayed digit: 10**-decimals, or, shown to significant digits, per value."""
    if not output.digits:
        return 10.0**-output.decimals
    with np.errstate(divide="ignore", invalid="ignore"):
        lead = np.floor(np.log10(np.abs(values)))
    return 10.0 ** np.where(np.isfinite(lead), lead - (output.digits - 1), 0.0)


def _shown(values: np.ndarray, unit) -> np.ndarray:
    """Values as the page shows them: counts of the displayed unit (a power of ten, per value or for all),
    rounded by the pages' one rule (ties away from zero); inf and NaN kept apart."""
    finite = np.isfinite(values)
    kept = np.where(finite, values, 0.0)
    powers = np.broadcast_to(-np.rint(np.log10(unit)).astype(np.int64), values.shape)
    counts = np.zeros(values.shape)
    for power in np.unique(powers):
        counts = np.where(powers == power, shown_integers(kept, int(power)), counts)
    return np.where(finite, counts, np.where(np.isnan(values), -1.5, np.sign(values) * 0.5))


def run_difference(run: Run, reference: Run, pb: Problem, scales, effects) -> float:
    """max |ΔR|/R0 between two runs over the samples both reached and the extrema read from them;
    inf when they ended differently (one stopped at an event the other did not reach)."""
    if run.status != reference.status:
        return np.inf
    both = np.isfinite(run.r) & np.isfinite(reference.r)
    worst = float(np.max(np.abs(run.r[both] - reference.r[both]), initial=0.0))
    mine, theirs = read_run(run, pb, scales, effects), read_run(reference, pb, scales, effects)
    for key in ("R_max", "R_min", "R_max2", "R_min2"):
        if np.isfinite(mine[key]) != np.isfinite(theirs[key]):
            return np.inf
        if np.isfinite(mine[key]):
            worst = max(worst, abs(mine[key] - theirs[key]))
    return worst
