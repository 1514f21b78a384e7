"""K5: energy bookkeeping in a plane sound wave in air, an incident wave plus its reflection (closed form).

    p' = P[cos a + R_r cos b],  u = P/(ρc)·[cos a − R_r cos b],  a = kx − ωt,  b = kx + ωt,

with the reflector at x = 0 and the incident wave coming from x < 0. Energy densities and intensity

    e_k = ½ρu²,  e_p = p'²/(2ρc²),  I = p'u,  and  ∂e/∂t + ∂I/∂x = 0  (exactly, for linear acoustics).

Phases are handled in degrees (kx from x/λ, ωt from the frame) with cosdg/sindg, which are exact at
quarter turns: a node is an exact zero, so "both energies vanish here" is decided without a tolerance.
The figure's curves are in units of the incident wave's mean energy density ⟨e⟩ᵢ = P²/(2ρc²), so they
depend on neither the level nor the frequency; the readouts carry the SI values.
"""

from __future__ import annotations

import numpy as np
from scipy.special import cosdg, sindg

from ...physics.base import Model, Output, Param

RHO, C = 1.204, 343.2  # air at 20 °C: kg/m³, m/s
P_REF, I_REF = 20e-6, 1e-12  # Pa (rms), W/m²
P0 = 101_325.0  # Pa, ambient pressure
R0 = 1.0  # m: with spherical spreading, the SPL slider gives the level at this distance from the source
X_POINTS = 49  # vertices of each curve over one wavelength: 7.5° of kx apart, smooth at pixel level
KX_DEG = np.linspace(-360.0, 0.0, X_POINTS)  # kx in degrees at the vertices (exact multiples of 7.5°)
X_OVER_LAMBDA = KX_DEG / 360.0  # the same vertices as x/λ, for the figure
VALID, INVALID = 0, 1


class AcousticEnergy(Model):
    """Kinetic and potential energy density and intensity of an incident plus reflected plane wave."""

    name = "acoustic_energy"
    title = "Acoustic energy bookkeeping in a sound wave"
    params = (
        Param("SPL", "incident SPL", "dB", 94.0, description="level of the incident wave (rms re 20 µPa)"),
        Param("f", "f", "Hz", 1000.0, lo=0.0, lo_open=True, description="frequency"),
        Param(
            "R_r",
            "R<sub>r</sub>",
            "",
            0.0,
            lo=0.0,
            hi=1.0,
            description="pressure reflection coefficient of the reflector at x = 0",
        ).with_effect("reflection"),
        Param("wt", "ωt", "°", 0.0, description="instant in the cycle"),
        Param(
            "x_probe",
            "x<sub>probe</sub>",
            "λ",
            0.0,
            description="where the kinetic share is read, in wavelengths (reflector at 0)",
        ),
        Param("alpha", "α", "Np/m", 0.0, lo=0.0, description="pressure absorption coefficient").with_effect(
            "absorption"
        ),
        Param("d", "d", "m", 100.0, lo=0.0, description="distance the incident wave travels").with_effect("absorption"),
        Param("r", "r", "m", 1.0, lo=0.0, lo_open=True, description="distance from a point source").with_effect(
            "spherical_spreading"
        ),
    )
    _frame = ("R_r", "wt")
    _curve = {"size": X_POINTS, "decimals": 2}  # 0.01 ⟨e⟩ᵢ on a 6 ⟨e⟩ᵢ axis: about a pixel
    outputs = (
        # Closed forms: four significant digits where the values span decades (SPL 0–140 dB: 14 in ⟨e⟩).
        Output("P", "pressure amplitude P", "Pa", ("SPL",), decimals=5, digits=4),
        Output("wavelength", "wavelength λ", "m", ("f",), decimals=4, digits=4),
        Output("e_avg", "⟨e⟩ (any x)", "µJ/m³", ("SPL", "R_r"), decimals=4, digits=4),
        Output("I_avg", "⟨I⟩", "mW/m²", ("SPL", "R_r"), decimals=4, digits=4),
        Output("e_inc", "incident ⟨e⟩ᵢ = P²/2ρc²", "µJ/m³", ("SPL",), decimals=4, digits=4),
        Output(
            "L_I",
            "intensity level L<sub>I</sub>",
            "dB",
            ("SPL", "R_r"),
            decimals=2,
            special="—",
            why="no net intensity: a standing wave's level is −∞ dB",
        ),
        Output("transport", "⟨I⟩/(c⟨e⟩)", "", ("R_r",), decimals=3),
        Output(
            "ek_share",
            "e<sub>k</sub>/(e<sub>k</sub> + e<sub>p</sub>) at the probe",
            "%",
            ("R_r", "wt", "x_probe"),
            decimals=1,
            digits=4,
            floor=1e-9,
            special="—",
            why="no energy at the probe at this instant",
        ),
        Output("validity", "linear acoustics", "", ("SPL",), labels=("valid", "invalid (P > 0.1 p₀ or U/c > 0.01)")),
        # The figure's curves along x, in units of ⟨e⟩ᵢ (I as I/c, derivatives per ω).
        Output("ek_x", "e<sub>k</sub>/⟨e⟩ᵢ", "", _frame, **_curve),
        Output("ep_x", "e<sub>p</sub>/⟨e⟩ᵢ", "", _frame, **_curve),
        Output("Ic_x", "I/(c⟨e⟩ᵢ)", "", _frame, **_curve),
        Output("ek_avg_x", "⟨e<sub>k</sub>⟩/⟨e⟩ᵢ", "", ("R_r",), **_curve),
        Output("ep_avg_x", "⟨e<sub>p</sub>⟩/⟨e⟩ᵢ", "", ("R_r",), **_curve),
        Output("I_avg_n", "⟨I⟩/(c⟨e⟩ᵢ)", "", ("R_r",), decimals=2),
        Output("dedt_x", "∂e/∂t/(ω⟨e⟩ᵢ)", "", _frame, **_curve),
        Output("neg_dIdx_x", "−∂I/∂x/(ω⟨e⟩ᵢ)", "", _frame, **_curve),
        # Absorption: the incident wave after travelling d.
        Output(
            "I_abs", "⟨I⟩ of the incident wave after d", "mW/m²", ("SPL", "alpha", "d"), decimals=4, effect="absorption"
        ),
        Output("L_abs", "its level", "dB", ("SPL", "alpha", "d"), decimals=2, effect="absorption"),
        Output("absorbed", "power absorbed over d", "%", ("alpha", "d"), decimals=2, effect="absorption"),
        # Spherical spreading: an outgoing spherical wave, SPL given at r₀ = 1 m.
        Output("I_r", "⟨I⟩ at r", "mW/m²", ("SPL", "r"), decimals=4, effect="spherical_spreading"),
        Output("L_I_r", "L<sub>I</sub> at r", "dB", ("SPL", "r"), decimals=2, effect="spherical_spreading"),
        Output("power", "⟨I⟩·4πr² (conserved)", "mW", ("SPL", "r"), decimals=4, effect="spherical_spreading"),
        Output(
            "ek_ep_r", "⟨e<sub>k</sub>⟩/⟨e<sub>p</sub>⟩ at r", "", ("f", "r"), decimals=3, effect="spherical_spreading"
        ),
        Output("transport_r", "⟨I⟩/(c⟨e⟩) at r", "", ("f", "r"), decimals=3, effect="spherical_spreading"),
    )
    effects = ("reflection", "absorption", "spherical_spreading")

    def _evaluate(self, x, wanted, effects):
        R = x["R_r"] if "reflection" in effects else np.zeros_like(x["R_r"])
        e_inc = incident_energy_density(x["SPL"])

        def curve(field):
            """A field at every vertex along x (a trailing axis) for each frame."""
            return field(KX_DEG, x["wt"][..., None], R[..., None])

        formulas = {
            "P": lambda: pressure_amplitude(x["SPL"]),
            "wavelength": lambda: C / x["f"],
            "e_avg": lambda: 1e6 * e_inc * (1.0 + R**2),
            "e_inc": lambda: 1e6 * e_inc,
            "I_avg": lambda: 1e3 * (C * e_inc * standing_factor(R)),
            "L_I": lambda: _level(C * e_inc * standing_factor(R)),
            "transport": lambda: standing_factor(R) / (1.0 + R**2),
            "ek_share": lambda: kinetic_share(360.0 * x["x_probe"], x["wt"], R),
            "validity": lambda: _validity(pressure_amplitude(x["SPL"])),
            "ek_x": lambda: curve(kinetic),
            "ep_x": lambda: curve(potential),
            "Ic_x": lambda: curve(flux),
            "ek_avg_x": lambda: mean_kinetic(KX_DEG, R[..., None]),
            "ep_avg_x": lambda: mean_potential(KX_DEG, R[..., None]),
            "I_avg_n": lambda: standing_factor(R),
            "dedt_x": lambda: curve(energy_rate),
            "neg_dIdx_x": lambda: curve(flux_convergence),
            "I_abs": lambda: 1e3 * _absorbed_intensity(e_inc, x["alpha"], x["d"]),
            "L_abs": lambda: _level(_absorbed_intensity(e_inc, x["alpha"], x["d"])),
            "absorbed": lambda: -100.0 * np.expm1(-2.0 * x["alpha"] * x["d"]),  # expm1: exact as αd → 0
            "I_r": lambda: 1e3 * _spherical_intensity(e_inc, x["r"]),
            "L_I_r": lambda: _level(_spherical_intensity(e_inc, x["r"])),
            "power": lambda: 1e3 * 4.0 * np.pi * x["r"] ** 2 * _spherical_intensity(e_inc, x["r"]),
            "ek_ep_r": lambda: 1.0 + 1.0 / (wavenumber(x["f"]) * x["r"]) ** 2,
            "transport_r": lambda: 1.0 / (1.0 + 0.5 / (wavenumber(x["f"]) * x["r"]) ** 2),
        }
        return {name: formulas[name]() for name in wanted}


# --- amplitudes and averages (SI) ------------------------------------------------------------------------------


def pressure_amplitude(spl):
    """P = √2 · 20 µPa · 10^(SPL/20): the peak pressure of the incident wave."""
    return np.sqrt(2.0) * P_REF * 10.0 ** (np.asarray(spl, float) / 20.0)


def incident_energy_density(spl):
    """⟨e⟩ᵢ = P²/(2ρc²), the incident wave's mean energy density, with P² = 2 p_ref² 10^(SPL/10)."""
    return P_REF**2 * 10.0 ** (np.asarray(spl, float) / 10.0) / (RHO * C**2)


def wavenumber(f):
    """k = 2πf/c."""
    return 2.0 * np.pi * np.asarray(f, float) / C


def standing_factor(R):
    """1 − R² as (1 − R)(1 + R): exact at R = 1 and without cancellation near it."""
    return (1.0 - R) * (1.0 + R)


def _level(intensity):
    """10 log₁₀(I/I_ref); −∞ for zero intensity (the page shows "—")."""
    with np.errstate(divide="ignore"):
        return 10.0 * np.log10(intensity / I_REF)


def _validity(P):
    """INVALID when the wave is too strong for linear acoustics (P > 0.1 p₀ or U/c > 0.01, as in K3)."""
    return np.where((P > 0.1 * P0) | (P / (RHO * C**2) > 0.01), INVALID, VALID)


def _absorbed_intensity(e_inc, alpha, d):
    """⟨I⟩ of the incident wave after a path d with pressure absorption α: c⟨e⟩ᵢ e^(−2αd)."""
    return C * e_inc * np.exp(-2.0 * alpha * d)


def _spherical_intensity(e_inc, r):
    """⟨I⟩ = P(r)²/(2ρc) of an outgoing spherical wave with P(r) = P·r₀/r (exact, near field included)."""
    return C * e_inc * (R0 / r) ** 2


# --- the fields along x, in units of ⟨e⟩ᵢ (phases in degrees) ----------------------------------------------------


def _components(kx, wt):
    """(cos a, cos b) with a = kx − ωt and b = kx + ωt, all in degrees."""
    return cosdg(kx - wt), cosdg(kx + wt)


def pressure_shape(kx, wt, R):
    """p'/P = cos a + R cos b."""
    ca, cb = _components(kx, wt)
    return ca + R * cb


def velocity_shape(kx, wt, R):
    """ρc·u/P = cos a − R cos b."""
    ca, cb = _components(kx, wt)
    return ca - R * cb


def kinetic(kx, wt, R):
    """e_k/⟨e⟩ᵢ = (cos a − R cos b)²."""
    return velocity_shape(kx, wt, R) ** 2


def potential(kx, wt, R):
    """e_p/⟨e⟩ᵢ = (cos a + R cos b)²."""
    return pressure_shape(kx, wt, R) ** 2


def flux(kx, wt, R):
    """I/(c⟨e⟩ᵢ) = 2 (p'/P)(ρcu/P)."""
    return 2.0 * pressure_shape(kx, wt, R) * velocity_shape(kx, wt, R)


def energy_rate(kx, wt, R):
    """(∂e/∂t)/(ω⟨e⟩ᵢ) from the time derivatives of p' and u: 2[p̂ ∂_t p̂ + û ∂_t û]/ω."""
    sa, sb = sindg(kx - wt), sindg(kx + wt)
    return 2.0 * (pressure_shape(kx, wt, R) * (sa - R * sb) + velocity_shape(kx, wt, R) * (sa + R * sb))


def flux_convergence(kx, wt, R):
    """(−∂I/∂x)/(ω⟨e⟩ᵢ) from the space derivatives of p' and u: −2[û ∂_x p̂ + p̂ ∂_x û]/k."""
    sa, sb = sindg(kx - wt), sindg(kx + wt)
    dp_dx = -(sa + R * sb)  # ∂(p'/P)/∂(kx)
    du_dx = -(sa - R * sb)  # ∂(ρcu/P)/∂(kx)
    return -2.0 * (velocity_shape(kx, wt, R) * dp_dx + pressure_shape(kx, wt, R) * du_dx)


def mean_kinetic(kx, R):
    """⟨e_k⟩/⟨e⟩ᵢ = ½(1 + R²) − R cos 2kx."""
    return 0.5 * (1.0 + R**2) - R * cosdg(2.0 * kx)


def mean_potential(kx, R):
    """⟨e_p⟩/⟨e⟩ᵢ = ½(1 + R²) + R cos 2kx."""
    return 0.5 * (1.0 + R**2) + R * cosdg(2.0 * kx)


def kinetic_share(kx, wt, R):
    """100·e_k/(e_k + e_p) in %; +∞ (shown "—") where both vanish, which the exact node phases decide."""
    ek, ep = kinetic(kx, wt, R), potential(kx, wt, R)
    total = ek + ep
    # e_k/total first: exactly ½ where e_k == e_p, so a travelling wave reads 50 % at every stop.
    fraction = np.divide(ek, total, out=np.full(np.broadcast(ek, total).shape, np.inf), where=total > 0)
    return 100.0 * fraction


# --- the fields in SI, for checks at arbitrary points ----------------------------------------------------------


def fields_si(x, t, spl, f, R):
    """p' (Pa), u (m/s), e_k, e_p (J/m³) and I (W/m²) at position x (m) and time t (s)."""
    P = pressure_amplitude(spl)
    kx = 360.0 * np.asarray(x, float) * np.asarray(f, float) / C
    wt = 360.0 * np.asarray(f, float) * np.asarray(t, float)
    p = P * pressure_shape(kx, wt, R)
    u = P / (RHO * C) * velocity_shape(kx, wt, R)
    return {"p": p, "u": u, "e_k": 0.5 * RHO * u**2, "e_p": p**2 / (2.0 * RHO * C**2), "I": p * u}


def balance_terms_si(x, t, spl, f, R):
    """∂e/∂t and ∂I/∂x (W/m³) at (x, t) from the analytic derivatives of p' and u."""
    e_inc = incident_energy_density(spl)
    kx = 360.0 * np.asarray(x, float) * np.asarray(f, float) / C
    wt = 360.0 * np.asarray(f, float) * np.asarray(t, float)
    omega = 2.0 * np.pi * np.asarray(f, float)
    return omega * e_inc * energy_rate(kx, wt, R), -omega * e_inc * flux_convergence(kx, wt, R)
