"""K3: Newton's second law for a thin slab of air in a plane sound wave, against Euler's point form.

At the slab's centre x_m the wave has phase φ, so p′(x) = P cos(φ + k(x − x_m)). The slab
[x₀, x₀ + Δx] = [x_m − Δx/2, x_m + Δx/2] carries ρₐΔx per unit area and feels the net force per area

    p′(x₀) − p′(x₀ + Δx) = 2P sin(kΔx/2) sin φ,

written as a product because the difference of the two face pressures, and worse of the absolute
pressures p₀ + p′, cancels catastrophically for a thin slab. Euler's equation ρₐ ∂u/∂t = −∂p′/∂x
gives the acceleration at the centre, a_m = (Pk/ρₐ) sin φ; the slab's mean acceleration is
a_m · sinc(kΔx/2). Lengths along the wave are in units of λ, so Δx is set by Δx/λ.

The wave runs toward −x, p′ = P cos(kx + ωt) with φ = kx_m + ωt, so that stepping φ forward (the
scene's animation) steps time forward and the wave moves past the slab to the left. No output depends
on the direction (they are amplitudes and the pressure balance); toward +x, φ = kx_m − ωt instead.
"""

from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.structure import Coord, Poly

RHO_AIR = 1.204  # kg/m³, air at 20 °C (docs/physics/README.md)
C_AIR = 343.2  # m/s
GAMMA_AIR = 1.4
P_AMBIENT = 101_325.0  # Pa
P_REF = 20e-6  # Pa rms, the SPL reference
G = 9.81  # m/s², the book's value (docs/physics/README.md)
BETA_AIR = (GAMMA_AIR + 1.0) / 2.0  # coefficient of nonlinearity of an ideal gas
# Transport properties of air at 20 °C for the classical absorption (docs/physics/euler_slab.md).
VISCOSITY_AIR = 1.813e-5  # Pa·s
CONDUCTIVITY_AIR = 0.02514  # W/(m·K)
CP_AIR = 1005.0  # J/(kg·K)
NEPER_TO_DB = 20.0 / np.log(10.0)

MACH_LIMIT = 0.01  # linear acoustics is trusted only below this U/c ...
PRESSURE_LIMIT = 0.1 * P_AMBIENT  # ... and below this amplitude
LINEAR, NONLINEAR = 0, 1

WAVE_X = tuple(k / 48.0 for k in range(-48, 49))  # x/λ of the drawn wave: two wavelengths, λ/48 apart
MIN_DRAWN_WIDTH = 0.025  # λ; a thinner slab is drawn this wide so that it stays visible


# --- exact forms for the page: each output is a product of one-slider (or two-slider) factors ---------
# P carries the level, k/ρₐ the frequency, and sin φ, sinc(kΔx/2) sin φ the geometry; a product of
# coordinates is multilinear in them, so 2 nodes per coordinate reproduce it.
_AMPLITUDE = Coord("P", ("spl",), lambda spl: pressure_amplitude(spl))
_INV_AMPLITUDE = Coord("inv_P", ("spl",), lambda spl: 1.0 / pressure_amplitude(spl))
_K_PER_RHO = Coord("k_per_rho", ("f",), lambda f: 2.0 * np.pi * f / (C_AIR * RHO_AIR))
_INV_F = Coord("inv_f", ("f",), lambda f: 1.0 / f)
_SIN_PHI = Coord("sin_phi", ("phi",), lambda phi: sin_pi(phi / 180.0))
_FACES = Coord("faces", ("dx_l", "phi"), lambda dx_l, phi: 2.0 * sin_pi(dx_l) * sin_pi(phi / 180.0))
_MEAN = Coord("sinc_sin_phi", ("dx_l", "phi"), lambda dx_l, phi: sin_pi(dx_l) / (np.pi * dx_l) * sin_pi(phi / 180.0))


def _product(*coords: Coord, scale: float = 1.0) -> Poly:
    """scale × the product of the coordinates (multilinear)."""

    def kernel(c):
        value = scale
        for coord in coords:
            value = value * c[coord.name]
        return value

    return Poly(kernel, tuple((coord, 1) for coord in coords))


class EulerSlab(Model):
    """A slab of air Δx thick in a plane progressive wave of amplitude P and frequency f."""

    name = "euler_slab"
    title = "Euler's equation for a slab of air"
    params = (
        Param("spl", "L<sub>p</sub>", "dB", 94.0, hi=200.0, description="sound pressure level, rms re 20 µPa"),
        Param("f", "f", "Hz", 1000.0, lo=0.0, lo_open=True, description="frequency"),
        Param("dx_l", "Δx/λ", "", 0.05, lo=0.0, hi=1.0, lo_open=True, description="slab thickness in wavelengths"),
        Param("phi", "φ", "°", 90.0, description="phase of the wave at the slab's centre"),
    )
    _all = ("spl", "f", "dx_l", "phi")
    outputs = (
        # Four significant digits where the values span decades (L_p 0–140 dB, f 20 Hz–20 kHz).
        Output("P", "pressure amplitude P", "Pa", ("spl",), decimals=5, digits=4),
        Output("wavelength", "wavelength λ", "m", ("f",), decimals=5, digits=4),
        Output(
            "net_force",
            "net force per area f",
            "Pa",
            ("spl", "dx_l", "phi"),
            decimals=5,
            structure=_product(_AMPLITUDE, _FACES),
        ),
        Output("slab_mass", "slab mass per area ρ<sub>a</sub>Δx", "g/m²", ("f", "dx_l"), decimals=3, digits=4),
        Output(
            "a_slab",
            "slab acceleration ā = f/(ρ<sub>a</sub>Δx)",
            "m/s²",
            _all,
            decimals=3,
            structure=_product(_AMPLITUDE, _K_PER_RHO, _MEAN),
        ),
        Output(
            "a_point",
            "Euler's point value a<sub>m</sub>",
            "m/s²",
            ("spl", "f", "phi"),
            decimals=3,
            structure=_product(_AMPLITUDE, _K_PER_RHO, _SIN_PHI),
        ),
        Output("sinc", "ratio ā/a<sub>m</sub> = sinc(kΔx/2)", "", ("dx_l",), decimals=6),
        Output("U", "particle velocity U", "mm/s", ("spl",), decimals=4, digits=4),
        Output(
            "xi",
            "displacement ξ",
            "nm",
            ("spl", "f"),
            decimals=2,
            digits=4,
            structure=_product(_AMPLITUDE, _INV_F, scale=1e9 / (RHO_AIR * C_AIR * 2.0 * np.pi)),
        ),
        Output("mach", "acoustic Mach U/c<sub>a</sub>", "× 10⁻⁶", ("spl",), decimals=3, digits=4),
        Output(
            "shock_distance",
            "shock-formation distance",
            "m",
            ("spl", "f"),
            decimals=1,
            digits=4,
            structure=_product(_INV_AMPLITUDE, _INV_F, scale=RHO_AIR * C_AIR**3 / (BETA_AIR * 2.0 * np.pi)),
        ),
        Output(
            "regime",
            "validity",
            "",
            ("spl",),
            labels=(
                "linear acoustics valid",
                "linear acoustics invalid (U/c > 0.01 or P > 0.1 p₀)",
            ),
        ),
        # Figure geometry: lengths in λ about the slab centre, pressures in units of P,
        # accelerations in units of the point-Euler amplitude Pk/ρₐ.
        Output("wave", "p′/P along the wave", "", ("phi",), decimals=3, size=len(WAVE_X)),
        Output("face_lo", "x₀ − x<sub>m</sub> (in λ)", "", ("dx_l",), decimals=3),
        Output("face_hi", "x₀ + Δx − x<sub>m</sub> (in λ)", "", ("dx_l",), decimals=3),
        Output("drawn_lo", "left edge of the drawn slab (in λ)", "", ("dx_l",), decimals=3),
        Output("drawn_hi", "right edge of the drawn slab (in λ)", "", ("dx_l",), decimals=3),
        Output("p_left", "p′(x₀)/P", "", ("dx_l", "phi"), decimals=3),
        Output("p_right", "p′(x₀ + Δx)/P", "", ("dx_l", "phi"), decimals=3),
        Output("bar_slab", "ā/(Pk/ρ<sub>a</sub>)", "", ("dx_l", "phi"), decimals=3),
        Output("bar_point", "a<sub>m</sub>/(Pk/ρ<sub>a</sub>)", "", ("phi",), decimals=3),
        # Effects: readouts of the terms the linear slab balance leaves out.
        Output(
            "convective_ratio",
            "convective / local acceleration",
            "× 10⁻⁶",
            ("spl",),
            decimals=3,
            effect="convective_term",
        ),
        Output(
            "hydrostatic",
            "hydrostatic difference ρ<sub>a</sub>gΔx (balances the slab's weight)",
            "Pa",
            ("f", "dx_l"),
            decimals=5,
            effect="gravity",
        ),
        Output("alpha", "classical absorption α", "dB/km", ("f",), decimals=4, effect="absorption"),
    )
    effects = ("convective_term", "gravity", "absorption")

    def _evaluate(self, x, wanted, effects):
        spl, f, dx_l, phi = (x[k] for k in self._all)
        P = pressure_amplitude(spl)
        wavelength = C_AIR / f
        k = 2.0 * np.pi / wavelength
        half = sin_pi(dx_l)  # sin(kΔx/2): kΔx/2 = π Δx/λ
        sin_phi = sin_pi(phi / 180.0)
        U = P / (RHO_AIR * C_AIR)

        def net_force():  # the product form: never a difference of face pressures
            return 2.0 * P * half * sin_phi

        # Every effect is a readout of a term the linear balance leaves out, so none changes the
        # base outputs and `effects` selects nothing here: an effect's output exists only when enabled.
        formulas = {
            "P": lambda: P,
            "wavelength": lambda: wavelength,
            "net_force": net_force,
            "slab_mass": lambda: 1e3 * RHO_AIR * dx_l * wavelength,
            "a_slab": lambda: net_force() / (RHO_AIR * dx_l * wavelength),  # Newton: force over mass
            "a_point": lambda: P * k / RHO_AIR * sin_phi,
            "sinc": lambda: half / (np.pi * dx_l),
            "U": lambda: 1e3 * U,
            "xi": lambda: 1e9 * U / (2.0 * np.pi * f),
            "mach": lambda: 1e6 * U / C_AIR,
            "shock_distance": lambda: 1.0 / (BETA_AIR * (U / C_AIR) * k),
            "regime": lambda: np.where((U / C_AIR > MACH_LIMIT) | (P > PRESSURE_LIMIT), NONLINEAR, LINEAR),
            "wave": lambda: wave_profile(np.asarray(WAVE_X), phi[..., None]),
            "face_lo": lambda: -0.5 * dx_l,
            "face_hi": lambda: 0.5 * dx_l,
            "drawn_lo": lambda: -0.5 * np.maximum(dx_l, MIN_DRAWN_WIDTH),
            "drawn_hi": lambda: 0.5 * np.maximum(dx_l, MIN_DRAWN_WIDTH),
            "p_left": lambda: wave_profile(-0.5 * dx_l, phi),
            "p_right": lambda: wave_profile(0.5 * dx_l, phi),
            "bar_slab": lambda: half / (np.pi * dx_l) * sin_phi,
            "bar_point": lambda: sin_phi,
            "convective_ratio": lambda: 1e6 * convective_to_local(U),
            "hydrostatic": lambda: RHO_AIR * G * dx_l * wavelength,
            "alpha": lambda: 1e3 * NEPER_TO_DB * classical_absorption(2.0 * np.pi * f),
        }
        return {name: formulas[name]() for name in wanted}


def pressure_amplitude(spl):
    """Peak pressure P = √2 p_ref 10^(SPL/20) of a sine at this rms sound pressure level."""
    return np.sqrt(2.0) * P_REF * 10.0 ** (np.asarray(spl) / 20.0)


def sin_pi(x):
    """sin(πx) with the argument reduced exactly first, so sin_pi(n/2) is exactly 0 or ±1."""
    x = np.asarray(x, dtype=float)
    quarter_turns = np.rint(2.0 * x)
    rest = x - 0.5 * quarter_turns  # exact: x and the nearest half-integer are within a factor 2 (Sterbenz)
    quadrant = np.remainder(quarter_turns, 4.0)
    s, c = np.sin(np.pi * rest), np.cos(np.pi * rest)
    return np.select([quadrant == 0, quadrant == 1, quadrant == 2], [s, c, -s], -c)


def wave_profile(x_over_lambda, phi_degrees):
    """p′/P at x − x_m = x_over_lambda·λ when the phase at the slab centre is φ (degrees)."""
    return sin_pi(0.5 + x_over_lambda * 2.0 + phi_degrees / 180.0)  # cos θ = sin(θ + π/2)


def convective_to_local(U):
    """Amplitude of u ∂u/∂x (U·Uk) over that of ∂u/∂t (Uω): U/c, since ω/k = c in a progressive wave."""
    return U / C_AIR


def classical_absorption(omega, viscosity=VISCOSITY_AIR, conductivity=CONDUCTIVITY_AIR):
    """Classical (viscous + thermal) absorption coefficient α in Np/m at angular frequency ω."""
    losses = 4.0 / 3.0 * viscosity + (GAMMA_AIR - 1.0) * conductivity / CP_AIR
    return np.asarray(omega) ** 2 / (2.0 * RHO_AIR * C_AIR**3) * losses
