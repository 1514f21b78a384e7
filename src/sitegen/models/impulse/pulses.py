"""The force pulses of the impulse model: the four shapes with their rises and areas, a shaped pulse and
the pulse of a spring–dashpot contact at every point, and the triangle's force and velocity for one pulse."""

from __future__ import annotations

import numpy as np

from ...physics import contact

SHAPES = ("triangle", "hann", "half_sine", "rectangle")
TRIANGLE = 0
# The drawn pulse: SAMPLES + 1 even times over the pulse (t = τ/2 among them: SAMPLES is even), the
# apex once more, and the polygon's corners (0, 0) and (end, 0) around them.
SAMPLES = 48


def _triangle(s):
    return np.maximum(0.0, 1.0 - np.abs(2.0 * s - 1.0))


def _hann(s):
    return np.sin(np.pi * s) ** 2


def _half_sine(s):
    return np.sin(np.pi * s)


def _rectangle(s):
    return np.ones_like(s)


def _triangle_rise(s):
    return np.where(s <= 0.5, s * s, 0.5 - (1.0 - s) ** 2)


def _hann_rise(s):
    return s / 2.0 - np.sin(2.0 * np.pi * s) / (4.0 * np.pi)


def _half_sine_rise(s):
    return 2.0 * np.sin(0.5 * np.pi * s) ** 2 / np.pi  # (1 − cos πs)/π without the cancellation at small s


def _rectangle_rise(s):
    return np.asarray(s, float)


# Each shape on 0 <= s = t/τ <= 1 with unit peak: its force F/F_pk, its running integral ∫₀^s F/F_pk ds'
# (so v(t) = v0 + F_pk τ · rise(t/τ)/m) and its area J/(F_pk τ).
SHAPE_FORCE = {"triangle": _triangle, "hann": _hann, "half_sine": _half_sine, "rectangle": _rectangle}
SHAPE_RISE = {
    "triangle": _triangle_rise,
    "hann": _hann_rise,
    "half_sine": _half_sine_rise,
    "rectangle": _rectangle_rise,
}
SHAPE_AREA = {"triangle": 0.5, "hann": 0.5, "half_sine": 2.0 / np.pi, "rectangle": 1.0}


class ShapedPulse:
    """A pulse of one of SHAPES at each point (the triangle unless the `shape` effect is on)."""

    def __init__(self, x, shaped: bool):
        self.F_pk, self.tau = x["F_pk"], x["tau"]
        self.codes = np.rint(x["shape"]).astype(int) if shaped else np.full(self.F_pk.shape, TRIANGLE)
        self.fractions = np.sort(np.concatenate([np.arange(SAMPLES + 1) / SAMPLES, [0.5]]))  # the apex τ/2 twice

    def _unit_curves(self, table) -> np.ndarray:
        """table[shape](fractions) at every point; each shape present is evaluated once, the others never."""
        out = np.empty(self.codes.shape + self.fractions.shape)
        for code in np.unique(self.codes):
            out[self.codes == code] = table[SHAPES[code]](self.fractions)
        return out

    def impulse(self):
        """J = F_pk τ × the shape's area (F_pk τ/2 for the triangle)."""
        area = np.array([SHAPE_AREA[name] for name in SHAPES])[self.codes]
        return area * self.F_pk * self.tau

    def apex_time(self):
        """τ/2, where every shape has its peak."""
        return 0.5 * self.tau

    def peak(self):
        """The largest force, F_pk."""
        return np.array(self.F_pk, float)

    def duration(self):
        """How long the force acts, τ."""
        return np.array(self.tau, float)

    def restitution(self):
        """A pulse without a contact has no restitution (NaN; the output exists only with the contact)."""
        return np.full(self.tau.shape, np.nan)

    def times(self):
        """The sample times s τ (last axis)."""
        return self.tau[..., None] * self.fractions

    def forces(self):
        """F at the sample times."""
        return self.F_pk[..., None] * self._unit_curves(SHAPE_FORCE)

    def gains(self):
        """∫₀^t F dt' at the sample times (m times the velocity gained)."""
        return (self.F_pk * self.tau)[..., None] * self._unit_curves(SHAPE_RISE)


class ContactPulse:
    """The force of a spring–dashpot contact: m_hit strikes m at speed Δ (contact.py)."""

    def __init__(self, x):
        m, m_hit = x["m"], x["m_hit"]
        self.mu = m_hit * (m / (m_hit + m))
        self.k, self.c, self.approach = 1e3 * x["k_c"], x["c_d"], x["v_rel"]

    def _zeta(self):
        return contact.damping_ratio(self.mu, self.k, self.c)

    def restitution(self):
        """e = exp(−ζπ/√(1 − ζ²)) of the contact."""
        return contact.restitution(self._zeta())

    def impulse(self):
        """J = μ(1 + e)Δ."""
        return self.mu * (1.0 + self.restitution()) * self.approach

    def apex_time(self):
        """The time of the largest force."""
        return contact.peak_time(self.mu, self.k, self.c)

    def peak(self):
        """The largest force."""
        return contact.peak_force(self.mu, self.k, self.c, self.approach)

    def duration(self):
        """The contact time t_c (∞ when overdamped)."""
        return contact.contact_time(self.mu, self.k, self.c)

    def times(self):
        """The sample times over the drawn contact, its peak among them (last axis)."""
        return contact.sample_times(self.mu, self.k, self.c, SAMPLES)

    def _column(self, value):
        return np.asarray(value, float)[..., None]

    def forces(self):
        """F at the sample times."""
        return contact.force(self.times(), *(self._column(v) for v in (self.mu, self.k, self.c, self.approach)))

    def gains(self):
        """∫₀^t F dt' = μ(Δ − δ'(t))."""
        mu, k, c, approach = (self._column(v) for v in (self.mu, self.k, self.c, self.approach))
        return mu * (approach - contact.overlap_rate(self.times(), mu, k, c, approach))


def force(t: np.ndarray, F_pk: float, tau: float) -> np.ndarray:
    """The force of the triangular pulse at times `t` (zero outside 0 <= t <= tau)."""
    return F_pk * np.maximum(0.0, 1.0 - np.abs(2.0 * np.asarray(t) / tau - 1.0))


def shaped_force(t: np.ndarray, F_pk: float, tau: float, shape: str) -> np.ndarray:
    """The force of a pulse of the given shape at times `t` (zero outside 0 <= t <= tau)."""
    s = np.asarray(t, float) / tau
    inside = (s >= 0.0) & (s <= 1.0)
    return np.where(inside, F_pk * SHAPE_FORCE[shape](np.clip(s, 0.0, 1.0)), 0.0)


def velocity(t: np.ndarray, F_pk: float, tau: float, m: float, v0: float = 0.0) -> np.ndarray:
    """The velocity of the mass during and after the pulse (piecewise quadratic in t)."""
    t = np.clip(np.asarray(t, float), 0.0, tau)
    rising = F_pk * t**2 / (m * tau)
    falling = (0.5 * F_pk * tau - F_pk * (tau - t) ** 2 / tau) / m
    return v0 + np.where(t <= 0.5 * tau, rising, falling)
