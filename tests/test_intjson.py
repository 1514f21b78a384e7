"""The numpy JSON writer of table entries gives exactly json.dumps's characters."""
import json

import numpy as np
import pytest

from sitegen.compute.quantize import SPECIAL
from sitegen.site import intjson


def _reference(values, lengths=None, nulls=None):
    rows = values.tolist()
    blanks = np.zeros(values.shape, bool).tolist() if nulls is None else nulls.tolist()
    if values.ndim == 1:
        rows = [None if blank else v for v, blank in zip(rows, blanks)]
    else:
        rows = [[None if blank else v for v, blank in zip(row, row_blanks)] for row, row_blanks in zip(rows, blanks)]
    if lengths is not None:
        rows = [row[:n] for row, n in zip(rows, lengths.tolist())]
    return json.dumps(rows, separators=(",", ":"))


@pytest.mark.parametrize("entries", [[0], [-1], [7, -7, 10, -10, 9999, 10000, -10**12], [2**63 - 1, -2**63 + 1],
                                     [SPECIAL, 3], list(range(-20000, 20000, 7))])
def test_lists_and_rows_as_json_writes_them(entries):
    values = np.array(entries, np.int64)
    assert intjson.dumps(values) == _reference(values)
    assert intjson.dumps(values[None, :]) == _reference(values[None, :])


def test_random_tables_with_ragged_and_empty_rows_and_nulls():
    rng = np.random.default_rng(7)
    for _ in range(400):
        rows, width = rng.integers(1, 7, size=2)
        bound = 10 ** int(rng.integers(0, 19))
        values = rng.integers(-bound, bound, size=(rows, width), endpoint=True)
        lengths = rng.integers(0, width + 1, rows)
        nulls = rng.random((rows, width)) < 0.2
        if rng.random() < 0.3:
            values[nulls] = SPECIAL
        assert intjson.dumps(values) == _reference(values)
        assert intjson.dumps(values, lengths) == _reference(values, lengths)
        assert intjson.dumps(values, lengths, nulls) == _reference(values, lengths, nulls)
        assert intjson.dumps(values.reshape(-1), None, nulls.reshape(-1)) == _reference(values.reshape(-1), None, nulls.reshape(-1))


def test_what_numpy_does_not_write_goes_through_json():
    assert intjson.dumps(np.array([1.5, -0.0])) == "[1.5,-0.0]"
    assert intjson.dumps(np.zeros((2, 0), np.int64)) == "[[],[]]"
    assert intjson.dumps(np.array([], np.int64)) == "[]"
    assert intjson.dumps(np.array([SPECIAL, 1])) == f"[{SPECIAL},1]"  # the marker, where it is not null, is a number
    assert intjson.dumps(np.array([2**70, -3], dtype=object)) == f"[{2**70},-3]"
