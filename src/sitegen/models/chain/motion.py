"""I5's physics: the exact motion of a chain of N masses and d'Alembert's continuum string it is held to.

The linear chain m ü_j = κ(u_{j+1} − 2u_j + u_{j−1}) is diagonalised by a sine transform (fixed
ends, DST-I), a cosine transform (free ends, DCT-II) or an FFT (a ring), so any time t is reached
in O(N log N) with no time-step error. The continuum is d'Alembert's solution of the wave equation
with the matching reflections.
"""

from __future__ import annotations

import numpy as np
import scipy.fft

from .modes import (
    AMPLITUDE,
    BARE,
    CENTRE,
    LENGTH,
    RIGHT_MOVING,
    SPEED,
    Terms,
    mass_and_stiffness,
    mode_frequencies,
    positions,
)

# --- initial state, the transforms and the exact evolution -----------------------------------------------------


def initial_state(x, sigma, launch, amplitude: float = AMPLITUDE):
    """u(0) = A exp(−(x−x0)²/2σ²); u̇(0) = −c u0'(x) for a right-moving pulse, 0 for the split launch."""
    x, sigma, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, sigma, launch)))
    u = amplitude * np.exp(-((x - CENTRE) ** 2) / (2 * sigma**2))
    v = np.where(launch == RIGHT_MOVING, SPEED * (x - CENTRE) / sigma**2 * u, 0.0)
    return u, v


def _forward(values: np.ndarray, ends: str) -> np.ndarray:
    if ends == "fixed":
        return scipy.fft.dst(values, type=1, axis=-1)
    if ends == "free":
        return scipy.fft.dct(values, type=2, axis=-1)
    return scipy.fft.fft(values, axis=-1)


def _inverse(coefficients: np.ndarray, ends: str) -> np.ndarray:
    if ends == "fixed":
        return scipy.fft.idst(coefficients, type=1, axis=-1)
    if ends == "free":
        return scipy.fft.idct(coefficients, type=2, axis=-1)
    return scipy.fft.ifft(coefficients, axis=-1).real  # ω(k) = ω(−k), so the result is real


def _oscillation(omega: np.ndarray, gamma: float, t: np.ndarray):
    """The decaying C(t) and S(t) of each mode: e^{−γt/2}·cos ω_d t and e^{−γt/2}·sin(ω_d t)/ω_d, ω_d² = ω² − γ²/4.

    S is sin(ω_d t)/ω_d, and t where ω_d = 0 (a rigid or critically damped mode); sin and cos of the
    same rounded phase keep each mode's energy exact at any t (t·sinc would round it differently). An overdamped
    mode (ω_d² < 0, rate r = |ω_d|) takes e^{−γt/2}·cosh rt and e^{−γt/2}·sinh(rt)/r, written with
    e^{(r − γ/2)t} so that they neither overflow nor lose digits; both join the others continuously.
    """
    if not gamma:
        phase = omega * t
        return np.cos(phase), _sine_over(phase, omega, t)
    return _damped_oscillation(omega, gamma, t)


def _damped_oscillation(omega: np.ndarray, gamma: float, t: np.ndarray):
    """C(t) and S(t) of `_oscillation` for γ > 0: the on-site damping term, composed only when enabled."""
    squared = omega**2 - gamma**2 / 4
    rate = np.sqrt(np.abs(squared))
    decay = np.exp(-gamma * t / 2)
    phase = rate * t
    under_c, under_s = decay * np.cos(phase), decay * _sine_over(phase, rate, t)
    over = squared < 0
    if not np.any(over):
        return under_c, under_s
    slowest = np.exp(-(omega**2) / (gamma / 2 + rate) * t)  # e^{(r − γ/2)t}, with r − γ/2 = −ω²/(γ/2 + r)
    twice = 2 * np.where(over, phase, 0.0)
    shrink = np.divide(-np.expm1(-twice), twice, out=np.ones_like(twice), where=twice > 0)  # (1 − e^{−2rt})/(2rt)
    over_c, over_s = slowest * (1 + np.exp(-twice)) / 2, slowest * t * shrink
    return np.where(over, over_c, under_c), np.where(over, over_s, under_s)


def _sine_over(phase, frequency, t):
    """sin(phase)/frequency, or t where the frequency is 0 (its limit)."""
    phase, frequency = np.broadcast_arrays(phase, frequency)
    still = frequency == 0
    return np.where(still, t, np.sin(phase) / np.where(still, 1.0, frequency))


def evolve(u0: np.ndarray, v0: np.ndarray, t, terms: Terms = BARE, velocity: bool = True):
    """The exact u(t), u̇(t) of chains (last axis: the masses) from u(0), u̇(0), at times t (one per chain);
    u̇(t) is None unless `velocity` (it costs a transform)."""
    n = u0.shape[-1]
    t = np.asarray(t, float)[..., None]
    a, b = _forward(u0, terms.ends), _forward(v0, terms.ends)
    omega = mode_frequencies(n, terms)
    cos, sine = _oscillation(omega, terms.gamma, t)
    # Each mode obeys ä + γȧ + ω²a = 0: a C + (b + γa/2) S, and its velocity, from C' = −(γ/2)C − ω_d²S, S' = C −
    # (γ/2)S.
    half = terms.gamma / 2
    u = a * cos + (b + half * a) * sine
    if not velocity:
        return _inverse(u, terms.ends), None
    v = b * cos - (omega**2 * a + half * b) * sine
    return _inverse(u, terms.ends), _inverse(v, terms.ends)


def chain_motion(n: int, sigma, t, launch, terms: Terms = BARE, amplitude: float = AMPLITUDE, velocity: bool = True):
    """u_j(t) and u̇_j(t) (None unless `velocity`) of an N-mass chain released as the Gaussian pulse, for arrays of (σ,
    t, launch)."""
    sigma, t, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (sigma, t, launch)))
    u0, v0 = initial_state(positions(n, terms.ends), sigma[..., None], launch[..., None], amplitude)
    return evolve(u0, v0, t, terms, velocity)


def energy(u: np.ndarray, v: np.ndarray, terms: Terms = BARE) -> np.ndarray:
    """E = ½m Σu̇² + ½κ Σ(u_{j+1} − u_j)² (+ ½mω0² Σu²), with the springs to the walls when the ends are fixed."""
    n = u.shape[-1]
    m, kappa = mass_and_stiffness(n, terms.ends)
    if terms.ends == "fixed":
        stretch = np.diff(u, axis=-1, prepend=0.0, append=0.0)
    elif terms.ends == "free":
        stretch = np.diff(u, axis=-1)
    else:
        stretch = np.roll(u, -1, axis=-1) - u
    kinetic = 0.5 * m * np.sum(v**2, axis=-1)
    potential = 0.5 * kappa * np.sum(stretch**2, axis=-1)
    onsite = 0.5 * m * terms.omega0**2 * np.sum(u**2, axis=-1) if terms.omega0 else 0.0
    return kinetic + potential + onsite


# --- the continuum string --------------------------------------------------------------------------------------


def _pulse_images(s, sigma, period: float, amplitude: float):
    """Σ_k u0(s − k·period): the initial pulse repeated with the period (three images suffice for σ ≤ 0.05 L)."""
    # Reduce s first (np.mod is exact), then measure from x0: s and s ± P then round identically.
    shifted = np.mod(s, period) - CENTRE
    shifted = np.where(shifted >= period / 2, shifted - period, shifted)  # the image of x0 nearest s
    spread = -2 * sigma**2  # x/(−2σ²) is −(x/2σ²) exactly: one pass fewer than negating
    total = None
    for k in (-1, 0, 1):  # u0 of each image, in place: the same floats as A exp(−(s − kP)²/2σ²)
        image = shifted - k * period if k else shifted * shifted
        if k:
            image *= image
        image /= spread
        np.exp(image, out=image)
        if amplitude != 1.0:
            image *= amplitude
        if total is None:  # the images add in order, −P first
            total = image
        else:
            total += image
    return total


def continuum(x, t, sigma, launch, ends: str = "fixed", amplitude: float = AMPLITUDE):
    """d'Alembert's u_c(x, t) for the same launch: odd reflections at fixed ends, even at free ends, or a ring."""
    x, t, sigma, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, t, sigma, launch)))
    period = LENGTH if ends == "periodic" else 2 * LENGTH
    sign = {"fixed": -1.0, "free": 1.0, "periodic": 0.0}[ends]

    splits = launch != RIGHT_MOVING  # only the split launch needs the images moving left

    def images(s, where=...):
        return _pulse_images(s, sigma[where], period, amplitude)

    # The launches share their images: x − ct, and −x − ct = −(x + ct) exactly (rounding is symmetric).
    behind, ahead = x - SPEED * t, x + SPEED * t
    moving = images(behind)
    if not sign:  # a ring needs no reflections
        right, split = moving, 0.5 * (moving[splits] + images(ahead[splits], splits))
    else:  # the extension of u0 beyond [0, L] that the ends impose, for each travelling half
        mirrored = images(-ahead)
        right = moving + sign * mirrored
        split = 0.5 * (
            (moving[splits] + sign * images(-behind[splits], splits))
            + (images(ahead[splits], splits) + sign * mirrored[splits])
        )
    right[splits] = split
    return right


def continuum_energy(sigma, launch):
    """The string's energy per μc²A²: √π/(2σ) for the right-moving pulse, half of that (all potential) when split."""
    sigma, launch = np.broadcast_arrays(np.asarray(sigma, float), np.asarray(launch, float))
    return np.sqrt(np.pi) / (2 * sigma) * np.where(launch == RIGHT_MOVING, 1.0, 0.5)


def deviation(n: int, sigma, t, launch, terms: Terms = BARE):
    """max_j |u_j − u_c(x_j)| / A: how far the chain is from the continuum string (the physics error)."""
    return deviation_of(
        chain_motion(n, sigma, t, launch, terms, amplitude=1.0, velocity=False)[0], n, sigma, t, launch, terms
    )


def deviation_of(u: np.ndarray, n: int, sigma, t, launch, terms: Terms):
    """`deviation` of displacements u/A already computed by chain_motion."""
    x = positions(n, terms.ends)
    sigma, t, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (sigma, t, launch)))
    reference = continuum(x, t[..., None], sigma[..., None], launch[..., None], terms.ends, amplitude=1.0)
    return np.max(np.abs(u - reference), axis=-1)
