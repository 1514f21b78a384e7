"""K4 compiled: the composed right-hand side and its analytic Jacobian, on a packed parameter vector.

The same terms as `terms.make_rhs`, in the same order of operations (so the two agree to the
last bit on the same state), with each term skipped when its coefficient is zero. A Problem is packed
once into a float vector; `rhs` and `jacobian` read it by the indices below.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.compiled import kernel
from .terms import CORE_MARGIN, KELLER_MIKSIS, KM_FLOOR, R_FLOOR, RADIATION, Problem

# Indices into the packed parameter vector. The floors travel in it too: a kernel reads no constant of terms.py,
# whose edits the compiled code's cache key (the kernel files' digest) would not see.
(
    P_INF,
    GAS,
    KAPPA,
    E3,
    VAPOUR,
    SIGMA2,
    VISC4,
    SOUND,
    COMPRESSIBLE,
    DRIVE,
    OMEGA,
    RAMP_TO,
    RAMP_TIME,
    VOLUME_FLOOR,
    RADIUS_FLOOR,
    DENOMINATOR_FLOOR,
) = range(16)
SIZE = 16
PLAIN_FORM, RADIATION_FORM, KM_FORM = 0.0, 1.0, 2.0  # the value at COMPRESSIBLE


def pack(pb: Problem) -> np.ndarray:
    """The parameter vector of a problem (the floors as make_rhs sets them)."""
    e3 = pb.eta**3
    form = {KELLER_MIKSIS: KM_FORM, RADIATION: RADIATION_FORM}.get(pb.compressible, PLAIN_FORM)
    # in the order of the indices above
    return np.array(
        (
            pb.p_inf,
            pb.gas,
            pb.kappa,
            e3,
            pb.vapour,
            2.0 * pb.sigma,
            4.0 * pb.visc,
            pb.sound,
            form,
            pb.drive,
            pb.omega,
            pb.ramp_to,
            pb.ramp_time,
            max(e3 * 3.0 * CORE_MARGIN, R_FLOOR**3),
            R_FLOOR,
            KM_FLOOR,
        ),
        float,
    )


@kernel
def unpacked(values):
    """The parameter vector as a tuple (SIZE floats), which kernels pass to kernels by value: an array
    would take and drop a reference count, two atomic operations, at every call of `rhs`."""
    return (
        values[0],
        values[1],
        values[2],
        values[3],
        values[4],
        values[5],
        values[6],
        values[7],
        values[8],
        values[9],
        values[10],
        values[11],
        values[12],
        values[13],
        values[14],
        values[15],
    )


@kernel
def far_field(p, t):
    """p∞(τ): the ambient or stepped value, the ramp and the drive (make_rhs's far_field)."""
    value = p[P_INF]
    if p[RAMP_TIME] != 0.0:
        value = value + (p[RAMP_TO] - p[P_INF]) * min(t / p[RAMP_TIME], 1.0)
    if p[DRIVE] != 0.0:
        value = value - p[DRIVE] * math.sin(p[OMEGA] * t)
    return value


@kernel
def wall(p, r, v):
    """(p_B, dp_B/dt without its R̈ part, dp_g/dt) at the wall, and their derivatives in r and ṙ.

    Returns p_B, ∂p_B/∂r, ∂p_B/∂ṙ, q, ∂q/∂r, ∂q/∂ṙ, g, ∂g/∂r, ∂g/∂ṙ with q = dp_B/dt and g = dp_g/dt.
    """
    pw, pw_r, pw_v = p[VAPOUR], 0.0, 0.0
    q, q_r, q_v = 0.0, 0.0, 0.0
    g, g_r, g_v = 0.0, 0.0, 0.0
    if p[GAS] > 0.0:
        kappa = p[KAPPA]
        volume, volume_r = r * r * r - p[E3], 3.0 * r * r
        if volume < p[VOLUME_FLOOR]:
            volume, volume_r = p[VOLUME_FLOOR], 0.0
        p_gas = p[GAS] * ((1.0 - p[E3]) / volume) ** kappa
        p_gas_r = -kappa * p_gas / volume * volume_r
        g = -3.0 * kappa * p_gas * r * r * v / volume
        g_r = (
            -3.0
            * kappa
            * v
            * (p_gas_r * r * r / volume + p_gas * 2.0 * r / volume - p_gas * r * r * volume_r / (volume * volume))
        )
        g_v = -3.0 * kappa * p_gas * r * r / volume
        pw, pw_r = pw + p_gas, p_gas_r
        q, q_r, q_v = g, g_r, g_v
    if p[SIGMA2] > 0.0:
        pw -= p[SIGMA2] / r
        pw_r += p[SIGMA2] / (r * r)
        q += p[SIGMA2] * v / (r * r)
        q_r += -2.0 * p[SIGMA2] * v / (r * r * r)
        q_v += p[SIGMA2] / (r * r)
    if p[VISC4] > 0.0:
        pw -= p[VISC4] * v / r
        pw_r += p[VISC4] * v / (r * r)
        pw_v += -p[VISC4] / r
        q += p[VISC4] * v * v / (r * r)
        q_r += -2.0 * p[VISC4] * v * v / (r * r * r)
        q_v += 2.0 * p[VISC4] * v / (r * r)
    return pw, pw_r, pw_v, q, q_r, q_v, g, g_r, g_v


@kernel
def rhs(p, t, y0, y1):
    """(ṙ, r̈) at (τ, r, ṙ): make_rhs's right-hand side (the terms again, without `wall`'s derivatives)."""
    r, v = max(y0, p[RADIUS_FLOOR]), y1
    pw, q, g = p[VAPOUR], 0.0, 0.0
    if p[GAS] > 0.0:
        volume = max(r * r * r - p[E3], p[VOLUME_FLOOR])
        p_gas = p[GAS] * ((1.0 - p[E3]) / volume) ** p[KAPPA]
        g = -3.0 * p[KAPPA] * p_gas * r * r * v / volume
        pw, q = pw + p_gas, g
    if p[SIGMA2] > 0.0:
        pw -= p[SIGMA2] / r
        q += p[SIGMA2] * v / (r * r)
    if p[VISC4] > 0.0:
        pw -= p[VISC4] * v / r
        q += p[VISC4] * v * v / (r * r)
    drive = pw - far_field(p, t)
    c = p[SOUND]
    if p[COMPRESSIBLE] == KM_FORM:
        numerator = (1.0 + v / c) * drive - 1.5 * (1.0 - v / (3.0 * c)) * v * v + r / c * q
        denominator = max((1.0 - v / c) * r + p[VISC4] / c, p[DENOMINATOR_FLOOR] * r)
        return v, numerator / denominator
    if p[COMPRESSIBLE] == RADIATION_FORM:
        return v, (drive - 1.5 * v * v + r / c * g) / r
    return v, (drive - 1.5 * v * v) / r


@kernel
def jacobian(p, t, y0, y1):
    """(∂r̈/∂r, ∂r̈/∂ṙ) at (τ, r, ṙ); the rest of the Jacobian is [0, 1]. Floors count as constants."""
    r, v = max(y0, p[RADIUS_FLOOR]), y1
    floor = 0.0 if y0 < p[RADIUS_FLOOR] else 1.0
    pw, pw_r, pw_v, q, q_r, q_v, g, g_r, g_v = wall(p, r, v)
    drive = pw - far_field(p, t)
    c = p[SOUND]
    if p[COMPRESSIBLE] == KM_FORM:
        numerator = (1.0 + v / c) * drive - 1.5 * (1.0 - v / (3.0 * c)) * v * v + r / c * q
        n_r = (1.0 + v / c) * pw_r + q / c + r / c * q_r
        n_v = drive / c + (1.0 + v / c) * pw_v + 0.5 * v * v / c - 3.0 * v * (1.0 - v / (3.0 * c)) + r / c * q_v
        denominator, d_r, d_v = (1.0 - v / c) * r + p[VISC4] / c, 1.0 - v / c, -r / c
        if denominator < p[DENOMINATOR_FLOOR] * r:
            denominator, d_r, d_v = p[DENOMINATOR_FLOOR] * r, p[DENOMINATOR_FLOOR], 0.0
        a = numerator / denominator
        return floor * (n_r - a * d_r) / denominator, (n_v - a * d_v) / denominator
    if p[COMPRESSIBLE] == RADIATION_FORM:
        a = (drive - 1.5 * v * v + r / c * g) / r
        return floor * ((pw_r + g / c + r / c * g_r) / r - a / r), (pw_v - 3.0 * v + r / c * g_v) / r
    a = (drive - 1.5 * v * v) / r
    return floor * (pw_r / r - a / r), (pw_v - 3.0 * v) / r
