"""The chain of masses' geometry and normal modes (shared by the exact motion in motion.py, the model and
the time-stepping integrators it is compared with in integrators.py). Units: L = 1 m, c = 1 m/s, μ = 1 kg/m."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

LENGTH, SPEED, DENSITY = 1.0, 1.0, 1.0  # L (m), c (m/s), μ (kg/m)
CENTRE = 0.3  # x0: where the pulse starts (m)
AMPLITUDE = 0.01  # A: the pulse height on the page (m); the model is linear, so everything scales with it
MAX_N = 256  # the largest chain the page shows: vector outputs are padded to this length
CONTINUUM_POINTS = 201  # the dashed curve's vertices; 2 px apart at the page's width, smooth at pixel level
PULSE_WAVENUMBERS = 3.0  # the pulse's spectrum e^{−k²σ²/2} is below 1.1 % beyond k = 3/σ
DRAWN_WALL = 0.025 * LENGTH  # figure geometry: how thick a fixed wall is drawn (m)
ENDS = ("fixed", "free", "periodic")
LAUNCHES = ("right-moving", "split")
RIGHT_MOVING, SPLIT = 0, 1
RESOLVED, UNDER_RESOLVED = 0, 1


@dataclass(frozen=True)
class Terms:
    """The optional terms of the chain: how its ends are held, on-site damping γ and on-site spring ω0."""

    ends: str = "fixed"
    gamma: float = 0.0  # 1/s: the force −mγu̇ on every mass
    omega0: float = 0.0  # rad/s: the force −mω0²u on every mass (Klein–Gordon)

    def __post_init__(self):
        if self.ends not in ENDS:
            raise ValueError(f"`ends` must be one of {', '.join(ENDS)}, not {self.ends!r}")
        if not (self.gamma >= 0 and self.omega0 >= 0):
            raise ValueError("`gamma` and `omega0` must be >= 0")


BARE = Terms()


# --- geometry and the normal modes ---------------------------------------------------------------------------


def spacing(n, ends: str = "fixed"):
    """Lattice spacing a: L/(N+1) between fixed walls, L/N for free ends or a ring."""
    return LENGTH / (np.asarray(n) + 1) if ends == "fixed" else LENGTH / np.asarray(n)


def positions(n: int, ends: str = "fixed") -> np.ndarray:
    """Rest positions x_j of the N masses: j·a between fixed walls, cell centres (j − ½)·a otherwise."""
    j = np.arange(1, n + 1, dtype=float)
    return j * spacing(n, ends) if ends == "fixed" else (j - 0.5) * spacing(n, ends)


def mass_and_stiffness(n, ends: str = "fixed"):
    """m = μa and κ = μc²/a, so that c = a√(κ/m) whatever N is."""
    a = spacing(n, ends)
    return DENSITY * a, DENSITY * SPEED**2 / a


def wavenumbers(n: int, ends: str = "fixed") -> np.ndarray:
    """k of each mode, in the order of the transform's coefficients."""
    if ends == "fixed":
        return np.pi * np.arange(1, n + 1) / LENGTH
    if ends == "free":
        return np.pi * np.arange(n) / LENGTH
    return 2 * np.pi * np.fft.fftfreq(n, d=1.0 / n) / LENGTH


def mode_frequencies(n: int, terms: Terms = BARE) -> np.ndarray:
    """ω of each mode: ω² = ω0² + (2c/a)² sin²(ka/2), in the order of the transform's coefficients."""
    a = spacing(n, terms.ends)
    lattice = 2 * SPEED / a * np.abs(np.sin(wavenumbers(n, terms.ends) * a / 2))
    return np.hypot(lattice, terms.omega0) if terms.omega0 else lattice


def cutoff_frequency(n, terms: Terms = BARE):
    """The top of the band, ω_max = √(ω0² + 4κ/m) = √(ω0² + (2c/a)²)."""
    return np.hypot(2 * SPEED / spacing(n, terms.ends), terms.omega0)
