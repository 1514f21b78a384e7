"""Display formatting (spec §0.3): integer quanta, unsigned zero, U+2212 minus, exact round trip."""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pytest

from sitegen.compute.quantize import MINUS, fmt, format_quantum, quantize


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
