"""A table's integers as VLQ text: every number comes back, nulls too, in the 64 characters only."""

import re

import numpy as np
import pytest

from sitegen.site import vlq


@pytest.mark.parametrize(
    "numbers, text",
    [
        ([0], "A"),
        ([1, -1], "CD"),
        ([15, -15, 16], "ef gB"),
        ([511, -512], "+fhgB"),
        ([], ""),
    ],
    ids=["zero", "one-each-sign", "one-and-two-characters", "two-and-three-characters", "empty"],
)
def test_numbers_are_written_as_source_maps_write_them(numbers, text):
    values = np.array(numbers, dtype=np.int64)
    assert vlq.dumps(values) == text.replace(" ", "")
    assert vlq.loads(vlq.dumps(values)) == numbers


def test_null_is_minus_zero():
    values, nulls = np.array([3, 0, -3], dtype=np.int64), np.array([False, True, False])
    assert vlq.dumps(values, nulls) == "GBH"
    assert vlq.loads("GBH") == [3, None, -3]


@pytest.mark.parametrize("bound", [1, 15, 16, 10**4, 10**9, 2**31, vlq.LIMIT - 1])
def test_random_numbers_come_back(bound):
    rng = np.random.default_rng(bound % 1000)
    values = rng.integers(-bound, bound, size=(50, 7), endpoint=True)
    text = vlq.dumps(values)
    assert re.fullmatch(r"[A-Za-z0-9+/]*", text)
    assert vlq.loads(text) == values.reshape(-1).tolist()


def test_what_it_cannot_hold_exactly_is_refused():
    assert vlq.fits(np.array([vlq.LIMIT - 1, -(vlq.LIMIT - 1)], dtype=np.int64))
    assert not vlq.fits(np.array([vlq.LIMIT], dtype=np.int64))
    assert not vlq.fits(np.array([1.5]))
    assert not vlq.fits(np.array([2**70], dtype=object))


@pytest.mark.parametrize("text", ["g", "A*", "é"], ids=["ends-inside-a-number", "outside-the-64", "not-ascii"])
def test_broken_text_is_an_error(text):
    with pytest.raises(ValueError):
        vlq.loads(text)
