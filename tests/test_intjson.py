"""The numpy JSON writer of table entries gives exactly json.dumps's characters; a scene's table holds
the entries the plain list-based encoding held."""

import itertools
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


@pytest.mark.parametrize(
    "entries",
    [
        [0],
        [-1],
        [7, -7, 10, -10, 9999, 10000, -(10**12)],
        [2**63 - 1, -(2**63) + 1],
        [SPECIAL, 3],
        list(range(-20000, 20000, 7)),
    ],
)
def test_lists_and_rows_as_json_writes_them(entries):
    values = np.array(entries, np.int64)
    assert intjson.dumps(values) == _reference(values)
    assert intjson.dumps(values[None, :]) == _reference(values[None, :])


@pytest.mark.parametrize("block", [intjson.BLOCK_ENTRIES, 1, 5], ids=["one-block", "a-row-a-block", "blocks-of-rows"])
def test_random_tables_with_ragged_and_empty_rows_and_nulls(block, monkeypatch):
    """Also when a table is written a few entries at a time (as a big one is)."""
    monkeypatch.setattr(intjson, "BLOCK_ENTRIES", block)
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
        assert intjson.dumps(values.reshape(-1), None, nulls.reshape(-1)) == _reference(
            values.reshape(-1), None, nulls.reshape(-1)
        )


def test_what_numpy_does_not_write_goes_through_json():
    assert intjson.dumps(np.array([1.5, -0.0])) == "[1.5,-0.0]"
    assert intjson.dumps(np.zeros((2, 0), np.int64)) == "[[],[]]"
    assert intjson.dumps(np.array([], np.int64)) == "[]"
    assert intjson.dumps(np.array([SPECIAL, 1])) == f"[{SPECIAL},1]"  # the marker, where it is not null, is a number
    assert intjson.dumps(np.array([2**70, -3], dtype=object)) == f"[{2**70},-3]"


# --- a table's JSON, against the plain list-based encoding ---------------------------------------


def _plain_table_json(table, unit):
    """What the page's JSON held before it was written from arrays: lists, written() per entry, json.dumps."""
    from sitegen.compute.quantize import written
    from sitegen.site.sizes import gzip_bytes

    rows = table.rows()
    if table.special:
        rows = [None if q == SPECIAL else q for q in rows]
    out = {"axes": list(table.axes), "shape": list(table.shape), "d": table.decimals, "q": rows}
    if table.digits:
        forms, indices, shown = {}, [], []
        for q, exponent in zip(rows, table.exponents.tolist()):
            form = written(0 if q is None else q, exponent, table.digits, unit)
            indices.append(forms.setdefault((form.decimals, form.suffix, form.power), len(forms)))
            shown.append(None if q is None else form.shown)
        out.update(q=shown, f=indices, forms=[list(key) for key in forms])
        rows = shown
    dump = lambda value: json.dumps(value, separators=(",", ":"), ensure_ascii=False)  # noqa: E731
    if not (table.special or table.labels or table.raw):
        if rows and isinstance(rows[0], list):
            deltas = [[b - a for a, b in zip([0, *row[:-1]], row)] for row in rows]
        else:
            deltas = [b - a for a, b in zip([0, *rows[:-1]], rows)]
        if gzip_bytes(dump(deltas).encode()) < gzip_bytes(dump(rows).encode()):
            out.update(q=deltas, enc="delta")
    if table.labels:
        out["labels"] = list(table.labels)
    if table.special:
        out["special"] = table.special
    return dump(out)


def _table_text(table, unit):
    from sitegen.site.payload import _spliced, _table_json

    encoded = []
    return _spliced(json.dumps(_table_json(table, unit, encoded), separators=(",", ":"), ensure_ascii=False), encoded)


def _entries(entry: dict) -> list:
    """A table's entries however they are written (JSON lists or VLQ text), differences added up."""
    from sitegen.review.decode import listed

    rows = listed(entry)
    if entry.get("enc") != "delta":
        return rows
    if rows and isinstance(rows[0], list):
        return [list(itertools.accumulate(row)) for row in rows]
    return list(itertools.accumulate(rows))


def assert_same_table(text: str, plain: str) -> None:
    """The page's table holds the entries and every other key of the plain one (the encoding may differ)."""
    got, want = json.loads(text), json.loads(plain)
    assert _entries(got) == _entries(want)
    encoding = ("q", "len", "enc")
    assert {k: v for k, v in got.items() if k not in encoding} == {k: v for k, v in want.items() if k not in encoding}


@pytest.mark.parametrize("unit", ["", "m", "J/m³", "Pa", "s", "× 10⁻⁶", "K"])
def test_significant_digit_tables_as_before(unit):
    from sitegen.compute.quantize import significant
    from sitegen.compute.table import Table

    rng = np.random.default_rng(len(unit))
    values = np.concatenate([10.0 ** rng.uniform(-16, 12, 300) * rng.choice([-1, 1], 300), [0.0, np.inf, -np.inf]])
    rng.shuffle(values)
    for special in ("", "∞"):
        mantissas, exponents = significant(values, 4, special=bool(special))
        table = Table("x", (0,), (len(values),), mantissas, 0, special=special, exponents=exponents, digits=4)
        assert_same_table(_table_text(table, unit), _plain_table_json(table, unit))


def test_vector_and_scalar_tables_as_before():
    from sitegen.compute.table import Table

    rng = np.random.default_rng(3)
    for _ in range(30):
        rows, width = (int(n) for n in rng.integers(1, 40, size=2))
        quanta = np.cumsum(rng.integers(-9, 10, size=(rows, width)), axis=1) * int(10 ** rng.integers(0, 16))
        lengths = rng.integers(0, width + 1, rows) if rng.random() < 0.5 else None
        vector = Table("v", (0,), (rows,), quanta.reshape(-1), 2, width=width, lengths=lengths)
        assert_same_table(_table_text(vector, ""), _plain_table_json(vector, ""))
        scalar = Table("s", (0,), (quanta.size,), quanta.reshape(-1), 2)
        assert_same_table(_table_text(scalar, ""), _plain_table_json(scalar, ""))
    huge = Table("h", (0,), (3,), np.array([2**62, -(2**62), 5], np.int64), 0)  # differences beyond int64
    assert _table_text(huge, "") == _plain_table_json(huge, "")  # too large for VLQ: JSON, as before
