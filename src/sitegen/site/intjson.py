"""JSON text of a table's integers, written by numpy: the same characters as `json.dumps` of the lists
(compact separators), without making a Python object per entry."""

from __future__ import annotations

import json

import numpy as np

_POWERS = 10 ** np.arange(1, 19, dtype=np.int64)  # a magnitude's digit count is one more than the powers it reaches
_FOUR_DIGITS = np.frombuffer(b"".join(b"%04d" % i for i in range(10000)), dtype=np.uint32)  # "0000" … "9999"
_NULL = np.frombuffer(b"null", dtype=np.uint32)[0]
_COMMA, _OPEN, _CLOSE, _MINUS = b",[]-"
BLOCK_ENTRIES = 1 << 18  # entries written at a time


def dumps(values: np.ndarray, lengths: np.ndarray | None = None, nulls: np.ndarray | None = None) -> str:
    """`json.dumps(rows, separators=(",", ":"))` of `values`: a list (1-D), or a list of rows (2-D), each row cut
    to its length in `lengths` if given; an entry where `nulls` (same shape as `values`) is true is null."""
    if values.dtype != np.int64 or not values.size or not _representable(values, nulls):
        return json.dumps(listed(values, lengths, nulls), separators=(",", ":"), ensure_ascii=False, allow_nan=False)
    # A block of rows at a time: the scratch arrays (several times the table's own size) stay small.
    step = max(1, BLOCK_ENTRIES // (values.shape[1] if values.ndim == 2 else 1))
    return (
        "["
        + ",".join(
            _entries(
                values[i : i + step],
                None if lengths is None else lengths[i : i + step],
                None if nulls is None else nulls[i : i + step],
            )
            for i in range(0, len(values), step)
        )
        + "]"
    )


def _entries(values: np.ndarray, lengths: np.ndarray | None, nulls: np.ndarray | None) -> str:
    """`dumps` of `values` without its outer brackets."""
    nested = values.ndim == 2
    empty = None  # an empty row is written as one entry of no digits between its brackets
    if nested and lengths is not None:
        kept = np.maximum(lengths, 1)
        inside = (np.arange(values.shape[1]) < kept[:, None]).reshape(-1)
        flat, nulls = _kept(values, inside), None if nulls is None else _kept(nulls, inside)
        if not lengths.all():
            empty = _kept((lengths == 0)[:, None] & (np.arange(values.shape[1]) == 0), inside)
    else:
        kept = np.full(len(values), values.shape[-1]) if nested else None
        flat, nulls = values.reshape(-1), None if nulls is None else nulls.reshape(-1)
    blank = nulls if empty is None else empty if nulls is None else nulls | empty
    magnitudes = np.abs(flat) if blank is None else np.abs(np.where(blank, 0, flat))
    top = int(magnitudes.max())
    chunks = -(-len(str(top)) // 4)
    digits = np.searchsorted(_POWERS, magnitudes, side="right") + 1
    # Each entry gets a row of cells: 4 for "[" and "-", 4 per group of four digits (right-aligned), 4 for "]," or ",".
    cells = np.empty((flat.size, chunks + 2), np.uint32)
    rest = magnitudes.astype(np.uint32) if top < 2**32 else magnitudes
    for chunk in range(chunks):
        cells[:, chunks - chunk] = np.take(_FOUR_DIGITS, rest % 10000)
        rest = rest // 10000
    text = cells.view(np.uint8)
    stop = 4 + 4 * chunks  # where the digits end
    negative = flat < 0
    if nulls is not None:
        cells[nulls, chunks] = _NULL
        digits[nulls] = 4
        negative &= ~nulls
    if empty is not None:
        digits[empty] = 0
        negative &= ~empty
    start = stop - digits - negative
    text[np.flatnonzero(negative), start[negative]] = _MINUS
    text[:, stop] = _COMMA
    after = np.ones(flat.size, np.int64)  # characters after the digits
    if nested:
        last = np.cumsum(kept) - 1
        first = last - kept + 1
        start[first] -= 1
        text[first, start[first]] = _OPEN
        text[last, stop] = _CLOSE
        text[last, stop + 1] = _COMMA
        after[last] = 2
    after[-1] -= 1  # no comma after the last entry
    # The cells kept in each row, looked up by (first cell, characters after the digits) as whole 4-byte words.
    width = text.shape[1]
    column = np.arange(width)
    masks = (column >= np.arange(width)[:, None, None]) & (column < stop + np.arange(3)[:, None])
    keep = np.take(masks.view(np.uint32).reshape(width * 3, width // 4), start * 3 + after, axis=0).view(bool)
    return _kept(text, keep.reshape(-1)).tobytes().decode("ascii")


def listed(values: np.ndarray, lengths: np.ndarray | None = None, nulls: np.ndarray | None = None) -> list:
    """The entries as lists (as `dumps` writes them): rows cut to `lengths`, None where `nulls`."""
    rows = values.tolist() if nulls is None else np.where(nulls, None, values).tolist()
    return rows if lengths is None else [row[:n] for row, n in zip(rows, lengths.tolist())]


def _kept(array: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """The entries of `array` (in C order) where the flat mask `keep` is true (np.compress beats boolean indexing)."""
    return np.compress(keep, array.reshape(-1))


def _representable(values: np.ndarray, nulls: np.ndarray | None) -> bool:
    """Whether every entry that is written has a magnitude numpy holds (not the most negative int64)."""
    lowest = np.iinfo(np.int64).min
    return not (values == lowest).any() if nulls is None else not ((values == lowest) & ~nulls).any()
