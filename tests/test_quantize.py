"""Display formatting (docs/physics/README.md): integer quanta, unsigned zero, U+2212 minus, exact round trip."""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pytest

from sitegen.compute.quantize import MINUS, fmt, format_quantum, quantize, shown_integers, significant


@pytest.mark.parametrize(
    "value, decimals, expected",
    [
        (-1e-17, 3, "0.000"),
        (-2.3333333, 3, "\u22122.333"),
        (250, 3, "250.000"),
        (0.0004, 3, "0.000"),
        (-0.0004, 3, "0.000"),
        (-0.0, 3, "0.000"),
        (1.2000000000000002, 3, "1.200"),
        (5 / 3, 3, "1.667"),
        (0.9999, 3, "1.000"),
        (-0.9999, 3, "\u22121.000"),
        (-0.0006, 3, "\u22120.001"),
        (5.5, 2, "5.50"),
        (-1e-16, 2, "0.00"),
        (99.99, 1, "100.0"),
        (0.1, 4, "0.1000"),
        (-7.0, 0, "\u22127"),
    ],
    ids=[
        "-1e-17-is-unsigned-zero",
        "-2.333-uses-U+2212",
        "250-keeps-all-digits",
        "0.0004-rounds-to-zero",
        "-0.0004-rounds-to-unsigned-zero",
        "negative-zero",
        "1.2-plus-roundoff",
        "five-thirds",
        "rounds-up-into-units",
        "negative-rounds-up-into-units",
        "smallest-negative-quantum",
        "two-decimals",
        "-1e-16-two-decimals",
        "rounds-up-to-three-digits",
        "four-decimals",
        "no-decimals",
    ],
)
def test_fmt(value, decimals, expected):
    """fmt writes a number as the page shows it."""
    assert fmt(value, decimals) == expected


@pytest.mark.parametrize(
    "quantum, expected",
    [(0, "0"), (5, "5"), (-5, "\u22125"), (250, "250"), (-1234567, "\u22121234567")],
    ids=["zero", "5", "-5", "250", "-1234567"],
)
def test_format_quantum_with_no_decimals(quantum, expected):
    """With decimals = 0 a quantum is written as a plain integer, without a decimal point."""
    assert format_quantum(quantum, 0) == expected


@pytest.mark.parametrize(
    "quantum, decimals, expected",
    [(7, 3, "0.007"), (-7, 3, "\u22120.007"), (-2333, 3, "\u22122.333"), (100, 2, "1.00"), (1000, 1, "100.0")],
    ids=["leading-zeros", "negative-leading-zeros", "-2.333", "1.00", "100.0"],
)
def test_format_quantum_pads_and_places_the_point(quantum, decimals, expected):
    """A quantum is zero-padded to at least one integer digit and the point sits `decimals` from the right."""
    assert format_quantum(quantum, decimals) == expected


def test_quantize_returns_int64_counts():
    """quantize returns int64 counts of 10^−d units, rounded to nearest."""
    q = quantize(np.array([1.2000000000000002, -2.3333333, 250.0, 0.0006]), 3)
    assert q.dtype == np.int64
    assert q.tolist() == [1200, -2333, 250000, 1]


def test_quantize_folds_negative_zero():
    """Values that round to zero (−1e−17, −0.0, −0.0004) quantize to 0 and format without a sign."""
    values = np.array([-1e-17, -0.0, -0.0004, 0.0004, -4.9e-4])
    q = quantize(values, 3)
    assert q.dtype == np.int64
    assert q.tolist() == [0, 0, 0, 0, 0]
    assert [format_quantum(int(x), 3) for x in q] == ["0.000"] * len(values)


def test_quantize_keeps_the_shape_of_its_input():
    """quantize works element-wise on arrays of any shape."""
    assert quantize(np.zeros((2, 3, 4)), 2).shape == (2, 3, 4)


@pytest.mark.parametrize("decimals", [0, 1, 2, 3, 4])
def test_format_quantum_round_trips(decimals):
    """format_quantum(q, d), read back as a decimal (− → -) and scaled by 10^d, is exactly q, for many quanta."""
    rng = np.random.default_rng(1000 + decimals)
    quanta = np.concatenate([rng.integers(-(10**9), 10**9, 2000), np.arange(-1100, 1101)])
    for q in quanta.tolist():
        text = format_quantum(q, decimals)
        assert "-" not in text and text.count(MINUS) == (q < 0)
        assert Decimal(text.replace(MINUS, "-")).scaleb(decimals) == q


@pytest.mark.parametrize("decimals", [1, 2, 3])
def test_fmt_agrees_with_printf_away_from_ties(decimals):
    """Away from half-quantum ties, fmt(x, d) is printf `%.{d}f` with U+2212 and no negative zero."""
    rng = np.random.default_rng(2000 + decimals)
    values = np.concatenate([rng.uniform(-60, 60, 3000), rng.uniform(-1e-2, 1e-2, 1000)])
    scaled = values * 10**decimals
    values = values[np.abs(scaled - np.floor(scaled) - 0.5) > 1e-6]  # skip values within 1e-6 quantum of a tie
    for x in values.tolist():
        expected = f"{x:.{decimals}f}".replace("-", MINUS)
        if expected.lstrip(MINUS).strip("0.") == "":
            expected = expected.lstrip(MINUS)  # printf writes "-0.000"; the page writes "0.000"
        assert fmt(x, decimals) == expected, x


# --- the one rounding rule: to the nearest, a value half-way (to 12 significant digits) away from zero ----------

TIES = [
    (0.125, 2, "0.13"),
    (0.5625, 3, "0.563"),
    (19.375, 2, "19.38"),
    (-0.125, 2, "\u22120.13"),
    (-0.5625, 3, "\u22120.563"),
    (-19.375, 2, "\u221219.38"),
    (2.5, 0, "3"),
    (-2.5, 0, "\u22123"),
    (1.005, 2, "1.01"),  # stored as 1.00499999999999989…: half-way to 12 digits, as the 1.005 written was
    (0.285, 2, "0.29"),  # 0.28499999999999998…
    (47.5 * 0.23 / 2, 3, "5.463"),  # 5.46250000000000036…
    (5.4624999999999995, 3, "5.463"),  # the same value a few units of its last place lower (an interpolation's)
    (5.46249999999, 3, "5.462"),  # 1e-11 below the tie: below, at 12 digits
    (0.49999999999999994, 0, "1"),  # the largest double below one half: half-way to 12 digits
    (0.4999999, 0, "0"),
]


@pytest.mark.parametrize("value, decimals, expected", TIES, ids=[f"{v!r}-to-{d}" for v, d, _ in TIES])
def test_a_value_half_way_rounds_away_from_zero(value, decimals, expected):
    """A value half-way between two shown digits goes away from zero (as a printed table rounds, and as
    sitegen.js does), judged to 12 significant digits, where a double computed from decimal inputs is exact."""
    assert fmt(value, decimals) == expected


def _by_the_rule(value: float, power: int) -> int:
    """The rule in exact decimal arithmetic: value × 10**power to the nearest integer, away from zero within
    1e-12 of the value (of one unit below one) of half-way."""
    scaled = abs(Decimal(value).scaleb(power))
    whole = int(scaled)
    rest = scaled - whole
    up = rest >= Decimal("0.5") - Decimal("1e-12") * max(whole, 1)
    return (whole + up) * (-1 if value < 0 else 1)


@pytest.mark.parametrize("decimals", [0, 1, 2, 3, 4])
def test_quantize_follows_the_rule_everywhere(decimals):
    """At 20,000 seeded values with few decimals (so that many land on or near a half) and at every multiple of
    1/16 in ±64, quantize equals the rule worked in exact decimals."""
    rng = np.random.default_rng(3000 + decimals)
    values = np.concatenate([np.round(rng.uniform(-100, 100, 20_000), decimals + 1), np.arange(-1024, 1025) / 16])
    assert quantize(values, decimals).tolist() == [_by_the_rule(v, decimals) for v in values.tolist()]


@pytest.mark.parametrize("power", [-1, -2, -3])
def test_shown_integers_divides_by_the_same_rule(power):
    """A negative power (a count of tens or hundreds) rounds the quotient the same way."""
    values = np.concatenate(
        [np.arange(-4000, 4001) * 5.0, np.random.default_rng(4000 - power).uniform(-1e6, 1e6, 5000)]
    )
    assert shown_integers(values, power).tolist() == [_by_the_rule(v, power) for v in values.tolist()]


@pytest.mark.parametrize(
    "value, digits, expected",
    [
        (0.5625, 3, (563, -3)),
        (-0.5625, 3, (-563, -3)),
        (19.375, 4, (1938, -2)),
        (999.5, 3, (100, 1)),
        (9.995, 3, (100, -1)),
        (0.000125, 2, (13, -5)),
    ],
    ids=["0.5625", "-0.5625", "19.375", "999.5-carries", "9.995-carries", "0.000125"],
)
def test_significant_digits_round_half_way_away_from_zero(value, digits, expected):
    """Shown to significant digits the same rule holds (Python's formatting alone would round these to even, or
    9.995, stored below half-way, down to 9.99)."""
    mantissa, exponent = significant([value], digits)
    assert (int(mantissa[0]), int(exponent[0])) == expected
