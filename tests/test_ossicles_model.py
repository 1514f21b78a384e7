"""K1 (middle-ear ossicle lever): exact rationals, the two ledgers kept apart, the matched load and the effects."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from sitegen.compute.quantize import fmt
from sitegen.models.ossicles.model import COCHLEA, WATER, Z_AIR, Z_WATER, Ossicles, transmission

EPS = np.finfo(float).eps
ALL = ("lever", "area_ratio", "load_model")
LOAD_IDS = {WATER: "water", COCHLEA: "cochlea"}


def _evaluate(wanted=None, effects=ALL, **inputs):
    """The model's outputs with every effect on unless told (others at their defaults)."""
    return Ossicles().evaluate(inputs, wanted=wanted, effects=effects)


def _exact(A_TM, A_FP, ell, spl_pressure, load) -> dict[str, Fraction]:
    """The rational outputs in exact arithmetic on the float inputs (T in %, impedances in Pa·s/m)."""
    A_TM, A_FP, ell = (Fraction(float(v)) for v in (A_TM, A_FP, ell))
    Z_a = Fraction(Z_AIR)
    Z_c = Fraction(Z_WATER) if load == WATER else Fraction(21.1e9) * A_FP * Fraction(1e-6)
    A_r = A_TM / A_FP
    Z_ref = Z_c / (ell**2 * A_r)

    def T(Z1, Z2):
        return 4 * Z1 * Z2 / (Z1 + Z2) ** 2

    return {
        "A_r": A_r,
        "G": ell * A_r,
        "p_OW": ell * A_r * Fraction(spl_pressure),
        "Z_c": Z_c,
        "Z_ref": Z_ref,
        "T0": 100 * T(Z_a, Z_c),
        "T1": 100 * T(Z_a, Z_ref),
        "ell_match_squared": Z_c / (Z_a * A_r),
    }


POINTS = [
    pytest.param(55.0, 3.2, 1.3, WATER, id="defaults-water"),
    pytest.param(55.0, 3.2, 1.3, COCHLEA, id="defaults-cochlea"),
    pytest.param(20.0, 5.0, 1.0, WATER, id="small-drum-big-plate"),
    pytest.param(90.0, 1.5, 3.0, COCHLEA, id="largest-gain-cochlea"),
    pytest.param(67.0, 2.7, 2.35, WATER, id="mid-water"),
    pytest.param(31.0, 4.1, 1.85, COCHLEA, id="mid-cochlea"),
]


# --- the readouts at the defaults ----------------------------------------------------------------------------

DEFAULT_READOUTS = [
    ("A_r", WATER, "17.19"),
    ("G", WATER, "22.34"),
    ("G_dB", WATER, "26.98"),
    ("p_TM", WATER, "0.0200"),
    ("p_OW", WATER, "0.447"),
    ("T0", WATER, "0.1117"),
    ("T0_dB", WATER, "\u221229.52"),
    ("T1", WATER, "3.19"),
    ("T1_dB", WATER, "\u221214.96"),
    ("ell_match", WATER, "14.43"),
    ("T0", COCHLEA, "2.4183"),
    ("T0_dB", COCHLEA, "\u221216.16"),
    ("T1", COCHLEA, "51.26"),
    ("T1_dB", COCHLEA, "\u22122.90"),
    ("ell_match", COCHLEA, "3.08"),
    ("Z_c", COCHLEA, "67520"),
    ("Z_c", WATER, "1479332"),
]


@pytest.mark.parametrize(
    "output, load, expected", DEFAULT_READOUTS, ids=[f"{o}-{LOAD_IDS[load]}" for o, load, _ in DEFAULT_READOUTS]
)
def test_defaults_display_the_spec_readouts(output, load, expected):
    """At the defaults (55 mm², 3.2 mm², ℓ = 1.3, 60 dB) the page shows docs/physics/ossicles.md's values (T in %)."""
    value = float(_evaluate([output], **{**Ossicles.defaults(), "load": load})[output])
    assert fmt(value, Ossicles.output(output).decimals) == expected


# --- exact rationals -----------------------------------------------------------------------------------------


@pytest.mark.parametrize("output", ["A_r", "G", "Z_c", "Z_ref", "T0", "T1"])
@pytest.mark.parametrize("A_TM, A_FP, ell, load", POINTS)
def test_outputs_against_exact_rationals(A_TM, A_FP, ell, load, output):
    """A_r, G, Z_c, Z_ref, T₀ and T₁ within 8ε rel of exact rational arithmetic on the same float inputs."""
    value = float(_evaluate([output], A_TM=A_TM, A_FP=A_FP, ell=ell, load=load)[output])
    exact = _exact(A_TM, A_FP, ell, 0.02, load)[output]
    assert abs(Fraction(value) - exact) / exact <= 8 * Fraction(EPS)


@pytest.mark.parametrize("A_TM, A_FP, ell, load", POINTS)
def test_pressure_at_the_oval_window_is_the_gain_times_the_eardrum_pressure(A_TM, A_FP, ell, load):
    """p_OW = ℓA_r·p_TM within 8ε rel, with p_TM = 20 µPa·10^(SPL/20) = 0.02 Pa at 60 dB."""
    out = _evaluate(["p_OW", "p_TM"], A_TM=A_TM, A_FP=A_FP, ell=ell, load=load, SPL=60.0)
    exact = _exact(A_TM, A_FP, ell, float(out["p_TM"]), load)["p_OW"]
    assert float(out["p_TM"]) == 0.02
    assert abs(Fraction(float(out["p_OW"])) - exact) / exact <= 8 * Fraction(EPS)


@pytest.mark.parametrize("A_TM, A_FP, ell, load", POINTS)
def test_lever_ratio_for_a_perfect_match(A_TM, A_FP, ell, load):
    """ℓ_match² = Z_c/(Z_a A_r) within 8ε rel; with ℓ = ℓ_match the transformer transmits T₁ = 100 % (within 1e−13)."""
    match = float(_evaluate(["ell_match"], A_TM=A_TM, A_FP=A_FP, load=load)["ell_match"])
    exact = _exact(A_TM, A_FP, ell, 0.02, load)["ell_match_squared"]
    assert abs(Fraction(match) ** 2 - exact) / exact <= 8 * Fraction(EPS)
    T1 = float(_evaluate(["T1"], A_TM=A_TM, A_FP=A_FP, ell=match, load=load)["T1"])
    assert abs(T1 - 100.0) <= 1e-13


@pytest.mark.parametrize("A_TM, A_FP, ell, load", POINTS)
def test_acoustic_impedance_transforms_by_one_over_G_squared(A_TM, A_FP, ell, load):
    """Second route to the referred load: (Z_ref/A_TM) = (Z_c/A_FP)/G² in acoustic terms, within 8ε rel."""
    out = _evaluate(["Z_ref", "Z_c", "G"], A_TM=A_TM, A_FP=A_FP, ell=ell, load=load)
    referred = float(out["Z_ref"]) / A_TM
    transformed = float(out["Z_c"]) / A_FP / float(out["G"]) ** 2
    assert abs(referred - transformed) <= 8 * EPS * transformed


def test_measured_cochlea_load_is_about_67500_at_the_default_footplate():
    """Z_c = 21.1 GΩ × 3.2 mm² = 6.752e4 Pa·s/m (docs/physics/ossicles.md: 6.75e4)."""
    assert float(_evaluate(["Z_c"], load=COCHLEA, A_FP=3.2)["Z_c"]) == pytest.approx(67520.0, rel=1e-15)


# --- hard case: pressure gain and power transmission are different ledgers -----------------------------------

NUMERIC = [o.name for o in Ossicles.outputs if not o.is_text and not o.size]


@pytest.mark.parametrize("A_TM, A_FP, ell, load", POINTS)
def test_no_output_adds_the_pressure_gain_to_a_power_transmission(A_TM, A_FP, ell, load):
    """No output equals G_dB + 10 log T₀ (or G_dB + 10 log T₁), even to the displayed 0.01 dB."""
    out = _evaluate(NUMERIC, A_TM=A_TM, A_FP=A_FP, ell=ell, load=load)
    for wrong in (out["G_dB"] + out["T0_dB"], out["G_dB"] + out["T1_dB"]):
        close = [name for name in NUMERIC if abs(float(out[name]) - float(wrong)) < 0.005]
        assert not close, f"{close} equal G_dB + 10 log T"


def test_the_transformer_lifts_water_transmission_from_minus_29_5_to_minus_15_dB():
    """Water load at the defaults: 10 log T goes −29.52 → −14.96 dB, a 14.56 dB power gain — not the 26.98 dB of
    G_dB."""
    out = _evaluate(["T0_dB", "T1_dB", "G_dB"], load=WATER)
    lift = float(out["T1_dB"] - out["T0_dB"])
    assert fmt(lift, 2) == "14.56" and abs(lift - float(out["G_dB"])) > 12


# --- hard case: equal impedances, and the formula's range ------------------------------------------------------


@pytest.mark.parametrize(
    "Z",
    [1e-100, 1e-5, 1.0, Z_AIR, 67520.0, Z_WATER, 3.7e12, 1e150],
    ids=["1e-100", "1e-5", "1", "Z_air", "Z_cochlea", "Z_water", "3.7e12", "1e150"],
)
def test_equal_impedances_transmit_everything_exactly(Z):
    """Z₁ = Z₂ gives T = 1.0 exactly (4Z·Z and (2Z)² round to the same double)."""
    assert transmission(Z, Z) == 1.0


@pytest.mark.parametrize("ratio", [1e-12, 1e-6, 0.37, 1.0, 2.9, 1e6, 1e12], ids=lambda r: f"Z2/Z1={r:g}")
def test_transmission_is_symmetric_and_at_most_one(ratio):
    """T(Z₁, Z₂) = T(Z₂, Z₁) bitwise and 0 < T ≤ 1; within 8ε rel of the exact 4r/(1 + r)²."""
    Z1, Z2 = Z_AIR, Z_AIR * ratio
    T = transmission(Z1, Z2)
    exact = 4 * Fraction(Z1) * Fraction(Z2) / (Fraction(Z1) + Fraction(Z2)) ** 2
    assert T == transmission(Z2, Z1) and 0 < T <= 1.0
    assert abs(Fraction(T) - exact) / exact <= 8 * Fraction(EPS)


def test_zero_db_input_is_fine():
    """SPL = 0 dB gives p_TM = 20 µPa and a finite p_OW (no dB of zero pressure is ever needed)."""
    out = _evaluate(["p_TM", "p_OW"], SPL=0.0)
    assert float(out["p_TM"]) == 20e-6 and math.isfinite(float(out["p_OW"]))


# --- effects and their vanishing limits ------------------------------------------------------------------------


def _random_inputs(seed: int, n: int = 300):
    rng = np.random.default_rng(seed)
    return {
        "A_TM": rng.uniform(20, 90, n),
        "A_FP": rng.uniform(1.5, 5.0, n),
        "ell": rng.uniform(1.0, 3.0, n),
        "SPL": rng.uniform(0, 120, n),
        "load": rng.integers(0, 2, n).astype(float),
    }


def _bitwise_equal(a, b) -> bool:
    return np.array_equal(np.asarray(a, float).view(np.uint8), np.asarray(b, float).view(np.uint8))


@pytest.mark.parametrize("output", ["G", "G_dB", "A_r"])
def test_lever_ratio_one_gives_the_area_ratio_alone(output):
    """Vanishing limit of `lever`: ℓ = 1 gives G = A_r bitwise (and G_dB = 20 log A_r)."""
    inputs = {**_random_inputs(seed=1), "ell": 1.0}
    out = _evaluate(["G", "A_r", "G_dB"], **inputs)
    reference = {"G": out["A_r"], "A_r": out["G"], "G_dB": 20 * np.log10(out["A_r"])}[output]
    assert _bitwise_equal(out[output], reference)


@pytest.mark.parametrize("output", NUMERIC)
def test_lever_off_equals_lever_ratio_one(output):
    """Without `lever` every output is bitwise the one with ℓ = 1 (whatever ℓ says)."""
    inputs = _random_inputs(seed=2)
    off = _evaluate([output], effects=("area_ratio", "load_model"), **inputs)[output]
    on = _evaluate([output], **{**inputs, "ell": 1.0})[output]
    assert _bitwise_equal(off, on)


@pytest.mark.parametrize("output", NUMERIC)
def test_area_ratio_off_equals_equal_areas(output):
    """Without `area_ratio` every output is bitwise the one with A_TM = A_FP (A_r = 1, G = ℓ)."""
    inputs = _random_inputs(seed=3)
    off = _evaluate([output], effects=("lever", "load_model"), **inputs)[output]
    on = _evaluate([output], **{**inputs, "A_TM": inputs["A_FP"]})[output]
    assert _bitwise_equal(off, on)


def test_area_ratio_off_leaves_the_lever_alone():
    """Without `area_ratio`: A_r = 1 exactly and G = ℓ exactly."""
    inputs = _random_inputs(seed=4)
    out = _evaluate(["A_r", "G"], effects=("lever", "load_model"), **inputs)
    assert np.all(out["A_r"] == 1.0) and np.array_equal(out["G"], inputs["ell"])


@pytest.mark.parametrize("output", NUMERIC)
def test_load_model_off_is_the_water_load(output):
    """Without `load_model` every output is bitwise the water half-space's."""
    inputs = _random_inputs(seed=5)
    off = _evaluate([output], effects=("lever", "area_ratio"), **inputs)[output]
    on = _evaluate([output], **{**inputs, "load": WATER})[output]
    assert _bitwise_equal(off, on)


@pytest.mark.parametrize("load", [WATER, COCHLEA], ids=["water", "cochlea"])
def test_no_transformer_transmission_ignores_the_lever(load):
    """T₀ depends on the load (and A_FP for the cochlea) only: ℓ and A_TM leave it bitwise unchanged."""
    inputs = {**_random_inputs(seed=6), "load": load}
    a = _evaluate(["T0"], **inputs)["T0"]
    b = _evaluate(["T0"], **{**inputs, "ell": 2.2, "A_TM": 44.0})["T0"]
    assert _bitwise_equal(a, b)


# --- figure geometry ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("ell", [1.0, 1.3, 2.05, 3.0], ids=lambda v: f"ell={v:g}")
def test_pivot_divides_the_bar_in_the_lever_ratio(ell):
    """The drawn pivot splits a unit bar into arms in the ratio ℓ : 1 (within 4ε)."""
    pivot = float(_evaluate(["pivot"], ell=ell)["pivot"])
    assert abs(pivot / (1 - pivot) - ell) <= 4 * EPS * ell


@pytest.mark.parametrize("output, area", [("span_TM", "A_TM"), ("span_FP", "A_FP")], ids=["eardrum", "footplate"])
def test_piston_spans_are_the_effective_diameters(output, area):
    """The drawn span of a piston is ±√(A/π): its length squared × π/4 gives back the area (within 8ε rel)."""
    inputs = _random_inputs(seed=7)
    span = _evaluate([output], **inputs)[output]
    diameter = span[:, 1] - span[:, 0]
    assert np.max(np.abs(np.pi * diameter**2 / 4 / inputs[area] - 1)) <= 8 * EPS


# --- invalid input -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "inputs",
    [
        {"A_TM": 0.0},
        {"A_TM": -5.0},
        {"A_FP": 0.0},
        {"ell": 0.0},
        {"ell": -1.3},
        {"load": 0.5},
        {"load": 2.0},
        {"SPL": float("nan")},
        {"A_FP": float("inf")},
    ],
    ids=["A_TM=0", "A_TM<0", "A_FP=0", "ell=0", "ell<0", "load=0.5", "load=2", "SPL=nan", "A_FP=inf"],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """Out-of-domain or non-finite inputs raise ValueError naming the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Ossicles().evaluate(inputs, effects=ALL)
