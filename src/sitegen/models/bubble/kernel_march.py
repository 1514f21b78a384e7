"""K4 compiled: a whole run — steps, events located on each step's interpolant, samples on the grid, caps.

The loop of scipy_path.py's `Stepper`, compiled: after each accepted step every event function is
compared at the step's two ends; a sign change in the event's direction is located by Brent's method
on the step's interpolant (DOP853's of order 7, Radau's collocation polynomial), events up to the
first terminal one are recorded, and the grid samples the step covers are read from the interpolant.
Events are rows of a table (kind, level, direction, stop code, record code) built by run.py's `event_table`.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.compiled import kernel
from .kernel_radau import CURRENT_JAC, FACTORISED, H_ABS, HAS_SOL, STATE_SIZE, radau_step
from .kernel_steppers import (
    DOP853_ORDER,
    RADAU_ORDER,
    STAGES,
    dop853_at,
    dop853_dense,
    dop853_step,
    initial_step,
    radau_at,
    set_jacobian,
)
from .kernel_terms import rhs, unpacked

DOP853_METHOD, RADAU_METHOD = 0, 1
G_SPEED, G_ACCELERATION, G_SPEED_LEVEL, G_RADIUS_LEVEL = 0, 1, 2, 3  # g = ṙ, r̈, ṙ − level, r − level
ENDED, FAILED_CODE, CAP_CODE = 0, 1, 2  # the run's end when no terminal event stopped it (else the event's code)
MACH_CODE, KM_CODE, POINT_CODE, CORE_CODE, UNBOUNDED_CODE = range(3, 8)  # the terminal events' codes (run.STATUS_CODES)
ROOT_EPS = 4.0 * np.finfo(np.float64).eps  # Brent's absolute and relative tolerance, as scipy_path's brentq


@kernel
def event_value(p, kind, level, t, r, v):
    """An event function g at (τ, r, ṙ)."""
    if kind == G_SPEED:
        return v
    if kind == G_ACCELERATION:
        return rhs(p, t, r, v)[1]
    if kind == G_SPEED_LEVEL:
        return v - level
    return r - level


@kernel
def interpolate(method, dense, t_old, h, y_old, t):
    """The accepted step's interpolant at t."""
    if method == DOP853_METHOD:
        return dop853_at(dense, t_old, h, y_old, t)
    return radau_at(dense, t_old, h, y_old, t)


@kernel
def event_on_step(p, kind, level, method, dense, t_old, h, y_old, t, count):
    """g on the step's interpolant at t."""
    r, v = interpolate(method, dense, t_old, h, y_old, t)
    if kind == G_ACCELERATION:
        count[0] += 1
    return event_value(p, kind, level, t, r, v)


@kernel
def locate(p, kind, level, method, dense, t_old, h, y_old, a, b, count):
    """The crossing of g in [a, b] by Brent's method; b when the interpolant misses the bracket."""
    fa = event_on_step(p, kind, level, method, dense, t_old, h, y_old, a, count)
    fb = event_on_step(p, kind, level, method, dense, t_old, h, y_old, b, count)
    if fa * fb > 0.0:
        return b
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    x_pre, x_cur, f_pre, f_cur = a, b, fa, fb
    x_blk, f_blk, s_pre, s_cur = 0.0, 0.0, 0.0, 0.0
    for _ in range(100):
        if f_pre != 0.0 and f_cur != 0.0 and (f_pre < 0.0) != (f_cur < 0.0):
            x_blk, f_blk = x_pre, f_pre
            s_pre = s_cur = x_cur - x_pre
        if abs(f_blk) < abs(f_cur):
            x_pre, x_cur, x_blk = x_cur, x_blk, x_cur
            f_pre, f_cur, f_blk = f_cur, f_blk, f_cur
        delta = (ROOT_EPS + ROOT_EPS * abs(x_cur)) / 2.0
        s_bis = (x_blk - x_cur) / 2.0
        if f_cur == 0.0 or abs(s_bis) < delta:
            return x_cur
        if abs(s_pre) > delta and abs(f_cur) < abs(f_pre):
            if x_pre == x_blk:  # secant
                s_try = -f_cur * (x_cur - x_pre) / (f_cur - f_pre)
            else:  # inverse quadratic interpolation
                d_pre = (f_pre - f_cur) / (x_pre - x_cur)
                d_blk = (f_blk - f_cur) / (x_blk - x_cur)
                s_try = -f_cur * (f_blk * d_blk - f_pre * d_pre) / (d_blk * d_pre * (f_blk - f_pre))
            if 2.0 * abs(s_try) < min(abs(s_pre), 3.0 * abs(s_bis) - delta):
                s_pre, s_cur = s_cur, s_try
            else:
                s_pre, s_cur = s_bis, s_bis
        else:
            s_pre, s_cur = s_bis, s_bis
        x_pre, f_pre = x_cur, f_cur
        x_cur += s_cur if abs(s_cur) > delta else (delta if s_bis > 0.0 else -delta)
        f_cur = event_on_step(p, kind, level, method, dense, t_old, h, y_old, x_cur, count)
    return x_cur


@kernel
def record(hits, count, code, t, r, v):
    """Append (code, τ, r, ṙ) to hits, doubling its rows when full; the (possibly new) array."""
    if count >= hits.shape[0]:
        bigger = np.empty((2 * hits.shape[0], 4))
        for i in range(count):  # element by element: see march
            for j in range(4):
                bigger[i, j] = hits[i, j]
        hits = bigger
    hits[count, 0], hits[count, 1], hits[count, 2], hits[count, 3] = code, t, r, v
    return hits


@kernel
def events_of(hits, code, column):
    """The (τ, r) or (τ, ṙ) (column 2 or 3) of the hits recorded with one code, in their order."""
    rows = np.empty((hits.shape[0], 2))
    n = 0
    for i in range(hits.shape[0]):
        if hits[i, 0] == code:
            rows[n, 0], rows[n, 1] = hits[i, 1], hits[i, column]
            n += 1
    return rows[:n].copy()


@kernel
def split_hits(hits, max_code, min_code, speed_code):
    """The maxima and minima (τ, r) and the speed extrema (τ, ṙ) among the hits."""
    return events_of(hits, max_code, 2), events_of(hits, min_code, 2), events_of(hits, speed_code, 3)


@kernel
def march(method, packed, y0, rtol, atol, t_bound, grid, events, max_nfev):
    """Step from y0 at τ = 0 to t_bound with events, samples and the evaluation cap.

    Returns (end code, (τ, r, ṙ) at the end, samples (len(grid) × 2, NaN past the end), hits (rows of
    record code, τ, r, ṙ), right-hand-side evaluations, the events' included).
    """
    p = unpacked(packed)
    count = np.zeros(1, np.int64)  # right-hand-side evaluations: the steppers' and the events'
    y, y_new, f = y0.copy(), np.empty(2), np.empty(2)
    K = np.empty((16, 2))
    # the step's interpolant: DOP853's 7 × 2 coefficients, or Radau's 2 × 3 collocation polynomial
    dense = np.empty((7, 2)) if method == DOP853_METHOD else np.empty((2, 3))
    state, J = np.full(STATE_SIZE, math.nan), np.empty((2, 2))
    inv_real, inv_complex, sol = np.empty((2, 2)), np.empty((2, 2), np.complex128), np.empty(4)
    work, fc = np.empty((6, 3, 2)), np.empty(2, np.complex128)  # Radau's scratch space
    samples = np.full((grid.shape[0], 2), math.nan)
    # Arrays are copied element by element: an array-to-array slice assignment brings in numba's formatting of
    # its shape-mismatch error, which takes seconds to compile into every kernel that reaches it.
    samples[0, 0], samples[0, 1] = y0[0], y0[1]
    hits, n_hits = np.empty((64, 4)), 0
    n_events = events.shape[0]
    g_old, g_new, roots = np.empty(n_events), np.empty(n_events), np.empty(n_events)
    t, next_sample = 0.0, 1
    count[0] += 1
    f[0], f[1] = rhs(p, t, y[0], y[1])
    order = DOP853_ORDER if method == DOP853_METHOD else RADAU_ORDER
    h_abs = initial_step(p, t, y, f, t_bound, order, rtol, atol, count)
    newton_tol = max(10.0 * np.finfo(np.float64).eps / rtol, min(0.03, rtol**0.5))  # Radau's, as scipy sets it
    if method == RADAU_METHOD:
        state[H_ABS], state[HAS_SOL], state[FACTORISED] = h_abs, 0.0, 0.0
        set_jacobian(p, t, y, J)
        state[CURRENT_JAC] = 1.0
    for i in range(n_events):
        g_old[i] = event_value(p, int(events[i, 0]), events[i, 1], t, y[0], y[1])
    end = (t, y[0], y[1])
    while True:
        if count[0] > max_nfev:
            return CAP_CODE, end, samples, hits[:n_hits], count[0]
        t_old = t
        if method == DOP853_METHOD:
            ok, t, h_abs = dop853_step(p, t_old, y, f, h_abs, t_bound, rtol, atol, K, y_new, count)
        else:
            ok, t = radau_step(
                p,
                t_old,
                y,
                f,
                state,
                J,
                inv_real,
                inv_complex,
                sol,
                dense,
                t_bound,
                rtol,
                atol,
                newton_tol,
                y_new,
                work,
                fc,
                count,
            )
        if not ok or not (math.isfinite(y_new[0]) and math.isfinite(y_new[1])):
            return FAILED_CODE, end, samples, hits[:n_hits], count[0]
        h = t - t_old
        if method == DOP853_METHOD:
            f[0], f[1] = K[STAGES, 0], K[STAGES, 1]
        else:
            count[0] += 1
            f[0], f[1] = rhs(p, t, y_new[0], y_new[1])
        crossed = False
        for i in range(n_events):
            kind, direction = int(events[i, 0]), events[i, 2]
            if kind == G_ACCELERATION:  # r̈ at the step's end is f[1], just computed
                g_new[i] = f[1]
            else:
                g_new[i] = event_value(p, kind, events[i, 1], t, y_new[0], y_new[1])
            a, b = g_old[i], g_new[i]
            rising, falling = a <= 0.0 <= b and a != b, a >= 0.0 >= b and a != b
            roots[i] = 0.0 if (rising and direction >= 0) or (falling and direction <= 0) else math.nan
            crossed = crossed or roots[i] == 0.0
        if method == DOP853_METHOD and (crossed or (next_sample < grid.shape[0] and grid[next_sample] <= t)):
            dop853_dense(p, t_old, h, y, y_new, K, dense, count)  # only when an event or a sample needs it
        stop, stop_t = -1, t
        for i in range(n_events):
            if not math.isnan(roots[i]):
                roots[i] = locate(p, int(events[i, 0]), events[i, 1], method, dense, t_old, h, y, t_old, t, count)
                if events[i, 3] > 0 and (stop < 0 or roots[i] < stop_t):
                    stop, stop_t = i, roots[i]
        for i in range(n_events):
            if not math.isnan(roots[i]) and events[i, 4] > 0 and (stop < 0 or roots[i] <= stop_t):
                r, v = interpolate(method, dense, t_old, h, y, roots[i])
                hits = record(hits, n_hits, events[i, 4], roots[i], r, v)
                n_hits += 1
        while next_sample < grid.shape[0] and grid[next_sample] <= stop_t:
            samples[next_sample, 0], samples[next_sample, 1] = interpolate(
                method, dense, t_old, h, y, grid[next_sample]
            )
            next_sample += 1
        if stop >= 0:
            r, v = interpolate(method, dense, t_old, h, y, stop_t)
            return int(events[stop, 3]), (stop_t, r, v), samples, hits[:n_hits], count[0]
        y[0], y[1] = y_new[0], y_new[1]
        end = (t, y[0], y[1])
        if t >= t_bound:
            return ENDED, end, samples, hits[:n_hits], count[0]
        for i in range(n_events):
            g_old[i] = g_new[i]
