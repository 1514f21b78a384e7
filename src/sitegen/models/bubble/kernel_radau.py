"""K4 compiled: one step of Radau IIA (order 5) with the analytic Jacobian, as scipy's Radau takes it.

The stepper's memory between steps lives in small arrays: `state` holds [h_abs, h_abs_old,
error_norm_old, current_jac, factorised] (NaN for "none yet"), J the Jacobian, the inverses of the
two iteration matrices, and the previous step's collocation polynomial (`sol`: t_old, h, y_old and
Q), from which each step's Newton iteration starts.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.compiled import kernel
from .kernel_steppers import (
    MAX_FACTOR,
    MIN_FACTOR,
    MU_COMPLEX,
    MU_REAL,
    NEWTON_MAXITER,
    RADAU_C,
    RADAU_E,
    RADAU_P,
    RADAU_T,
    RADAU_TI,
    min_step,
    radau_at,
    radau_inverses,
    set_jacobian,
    times,
)
from .kernel_terms import rhs

H_ABS, H_ABS_OLD, ERROR_OLD, CURRENT_JAC, FACTORISED, HAS_SOL = range(6)
STATE_SIZE = 6


@kernel
def predict_factor(h_abs, h_abs_old, error_norm, error_norm_old):
    """The step-size factor of Gustafsson's predictive controller (scipy's predict_factor)."""
    if math.isnan(error_norm_old) or math.isnan(h_abs_old) or error_norm == 0.0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (error_norm_old / error_norm) ** 0.25
    return min(1.0, multiplier) * error_norm**-0.25


@kernel
def newton(p, t, y, h, Z, scale, tol, inv_real, inv_complex, work, fc, count):
    """The simplified Newton iteration of the collocation system; Z holds the start and the result.

    `work` (rows 3 to 5 and row 2's second pair) and the complex pair `fc` are its scratch space.
    Returns (converged, iterations, rate of convergence or NaN).
    """
    W, F, dW, fr = work[3], work[4], work[5], work[2, 1]
    times(RADAU_TI, Z, W)
    m_real, m_complex = MU_REAL / h, MU_COMPLEX / h
    norm_old, rate = math.nan, math.nan
    for k in range(NEWTON_MAXITER):
        for i in range(3):
            count[0] += 1
            F[i, 0], F[i, 1] = rhs(p, t + h * RADAU_C[i], y[0] + Z[i, 0], y[1] + Z[i, 1])
        finite = True  # np.all(np.isfinite(F)), without compiling numpy's array expressions
        for i in range(3):
            finite = finite and math.isfinite(F[i, 0]) and math.isfinite(F[i, 1])
        if not finite:
            return False, k + 1, rate
        for j in range(2):
            fr[j] = F[0, j] * RADAU_TI[0, 0] + F[1, j] * RADAU_TI[0, 1] + F[2, j] * RADAU_TI[0, 2] - m_real * W[0, j]
            re = F[0, j] * RADAU_TI[1, 0] + F[1, j] * RADAU_TI[1, 1] + F[2, j] * RADAU_TI[1, 2]
            im = F[0, j] * RADAU_TI[2, 0] + F[1, j] * RADAU_TI[2, 1] + F[2, j] * RADAU_TI[2, 2]
            fc[j] = (re + 1j * im) - m_complex * (W[1, j] + 1j * W[2, j])
        for j in range(2):
            dW[0, j] = inv_real[j, 0] * fr[0] + inv_real[j, 1] * fr[1]
            z = inv_complex[j, 0] * fc[0] + inv_complex[j, 1] * fc[1]
            dW[1, j], dW[2, j] = z.real, z.imag
        total = 0.0
        for i in range(3):
            for j in range(2):
                total += (dW[i, j] / scale[j]) ** 2
        dw_norm = math.sqrt(total / 6.0)
        if not math.isnan(norm_old):
            rate = dw_norm / norm_old
        if not math.isnan(rate) and (rate >= 1.0 or rate ** (NEWTON_MAXITER - k) / (1.0 - rate) * dw_norm > tol):
            return False, k + 1, rate
        W += dW
        times(RADAU_T, W, Z)
        if dw_norm == 0.0 or (not math.isnan(rate) and rate / (1.0 - rate) * dw_norm < tol):
            return True, k + 1, rate
        norm_old = dw_norm
    return False, NEWTON_MAXITER, rate


@kernel
def radau_step(
    p, t, y, f, state, J, inv_real, inv_complex, sol, Q, t_bound, rtol, atol, newton_tol, y_new, work, fc, count
):
    """One accepted Radau step from (t, y) into y_new; updates the stepper's memory and the interpolant.

    `work` (6 × 3 × 2) and `fc` (2, complex) are scratch space, made once per run rather than at every step
    (every entry is written before it is read). Returns (accepted, t_new); not accepted means the step size
    underflowed.
    """
    h_abs, h_abs_old, error_old = state[H_ABS], state[H_ABS_OLD], state[ERROR_OLD]
    if h_abs < min_step(t):
        h_abs, h_abs_old, error_old = min_step(t), math.nan, math.nan
    Z, start, scale = work[0], work[1], work[2, 0]
    rejected = False
    while True:
        if h_abs < min_step(t):
            return False, t
        t_new = min(t + h_abs, t_bound)
        h = t_new - t
        h_abs = abs(h)
        for i in range(3):
            if state[HAS_SOL]:
                Z[i, 0], Z[i, 1] = radau_at(Q, sol[0], sol[1], sol[2:4], t + h * RADAU_C[i])
                Z[i, 0], Z[i, 1] = Z[i, 0] - y[0], Z[i, 1] - y[1]
            else:
                Z[i, 0], Z[i, 1] = 0.0, 0.0
        for i in range(3):
            start[i, 0], start[i, 1] = Z[i, 0], Z[i, 1]
        scale[0], scale[1] = atol + abs(y[0]) * rtol, atol + abs(y[1]) * rtol
        while True:
            if not state[FACTORISED]:
                radau_inverses(h, J, inv_real, inv_complex)
                state[FACTORISED] = 1.0
            for i in range(3):  # element by element: see kernel_march.march
                Z[i, 0], Z[i, 1] = start[i, 0], start[i, 1]
            converged, iterations, rate = newton(
                p, t, y, h, Z, scale, newton_tol, inv_real, inv_complex, work, fc, count
            )
            if converged or state[CURRENT_JAC]:
                break
            set_jacobian(p, t, y, J)
            state[CURRENT_JAC], state[FACTORISED] = 1.0, 0.0
        if not converged:
            h_abs *= 0.5
            state[FACTORISED] = 0.0
            continue
        y_new[0], y_new[1] = y[0] + Z[2, 0], y[1] + Z[2, 1]
        error_norm, e0, e1 = radau_error(Z, h, f, y, y_new, inv_real, rtol, atol)
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + iterations)
        if rejected and error_norm > 1.0:
            count[0] += 1
            g0, g1 = rhs(p, t, y[0] + e0, y[1] + e1)
            error_norm, e0, e1 = radau_error(Z, h, np.array([g0, g1]), y, y_new, inv_real, rtol, atol)
        if error_norm > 1.0:
            factor = predict_factor(h_abs, h_abs_old, error_norm, error_old)
            h_abs *= max(MIN_FACTOR, safety * factor)
            state[FACTORISED] = 0.0
            rejected = True
            continue
        break
    recompute_jac = iterations > 2 and rate > 1e-3
    factor = min(MAX_FACTOR, safety * predict_factor(h_abs, h_abs_old, error_norm, error_old))
    if not recompute_jac and factor < 1.2:
        factor = 1.0
    else:
        state[FACTORISED] = 0.0
    if recompute_jac:
        set_jacobian(p, t_new, y_new, J)
    state[CURRENT_JAC] = 1.0 if recompute_jac else 0.0
    state[H_ABS_OLD], state[ERROR_OLD], state[H_ABS] = state[H_ABS], error_norm, h_abs * factor
    times(Z.T, RADAU_P, Q)
    sol[0], sol[1], sol[2], sol[3] = t, h, y[0], y[1]
    state[HAS_SOL] = 1.0
    return True, t_new


@kernel
def radau_error(Z, h, f, y, y_new, inv_real, rtol, atol):
    """Radau's error estimate (its norm and components) from the collocation solution."""
    ze0 = (Z[0, 0] * RADAU_E[0] + Z[1, 0] * RADAU_E[1] + Z[2, 0] * RADAU_E[2]) / h
    ze1 = (Z[0, 1] * RADAU_E[0] + Z[1, 1] * RADAU_E[1] + Z[2, 1] * RADAU_E[2]) / h
    b0, b1 = f[0] + ze0, f[1] + ze1
    e0, e1 = inv_real[0, 0] * b0 + inv_real[0, 1] * b1, inv_real[1, 0] * b0 + inv_real[1, 1] * b1
    s0 = atol + max(abs(y[0]), abs(y_new[0])) * rtol
    s1 = atol + max(abs(y[1]), abs(y_new[1])) * rtol
    return math.sqrt(((e0 / s0) ** 2 + (e1 / s1) ** 2) / 2.0), e0, e1
