"""A scene's inline tables (the JSON a built page ships) decoded back into values: tables, summed
differences, phrases and the expressions the page computes (evaluated as the script would)."""

from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal

import numpy as np

from ..compute.expression import shown
from ..compute.structure import Structured
from ..compute.table import Table
from ..site import vlq


@dataclass(frozen=True)
class Axis:
    """One slider of a scene: its stops as keys (to match stops across builds) and as the page writes them."""

    param: str
    keys: tuple[str, ...]
    texts: tuple[str, ...]


@dataclass(frozen=True)
class Decoded:
    """One output's values over the sliders it depends on (float; NaN pads a short vector; inf is special)."""

    params: tuple[str, ...]
    values: np.ndarray  # float, or object (the phrases of a text output); a trailing axis for a vector
    decimals: int
    is_text: bool
    is_vector: bool


def scene_axes(data: dict) -> dict[str, Axis]:
    """The scene's sliders by parameter."""
    return {s["param"]: _axis(s) for s in data.get("sliders", [])}


def _axis(slider: dict) -> Axis:
    unit = slider.get("unit", "")
    if "texts" in slider:
        texts = tuple(slider["texts"])
        if slider.get("kind") == "choice":
            return Axis(slider["param"], tuple(f"choice:{t}" for t in texts), texts)
        return Axis(slider["param"], tuple(_key(Decimal(repr(float(v)))) for v in slider["values"]), texts)
    d = slider["d"]
    values = [Decimal(slider["lo"] + k * slider["step"]).scaleb(-d) for k in range(slider["count"])]
    return Axis(slider["param"], tuple(_key(v) for v in values), tuple(with_unit(f"{v:.{d}f}", unit) for v in values))


def _key(value: Decimal) -> str:
    text = format(value.normalize(), "f")
    return "0" if text == "-0" else text


def with_unit(text: str, unit: str) -> str:
    return f"{text} {unit}".strip() if unit not in ("×", "°") else text + unit


EVALUATED_UP_TO = 500_000  # an expression over more stops is compared as an expression only


def decode(data: dict, name: str) -> Decoded | None:
    """One table of a scene's data, decoded (aliases followed, differences summed, specials as inf);
    an output the page computes from an expression is evaluated at every stop of the sliders it
    reads, or None when they are more than EVALUATED_UP_TO."""
    tables, seen = data["tables"], set()
    entry = tables[name]
    while "same" in entry and entry["same"] not in seen:
        seen.add(entry["same"])
        entry = tables[entry["same"]]
    if "expr" in entry:
        return _evaluated(data, entry)
    params = tuple(data["sliders"][a]["param"] for a in entry["axes"])
    shape, d, q = tuple(entry["shape"]), entry["d"], listed(entry)
    delta = entry.get("enc") == "delta"
    if entry.get("sum"):  # stored along the sum of its axes' stops: spread it over the grid
        counts = tuple(data["sliders"][a]["count"] for a in entry["axes"])
        values = np.asarray(q, dtype=float)[sum(np.indices(counts))]
        return Decoded(params, values if entry.get("raw") else values / 10.0**d, d, False, False)
    if entry.get("raw"):
        return Decoded(params, np.asarray(q, dtype=float).reshape(shape), d, False, False)
    if "labels" in entry:
        labels = np.array(entry["labels"], dtype=object)
        return Decoded(params, labels[np.asarray(q, dtype=np.int64)].reshape(shape), d, True, False)
    if q and isinstance(q[0], list):
        rows = [_numbers(np.cumsum(r) if delta else r) for r in q]
        width = max((len(r) for r in rows), default=0)
        values = np.full((len(rows), width), np.nan)
        for i, row in enumerate(rows):
            values[i, : len(row)] = row
        return Decoded(params, values.reshape(shape + (width,)) / 10.0**d, d, False, True)
    values = _numbers(np.cumsum(np.asarray(q, dtype=np.int64)) if delta else q)
    return Decoded(params, values.reshape(shape) / 10.0**d, d, False, False)


def listed(entry: dict) -> list:
    """A table's entries as lists (as JSON writes them): its VLQ text read, a vector's cut into rows."""
    if not isinstance(entry["q"], str):
        return entry["q"]
    numbers = vlq.loads(entry["q"])
    if "len" not in entry:
        return numbers
    ends = np.cumsum(vlq.loads(entry["len"])).tolist()
    return [numbers[start:end] for start, end in zip([0, *ends[:-1]], ends)]


def _numbers(row) -> np.ndarray:
    if isinstance(row, np.ndarray):
        return row.astype(float)
    return np.array([np.inf if v is None else v for v in row], dtype=float)


def _evaluated(data: dict, entry: dict) -> Decoded | None:
    """An expression's shown values over the grid of the sliders it reads (the script's arithmetic)."""
    names = _leaves(entry["expr"], "t")
    parts = {n: _as_table(n, data["tables"][n]) for n in names}
    axes = sorted(_leaves(entry["expr"], "x") | {a for t in parts.values() for a in t.axes})
    counts = [data["sliders"][a]["count"] for a in axes]
    if int(np.prod(counts)) > EVALUATED_UP_TO:
        return None
    stops = np.zeros((int(np.prod(counts)), len(data["sliders"])), dtype=np.int64)
    for column, index in zip(axes, np.indices(counts).reshape(len(axes), -1)):
        stops[:, column] = index
    table = Structured(
        "",
        entry["expr"],
        entry["d"],
        tuple(entry.get("labels", ())),
        entry.get("n", 0),
        "",
        parts,
        tuple(_slider_values(s) for s in data["sliders"]),
    )
    values = shown(table, stops)
    params = tuple(data["sliders"][a]["param"] for a in axes)
    grid = tuple(counts) + ((table.width,) if table.width else ())
    if table.labels:
        return Decoded(params, np.array(table.labels, dtype=object)[values].reshape(grid), table.decimals, True, False)
    return Decoded(params, (values / 10.0**table.decimals).reshape(grid), table.decimals, False, bool(table.width))


def _leaves(expr, key: str) -> set:
    """Every value under `key` in an expression: the tables ("t") or sliders ("x") it reads."""
    if isinstance(expr, dict):
        return ({expr[key]} if key in expr else set()).union(*(_leaves(v, key) for v in expr.values()))
    if isinstance(expr, list):
        return set().union(*(_leaves(v, key) for v in expr))
    return set()


def _as_table(name: str, entry: dict) -> Table:
    """A scalar table of the page's data as the build held it (differences summed)."""
    quanta = np.asarray(listed(entry), dtype=float if entry.get("raw") else np.int64)
    if entry.get("enc") == "delta":
        quanta = np.cumsum(quanta)
    return Table(
        name,
        tuple(entry["axes"]),
        tuple(entry["shape"]),
        quanta,
        entry["d"],
        tuple(entry.get("labels", ())),
        summed_axes=bool(entry.get("sum")),
        raw=bool(entry.get("raw")),
    )


def _slider_values(slider: dict) -> np.ndarray:
    """A control's value at each stop, as the page's script computes it."""
    if slider["kind"] == "choice":
        return np.arange(slider["count"], dtype=float)
    if "values" in slider:
        return np.asarray(slider["values"], dtype=float)
    return np.array([(slider["lo"] + k * slider["step"]) / 10.0 ** slider["d"] for k in range(slider["count"])])


def expression(data: dict, name: str) -> dict | None:
    """The expression an output is computed from (None for a table of values)."""
    entry = data["tables"][name]
    while "same" in entry:
        entry = data["tables"][entry["same"]]
    return entry if "expr" in entry else None
