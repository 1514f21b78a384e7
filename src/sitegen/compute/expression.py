"""The page script's arithmetic in numpy, over many stops at once: what an expression shown by the
page evaluates to, in the script's order of operations (so that what the build verifies is what the
page shows)."""

from __future__ import annotations

import itertools

import numpy as np

from .quantize import shown_integers
from .table import Table


def table_values(table: Table, rows=slice(None)) -> np.ndarray:
    """A scalar table's values (at `rows`): doubles as stored, or quanta scaled to their digits."""
    entries = table.quanta[rows]
    if table.raw:
        return entries.astype(float)
    return entries.astype(float) if table.labels else entries / 10.0**table.decimals


def evaluate(expr: dict, parts: dict[str, Table], sliders, stops: np.ndarray) -> np.ndarray:
    """The expression's value at each row of `stops` (n × sliders), as the page's script computes it."""
    n = len(stops)
    if "c" in expr:
        return np.full(n, expr["c"])
    if "x" in expr:
        return sliders[expr["x"]][stops[:, expr["x"]]]
    if "t" in expr:
        table = parts[expr["t"]]
        return table_values(table, table.flat_indices(stops))
    if "poly" in expr:
        return _poly_value(expr, parts, sliders, stops)
    if "sel" in expr:
        which = evaluate(expr["sel"], parts, sliders, stops).astype(np.int64)
        branches = [evaluate(b, parts, sliders, stops) for b in expr["of"]]
        return np.choose(which[(...,) + (None,) * (branches[0].ndim - 1)], branches)
    if "cut" in expr:
        value = evaluate(expr["cut"], parts, sliders, stops)
        count = sum((value > edge).astype(np.int64) for edge in expr["edges"])
        return np.asarray(expr["map"], dtype=float)[count]
    if "log10" in expr:
        return expr["k"] * np.log10(evaluate(expr["log10"], parts, sliders, stops))
    if "ratio" in expr:
        top, bottom = (evaluate(e, parts, sliders, stops) for e in expr["ratio"])
        safe = np.where(bottom == 0, 1.0, bottom)
        return np.where(bottom == 0, expr["zero"], expr["k"] * top / safe)
    raise ValueError(f"unknown expression {sorted(expr)}")


def _poly_value(expr: dict, parts, sliders, stops: np.ndarray) -> np.ndarray:
    """Tensor-product Lagrange interpolation, in the script's order of operations."""
    weights = []
    for coord, nodes in zip(expr["poly"], expr["nodes"]):
        c = evaluate(coord, parts, sliders, stops)
        per_node = []
        for j, xj in enumerate(nodes):
            w = np.ones(len(stops))
            for m, xm in enumerate(nodes):
                if m != j:
                    w = w * (c - xm) / (xj - xm)
            per_node.append(w)
        weights.append(per_node)
    values = np.asarray(expr["v"], dtype=float)
    total = np.zeros((len(stops),) + values.shape[1:])
    for flat, index in enumerate(itertools.product(*[range(len(n)) for n in expr["nodes"]])):
        product = np.ones(len(stops))
        for i, j in enumerate(index):
            product = product * weights[i][j]
        total = total + (values[flat] * product[:, None] if values.ndim > 1 else values[flat] * product)
    return total


def shown(table, stops: np.ndarray) -> np.ndarray:
    """What the page shows of a `Structured` table at each row of `stops`: a label index, or integers of the last digit
    (rounded as every shown number is, ties away from zero: the script's toQuantum takes the same steps)."""
    value = evaluate(table.expr, table.parts, table.sliders, stops)
    if table.labels:
        return value.astype(np.int64)
    return shown_integers(value, table.decimals)
