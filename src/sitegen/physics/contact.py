"""A finite-duration contact between two bodies: a linear spring k_c and a dashpot c_d in parallel.

The overlap δ = x1 − x2 of the bodies (positive while they press into each other) obeys

    μ δ'' + c_d δ' + k_c δ = 0,   δ(0) = 0,   δ'(0) = Δ > 0 (the approach speed),

with the reduced mass μ = m1 m2/(m1 + m2), ω_n = √(k_c/μ), ζ = c_d/(2√(k_c μ)), ω_d = ω_n √(1 − ζ²).
The force on body 2 is F = k_c δ + c_d δ' = −μ δ''.

Criterion: **the contact ends when the overlap closes, δ = 0** (not when F = 0). Just before that the
dashpot pulls (F < 0: the contact is briefly tensile, as docs/physics/collision.md notes); ending at F = 0
instead would give a different restitution. With this criterion, for ζ < 1,

    t_c = π/ω_d,   e = −δ'(t_c)/Δ = exp(−ζπ/√(1 − ζ²))   exactly,

and the impulse is J = ∫F dt = μ(1 + e)Δ. For ζ ≥ 1 the overlap never returns to zero: the bodies
end up moving together (e = 0) and t_c is infinite. Time samples of F(t) for a figure cover [0, t_c]
(a few decay times when overdamped) and always include the time of the peak force.

Pure numpy, vectorised over arrays of (μ, k_c, c_d, Δ).
"""

from __future__ import annotations

import numpy as np

OVERDAMPED_DECAY_TIMES = 5.0  # an overdamped contact is drawn for this many of its slowest decay times


def natural_frequency(mu, k):
    """ω_n = √(k_c/μ)."""
    return np.sqrt(np.asarray(k, float) / np.asarray(mu, float))


def damping_ratio(mu, k, c):
    """ζ = c_d/(2√(k_c μ))."""
    return np.asarray(c, float) / (2.0 * np.sqrt(np.asarray(k, float) * np.asarray(mu, float)))


def _underdamped_root(zeta):
    """√(1 − ζ²) written as √((1 − ζ)(1 + ζ)), which keeps its digits as ζ → 1; 0 when ζ ≥ 1."""
    return np.sqrt(np.maximum((1.0 - zeta) * (1.0 + zeta), 0.0))


def restitution(zeta):
    """e = exp(−ζπ/√(1 − ζ²)) for ζ < 1 (exactly 1 at ζ = 0); 0 when the contact is (over)critically damped."""
    zeta = np.asarray(zeta, float)
    root = _underdamped_root(zeta)
    exponent = np.divide(-np.pi * zeta, root, out=np.full(zeta.shape, -np.inf), where=root > 0)
    return np.exp(exponent)


def contact_time(mu, k, c):
    """t_c = π/ω_d, the time until the overlap closes; ∞ when ζ ≥ 1 (it never does)."""
    omega_d = natural_frequency(mu, k) * _underdamped_root(damping_ratio(mu, k, c))
    return np.divide(np.pi, omega_d, out=np.full(omega_d.shape, np.inf), where=omega_d > 0)


def _modes(mu, k, c):
    """(ω_n², a, q, over): the decay rate a = ζω_n, the frequency q = |ω_n² − a²|^½ and whether overdamped."""
    omega_sq = np.asarray(k, float) / np.asarray(mu, float)
    zeta = damping_ratio(mu, k, c)
    a = zeta * np.sqrt(omega_sq)
    q = np.sqrt(omega_sq) * np.sqrt(np.abs((1.0 - zeta) * (1.0 + zeta)))
    return omega_sq, a, q, zeta > 1.0


def _growth(modes, t):
    """(C, S): cos qt and sin(qt)/q (underdamped), cosh and sinh(qt)/q (overdamped), 1 and t at q = 0,
    each multiplied by e^{−at}; the overdamped pair is written with e^{(q − a)t} so it cannot overflow."""
    omega_sq, a, q, over = modes
    phase = q * t
    decay = np.exp(-a * t)
    still = q == 0
    safe_q = np.where(still, 1.0, q)
    under_c, under_s = decay * np.cos(phase), decay * np.where(still, t, np.sin(phase) / safe_q)
    slow = np.exp(-omega_sq / (a + q) * t)  # e^{(q − a)t}, with q − a = −ω_n²/(a + q) when overdamped
    over_c, over_s = slow * (1.0 + np.exp(-2.0 * phase)) / 2.0, slow * -np.expm1(-2.0 * phase) / (2.0 * safe_q)
    return np.where(over, over_c, under_c), np.where(over, over_s, under_s)


def overlap(t, mu, k, c, approach):
    """δ(t) = Δ e^{−at} S(t)."""
    _, s = _growth(_modes(mu, k, c), np.asarray(t, float))
    return approach * s


def overlap_rate(t, mu, k, c, approach):
    """δ'(t) = Δ e^{−at} (C(t) − a S(t))."""
    modes = _modes(mu, k, c)
    cos, sin = _growth(modes, np.asarray(t, float))
    return approach * (cos - modes[1] * sin)


def force(t, mu, k, c, approach):
    """F(t) = k_c δ + c_d δ' = μΔ e^{−at}[(ω_n² − 2a²) S + 2a C] on body 2 (compressive > 0)."""
    modes = _modes(mu, k, c)
    omega_sq, a = modes[:2]
    cos, sin = _growth(modes, np.asarray(t, float))
    return mu * approach * ((omega_sq - 2.0 * a * a) * sin + 2.0 * a * cos)


def peak_time(mu, k, c):
    """When F is largest: (atan2(ω_d, a) − φ)/ω_d with tan φ = 2aω_d/(ω_n² − 2a²) for ζ < ½; t = 0 otherwise
    (for ζ ≥ ½ the force starts at its largest value c_d Δ and only falls)."""
    omega_sq, a, q, _ = _modes(mu, k, c)
    rising = omega_sq > 4.0 * a * a  # F'(0) ∝ ω_n² − 4a²
    safe_q = np.where(rising, q, 1.0)
    phi = np.arctan2(2.0 * a, (omega_sq - 2.0 * a * a) / safe_q)
    return np.where(rising, (np.arctan2(safe_q, a) - phi) / safe_q, 0.0)


def peak_force(mu, k, c, approach):
    """The largest force of the contact, F at `peak_time`."""
    return force(peak_time(mu, k, c), mu, k, c, approach)


def drawn_duration(mu, k, c):
    """The time span a figure shows: t_c, or a few of the slowest decay times when the contact never ends."""
    omega_sq, a, q, _ = _modes(mu, k, c)
    ends = contact_time(mu, k, c)
    slowest = omega_sq / (a + q)  # the overdamped rate a − q, written without cancellation
    return np.where(np.isfinite(ends), ends, OVERDAMPED_DECAY_TIMES / slowest)


def sample_times(mu, k, c, count: int):
    """`count` + 1 even times over the drawn duration with the peak time put in its place (last axis)."""
    end = drawn_duration(mu, k, c)[..., None]
    even = end * (np.arange(count + 1) / count)
    times = np.concatenate([even, np.asarray(peak_time(mu, k, c), float)[..., None]], axis=-1)
    return np.sort(times, axis=-1)
