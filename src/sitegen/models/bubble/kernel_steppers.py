"""K4 compiled: one step of DOP853 (non-stiff) or of Radau IIA order 5 (stiff), with their dense output.

Both follow scipy's solvers (integrate/_ivp: rk.py and radau.py): the same tableaux (DOP853's in
kernel_dop853.py, as Hairer publishes them), the same error estimators, step-size control, initial step and dense
output, specialised to the bubble's two-component state. Radau's Newton iteration uses the analytic
Jacobian of the composed right-hand side; its 2×2 real and complex systems are solved in closed form.
`count[0]` counts right-hand-side evaluations.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.compiled import kernel
from .kernel_dop853 import E3, E5, STAGES, A, B, C, D
from .kernel_terms import jacobian, rhs

SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
DOP853_ORDER = 7  # of its error estimator: sets the step-size exponent and the initial step

# Radau IIA of order 5 (three stages): its nodes, error estimator, the eigenvalues of the inverse of its
# coefficient matrix (one real, a complex pair) and the eigenvector basis T, as E. Hairer and G. Wanner give them in
# Solving Ordinary Differential Equations II, 2nd ed., Springer 1996, section IV.8, and in their code RADAU5.
S6 = 6**0.5
RADAU_C = np.array([(4 - S6) / 10, (4 + S6) / 10, 1.0])
RADAU_E = np.array([-13 - 7 * S6, -13 + 7 * S6, -1.0]) / 3
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
MU_COMPLEX = (3 + 0.5 * (3 ** (1 / 3) - 3 ** (2 / 3))) - 0.5j * (3 ** (5 / 6) + 3 ** (7 / 6))
# T and its inverse: the eigenvector basis that splits the collocation system into a real and a complex one.
RADAU_T = np.array(
    [
        [0.09443876248897524, -0.14125529502095421, 0.03002919410514742],
        [0.25021312296533332, 0.20412935229379994, -0.38294211275726192],
        [1.0, 1.0, 0.0],
    ]
)
RADAU_TI = np.array(
    [
        [4.17871859155190428, 0.32768282076106237, 0.52337644549944951],  # T⁻¹, as published
        [-4.17871859155190428, -0.32768282076106237, 0.47662355450055044],
        [0.50287263494578682, -2.57192694985560522, 0.59603920482822492],
    ]
)
RADAU_P = np.array(
    [
        [13 / 3 + 7 * S6 / 3, -23 / 3 - 22 * S6 / 3, 10 / 3 + 5 * S6],
        [13 / 3 - 7 * S6 / 3, -23 / 3 + 22 * S6 / 3, 10 / 3 - 5 * S6],
        [1 / 3, -8 / 3, 10 / 3],
    ]
)
NEWTON_MAXITER = 6
RADAU_ORDER = 3  # the initial step's order, as scipy's Radau uses


@kernel
def rms(a, b):
    """The RMS norm of a two-component vector."""
    return math.sqrt((a * a + b * b) / 2.0)


@kernel
def initial_step(p, t, y, f, t_bound, order, rtol, atol, count):
    """scipy's select_initial_step for a two-component state."""
    length = t_bound - t
    s0, s1 = atol + abs(y[0]) * rtol, atol + abs(y[1]) * rtol
    d0, d1 = rms(y[0] / s0, y[1] / s1), rms(f[0] / s0, f[1] / s1)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, length)
    count[0] += 1
    g0, g1 = rhs(p, t + h0, y[0] + h0 * f[0], y[1] + h0 * f[1])
    d2 = rms((g0 - f[0]) / s0, (g1 - f[1]) / s1) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100.0 * h0, h1, length)


@kernel
def min_step(t):
    """Ten spacings of floating-point numbers at t: below this a step has failed."""
    return 10.0 * abs(np.nextafter(t, np.inf) - t)


@kernel
def dop853_stages(p, t, y, h, K, first, last, count):
    """Stages first..last-1 of the extended tableau into K (K[0] and earlier stages already set)."""
    for s in range(first, last):
        dy0, dy1 = 0.0, 0.0
        for j in range(s):
            dy0 += K[j, 0] * A[s, j]
            dy1 += K[j, 1] * A[s, j]
        count[0] += 1
        K[s, 0], K[s, 1] = rhs(p, t + C[s] * h, y[0] + dy0 * h, y[1] + dy1 * h)


@kernel
def dop853_step(p, t, y, f, h_abs, t_bound, rtol, atol, K, y_new, count):
    """One accepted DOP853 step from (t, y); fills y_new and K (K[12] = f at the end).

    Returns (accepted, t_new, h_abs for the next step); not accepted means the step size underflowed.
    """
    exponent = -1.0 / (DOP853_ORDER + 1)
    h_abs = max(h_abs, min_step(t))
    rejected = False
    while True:
        if h_abs < min_step(t):
            return False, t, h_abs
        t_new = min(t + h_abs, t_bound)
        h = t_new - t
        h_abs = abs(h)
        K[0, 0], K[0, 1] = f[0], f[1]
        dop853_stages(p, t, y, h, K, 1, STAGES, count)
        b0, b1 = 0.0, 0.0
        for j in range(STAGES):
            b0 += K[j, 0] * B[j]
            b1 += K[j, 1] * B[j]
        y_new[0], y_new[1] = y[0] + h * b0, y[1] + h * b1
        count[0] += 1
        K[STAGES, 0], K[STAGES, 1] = rhs(p, t_new, y_new[0], y_new[1])
        error = dop853_error(K, h, y, y_new, rtol, atol)
        if error < 1.0:
            factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error**exponent)
            if rejected:
                factor = min(1.0, factor)
            return True, t_new, h_abs * factor
        factor = SAFETY * error**exponent
        h_abs *= factor if factor > MIN_FACTOR else MIN_FACTOR  # a NaN error shrinks by MIN_FACTOR
        rejected = True


@kernel
def dop853_error(K, h, y, y_new, rtol, atol):
    """DOP853's error norm: the fifth-order estimate, corrected by the third-order one."""
    n5, n3 = 0.0, 0.0
    for i in range(2):
        scale = atol + max(abs(y[i]), abs(y_new[i])) * rtol
        e5, e3 = 0.0, 0.0
        for j in range(STAGES + 1):
            e5 += K[j, i] * E5[j]
            e3 += K[j, i] * E3[j]
        n5 += (e5 / scale) ** 2
        n3 += (e3 / scale) ** 2
    if n5 == 0.0 and n3 == 0.0:
        return 0.0
    return abs(h) * n5 / math.sqrt((n5 + 0.01 * n3) * 2.0)


@kernel
def dop853_dense(p, t_old, h, y_old, y, K, F, count):
    """The step's interpolant (order 7) into F (7 × 2), after three more stages."""
    dop853_stages(p, t_old, y_old, h, K, STAGES + 1, 16, count)
    for i in range(2):
        delta = y[i] - y_old[i]
        F[0, i] = delta
        F[1, i] = h * K[0, i] - delta
        F[2, i] = 2.0 * delta - h * (K[STAGES, i] + K[0, i])
        for row in range(4):
            total = 0.0
            for j in range(16):
                total += D[row, j] * K[j, i]
            F[3 + row, i] = h * total


@kernel
def dop853_at(F, t_old, h, y_old, t):
    """The DOP853 interpolant at t: (r, ṙ)."""
    x = (t - t_old) / h
    out0, out1 = 0.0, 0.0
    for k in range(7):
        row = 6 - k
        out0 += F[row, 0]
        out1 += F[row, 1]
        if k % 2 == 0:
            out0 *= x
            out1 *= x
        else:
            out0 *= 1.0 - x
            out1 *= 1.0 - x
    return out0 + y_old[0], out1 + y_old[1]


@kernel
def radau_at(Q, t_old, h, y_old, t):
    """Radau's collocation polynomial at t: (r, ṙ)."""
    x = (t - t_old) / h
    out0, out1, power = 0.0, 0.0, 1.0
    for k in range(3):
        power *= x
        out0 += Q[0, k] * power
        out1 += Q[1, k] * power
    return out0 + y_old[0], out1 + y_old[1]


@kernel
def radau_inverses(h, J, inv_real, inv_complex):
    """Inverses of (MU_REAL/h) I − J and (MU_COMPLEX/h) I − J (2 × 2, in closed form)."""
    a, b, c, d = MU_REAL / h - J[0, 0], -J[0, 1], -J[1, 0], MU_REAL / h - J[1, 1]
    det = a * d - b * c
    inv_real[0, 0], inv_real[0, 1], inv_real[1, 0], inv_real[1, 1] = d / det, -b / det, -c / det, a / det
    za, zd = MU_COMPLEX / h - J[0, 0], MU_COMPLEX / h - J[1, 1]
    zb, zc = -J[0, 1] + 0j, -J[1, 0] + 0j
    zdet = za * zd - zb * zc
    inv_complex[0, 0], inv_complex[0, 1], inv_complex[1, 0], inv_complex[1, 1] = (
        zd / zdet,
        -zb / zdet,
        -zc / zdet,
        za / zdet,
    )


@kernel
def times(M, X, out):
    """out = M @ X for small matrices, summed in a fixed order (no BLAS: its kernels differ between CPUs)."""
    for i in range(M.shape[0]):
        for j in range(X.shape[1]):
            total = 0.0
            for k in range(M.shape[1]):
                total += M[i, k] * X[k, j]
            out[i, j] = total


@kernel
def set_jacobian(p, t, y, J):
    """J = ∂(ṙ, r̈)/∂(r, ṙ) at (t, y)."""
    J[0, 0], J[0, 1] = 0.0, 1.0
    J[1, 0], J[1, 1] = jacobian(p, t, y[0], y[1])
