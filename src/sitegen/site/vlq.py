"""A table's integers as text the page reads fast: base-64 VLQ, the encoding of source maps.

A number is written low bits first, five to a character, the sixth bit of each character set on all but
the last; the lowest bit of the first is the sign. So |n| <= 15 takes one character and |n| <= 511 two,
against up to four for "-12," in JSON, and the text is parsed by a loop over character codes rather than
as a JSON array of numbers. "Minus zero" ("B") stands for null. The 64 characters need no escaping in
JSON or in a <script> element.
"""

from __future__ import annotations

import numpy as np

DIGITS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"
LIMIT = 2**50  # beyond, a number (or a difference of two) would not come back exact in JavaScript: JSON
_ALPHABET = np.frombuffer(DIGITS.encode(), dtype=np.uint8)
_VALUES = np.full(128, 255, dtype=np.uint8)
_VALUES[_ALPHABET] = np.arange(64, dtype=np.uint8)


def fits(values: np.ndarray) -> bool:
    """Whether `values` are integers that every reader of the text gets back exactly."""
    return values.dtype == np.int64 and (not values.size or int(np.abs(values).max()) < LIMIT)


def dumps(values: np.ndarray, nulls: np.ndarray | None = None) -> str:
    """`values` (int64 that `fits`, read in C order) as VLQ text; an entry where `nulls` is true as null."""
    flat = values.reshape(-1)
    code = np.abs(flat) << 1 | (flat < 0)
    if nulls is not None:
        code[nulls.reshape(-1)] = 1
    if code.size and code.max() < 2**31:
        code = code.astype(np.int32)  # the common case, in half the memory and time
    columns, count = [], np.ones(code.size, dtype=np.int8)  # characters per number
    while True:  # one column of characters per five bits, as long as any number needs another
        rest = code >> 5
        more = rest > 0
        columns.append((code & 31).astype(np.uint8) | np.where(more, np.uint8(32), np.uint8(0)))
        if not more.any():
            break
        count += more
        code = rest
    digits = np.stack(columns, axis=1)
    written = np.arange(len(columns)) < count[:, None]  # a number's characters, up to its last
    return _ALPHABET[np.compress(written.reshape(-1), digits.reshape(-1))].tobytes().decode("ascii")


def loads(text: str) -> list[int | None]:
    """The numbers of VLQ text, None for null."""
    if not text:
        return []
    digits = _VALUES[np.frombuffer(text.encode("ascii"), dtype=np.uint8)].astype(np.uint64)
    if (digits == 255).any():
        raise ValueError("not VLQ text: a character outside its 64")
    last = digits < 32
    if not last[-1]:
        raise ValueError("VLQ text ends inside a number")
    number = np.concatenate(([0], np.cumsum(last)[:-1]))  # which number each character belongs to
    first = np.flatnonzero(np.concatenate(([True], last[:-1])))
    shift = np.uint64(5) * (np.arange(digits.size) - first[number]).astype(np.uint64)
    code = np.zeros(first.size, dtype=np.uint64)
    np.add.at(code, number, (digits & np.uint64(31)) << shift)
    magnitude = (code >> np.uint64(1)).astype(np.int64)
    signed = np.where(code & np.uint64(1), -magnitude, magnitude).tolist()
    return [None if c == 1 else n for c, n in zip(code.tolist(), signed)]
