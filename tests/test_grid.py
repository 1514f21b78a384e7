"""Slider grids: evenly spaced stops held exactly, including steps such as 1/60 that no decimal holds."""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

from sitegen.compute.grid import LIST, RANGE, Axis, as_decimal
from sitegen.compute.structure import slider_values


def test_a_fraction_step_gives_exact_frames():
    """0..2 step 1/60: 121 stops, each the float nearest k/60, texts that tell every stop apart."""
    axis = Axis.evenly("t", Decimal(0), Fraction(1, 60), 121)
    assert axis.kind == LIST and axis.count == 121
    assert [float(s) for s in axis.stops] == [k / 60 for k in range(121)]
    assert axis.decimals == 2  # 1/60 ≈ 0.0167 apart: two decimals already differ at every stop
    quanta = [axis.quantum(k) for k in range(121)]
    assert len(set(quanta)) == 121 and quanta[31] == 52 and quanta[120] == 200
    assert axis.index_of(Decimal("0.5")) == 30  # an author's decimal default finds its fraction


def test_a_fraction_that_is_a_decimal_stays_a_decimal_range():
    """step 1/4 is 0.25 exactly: the grid is the ordinary evenly spaced one."""
    axis = Axis.evenly("v", Decimal(-1), Fraction(1, 4), 9)
    assert axis.kind == RANGE and axis.stops == Axis.evenly("v", Decimal(-1), Decimal("0.25"), 9).stops
    assert as_decimal(Fraction(3, 8)) == Decimal("0.375") and as_decimal(Fraction(1, 3)) == Fraction(1, 3)


def test_negative_fraction_stops_round_to_the_nearest_shown_digit():
    """−1..1 step 1/6: one decimal tells the stops apart; −5/6 shows as −0.8, −1/2 exactly as −0.5."""
    axis = Axis.evenly("x", Decimal(-1), Fraction(1, 6), 13)
    assert axis.decimals == 1
    assert [axis.quantum(k) for k in range(13)] == [-10, -8, -7, -5, -3, -2, 0, 2, 3, 5, 7, 8, 10]


def test_exact_stops_keep_their_digits_among_fractions():
    """−1..1 step 1/24 holds −0.875 exactly: the grid shows three decimals, so −1/8 reads −0.125."""
    axis = Axis.evenly("x", Decimal(-1), Fraction(1, 24), 49)
    assert axis.decimals == 3 and axis.quantum(21) == -125


def test_the_script_sees_the_same_floats():
    """slider_values (what the page's script computes) of a fraction grid are the model's floats."""

    class Scene:
        axes = (Axis.evenly("t", Decimal(0), Fraction(1, 60), 121),)

    (values,) = slider_values(Scene())
    assert values.tolist() == [k / 60 for k in range(121)]
