"""The lever's mechanics: torques, balance and tipping of the bar on its pivot, and its rotation from rest
to the stop (an incomplete elliptic integral). Sign convention: a torque is positive when it turns the bar
counter-clockwise, i.e. when it pushes the left end down."""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ellipkinc

# the book needs 9.81 (docs/physics/README.md): the seed's 2 kg · 9.81 m/s² · 1 m = 19.62 N·m (9.80665 shows 19.61)
G = 9.81
LENGTH = 2.0  # ℓ, the bar's length (m)
BALANCED, TIPS_LEFT, TIPS_RIGHT = 0, 1, 2
STATES = ("balanced", "tips left", "tips right")
# Relative slack on the balance test, so that a balance point exactly midway between two pivot
# stops counts for both (the rule is |x_p − x*| ≤ Δx_p/2) whatever the last-bit rounding of the
# floats. On the 0.01 m × 0.1 kg grids a true |x_p − x*| that is not exactly Δx_p/2 differs from it
# by at least 0.5 % of Δx_p/2, so the slack changes no other verdict.
BALANCE_SLACK = 1e-9
EPS = np.finfo(float).eps


def torque_per_g(x, with_bar: bool = False):
    """Net torque over g, m_L x_p − m_R (ℓ − x_p) [+ m_b (x_p − ℓ/2)], computed directly (0.0 at balance)."""
    x_p = x["x_p"]
    masses = x["m_L"] * x_p - x["m_R"] * (LENGTH - x_p)
    return masses + x["m_b"] * (x_p - 0.5 * LENGTH) if with_bar else masses


def total_mass(x, with_bar: bool):
    """m_L + m_R, and the bar's m_b when it counts."""
    return x["m_L"] + x["m_R"] + x["m_b"] if with_bar else x["m_L"] + x["m_R"]


def balance_point(x, with_bar: bool):
    """x* = ℓ m_R / (m_L + m_R): the centre of mass; the bar adds m_b at ℓ/2."""
    heavy_right = x["m_R"] + 0.5 * x["m_b"] if with_bar else x["m_R"]
    return LENGTH * heavy_right / total_mass(x, with_bar)


def tip_state(x, with_bar: bool):
    """Balanced iff |x_p − x*| ≤ tolerance; else the bar tips towards the side of the centre of mass."""
    # |x_p − x*| = |τ/g| / M: compare torques, no subtraction of nearly equal positions.
    torque = torque_per_g(x, with_bar)
    allowed = x["balance_tolerance"] * (1.0 + BALANCE_SLACK) * total_mass(x, with_bar)
    return np.where(np.abs(torque) <= allowed, BALANCED, np.where(torque > 0, TIPS_LEFT, TIPS_RIGHT))


def mechanical_advantage(x_p):
    """MA = x_p / (ℓ − x_p): +∞ with the pivot at the right end, never NaN."""
    right_arm = LENGTH - x_p  # exact for x_p in [ℓ/2, ℓ] (Sterbenz), so 0 only at x_p = ℓ
    return np.divide(x_p, right_arm, out=np.full(np.shape(x_p), np.inf), where=right_arm > 0)


def moment_of_inertia(x, with_bar: bool = False):
    """Moment of inertia about the pivot: the two point masses [+ the uniform bar, m_b(ℓ²/12 + (ℓ/2 − x_p)²)]."""
    masses = x["m_L"] * x["x_p"] ** 2 + x["m_R"] * (LENGTH - x["x_p"]) ** 2
    return masses + x["m_b"] * (LENGTH**2 / 12.0 + (0.5 * LENGTH - x["x_p"]) ** 2) if with_bar else masses


def tipping_integral(theta):
    """∫₀^θ dφ/√(sin φ) for 0 < θ ≤ π/2, in closed form: √2 F(ψ | ½) with tan ψ = √(2 sin θ/(1 − sin θ)).

    This is Legendre's complement of √2 (K(½) − F(arccos √(sin θ) | ½)), which cancels as θ → 0.
    """
    sine = np.sin(theta)
    psi = np.where(sine < 1.0, np.arctan(np.sqrt(2.0 * sine / np.maximum(1.0 - sine, np.finfo(float).tiny))), np.pi / 2)
    return math.sqrt(2.0) * ellipkinc(psi, 0.5)


def moving_torque(x, with_bar: bool = False):
    """The net torque that sets the bar turning, with the roundoff of an exact balance set to 0.

    m_L x_p − m_R (ℓ − x_p) carries at most about 3ε (m_L x_p + m_R (ℓ − x_p)) of rounding; a
    residue that small is a balance (e.g. 0.3 kg · 0.5 m against 0.1 kg · 1.5 m), not a slow tip
    that would take 10⁷ s. On the slider grids a true imbalance is at least 0.001 kg·m. The bar's
    own weight acts at its middle: m_b (x_p − ℓ/2), a torque that also scales with cos θ.
    """
    per_g = torque_per_g(x, with_bar)
    arms = x["m_L"] * x["x_p"] + x["m_R"] * (LENGTH - x["x_p"])
    roundoff = 4.0 * EPS * (arms + x["m_b"] * np.abs(x["x_p"] - 0.5 * LENGTH) if with_bar else arms)
    return np.where(np.abs(per_g) <= roundoff, 0.0, G * per_g)


def time_to_stop(x, with_bar: bool = False):
    """Time from rest to the stop: I θ'' = τ cos θ has the first integral ½ I θ'² = τ sin θ, so
    t = √(I / 2|τ|) ∫₀^θs dφ/√(sin φ); ∞ when there is no net torque (the bar never moves)."""
    torque = np.abs(moving_torque(x, with_bar))
    scale = np.divide(
        moment_of_inertia(x, with_bar), 2.0 * torque, out=np.full(np.shape(torque), np.inf), where=torque > 0
    )
    # θ_s takes a handful of values over a whole grid: evaluate the elliptic integral once for each.
    angles, where = np.unique(np.radians(x["theta_s"]), return_inverse=True)
    return np.sqrt(scale) * tipping_integral(angles)[where].reshape(scale.shape)


def angular_velocity_at_stop(x, with_bar: bool = False):
    """ω at the stop from ½ I ω² = τ sin θs; positive when the bar turns counter-clockwise (left end down)."""
    torque = moving_torque(x, with_bar)
    speed = np.sqrt(2.0 * np.abs(torque) * np.sin(np.radians(x["theta_s"])) / moment_of_inertia(x, with_bar))
    return np.copysign(speed, torque) + 0.0  # + 0.0: no signed zero when the bar stays put
