"""K3 (Euler's equation for a slab of air): 50-digit references, the cancellation hard case, Δx = λ,
the linear-acoustics flag, the effects' vanishing limits and the readouts at the defaults."""

from __future__ import annotations

from decimal import Decimal, localcontext

import numpy as np
import pytest

from sitegen.compute.quantize import fmt
from sitegen.models.euler_slab.model import (
    C_AIR,
    CONDUCTIVITY_AIR,
    CP_AIR,
    GAMMA_AIR,
    LINEAR,
    NONLINEAR,
    P_AMBIENT,
    RHO_AIR,
    VISCOSITY_AIR,
    WAVE_X,
    EulerSlab,
    G,
    classical_absorption,
    sin_pi,
)

EPS = np.finfo(float).eps
DIGITS = 50
PI = Decimal("3.14159265358979323846264338327950288419716939937510582097494459")


# --- the 50-digit reference (mpmath is not installed; decimal with Taylor series stands in) ------------------


def _dsin(x: Decimal) -> Decimal:
    """sin x by its Taylor series in 50-digit decimal arithmetic (|x| ≤ 4 in every use here)."""
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        term = total = +x
        n = 1
        while abs(term) > Decimal(10) ** -(DIGITS + 5):
            term = -term * x * x / ((2 * n) * (2 * n + 1))
            total += term
            n += 1
    return total


def _dsin_pi(x: float) -> Decimal:
    """sin(πx) for a float x in [−2, 2], reduced to |πr| ≤ π/2 exactly in decimal."""
    r = Decimal(float(x))
    sign = 1
    if r < 0:
        r, sign = -r, -1
    if r > 1:
        r, sign = r - 1, -sign
    if r > Decimal("0.5"):
        r = 1 - r
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        return sign * _dsin(PI * r)


def _d_pressure(spl: float) -> Decimal:
    """P = √2 · 20 µPa · 10^(SPL/20) in 50-digit arithmetic."""
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        return Decimal(2).sqrt() * Decimal(20e-6) * Decimal(10) ** (Decimal(float(spl)) / 20)


def _d_net_force(spl: float, dx_l: float, phi: float) -> Decimal:
    """2P sin(πΔx/λ) sin φ (φ in degrees) in 50-digit arithmetic on the float inputs."""
    return 2 * _d_pressure(spl) * _dsin_pi(dx_l) * _dsin_pi(phi / 180.0)


def _rel(value: float, exact: Decimal) -> float:
    return float(abs(Decimal(float(value)) - exact) / abs(exact))


def _evaluate(wanted, effects=(), **inputs):
    """The model's outputs at one point (or broadcast arrays of points)."""
    return EulerSlab().evaluate(inputs, wanted=wanted, effects=effects)


def test_reference_sine_agrees_with_the_float_sine():
    """Sanity of the reference itself: _dsin_pi matches math's sine to 2ε at a few points."""
    for x in (1e-8, 0.05, 0.25, 0.4, 0.5, -0.3, 1.2):
        assert abs(float(_dsin_pi(x)) - np.sin(np.pi * x)) <= 2 * EPS


# --- hard case: the net force from absolute pressures cancels; the product form does not ------------------------

DX_DECADES = [1e-8, 3e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.25, 1 / 3, 0.5]
PHASES = [15.0, 90.0, 165.0, 210.0, 345.0]


@pytest.mark.parametrize("phi", PHASES, ids=[f"phi={p:g}deg" for p in PHASES])
@pytest.mark.parametrize("dx_l", DX_DECADES, ids=[f"dx/lambda={d:.3g}" for d in DX_DECADES])
def test_net_force_product_form_within_1e14_of_50_digit_reference(dx_l, phi):
    """Product form 2P sin(kΔx/2) sin φ at 0 dB: rel ≤ 1e−14 vs the 50-digit reference, Δx/λ in [1e−8, 0.5]."""
    value = float(_evaluate(["net_force"], spl=0.0, dx_l=dx_l, phi=phi)["net_force"])
    assert _rel(value, _d_net_force(0.0, dx_l, phi)) <= 1e-14


def test_net_force_product_form_over_random_thicknesses():
    """Worst rel error over 300 random Δx/λ log-uniform in [1e−8, 0.5] and random SPL and phase stops is ≤ 1e−14."""
    rng = np.random.default_rng(3)
    dx_l = 10.0 ** rng.uniform(-8, np.log10(0.5), 300)
    spl = rng.integers(0, 141, 300).astype(float)
    phi = 15.0 * rng.integers(0, 24, 300)
    phi[phi % 180 == 0] = 45.0  # sin φ = 0 has no relative error to speak of
    values = _evaluate(["net_force"], spl=spl, dx_l=dx_l, phi=phi)["net_force"]
    worst = max(_rel(v, _d_net_force(s, d, p)) for v, s, d, p in zip(values, spl, dx_l, phi))
    assert worst <= 1e-14, f"worst rel error {worst:.3g}"


def _absolute_pressure_difference(dx_l: float) -> float:
    """The naive way: (p₀ + p′(x₀)) − (p₀ + p′(x₀ + Δx)) at 0 dB, 1 kHz, φ = 90°, in float64."""
    P = np.sqrt(2.0) * 20e-6
    k = 2.0 * np.pi * 1000.0 / C_AIR
    dx = dx_l * C_AIR / 1000.0
    phi = np.pi / 2
    return (P_AMBIENT + P * np.cos(phi - k * dx / 2)) - (P_AMBIENT + P * np.cos(phi + k * dx / 2))


# docs/physics/euler_slab.md measured these relative errors of the absolute-pressure difference (0 dB SPL, 1 kHz).
NAIVE_MEASURED = [(1e-3, 6.8e-5), (1e-4, 7.5e-4), (1e-6, 1.7e-2)]


@pytest.mark.parametrize("dx_l, measured", NAIVE_MEASURED, ids=["dx/lambda=1e-3", "dx/lambda=1e-4", "dx/lambda=1e-6"])
def test_absolute_pressure_difference_loses_digits_as_physics_md_measured(dx_l, measured):
    """The naive difference is off by docs/physics/euler_slab.md's measured rel error (within a factor 10); the product
    form is not."""
    exact = _d_net_force(0.0, dx_l, 90.0)
    naive = _rel(_absolute_pressure_difference(dx_l), exact)
    product = _rel(float(_evaluate(["net_force"], spl=0.0, dx_l=dx_l, phi=90.0)["net_force"]), exact)
    assert measured / 10 <= naive <= measured * 10, f"naive rel error {naive:.3g}"
    assert product <= 1e-14 and naive >= 1e9 * max(product, EPS**2)


def test_absolute_pressure_difference_returns_zero_for_the_thinnest_slab():
    """At Δx = 1e−8 λ and 0 dB the two absolute pressures round to the same float: the naive force is 0 (100 %
    error)."""
    assert _absolute_pressure_difference(1e-8) == 0.0
    assert float(_evaluate(["net_force"], spl=0.0, dx_l=1e-8, phi=90.0)["net_force"]) > 0.0


def test_difference_of_perturbations_is_far_less_accurate_than_the_product():
    """p′(x₀) − p′(x₀ + Δx) without p₀ still loses digits: worst rel error over [1e−8, 0.5] is ≥ 1e−11 (product ≤
    1e−14)."""
    P, k = np.sqrt(2.0) * 20e-6, 2.0 * np.pi / C_AIR * 1000.0
    worst = 0.0
    for dx_l in np.logspace(-8, np.log10(0.5), 60):
        dx = dx_l * C_AIR / 1000.0
        value = P * np.cos(np.pi / 2 - k * dx / 2) - P * np.cos(np.pi / 2 + k * dx / 2)
        worst = max(worst, _rel(value, _d_net_force(0.0, dx_l, 90.0)))
    assert 1e-11 <= worst <= 1e-8, f"worst rel error {worst:.3g}"


# --- hard case: Δx = λ ------------------------------------------------------------------------------------------


@pytest.mark.parametrize("output", ["net_force", "sinc", "a_slab", "bar_slab"])
@pytest.mark.parametrize("phi", [15.0, 90.0, 300.0], ids=["phi=15deg", "phi=90deg", "phi=300deg"])
def test_slab_one_wavelength_thick_feels_no_net_force(phi, output):
    """Δx = λ: both faces see the same pressure, so the net force, ā, the bar and the sinc ratio are exactly 0."""
    value = float(_evaluate([output], spl=140.0, f=250.0, dx_l=1.0, phi=phi)[output])
    assert value == 0.0


def test_sinc_ratio_shows_zero_at_one_wavelength():
    """Δx = λ: the page shows the sinc ratio as 0.000000 (unsigned)."""
    value = float(_evaluate(["sinc"], dx_l=1.0)["sinc"])
    assert fmt(value, EulerSlab.output("sinc").decimals) == "0.000000"


# --- hard case: the flag "linear acoustics invalid" -------------------------------------------------------------

# U/c = 0.01 at P = 0.01 ρc², i.e. SPL = 20 log10(P / (√2 · 20 µPa)) ≈ 154.0 dB; P = 0.1 p₀ at ≈ 171.1 dB.
SPL_MACH_LIMIT = 20 * np.log10(0.01 * RHO_AIR * C_AIR**2 / (np.sqrt(2) * 20e-6))


@pytest.mark.parametrize(
    "spl, expected",
    [
        (0.0, LINEAR),
        (94.0, LINEAR),
        (140.0, LINEAR),
        (SPL_MACH_LIMIT - 1e-9, LINEAR),
        (SPL_MACH_LIMIT + 1e-9, NONLINEAR),
        (160.0, NONLINEAR),
        (180.0, NONLINEAR),
        (191.0, NONLINEAR),
        (200.0, NONLINEAR),
    ],
    ids=[
        "0dB",
        "94dB",
        "140dB",
        "just-below-U/c=0.01",
        "just-above-U/c=0.01",
        "160dB",
        "180dB-P>0.1p0",
        "191dB-P>p0",
        "200dB",
    ],
)
def test_linear_acoustics_flag(spl, expected):
    """The regime is NONLINEAR exactly when U/c > 0.01 or P > 0.1 p₀."""
    assert int(_evaluate(["regime"], spl=spl)["regime"]) == expected


def test_whole_slider_range_is_linear():
    """Every SPL stop 0–140 dB is inside linear acoustics (U/c ≤ 2e−3)."""
    assert np.all(_evaluate(["regime"], spl=np.arange(0.0, 141.0))["regime"] == LINEAR)


# --- Newton for the slab against Euler at a point ---------------------------------------------------------------


def _grid():
    spl, f, dx_l, phi = np.meshgrid([0.0, 94.0, 140.0], [20.0, 1000.0, 20000.0], [1e-4, 0.05, 0.5], [15.0, 90.0, 210.0])
    return {"spl": spl.ravel(), "f": f.ravel(), "dx_l": dx_l.ravel(), "phi": phi.ravel()}


def test_slab_acceleration_is_euler_value_times_sinc():
    """ā = a_m · sinc(kΔx/2) within 8ε rel over SPL, f, Δx/λ and φ (Newton on the slab agrees with Euler's equation)."""
    out = EulerSlab().evaluate(_grid(), wanted=["a_slab", "a_point", "sinc"])
    np.testing.assert_allclose(out["a_slab"], out["a_point"] * out["sinc"], rtol=8 * EPS, atol=0)


@pytest.mark.parametrize("dx_l", [1e-8, 1e-6, 1e-4, 1e-2], ids=["1e-8", "1e-6", "1e-4", "1e-2"])
def test_slab_acceleration_tends_to_euler_value_for_thin_slabs(dx_l):
    """|ā/a_m − 1| equals (πΔx/λ)²/6 to leading order (within 1 % of it, or 4ε) as Δx → 0."""
    out = _evaluate(["a_slab", "a_point"], dx_l=dx_l)
    deficit = 1.0 - float(out["a_slab"] / out["a_point"])
    expected = (np.pi * dx_l) ** 2 / 6
    assert abs(deficit - expected) <= max(0.01 * expected, 4 * EPS)


@pytest.mark.parametrize("dx_l", [1e-8, 1e-4, 0.05, 0.25, 0.5, 0.9], ids=["1e-8", "1e-4", "0.05", "0.25", "0.5", "0.9"])
def test_sinc_ratio_within_1e14_of_50_digit_reference(dx_l):
    """sin(πΔx/λ)/(πΔx/λ) within 1e−14 rel of the 50-digit reference."""
    exact = _dsin_pi(dx_l) / (PI * Decimal(dx_l))
    assert _rel(float(_evaluate(["sinc"], dx_l=dx_l)["sinc"]), exact) <= 1e-14


@pytest.mark.parametrize("phi", [0.0, 180.0, 360.0, -180.0], ids=["0deg", "180deg", "360deg", "-180deg"])
def test_no_force_when_the_slab_centre_sits_at_a_pressure_extreme(phi):
    """sin φ = 0 exactly at φ = 0°, 180°: the net force and both accelerations are exactly 0 (no ±1e−16 residue)."""
    out = _evaluate(["net_force", "a_slab", "a_point"], spl=140.0, phi=phi)
    assert all(float(v) == 0.0 for v in out.values())


def test_sin_pi_is_exact_at_half_integers():
    """sin_pi(n/2) is exactly 0, 1 or −1 for n = −8..8 (the reduction is exact)."""
    n = np.arange(-8, 9)
    expected = np.array([0.0, 1.0, 0.0, -1.0])[n % 4]
    assert np.array_equal(sin_pi(n / 2.0), expected)


# --- the other readouts against 50-digit closed forms ------------------------------------------------------------


def _d_closed_forms(spl: float, f: float, dx_l: float, phi: float) -> dict[str, Decimal]:
    """Every readout of the base model (in its display unit) in 50-digit arithmetic on the float inputs."""
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        rho, c, P = Decimal(RHO_AIR), Decimal(C_AIR), _d_pressure(spl)
        lam = c / Decimal(f)
        k = 2 * PI / lam
        U = P / (rho * c)
        net = _d_net_force(spl, dx_l, phi)
        mass = rho * Decimal(dx_l) * lam
        return {
            "P": P,
            "wavelength": lam,
            "net_force": net,
            "slab_mass": 1000 * mass,
            "a_slab": net / mass,
            "a_point": P * k / rho * _dsin_pi(phi / 180.0),
            "U": 1000 * U,
            "xi": Decimal(10) ** 9 * U / (2 * PI * Decimal(f)),
            "mach": Decimal(10) ** 6 * U / c,
            "shock_distance": 1 / ((Decimal(GAMMA_AIR) + 1) / 2 * (U / c) * k),
        }


POINTS = [
    pytest.param(94.0, 1000.0, 0.05, 90.0, id="defaults"),
    pytest.param(0.0, 20.0, 1e-4, 15.0, id="quiet-low-thin"),
    pytest.param(140.0, 20000.0, 0.5, 210.0, id="loud-high-thick"),
    pytest.param(63.0, 31.5, 0.002, 345.0, id="mid"),
]


@pytest.mark.parametrize(
    "output", ["P", "wavelength", "net_force", "slab_mass", "a_slab", "a_point", "U", "xi", "mach", "shock_distance"]
)
@pytest.mark.parametrize("spl, f, dx_l, phi", POINTS)
def test_readouts_within_1e14_of_closed_forms(spl, f, dx_l, phi, output):
    """Each readout within 1e−14 rel of its closed form evaluated in 50-digit arithmetic."""
    value = float(_evaluate([output], spl=spl, f=f, dx_l=dx_l, phi=phi)[output])
    assert _rel(value, _d_closed_forms(spl, f, dx_l, phi)[output]) <= 1e-14


# --- the figure's geometry -----------------------------------------------------------------------------------


def _dcos_wave(x: float, phi: float) -> Decimal:
    """cos(2πx + φ) (φ in degrees) in 50 digits: sin(π(2x + φ/180 + 1/2)) with the argument reduced exactly."""
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        turns = 2 * Decimal(x) + Decimal(phi) / 180 + Decimal("0.5")
        turns -= 2 * (turns / 2).to_integral_value()  # into [−1, 1], exactly
        return _dsin_pi_exact(turns)


def _dsin_pi_exact(r: Decimal) -> Decimal:
    """sin(πr) for a decimal r in [−1, 1]."""
    sign = -1 if r < 0 else 1
    r = abs(r)
    r = 1 - r if r > Decimal("0.5") else r
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        return sign * _dsin(PI * r)


@pytest.mark.parametrize("phi", [0.0, 45.0, 90.0, 210.0, 345.0], ids=["0deg", "45deg", "90deg", "210deg", "345deg"])
def test_wave_curve_is_the_cosine_through_the_slab_centre(phi):
    """p′/P at the drawn x/λ is cos(2πx/λ + φ) within 16ε abs of the 50-digit value (the argument's rounding)."""
    wave = _evaluate(["wave"], phi=phi)["wave"]
    worst = max(abs(Decimal(float(w)) - _dcos_wave(x, phi)) for w, x in zip(wave, WAVE_X))
    assert float(worst) <= 16 * EPS, f"worst abs error {float(worst) / EPS:.3g} ε"


@pytest.mark.parametrize("dx_l", [1e-4, 0.05, 0.5], ids=["1e-4", "0.05", "0.5"])
def test_face_pressures_differ_by_the_net_force(dx_l):
    """P·(p_left − p_right) equals the net force within 1e−12 of P (the dots show the force's cause)."""
    out = _evaluate(["p_left", "p_right", "net_force", "P"], spl=94.0, dx_l=dx_l, phi=60.0)
    assert abs(out["P"] * (out["p_left"] - out["p_right"]) - out["net_force"]) <= 1e-12 * out["P"]


def test_drawn_slab_is_true_width_or_the_minimum():
    """The shaded band is [x₀, x₀ + Δx] when Δx ≥ λ/40, and λ/40 wide (centred) when thinner."""
    out = _evaluate(["drawn_lo", "drawn_hi", "face_lo", "face_hi"], dx_l=np.array([1e-4, 0.02, 0.05, 0.5]))
    np.testing.assert_array_equal(out["drawn_hi"] - out["drawn_lo"], [0.025, 0.025, 0.05, 0.5])
    np.testing.assert_array_equal(out["face_hi"] - out["face_lo"], [1e-4, 0.02, 0.05, 0.5])


# --- effects: each a readout with a vanishing limit ------------------------------------------------------------

BASE = ("net_force", "a_slab", "a_point", "sinc", "U", "regime")


@pytest.mark.parametrize("effect", ["convective_term", "gravity", "absorption"])
def test_enabling_an_effect_leaves_the_slab_balance_bitwise_unchanged(effect):
    """Each effect is a readout only: the base outputs are bitwise identical with and without it."""
    grid = _grid()
    plain = EulerSlab().evaluate(grid, wanted=BASE)
    with_effect = EulerSlab().evaluate(grid, wanted=BASE, effects=[effect])
    for name in BASE:
        assert np.array_equal(plain[name], with_effect[name])


def test_convective_ratio_vanishes_with_the_amplitude():
    """U/c → 0 as P → 0: it falls exactly tenfold per 20 dB (rel 1e−14) and is below 1e−15 at −120 dB."""
    spl = np.array([-120.0, -100.0, 74.0, 94.0])
    ratio = _evaluate(["convective_ratio"], effects=["convective_term"], spl=spl)["convective_ratio"] * 1e-6
    assert ratio[0] < 1e-15
    np.testing.assert_allclose(ratio[[0, 2]] / ratio[[1, 3]], 0.1, rtol=1e-14)


def test_convective_ratio_is_the_acoustic_mach_number():
    """The ratio |u ∂u/∂x| / |∂u/∂t| = U·Uk/(Uω) equals U/c (9.996e−6 at the defaults)."""
    out = _evaluate(["convective_ratio", "mach"], effects=["convective_term"])
    assert float(out["convective_ratio"]) == float(out["mach"])
    assert fmt(float(out["convective_ratio"]), 3) == "9.996"


def test_hydrostatic_difference_vanishes_with_the_slab():
    """ρgΔx → 0 linearly as Δx → 0: hydrostatic/(Δx/λ) is ρgλ within 2ε, down to Δx/λ = 1e−12."""
    dx_l = np.array([1e-12, 1e-8, 1e-4, 0.05, 0.5])
    value = _evaluate(["hydrostatic"], effects=["gravity"], dx_l=dx_l)["hydrostatic"]
    np.testing.assert_allclose(value / dx_l, RHO_AIR * G * C_AIR / 1000.0, rtol=2 * EPS)


def test_hydrostatic_difference_at_defaults():
    """ρₐgΔx = 1.204 · 9.81 · 0.05 · 0.3432 = 0.20268 Pa at the defaults."""
    value = float(_evaluate(["hydrostatic"], effects=["gravity"])["hydrostatic"])
    assert fmt(value, EulerSlab.output("hydrostatic").decimals) == "0.20268"


def test_absorption_vanishes_without_viscosity_and_conduction():
    """α = 0 exactly when μ = k_th = 0, and α scales linearly with each loss as it → 0."""
    omega = 2 * np.pi * 1000.0
    assert classical_absorption(omega, 0.0, 0.0) == 0.0
    for scale in (1e-3, 1e-9):
        scaled = classical_absorption(omega, scale * VISCOSITY_AIR, scale * CONDUCTIVITY_AIR)
        assert abs(scaled / (scale * classical_absorption(omega)) - 1.0) <= 4 * EPS


def test_absorption_vanishes_as_frequency_squared():
    """α ∝ ω²: α(f)/f² is constant within 4ε from 20 Hz to 20 kHz, and α → 0 as f → 0."""
    f = np.array([1e-6, 20.0, 1000.0, 20000.0])
    alpha = _evaluate(["alpha"], effects=["absorption"], f=f)["alpha"]
    np.testing.assert_allclose(alpha / f**2, alpha[2] / 1000.0**2, rtol=4 * EPS)
    assert alpha[0] < 1e-13


def test_absorption_at_one_kilohertz():
    """Classical α at 1 kHz: ω²/(2ρc³)(4μ/3 + (γ−1)k_th/c_p) in dB/km, recomputed in 50 digits (1e−14 rel)."""
    with localcontext() as ctx:
        ctx.prec = DIGITS
        omega = 2 * PI * 1000
        losses = Decimal(4) / 3 * Decimal(VISCOSITY_AIR) + (Decimal(GAMMA_AIR) - 1) * Decimal(
            CONDUCTIVITY_AIR
        ) / Decimal(CP_AIR)
        neper = omega**2 / (2 * Decimal(RHO_AIR) * Decimal(C_AIR) ** 3) * losses
        exact = 1000 * 20 * neper / Decimal(10).ln()
    value = float(_evaluate(["alpha"], effects=["absorption"])["alpha"])
    assert _rel(value, exact) <= 1e-14
    assert fmt(value, EulerSlab.output("alpha").decimals) == "0.1204"


# --- the readouts at the defaults, as the page shows them ---------------------------------------------------------


@pytest.mark.parametrize(
    "output, expected",
    [
        ("P", "1.41757"),  # Pa
        ("wavelength", "0.34320"),  # m
        ("net_force", "0.44351"),  # Pa
        ("slab_mass", "20.661"),  # g/m² = 2.0661e−2 kg/m²
        ("a_slab", "21.467"),  # m/s²
        ("a_point", "21.555"),  # m/s²
        ("sinc", "0.995893"),
        ("U", "3.4306"),  # mm/s = 3.4306e−3 m/s
        ("xi", "546.00"),  # nm = 5.460e−7 m
        ("mach", "9.996"),  # × 1e−6
        ("shock_distance", "4553.7"),  # m ≈ 4554 m
    ],
    ids=["P", "wavelength", "net_force", "slab_mass", "a_slab", "a_point", "sinc", "U", "xi", "mach", "shock_distance"],
)
def test_defaults_display_physics_md_values(output, expected):
    """At 94 dB, 1 kHz, Δx/λ = 0.05, φ = 90° the page shows docs/physics/euler_slab.md's values in the chosen units."""
    value = float(EulerSlab().evaluate(EulerSlab.defaults(), wanted=[output])[output])
    assert fmt(value, EulerSlab.output(output).decimals) == expected


def test_shock_distance_at_140_dB():
    """At 140 dB and 1 kHz the shock forms after 22.8 m."""
    value = float(_evaluate(["shock_distance"], spl=140.0)["shock_distance"])
    assert fmt(value, EulerSlab.output("shock_distance").decimals) == "22.8"


# --- invalid input ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "inputs",
    [
        {"f": 0.0},
        {"f": -20.0},
        {"dx_l": 0.0},
        {"dx_l": 1.5},
        {"spl": 201.0},
        {"spl": float("nan")},
        {"phi": float("inf")},
        {"dx_l": np.array([0.05, -1e-300])},
    ],
    ids=["f=0", "f<0", "dx=0", "dx>lambda", "spl>200", "spl=nan", "phi=inf", "dx-array-negative"],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """f ≤ 0, Δx/λ outside (0, 1], SPL above 200 dB or non-finite values raise ValueError naming the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        EulerSlab().evaluate(inputs)
