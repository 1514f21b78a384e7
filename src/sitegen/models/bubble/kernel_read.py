"""K4 compiled: one solved run read into every dynamic output, as a row of floats (behind point.read_run).

Compiled so that a scene's stops cost their solve and little else: the extrema of each window from the
events and the window's ends, the model check, the Blake verdict, the gas at the minimum, the figure's
curve (grid samples with the visible extrema and the stop merged in), its marks, and why a number is
missing. Runs of both solving paths are read here. Ties and NaNs are settled as numpy and Python settle
them (argmax: the first maximum, a NaN first; max(): a later value only if larger), and every formula keeps
the order of operations of the numpy reading it replaced, so the tables did not change by a bit.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.compiled import kernel
from .kernel_extrema import larger_of, nan_max, window
from .kernel_march import CAP_CODE, FAILED_CODE, MACH_CODE, UNBOUNDED_CODE

CURVE_EXTREMA = 200  # event-detected extrema merged into the drawn curve (the deepest, if more)
CURVE_GAP = 1e-3  # the drawn curve's resolution in y (its 3 decimals): extrema closer to the chord add nothing

# The reading vector of a point (point.reading): its window, terms, figure axes, Blake point and units.
(
    Q_TAU_END,
    Q_PART,
    Q_SOUND,
    Q_INVALID_SPEED,
    Q_ETA,
    Q_E3,
    Q_GAS,
    Q_KAPPA,
    Q_RAMP_TO,
    Q_Y_KIND,
    Q_Y_SCALE,
    Q_T_REF,
    Q_X_UNIT,
    Q_R_B,
    Q_P_BLAKE,
    Q_P0,
    Q_T0,
) = range(17)
READING_SIZE = 17
Y_PLAIN, Y_LOG, Y_LOG_BLAKE = 0.0, 1.0, 2.0  # the figure's y: R/R0, log10(R/R0), log10(R/R_B)

# The row: scalars, then why each number of WHY_OF is missing, the marks, the stop, and the curve.
SCALARS = (
    "R_max",
    "t_Rmax",
    "R_min",
    "t_Rmin",
    "mach",
    "R_max2",
    "R_min2",
    "flag",
    "growth",
    "pg_peak",
    "Tg_peak",
    "Rmin_h",
    "solver",
)
(R_MAX, T_RMAX, R_MIN, T_RMIN, MACH_NO, R_MAX2, R_MIN2, FLAG, GROWTH, PG_PEAK, TG_PEAK, RMIN_H, SOLVER) = range(13)
WHY_OF = (R_MAX, T_RMAX, R_MIN, T_RMIN, MACH_NO, PG_PEAK, TG_PEAK, RMIN_H, R_MAX2, R_MIN2)
WHY, MARK_X, MARK_Y, STOP_X, STOP_Y, CURVE_X = 13, 23, 25, 27, 28, 29
# Why a number has no value (point.MISSING): how the run ended (flags 2..8), or these.
NO_GAS, NO_CORE, NOT_REACHED = 9, 10, 11


@kernel
def flag_of_code(code):
    """point.FLAGS index of how a run ended (0: it reached the end of its window)."""
    if MACH_CODE <= code <= UNBOUNDED_CODE:  # FLAGS 2..6 name the terminal events in their codes' order
        return 2 + code - MACH_CODE
    if code == CAP_CODE:
        return 7
    return 8 if code == FAILED_CODE else 0


@kernel
def to_y(q, r):
    """The figure's radius coordinate of r: R/R0, or a logarithm where radii span decades (driven, ramped)."""
    if q[Q_Y_KIND] == Y_LOG:
        return math.log10(r)
    if q[Q_Y_KIND] == Y_LOG_BLAKE:
        return math.log10(r / q[Q_Y_SCALE])
    return r


@kernel
def to_x(q, tau):
    """Nondimensional time in the figure's unit (as point.Scales.x)."""
    return tau * q[Q_T_REF] / q[Q_X_UNIT]


@kernel
def is_event(t, x, rows, a, b):
    """Whether (t, x) is one of the rows of [a, b] (an extremum found by events, not a window's end)."""
    for i in range(rows.shape[0]):
        if a <= rows[i, 0] <= b and rows[i, 0] == t and rows[i, 1] == x:
            return True
    return False


@kernel
def visible(t, y_event, tau, y, n, spacing):
    """Whether an extremum (t, y) lies farther than CURVE_GAP from the chord between the first n grid samples
    around it (or past the last one, where there is no chord)."""
    left = int(math.floor(t / spacing))
    if left + 1 >= n:
        return True
    chord = y[left] + (y[min(left + 1, n - 1)] - y[left]) * (t - tau[left]) / spacing
    return abs(y_event - chord) > CURVE_GAP


@kernel
def add_visible(q, rows, t_stop, tau, y, n, spacing, t_out, y_out, count):
    """Append the rows (τ, r) up to t_stop that are visible (as (τ, y)) to t_out, y_out after `count`; the new count."""
    for i in range(rows.shape[0]):
        if rows[i, 0] <= t_stop:
            y_row = to_y(q, rows[i, 1])
            if visible(rows[i, 0], y_row, tau, y, n, spacing):
                t_out[count], y_out[count] = rows[i, 0], y_row
                count += 1
    return count


@kernel
def deepest(depth, count):
    """Which entries np.argsort(−depth, kind="stable")[:count] keeps: the deepest, ties to the earlier, NaN last."""
    n = depth.shape[0]
    keep, finite, nans = np.zeros(n, np.bool_), 0, 0
    for j in range(n):
        finite += 0 if math.isnan(depth[j]) else 1
    for i in range(n):
        if math.isnan(depth[i]):
            rank, nans = finite + nans, nans + 1
        else:
            rank = 0
            for j in range(n):
                rank += 1 if depth[j] > depth[i] or (depth[j] == depth[i] and j < i) else 0
        keep[i] = rank < count
    return keep


@kernel
def sort_by_time(t, y, n):
    """Sort the first n (t, y) by t, ties kept in order (as a stable sort; a few hundred extrema at most)."""
    for k in range(1, n):
        t_k, y_k, j = t[k], y[k], k - 1
        while j >= 0 and t[j] > t_k:
            t[j + 1], y[j + 1] = t[j], y[j]
            j -= 1
        t[j + 1], y[j + 1] = t_k, y_k


@kernel
def curve(q, tau, r, end, code, maxima, minima, out_x, out_y):
    """The drawn curve into out_x, out_y (left NaN past its end): the reached samples, the visible extrema up to the
    stop (the deepest CURVE_EXTREMA) and a terminal stop, in time order, one point per time.

    Grid samples alone miss a violent collapse (in preset B they bottom out near 0.5 R0 while the event-detected
    minimum is 0.176 R0), so the curve passes through the events; but an extremum joins it only where the line
    through the samples would miss it by more than the drawing's resolution. That keeps the curve well defined:
    where R(t) is quasi-static, ringing far below the resolution makes tiny extrema (about 1e-10 R0) whose number
    and times differ between any two solvers, and merging them would shift every later point of the curve.
    """
    t_grid, y_grid, n_grid = np.empty(tau.shape[0]), np.empty(tau.shape[0]), 0
    for k in range(tau.shape[0]):
        if math.isfinite(r[k]):
            t_grid[n_grid], y_grid[n_grid] = tau[k], to_y(q, r[k])
            n_grid += 1
    spacing = tau[1] - tau[0]
    t_ext, y_ext = np.empty(maxima.shape[0] + minima.shape[0]), np.empty(maxima.shape[0] + minima.shape[0])
    n_ext = add_visible(q, maxima, end[0], t_grid, y_grid, n_grid, spacing, t_ext, y_ext, 0)
    n_ext = add_visible(q, minima, end[0], t_grid, y_grid, n_grid, spacing, t_ext, y_ext, n_ext)
    if n_ext > CURVE_EXTREMA:  # the deepest, in their order
        keep, kept = deepest(np.abs(y_ext[:n_ext] - y_grid[0]), CURVE_EXTREMA), 0
        for i in range(n_ext):
            if keep[i]:
                t_ext[kept], y_ext[kept] = t_ext[i], y_ext[i]
                kept += 1
        n_ext = kept
    sort_by_time(t_ext, y_ext, n_ext)
    # Merge in time order, samples before extrema before the stop at one time (a stable sort of them all),
    # keeping the first point of each time.
    stop = 1 if MACH_CODE <= code <= UNBOUNDED_CODE else 0
    i, j, n, previous = 0, 0, 0, 0.0
    while i < n_grid or j < n_ext or stop:
        if i < n_grid and (j >= n_ext or t_grid[i] <= t_ext[j]) and (not stop or t_grid[i] <= end[0]):
            t, y, i = t_grid[i], y_grid[i], i + 1
        elif j < n_ext and (not stop or t_ext[j] <= end[0]):
            t, y, j = t_ext[j], y_ext[j], j + 1
        else:
            t, y, stop = end[0], to_y(q, end[1]), 0
        if n == 0 or t > previous:
            out_x[n], out_y[n] = to_x(q, t), y
            n += 1
        previous = t


@kernel
def flag(q, v, code, speeds):
    """point.FLAGS index: how the run ended, or invalid if the incompressible wall passed 0.2c (Q_INVALID_SPEED)."""
    if code != UNBOUNDED_CODE and flag_of_code(code) > 0:
        return flag_of_code(code)
    fastest = nan_max(v, True)  # Python's max over the speed extrema's sizes, then this
    if speeds.shape[0]:
        best = abs(speeds[0, 1])
        for i in range(1, speeds.shape[0]):
            best = larger_of(best, abs(speeds[i, 1]))
        fastest = larger_of(best, fastest)
    if fastest > q[Q_INVALID_SPEED]:
        return 1
    return flag_of_code(code)


@kernel
def blake_state(q, r, end, code, maxima):
    """point.BLAKE_LABELS index: the verdict on the nucleus at the end of the ramp and hold.

    A large nucleus grows slowly: within the hold it may not reach R_B even beyond the threshold, so the
    verdict reads the end of the run too (R > R_B and Ṙ > 0: past the unstable size, it goes on growing)
    and, below R_B, whether any size is in equilibrium at the final pressure (beyond the threshold, none
    is: a pressure below p_Blake pulls every nucleus open, however slowly).
    """
    if code == UNBOUNDED_CODE:
        return 4
    if end[1] > q[Q_R_B] and end[2] > 0.0:
        return 2
    if q[Q_RAMP_TO] < q[Q_P_BLAKE]:
        return 3
    largest = nan_max(r, False)  # Python's max over this, then the maxima
    for i in range(maxima.shape[0]):
        largest = larger_of(largest, maxima[i, 1])
    return 1 if largest > q[Q_R_B] else 0


@kernel
def gas_peaks(q, r_min):
    """Peak gas pressure (GPa), adiabatic temperature (K) and R_min/h at the minimum radius."""
    found = math.isfinite(r_min)
    ratio = r_min / q[Q_ETA] if found and q[Q_ETA] != 0.0 else math.inf
    if not (found and q[Q_GAS] != 0.0):
        return math.inf, math.inf, ratio
    e3 = q[Q_E3]
    compression = (1.0 - e3) / (r_min**3.0 - e3)
    return q[Q_GAS] * compression ** q[Q_KAPPA] * q[Q_P0] * 1e-9, q[Q_T0] * compression ** (q[Q_KAPPA] - 1.0), ratio


@kernel
def read(q, tau, r, v, end, code, maxima, minima, speeds):
    """Every dynamic output of one run as a row (the layout above; the solver's label is left to the caller)."""
    size = tau.shape[0] + CURVE_EXTREMA + 1  # the curve: samples, merged extrema and the stop
    row = np.empty(CURVE_X + 2 * size)
    row[:] = math.nan
    tau_end, part = q[Q_TAU_END], q[Q_PART]
    t_max, r_max, t_min, r_min, speed = window(tau, r, v, end, code, maxima, minima, speeds, 0.0, part, tau_end)
    row[R_MAX], row[T_RMAX], row[R_MIN], row[T_RMIN] = r_max, to_x(q, t_max), r_min, to_x(q, t_min)
    row[MACH_NO] = speed / q[Q_SOUND]
    second = window(tau, r, v, end, code, maxima, minima, speeds, part, tau_end, tau_end)
    row[R_MAX2], row[R_MIN2] = second[1], second[3]
    row[FLAG], row[GROWTH] = flag(q, v, code, speeds), blake_state(q, r, end, code, maxima)
    row[PG_PEAK], row[TG_PEAK], row[RMIN_H] = gas_peaks(q, r_min)
    ended = row[FLAG] if row[FLAG] >= 2 else NOT_REACHED
    for i in range(len(WHY_OF)):
        key = WHY_OF[i]
        reason = 0.0 if math.isfinite(row[key]) else ended
        if reason and math.isfinite(row[R_MIN]):  # the minimum exists: the quantity needs what is missing
            reason = NO_CORE if key == RMIN_H else NO_GAS if key == PG_PEAK or key == TG_PEAK else reason
        row[WHY + i] = reason
    if MACH_CODE <= code <= UNBOUNDED_CODE:
        row[STOP_X], row[STOP_Y] = to_x(q, end[0]), to_y(q, end[1])
    marked = 0  # the R_max and R_min dots: extrema found by events, after the start
    for t, x in ((t_max, r_max), (t_min, r_min)):
        if t > 0 and (is_event(t, x, maxima, 0.0, part) or is_event(t, x, minima, 0.0, part)):
            row[MARK_X + marked], row[MARK_Y + marked] = to_x(q, t), to_y(q, x)
            marked += 1
    curve(q, tau, r, end, code, maxima, minima, row[CURVE_X : CURVE_X + size], row[CURVE_X + size :])
    return row
