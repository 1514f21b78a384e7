"""K4 compiled: the extrema of a window of a solved run (R_max, R_min, the fastest wall) and the folds that
settle ties and NaNs as numpy's argmax/argmin, np.max, np.nanmax and Python's max() settle them."""

from __future__ import annotations

import math

import numpy as np

from ...physics.compiled import kernel
from .kernel_march import CAP_CODE, CORE_CODE, FAILED_CODE, KM_CODE, MACH_CODE, UNBOUNDED_CODE


@kernel
def better(candidate, best, larger):
    """Whether `candidate` replaces `best` as numpy's argmax (larger) or argmin picks: NaN first, ties to the
    earlier."""
    if math.isnan(best):
        return False
    if math.isnan(candidate):
        return True
    return candidate > best if larger else candidate < best


@kernel
def extreme_of(rows, a, b, larger, t, x):
    """Fold the rows of (τ, x) with a ≤ τ ≤ b into the running extreme (t, x); t is NaN while there is none."""
    for i in range(rows.shape[0]):
        if a <= rows[i, 0] <= b and (math.isnan(t) or better(rows[i, 1], x, larger)):
            t, x = rows[i, 0], rows[i, 1]
    return t, x


@kernel
def window(tau, r, v, end, code, maxima, minima, speeds, a, b, tau_end):
    """R_max (τ, r), R_min (τ, r) and max |ṙ| over [a, b]: the events inside, then the window's ends if the
    run covered them, then the stop where it decides; inf where there is no value.

    A run stopped by a guard inside [a, b] has no R_min there (the collapse it was heading into is not
    computed, e.g. the empty collapse stopped at |Ṙ| = c); an abandoned run has no value at all.
    """
    if code == CAP_CODE or code == FAILED_CODE:  # an abandoned run has no value at all
        return math.inf, math.inf, math.inf, math.inf, math.inf
    t_max, r_max = extreme_of(maxima, a, b, True, math.nan, math.nan)
    t_min, r_min = extreme_of(minima, a, b, False, math.nan, math.nan)
    speed, any_speed = math.nan, False
    for i in range(speeds.shape[0]):
        if a <= speeds[i, 0] <= b:
            speed, any_speed = max_nan(speed, abs(speeds[i, 1]), any_speed), True
    n = tau.shape[0]
    first, last = int(np.rint(a / tau_end * (n - 1))), int(np.rint(b / tau_end * (n - 1)))
    if not math.isnan(r[last]):  # the run covered [a, b]: its ends are candidates too
        for k in (first, last):
            if math.isnan(t_max) or better(r[k], r_max, True):
                t_max, r_max = tau[k], r[k]
            if math.isnan(t_min) or better(r[k], r_min, False):
                t_min, r_min = tau[k], r[k]
            speed, any_speed = max_nan(speed, abs(v[k]), any_speed), True
    inside = a <= end[0] <= b
    if inside and code == UNBOUNDED_CODE and (math.isnan(t_max) or better(end[1], r_max, True)):
        t_max, r_max = end[0], end[1]
    if inside and (code == MACH_CODE or code == KM_CODE):
        speed, any_speed = max_nan(speed, abs(end[2]), any_speed), True
    if inside and MACH_CODE <= code <= CORE_CODE:  # a guard stopped the run: the minimum lies beyond it
        t_min = math.nan
    if math.isnan(t_max):
        t_max = r_max = math.inf
    if math.isnan(t_min):
        t_min = r_min = math.inf
    return t_max, r_max, t_min, r_min, speed if any_speed else math.inf


@kernel
def max_nan(a, b, started):
    """np.max's fold: b alone when nothing came before, else the larger, NaN if either is."""
    if not started:
        return b
    if math.isnan(a) or math.isnan(b):
        return math.nan
    return a if a >= b else b


@kernel
def larger_of(best, x):
    """One step of Python's max() over a sequence: x replaces the running value only if it compares larger."""
    return x if x > best else best


@kernel
def nan_max(values, absolute):
    """np.nanmax of the values (or of their sizes): NaN only when every one is NaN."""
    best = math.nan
    for x in values:
        x = abs(x) if absolute else x
        if not math.isnan(x) and (math.isnan(best) or x > best):
            best = x
    return best
