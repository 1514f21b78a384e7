"""K5 (acoustic energy bookkeeping): closed-form averages, the local balance, the standing-wave limit and the
effects."""

from __future__ import annotations

import json
from decimal import Decimal, localcontext
from fractions import Fraction

import numpy as np
import pytest
from helpers import resolved_scene

from sitegen.compute.quantize import SPECIAL, fmt, quantize
from sitegen.compute.tabulate import tabulate_scene
from sitegen.models.acoustic_energy.model import (
    INVALID,
    RHO,
    VALID,
    AcousticEnergy,
    C,
    balance_terms_si,
    fields_si,
    incident_energy_density,
    standing_factor,
)
from sitegen.site.assemble import readout_text
from sitegen.site.payload import scene_payload

EPS = np.finfo(float).eps
ALL = ("reflection", "absorption", "spherical_spreading")
R_VALUES = [0.0, 0.35, 0.95, 1.0]
R_IDS = ["R=0", "R=0.35", "R=0.95", "R=1"]


def _evaluate(wanted, effects=("reflection",), **inputs):
    """The model's outputs for broadcastable inputs (others at their defaults)."""
    return AcousticEnergy().evaluate(inputs, wanted=wanted, effects=effects)


def _e_inc_exact(spl) -> Decimal:
    """⟨e⟩ᵢ = p_ref² 10^(SPL/10)/(ρc²) in 40-digit decimal arithmetic."""
    with localcontext() as ctx:
        ctx.prec = 40
        return Decimal("20e-6") ** 2 * Decimal(10) ** (Decimal(spl) / 10) / (Decimal("1.204") * Decimal("343.2") ** 2)


def _rel(value, exact: Decimal) -> float:
    return float(abs(Decimal(float(value)) - exact) / abs(exact))


def _sample_points(seed: int, n: int = 64):
    """Random positions (m) and times (s) at 1 kHz, and the wave's k and ω."""
    rng = np.random.default_rng(seed)
    f = 1000.0
    return rng.uniform(-0.5, 0.0, n), rng.uniform(0.0, 1e-3, n), f


# --- the readouts at the defaults ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "output, expected",
    [
        ("P", "1.41757"),
        ("wavelength", "0.3432"),
        ("e_avg", "7.0850"),
        ("I_avg", "2.4316"),
        ("L_I", "93.86"),
        ("transport", "1.000"),
        ("ek_share", "50.0"),
    ],
    ids=["P", "wavelength", "e_avg-uJ", "I_avg-mW", "L_I", "transport", "ek_share"],
)
def test_defaults_display_the_spec_readouts(output, expected):
    """At the defaults (94 dB, 1 kHz, R_r = 0, ωt = 0) the page shows docs/physics/acoustic_energy.md's values."""
    value = float(_evaluate([output], **AcousticEnergy.defaults())[output])
    assert fmt(value, AcousticEnergy.output(output).decimals) == expected


def test_intensity_level_differs_from_spl_because_rho_c_is_not_400():
    """L_I = SPL + 10 log₁₀(400/ρc) for a travelling wave: 93.86 dB at 94 dB, not 94."""
    value = float(_evaluate(["L_I"], SPL=94.0)["L_I"])
    assert abs(value - (94.0 + 10 * np.log10(2 * 20e-6**2 / (2 * RHO * C * 1e-12)))) <= 1e-12


# --- closed forms against 40-digit references ---------------------------------------------------------------


@pytest.mark.parametrize("R", R_VALUES, ids=R_IDS)
@pytest.mark.parametrize("spl", [0.0, 37.0, 94.0, 140.0], ids=["0dB", "37dB", "94dB", "140dB"])
def test_mean_energy_density_against_decimal_reference(spl, R):
    """⟨e⟩ = P²(1 + R²)/(2ρc²) within 1e−14 rel of a 40-digit reference."""
    value = float(_evaluate(["e_avg"], SPL=spl, R_r=R)["e_avg"]) * 1e-6
    exact = _e_inc_exact(spl) * (1 + Decimal(R) ** 2)
    assert _rel(value, exact) <= 1e-14


@pytest.mark.parametrize("R", R_VALUES[:-1], ids=R_IDS[:-1])
@pytest.mark.parametrize("spl", [0.0, 37.0, 94.0, 140.0], ids=["0dB", "37dB", "94dB", "140dB"])
def test_mean_intensity_against_decimal_reference(spl, R):
    """⟨I⟩ = P²(1 − R)(1 + R)/(2ρc) within 1e−14 rel of a 40-digit reference."""
    value = float(_evaluate(["I_avg"], SPL=spl, R_r=R)["I_avg"]) * 1e-3
    exact = Decimal("343.2") * _e_inc_exact(spl) * (1 - Decimal(R)) * (1 + Decimal(R))
    assert _rel(value, exact) <= 1e-14


# --- hard case: the standing wave R_r = 1 --------------------------------------------------------------------


@pytest.mark.parametrize("output", ["I_avg", "I_avg_n", "transport"])
def test_standing_wave_carries_exactly_zero_mean_intensity(output):
    """R_r = 1: ⟨I⟩, ⟨I⟩/(c⟨e⟩ᵢ) and ⟨I⟩/(c⟨e⟩) are 0.0 exactly at every level."""
    values = _evaluate([output], SPL=np.arange(0.0, 141.0), R_r=1.0)[output]
    assert np.all(values == 0.0)


def test_standing_wave_level_is_minus_infinity_and_marked_special():
    """R_r = 1: L_I = −∞ exactly, which quantises to the SPECIAL marker (never a float in JSON)."""
    value = _evaluate(["L_I"], R_r=1.0)["L_I"]
    assert value == -np.inf
    assert quantize(value, 2, special=True) == SPECIAL


def _energy_scene(extra: str = ""):
    """A small scene (SPL × R_r) resolved and tabulated as the build would."""
    lines = [
        "model: acoustic_energy",
        "slider SPL: 90..94 step 1 default 94",
        "slider R_r: 0..1 step 0.25 default 1",
        "slider wt: 0..90 step 30 default 90",
        "effects: reflection",
        "readouts: I_avg L_I ek_share",
        extra,
    ]
    scene = resolved_scene(lines)
    return scene, tabulate_scene(scene, [o.name for o in scene.readouts])


def test_standing_wave_level_is_shown_as_a_dash_and_the_json_is_valid():
    """The tabulated L_I at R_r = 1 reads "—", and the scene JSON parses with no Infinity or NaN in it."""
    scene, tables = _energy_scene()
    text = scene_payload(scene, tables, ())
    assert "Infinity" not in text and "NaN" not in text
    json.loads(text)  # strict JSON
    assert readout_text(tables["L_I"], "dB", scene.default_stops) == "—"
    assert (
        readout_text(tables["I_avg"], "mW/m²", scene.default_stops) == "0 mW/m²"
    )  # exactly zero, shown without digits it does not have


@pytest.mark.parametrize(
    "R",
    [0.95, 1 - 2.0**-20, 1 - 1e-9, 1 - 2.0**-52, 0.5, 1e-8],
    ids=["0.95", "1-2^-20", "1-1e-9", "1-2^-52", "0.5", "1e-8"],
)
def test_one_minus_R_squared_is_computed_without_cancellation(R):
    """(1 − R)(1 + R) is within 2ε rel of the exact 1 − R² for R up to 1 − 2⁻⁵²."""
    exact = 1 - Fraction(R) ** 2
    assert abs(Fraction(float(standing_factor(R))) - exact) / exact <= 2 * Fraction(EPS)


def test_naive_one_minus_R_squared_would_lose_digits_near_one():
    """The form the model avoids: 1 − R·R at R = 1 − 1e−9 is off by ~δ/2 = 5e−10 rel (the cancellation is real)."""
    R = 1 - 1e-9
    exact = 1 - Fraction(R) ** 2
    assert abs(Fraction(1 - R * R) - exact) / exact > 1e-10


# --- hard case: time averages from equispaced samples ---------------------------------------------------------


def _sampled_means(R, samples: int, x, t0, f=1000.0, spl=94.0):
    """Mean of e and I over `samples` equispaced instants of one period starting at t0."""
    t = t0 + np.arange(samples)[:, None] / (samples * f)
    fields = fields_si(x[None, :], t, spl, f, R)
    return (fields["e_k"] + fields["e_p"]).mean(axis=0), fields["I"].mean(axis=0)


@pytest.mark.parametrize("R", [0.0, 0.35, 1.0], ids=["R=0", "R=0.35", "R=1"])
@pytest.mark.parametrize("samples", [3, 4, 7, 24], ids=["M=3", "M=4", "M=7", "M=24"])
def test_sampled_mean_energy_is_exact_with_three_or_more_samples(samples, R):
    """M ≥ 3 equispaced samples of one period give ⟨e⟩ = P²(1 + R²)/(2ρc²) at any x within 1e−14 rel."""
    x, t, f = _sample_points(seed=samples)
    mean_e, _ = _sampled_means(R, samples, x, t[0], f)
    exact = incident_energy_density(94.0) * (1 + R**2)
    assert np.max(np.abs(mean_e - exact)) / exact <= 1e-14


@pytest.mark.parametrize("R", [0.0, 0.35, 1.0], ids=["R=0", "R=0.35", "R=1"])
@pytest.mark.parametrize("samples", [3, 4, 7, 24], ids=["M=3", "M=4", "M=7", "M=24"])
def test_sampled_mean_intensity_is_exact_with_three_or_more_samples(samples, R):
    """M ≥ 3 samples give ⟨I⟩ = c⟨e⟩ᵢ(1 − R)(1 + R) within 1e−14 of c⟨e⟩ᵢ (relative; absolute at R = 1, where ⟨I⟩ =
    0)."""
    x, t, f = _sample_points(seed=10 + samples)
    _, mean_I = _sampled_means(R, samples, x, t[0], f)
    scale = C * incident_energy_density(94.0)
    assert np.max(np.abs(mean_I - scale * standing_factor(R))) / scale <= 1e-14


@pytest.mark.parametrize("quantity", ["e", "I"])
def test_two_samples_are_not_enough(quantity):
    """M = 2 (R_r = 0) gives 2cos²(kx − ωt₀) × the truth: 0.743 × truth where cos² = 0.3715
    (docs/physics/acoustic_energy.md's measurement)."""
    phase = np.arccos(np.sqrt(0.3715))  # kx − ωt₀ in radians
    f = 1000.0
    x = np.array([phase / (2 * np.pi * f / C)])
    mean_e, mean_I = _sampled_means(0.0, 2, x, 0.0, f)
    truth = incident_energy_density(94.0) * (C if quantity == "I" else 1.0)
    ratio = float((mean_I if quantity == "I" else mean_e)[0] / truth)
    assert abs(ratio - 0.743) <= 1e-12


def test_frame_average_of_the_curves_equals_the_mean_curves():
    """Averaging e_k(x), e_p(x) over the 24 frames of ωt reproduces ⟨e_k⟩(x), ⟨e_p⟩(x) within 1e−14."""
    wt = np.arange(24.0)[:, None] * 15.0
    out = _evaluate(["ek_x", "ep_x", "ek_avg_x", "ep_avg_x"], R_r=0.65, wt=wt)
    assert np.max(np.abs(out["ek_x"].mean(axis=0) - out["ek_avg_x"][0])) <= 1e-14
    assert np.max(np.abs(out["ep_x"].mean(axis=0) - out["ep_avg_x"][0])) <= 1e-14


# --- hard case: the local balance ∂e/∂t + ∂I/∂x = 0 ------------------------------------------------------------


@pytest.mark.parametrize("R", R_VALUES, ids=R_IDS)
def test_local_balance_with_analytic_derivatives(R):
    """∂e/∂t + ∂I/∂x from the analytic derivatives of p' and u vanishes within 1e−14 of ω⟨e⟩ᵢ at random (x, t)."""
    x, t, f = _sample_points(seed=3)
    de_dt, dI_dx = balance_terms_si(x, t, 94.0, f, R)
    scale = 2 * np.pi * f * incident_energy_density(94.0)
    assert np.max(np.abs(de_dt + dI_dx)) / scale <= 1e-14


def _central_differences(x, t, f, R, dx, dt, flux=None):
    """∂e/∂t and ∂I/∂x by central differences of the SI fields (flux: an alternative intensity to test)."""

    def energy(x, t):
        fields = fields_si(x, t, 94.0, f, R)
        return fields["e_k"] + fields["e_p"]

    intensity = flux or (lambda x, t: fields_si(x, t, 94.0, f, R)["I"])
    de_dt = (energy(x, t + dt) - energy(x, t - dt)) / (2 * dt)
    dI_dx = (intensity(x + dx, t) - intensity(x - dx, t)) / (2 * dx)
    return de_dt, dI_dx


def _steps(h, ratio, f):
    """Δx and Δt with ωΔt = h and kΔx = ratio·h."""
    omega, k = 2 * np.pi * f, 2 * np.pi * f / C
    return ratio * h / k, h / omega


@pytest.mark.parametrize("R", [0.0, 0.5, 1.0], ids=["R=0", "R=0.5", "R=1"])
@pytest.mark.parametrize("derivative", ["de_dt", "dI_dx"])
def test_analytic_derivatives_match_central_differences(derivative, R):
    """Each analytic term agrees with its central difference to O(h²): within 1.5·(8/6)(1+R)²h² of ω⟨e⟩ᵢ at h = 1e−3."""
    x, t, f = _sample_points(seed=4)
    dx, dt = _steps(1e-3, 1.0, f)
    numeric = dict(zip(("de_dt", "dI_dx"), _central_differences(x, t, f, R, dx, dt)))
    analytic = dict(zip(("de_dt", "dI_dx"), balance_terms_si(x, t, 94.0, f, R)))
    scale = 2 * np.pi * f * incident_energy_density(94.0)
    bound = 1.5 * 8 / 6 * (1 + R) ** 2 * 1e-6
    assert np.max(np.abs(numeric[derivative] - analytic[derivative])) / scale <= bound


def _fd_residual(h, ratio, R, seed=5, flux=None):
    """max |D_t e + D_x I| / (ω⟨e⟩ᵢ) with ωΔt = h, kΔx = ratio·h."""
    x, t, f = _sample_points(seed)
    dx, dt = _steps(h, ratio, f)
    de_dt, dI_dx = _central_differences(x, t, f, R, dx, dt, flux)
    return np.max(np.abs(de_dt + dI_dx)) / (2 * np.pi * f * incident_energy_density(94.0))


MISMATCH = 1.7  # kΔx = 1.7 ωΔt


@pytest.mark.parametrize("R", [0.0, 0.5, 1.0], ids=["R=0", "R=0.5", "R=1"])
@pytest.mark.parametrize("h", [0.04, 0.02, 0.01], ids=["h=0.04", "h=0.02", "h=0.01"])
def test_local_balance_by_finite_differences_with_mismatched_steps(h, R):
    """kΔx = 1.7ωΔt: the residual is O(h²), within 1.1·(8/6)(1 + R²)|1.7² − 1|h² of ω⟨e⟩ᵢ, and not zero."""
    residual = _fd_residual(h, MISMATCH, R)
    bound = 1.1 * 8 / 6 * (1 + R**2) * (MISMATCH**2 - 1) * h**2
    assert 1e-3 * bound < residual <= bound


@pytest.mark.parametrize("R", [0.0, 0.5, 1.0], ids=["R=0", "R=0.5", "R=1"])
def test_mismatched_residual_converges_at_second_order(R):
    """Halving h divides the mismatched-step residual by 4 (observed order within 2 ± 0.05)."""
    order = np.log2(_fd_residual(0.02, MISMATCH, R) / _fd_residual(0.01, MISMATCH, R))
    assert abs(order - 2.0) <= 0.05


@pytest.mark.parametrize("R", [0.0, 0.5, 1.0], ids=["R=0", "R=0.5", "R=1"])
def test_matched_steps_make_the_balance_test_vacuous(R):
    """ωΔt = kΔx = 0.3: each difference quotient is off by > 0.5 % of ω⟨e⟩ᵢ, yet the residual is at roundoff (≤
    1e−13)."""
    x, t, f = _sample_points(seed=6)
    dx, dt = _steps(0.3, 1.0, f)
    de_dt, dI_dx = _central_differences(x, t, f, R, dx, dt)
    analytic, _ = balance_terms_si(x, t, 94.0, f, R)
    scale = 2 * np.pi * f * incident_energy_density(94.0)
    assert np.max(np.abs(de_dt - analytic)) / scale > 5e-3  # the derivatives themselves are poor ...
    assert np.max(np.abs(de_dt + dI_dx)) / scale <= 1e-13  # ... and the matched residual cannot tell


def test_mismatched_steps_catch_a_wrong_intensity():
    """The travelling-wave guess I = c·e (wrong when R_r ≠ 0) fails the mismatched test by far more than its bound."""
    R, f = 0.5, 1000.0

    def wrong_flux(x, t):
        fields = fields_si(x, t, 94.0, f, R)
        return C * (fields["e_k"] + fields["e_p"])

    bound = 1.1 * 8 / 6 * (1 + R**2) * (MISMATCH**2 - 1) * 0.01**2
    assert _fd_residual(0.01, MISMATCH, R, flux=wrong_flux) > 100 * bound


# --- hard case: e_k and e_p both zero ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "R, x_probe, wt",
    [(0.0, 0.0, 90.0), (0.0, -0.25, 0.0), (0.0, -0.5, 270.0), (1.0, 0.0, 90.0), (1.0, -0.25, 0.0), (0.5, 0.0, 270.0)],
    ids=[
        "R=0-x=0-90deg",
        "R=0-x=-0.25-0deg",
        "R=0-x=-0.5-270deg",
        "R=1-x=0-90deg",
        "R=1-x=-0.25-0deg",
        "R=0.5-x=0-270deg",
    ],
)
def test_kinetic_share_is_undefined_where_both_energies_vanish(R, x_probe, wt):
    """Where p' = u = 0 exactly (a node at that instant) the share is +∞, shown "—" (no 0/0, no tolerance)."""
    value = _evaluate(["ek_share"], R_r=R, x_probe=x_probe, wt=wt)["ek_share"]
    assert value == np.inf and quantize(value, 1, special=True) == SPECIAL


def test_kinetic_share_dash_appears_in_the_tabulated_scene():
    """In a tabulated scene the share at R_r = 1, x = 0, ωt = 90° reads "—", and 0.0 % at ωt = 0 (velocity node)."""
    scene, tables = _energy_scene()
    assert readout_text(tables["ek_share"], "%", scene.default_stops) == "—"
    stops = list(scene.default_stops)
    stops[scene.axis_index("wt")] = 0
    assert readout_text(tables["ek_share"], "%", tuple(stops)) == "0 %"


def test_travelling_wave_shares_energy_equally_wherever_defined():
    """R_r = 0: the share is 50 % exactly at every probe stop and frame except the exact nodes, which are "—"."""
    x_probe, wt = np.meshgrid(np.arange(-20, 1) / 20, np.arange(24) * 15.0, indexing="ij")  # the slider's stops
    share = _evaluate(["ek_share"], R_r=0.0, x_probe=x_probe, wt=wt)["ek_share"]
    node = np.isclose(np.cos(np.deg2rad(360 * x_probe - wt)), 0.0, atol=1e-9)
    assert np.all(share[~node] == 50.0) and np.all(share[node] == np.inf) and node.sum() == 10


@pytest.mark.parametrize("wt", [0.0, 15.0, 30.0, 45.0, 60.0, 75.0], ids=lambda v: f"wt={v:g}")
def test_standing_wave_sloshes_energy_between_kinetic_and_potential(wt):
    """R_r = 1 at x = −λ/8: e_k/(e_k + e_p) = sin²ωt (within 1e−12 %)."""
    share = float(_evaluate(["ek_share"], R_r=1.0, x_probe=-0.125, wt=wt)["ek_share"])
    assert abs(share - 100 * np.sin(np.deg2rad(wt)) ** 2) <= 1e-12


# --- hard case: the linear-acoustics flag ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "spl, expected",
    [(140.0, VALID), (153.0, VALID), (155.0, INVALID), (171.0, INVALID), (172.0, INVALID)],
    ids=["140dB-valid", "153dB-valid", "155dB-U/c>0.01", "171dB-U/c", "172dB-P>0.1p0"],
)
def test_linear_acoustics_flag(spl, expected):
    """Invalid once U/c = P/(ρc²) > 0.01 (P > 1418 Pa, 154.0 dB) or P > 0.1 p₀ (171.1 dB), as in K3."""
    assert int(_evaluate(["validity"], SPL=spl)["validity"]) == expected


# --- effects and their vanishing limits ------------------------------------------------------------------------

BASE_SCALARS = ("P", "wavelength", "e_avg", "I_avg", "L_I", "transport", "ek_share", "validity", "I_avg_n")
BASE_VECTORS = ("ek_x", "ep_x", "Ic_x", "ek_avg_x", "ep_avg_x", "dedt_x", "neg_dIdx_x")


def _random_inputs(seed: int, n: int = 200):
    rng = np.random.default_rng(seed)
    return {
        "SPL": rng.uniform(0, 140, n),
        "f": 10 ** rng.uniform(1.3, 4.3, n),
        "wt": rng.integers(0, 24, n) * 15.0,
        "x_probe": rng.integers(-20, 1, n) * 0.05,
        "alpha": rng.uniform(0, 0.1, n),
        "d": rng.uniform(0, 500, n),
        "r": 10 ** rng.uniform(-2, 3, n),
    }


@pytest.mark.parametrize("output", BASE_SCALARS + BASE_VECTORS)
def test_reflection_with_zero_coefficient_is_the_travelling_wave_bitwise(output):
    """Vanishing limit of `reflection`: R_r = 0 with the effect gives bitwise the outputs without it."""
    inputs = _random_inputs(seed=7)
    on = _evaluate([output], effects=("reflection",), R_r=0.0, **inputs)[output]
    off = _evaluate([output], effects=(), **inputs)[output]
    assert np.array_equal(np.asarray(on).view(np.uint8), np.asarray(off).view(np.uint8))


def test_reflection_off_ignores_the_coefficient():
    """Without `reflection` the travelling wave is computed whatever R_r says (the term is not evaluated)."""
    with_R = _evaluate(["e_avg", "ek_x"], effects=(), R_r=0.8)
    without = _evaluate(["e_avg", "ek_x"], effects=(), R_r=0.0)
    assert all(np.array_equal(with_R[k], without[k]) for k in with_R)


@pytest.mark.parametrize("wt", np.arange(24) * 15.0, ids=lambda v: f"wt={v:g}")
def test_travelling_wave_kinetic_equals_potential_pointwise(wt):
    """R_r = 0: e_k(x) == e_p(x) bitwise at every vertex of every frame, and I/c = e_k + e_p within 1 ulp."""
    out = _evaluate(["ek_x", "ep_x", "Ic_x"], R_r=0.0, wt=wt)
    assert np.array_equal(out["ek_x"], out["ep_x"])
    assert np.max(np.abs(out["Ic_x"] - (out["ek_x"] + out["ep_x"]))) <= 4 * EPS


def test_absorption_with_zero_coefficient_leaves_the_intensity_unchanged():
    """Vanishing limit of `absorption`: α = 0 gives ⟨I⟩ and L_I of the travelling wave bitwise and 0 % absorbed."""
    inputs = {**_random_inputs(seed=8), "alpha": 0.0}
    out = _evaluate(["I_abs", "L_abs", "absorbed"], effects=ALL, **inputs)
    plain = _evaluate(["I_avg", "L_I"], effects=(), **inputs)
    assert np.array_equal(out["I_abs"], plain["I_avg"]) and np.array_equal(out["L_abs"], plain["L_I"])
    assert np.all(out["absorbed"] == 0.0)


@pytest.mark.parametrize("alpha_d", [1e-15, 1e-9, 1e-3, 0.5], ids=["1e-15", "1e-9", "1e-3", "0.5"])
def test_absorbed_fraction_is_accurate_as_alpha_d_vanishes(alpha_d):
    """absorbed = 100(1 − e^(−2αd)) within 4ε rel even at αd = 1e−15 (expm1, no cancellation)."""
    value = float(_evaluate(["absorbed"], effects=ALL, alpha=alpha_d, d=1.0)["absorbed"])
    with localcontext() as ctx:
        ctx.prec = 40
        exact = 100 * (1 - (-2 * Decimal(alpha_d)).exp())
    assert _rel(value, exact) <= 4 * EPS


def test_spherical_spreading_at_the_reference_distance_is_the_plane_wave():
    """At r = r₀ = 1 m the spherical ⟨I⟩ and L_I equal the plane travelling wave's bitwise."""
    inputs = {**_random_inputs(seed=9), "r": 1.0}
    out = _evaluate(["I_r", "L_I_r"], effects=ALL, **inputs)
    plain = _evaluate(["I_avg", "L_I"], effects=(), **inputs)
    assert np.array_equal(out["I_r"], plain["I_avg"]) and np.array_equal(out["L_I_r"], plain["L_I"])


def test_spherical_power_is_conserved():
    """⟨I⟩·4πr² is the same at every r from 1 cm to 1 km (within 4ε rel): the power through any sphere."""
    r = np.geomspace(0.01, 1000.0, 301)
    power = _evaluate(["power"], effects=ALL, r=r)["power"]
    assert np.max(np.abs(power / power[150] - 1)) <= 4 * EPS


@pytest.mark.parametrize("kr", [0.05, 0.5, 1.0, 3.0, 30.0], ids=["kr=0.05", "kr=0.5", "kr=1", "kr=3", "kr=30"])
@pytest.mark.parametrize("output", ["ek_ep_r", "transport_r"])
def test_spherical_near_field_against_complex_amplitudes(output, kr):
    """⟨e_k⟩/⟨e_p⟩ and ⟨I⟩/(c⟨e⟩) of p = A e^(ikr)/r, u = p(1 − 1/(ikr))/(ρc), within 1e−13 rel."""
    f = 1000.0
    r = kr / (2 * np.pi * f / C)
    p = np.exp(1j * kr) / r
    u = p * (1 - 1 / (1j * kr)) / (RHO * C)
    ek, ep = RHO * abs(u) ** 2 / 4, abs(p) ** 2 / (4 * RHO * C**2)
    intensity = 0.5 * (p * np.conj(u)).real
    reference = {"ek_ep_r": ek / ep, "transport_r": intensity / (C * (ek + ep))}[output]
    value = float(_evaluate([output], effects=ALL, f=f, r=r)[output])
    assert abs(value - reference) <= 1e-13 * reference


@pytest.mark.parametrize("output", ["ek_ep_r", "transport_r"])
def test_spherical_far_field_tends_to_the_plane_wave(output):
    """Vanishing limit of `spherical_spreading` (1/kr → 0): both ratios → 1, with error ≤ 1/(kr)² (+ roundoff)."""
    f = 1000.0
    r = np.geomspace(10.0, 1e4, 7)
    kr = 2 * np.pi * f / C * r
    values = _evaluate([output], effects=ALL, f=f, r=r)[output]
    assert np.all(np.abs(values - 1.0) <= 1.0 / kr**2 + 4 * EPS)


# --- invalid input -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "inputs",
    [
        {"f": 0.0},
        {"f": -1.0},
        {"R_r": -0.05},
        {"R_r": 1.05},
        {"alpha": -1e-3},
        {"d": -1.0},
        {"r": 0.0},
        {"SPL": float("nan")},
        {"wt": float("inf")},
        {"x_probe": float("nan")},
    ],
    ids=["f=0", "f<0", "R<0", "R>1", "alpha<0", "d<0", "r=0", "SPL=nan", "wt=inf", "x_probe=nan"],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """Out-of-domain or non-finite inputs raise ValueError naming the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        AcousticEnergy().evaluate(inputs, effects=ALL)
