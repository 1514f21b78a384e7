"""K4 helpers: the bubble's terms in nondimensional form and the closed-form references.

Variables: r = R/R_i (R_i the radius at rest at t = 0), speed in U = sqrt(p0/ρ), time in R_i/U,
pressure in p0. In these units ρ = 1, R_i = 1 and every state component is of order one, so the
solver's absolute tolerance means the same thing for a 0.1 µm nucleus and a 10 mm cavity (in SI,
atol = 1e-6 m is 0.2 R0 for R0 = 4.5 µm; docs/physics/bubble.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import beta, betainc, betaincinv

P0 = 101_325.0  # ambient pressure and pressure unit, Pa (1 atm)
T0 = 293.15  # liquid and initial gas temperature, K
WATER = {"rho": 998.2, "c": 1482.0, "mu": 1.002e-3, "sigma": 0.0728, "p_v": 2339.0}  # 20 °C

R_FLOOR = 1e-9  # radius floor for trial stages only (no physical state comes near it)
EPSILON = 1e-2  # the empty collapse stops at R = εR_i: the singularity itself is never integrated
CORE_MARGIN = 1e-6  # the hard-core event sits at R = h(1 + margin)
KM_LIMIT = 0.9  # Keller–Miksis is stopped at |Ṙ| = 0.9c; its denominator vanishes at Ṙ → c
KM_FLOOR = 1.0 - 0.95  # the denominator is kept above (1 − 0.95)R, i.e. as at Ṙ = 0.95c
INVALID_MACH = 0.2  # above this wall Mach number the incompressible model is flagged invalid
UNBOUNDED = 10.0  # growth past 10 R_B counts as unbounded (Blake)
RAYLEIGH_B = float(beta(5 / 6, 1 / 2))  # t_c = R sqrt(ρ/6Δp) B(5/6, 1/2) = 0.914681 R sqrt(ρ/Δp)

NONE, RADIATION, KELLER_MIKSIS = "", "radiation", "keller_miksis"


@dataclass(frozen=True)
class Problem:
    """One bubble in nondimensional form. A term whose coefficient is zero is not composed.

    Equal problems give equal solutions, so points that differ only in a scale the enabled terms
    do not see (R0 for an inviscid bubble without surface tension) are solved once.
    """

    p_inf: float = 1.0  # far-field pressure from t = 0 (1 = ambient; another value: the step)
    gas: float = 0.0  # gas pressure at r = 1 (0: no gas term)
    kappa: float = 1.0  # polytropic exponent (effective one with thermal damping)
    eta: float = 0.0  # hard-core radius h/R_i
    vapour: float = 0.0  # p_v/p0
    sigma: float = 0.0  # σ/(p0 R_i)
    visc: float = 0.0  # (µ + µ_th)/(R_i sqrt(ρ p0))
    sound: float = math.inf  # c/U
    compressible: str = NONE  # "", "radiation" or "keller_miksis"
    drive: float = 0.0  # p_a/p0
    omega: float = 0.0  # drive angular frequency in units U/R_i
    ramp_to: float = 1.0  # far-field pressure at the end of the ramp
    ramp_time: float = 0.0  # 0: no ramp
    tau_end: float = 1.0  # end of the run
    r_unbounded: float = math.inf  # growth stops here (10 R_B/R_i under the ramp)

    @property
    def singular(self) -> bool:
        """Whether the collapse can reach R = 0 (no gas cushions it)."""
        return self.gas == 0.0

    @property
    def speed_limit(self) -> float:
        """The wall speed at which the run stops: 0.9c with Keller–Miksis, c otherwise."""
        return KM_LIMIT * self.sound if self.compressible == KELLER_MIKSIS else self.sound

    @property
    def stiffness(self) -> float:
        """4µT/(ρR0²): viscous relaxation rate times the run length (implicit solver above 10³)."""
        return 4.0 * self.visc * self.tau_end

    @property
    def is_rayleigh(self) -> bool:
        """Whether only inertia and a constant pressure difference act: the analytic collapse."""
        quiet = (self.gas, self.sigma, self.visc, self.drive, self.ramp_time) == (0.0,) * 5
        return quiet and self.compressible == NONE and self.p_inf > self.vapour


def far_field(pb: Problem):
    """p∞(τ): the ambient (or stepped) value, plus the ramp and the drive when they are enabled."""
    base, ramp_time, rise = pb.p_inf, pb.ramp_time, pb.ramp_to - pb.p_inf
    amplitude, omega = pb.drive, pb.omega
    if ramp_time and amplitude:
        return lambda t: base + rise * min(t / ramp_time, 1.0) - amplitude * math.sin(omega * t)
    if ramp_time:
        return lambda t: base + rise * min(t / ramp_time, 1.0)
    if amplitude:
        return lambda t: base - amplitude * math.sin(omega * t)
    return lambda t: base


def gas_pressure(pb: Problem, r):
    """p_g(r) = p_g0((1 − η³)/(r³ − η³))^κ (works on arrays)."""
    e3 = pb.eta**3
    return pb.gas * ((1.0 - e3) / (np.asarray(r, float) ** 3 - e3)) ** pb.kappa


def make_rhs(pb: Problem):
    """The right-hand side (τ, [r, ṙ]) -> (ṙ, r̈) with only the enabled terms composed.

    Each disabled term is skipped by a flag fixed here, so it is never evaluated.
    """
    has_gas, has_tension, has_visc = pb.gas > 0.0, pb.sigma > 0.0, pb.visc > 0.0
    gas0, kappa, e3 = pb.gas, pb.kappa, pb.eta**3
    gas_volume0 = 1.0 - e3
    # A wild trial stage can put r inside the core or at r ≤ 0. Floors on r and on the gas volume
    # keep every term finite and huge there, so the step is rejected rather than turned into NaN or
    # an overflow; accepted states never come near them (terminal events stop the run first).
    volume_floor = max(e3 * 3.0 * CORE_MARGIN, R_FLOOR**3)
    two_sigma, visc4, vapour, c = 2.0 * pb.sigma, 4.0 * pb.visc, pb.vapour, pb.sound
    km, radiation = pb.compressible == KELLER_MIKSIS, pb.compressible == RADIATION
    p_far = far_field(pb)

    def rhs(t, y):
        r, v = max(float(y[0]), R_FLOOR), float(y[1])
        p_wall, p_wall_rate, p_gas_rate = vapour, 0.0, 0.0
        if has_gas:
            volume = max(r * r * r - e3, volume_floor)
            p_gas = gas0 * (gas_volume0 / volume) ** kappa
            p_gas_rate = -3.0 * kappa * p_gas * r * r * v / volume
            p_wall += p_gas
            p_wall_rate += p_gas_rate
        if has_tension:
            p_wall -= two_sigma / r
            p_wall_rate += two_sigma * v / (r * r)
        if has_visc:  # the −4µR̈/R part of dp_B/dt is moved into the denominator below
            p_wall -= visc4 * v / r
            p_wall_rate += visc4 * v * v / (r * r)
        drive = p_wall - p_far(t)
        if km:
            numerator = (1.0 + v / c) * drive - 1.5 * (1.0 - v / (3.0 * c)) * v * v + r / c * p_wall_rate
            # The denominator vanishes only for outward Ṙ → c. Accepted states stop at 0.9c (an event);
            # a wild trial stage past that gets a finite, huge r̈ so its step is rejected, not a 1/0.
            denominator = max((1.0 - v / c) * r + visc4 / c, KM_FLOOR * r)
            return (v, numerator / denominator)
        if radiation:
            return (v, (drive - 1.5 * v * v + r / c * p_gas_rate) / r)
        return (v, (drive - 1.5 * v * v) / r)

    return rhs


# --- closed forms ---------------------------------------------------------------------------------------


def rayleigh_tau(delta_p: float) -> float:
    """Nondimensional Rayleigh collapse time τ_c = B(5/6, 1/2)/sqrt(6ΔP) of an empty cavity."""
    return RAYLEIGH_B / math.sqrt(6.0 * delta_p)


def rayleigh_radius(fraction):
    """r(t/t_c) = [I⁻¹_{1 − t/t_c}(5/6, 1/2)]^{1/3}, exact (betaincinv)."""
    return betaincinv(5 / 6, 1 / 2, 1.0 - np.asarray(fraction, float)) ** (1 / 3)


def rayleigh_fraction(r):
    """t/t_c at which the empty cavity has radius r: 1 − I_{r³}(5/6, 1/2)."""
    return 1.0 - betainc(5 / 6, 1 / 2, np.asarray(r, float) ** 3)


def mach_one_radius(delta_p, sound):
    """r where the incompressible collapse reaches |Ṙ| = c: (1 + 3C²/2ΔP)^(−1/3)."""
    return (1.0 + 1.5 * np.asarray(sound, float) ** 2 / np.asarray(delta_p, float)) ** (-1 / 3)


def stiffness_k(pb: Problem) -> float:
    """The linear restoring coefficient K = 3κp_g0/(1 − η³) − 2Σ (nondimensional)."""
    return 3.0 * pb.kappa * pb.gas / (1.0 - pb.eta**3) - 2.0 * pb.sigma


def natural_omega(pb: Problem) -> float:
    """Linear (undamped) angular frequency ω0 = sqrt(K) in units U/R0 (ρ = R0 = 1)."""
    return math.sqrt(max(stiffness_k(pb), 0.0))


def thermal_phi(gamma: float, chi: float) -> complex:
    """Prosperetti's Φ = 3γ/(1 − 3(γ−1)iχ[(i/χ)^½ coth (i/χ)^½ − 1]) with χ = D/(ωR0²)."""
    if chi == 0.0:
        return complex(3.0 * gamma)
    z = np.sqrt(1j / chi)
    bracket = z / np.tanh(z) - 1.0
    return complex(3.0 * gamma / (1.0 - 3.0 * (gamma - 1.0) * 1j * chi * bracket))


def blake(gas0, sigma, vapour):
    """(r_B, p_Blake) of the isothermal quasi-static bubble: r_B = sqrt(3p_g0/2Σ), p_v − 4Σ/3r_B."""
    gas0, sigma = np.asarray(gas0, float), np.asarray(sigma, float)
    r_b = np.sqrt(1.5 * gas0 / sigma)
    return r_b, vapour - 4.0 * sigma / (3.0 * r_b)


def blake_nucleus(sigma, vapour):
    """Blake's (r_B, p_Blake) for the nucleus in equilibrium at p0: p_g0 = 1 − P_v + 2Σ.

    Without surface tension r_B is infinite and p_Blake = P_v (the limit σ → 0).
    """
    sigma, vapour = np.asarray(sigma, float), np.asarray(vapour, float)
    safe = np.where(sigma > 0, sigma, 1.0)
    r_b, p_blake = blake(1.0 - vapour + 2.0 * safe, safe, vapour)
    return np.where(sigma > 0, r_b, np.inf), np.where(sigma > 0, p_blake, vapour)


def energy(pb: Problem, r, v):
    """E/ρR0³U² = 2πr³ṙ² + (4π/3)(P∞ − P_v)r³ + 4πΣr² + U_g: conserved without µ and drive."""
    r, v = np.asarray(r, float), np.asarray(v, float)
    e3 = pb.eta**3
    total = 2 * np.pi * r**3 * v**2 + 4 * np.pi / 3 * (pb.p_inf - pb.vapour) * r**3 + 4 * np.pi * pb.sigma * r**2
    if pb.gas:
        gas = gas_pressure(pb, r)
        total = total + (
            4 * np.pi / 3 * gas * (r**3 - e3) / (pb.kappa - 1.0)
            if pb.kappa != 1.0
            else -4 * np.pi / 3 * pb.gas * (1 - e3) * np.log((r**3 - e3) / (1 - e3))
        )
    return total
