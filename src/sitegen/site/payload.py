"""The data a scene's script selects from: its tables, slider grids, readouts and layer recipes as JSON
(inline in the page, inside a <script> element). A table's integers are one string of VLQ text (vlq.py),
as values or as differences between neighbours, whichever is the smaller as sent."""

from __future__ import annotations

import functools
import itertools
import json
import re

import numpy as np

from ..compute.grid import RANGE
from ..compute.quantize import SPECIAL, written
from ..compute.scenes import ResolvedScene
from ..compute.structure import Structured
from ..compute.table import Table
from ..render.layers import Layer
from . import intjson, vlq
from .assemble import fixed_text, slider_text
from .sizes import gzip_bytes


def scene_payload(scene: ResolvedScene, tables: dict[str, Table], layers: tuple[Layer, ...]) -> str:
    """The scene's tables, slider grids and layer recipes as JSON safe inside a <script> element."""
    sliders = [_axis_json(scene, i) for i in range(len(scene.axes))]
    encoded: list[str] = []
    payload = {
        "sliders": sliders,
        "tables": _tables_json(tables, {o.name: o.unit for o in scene.model.outputs}, encoded),
        "readouts": [_readout_json(o) for o in scene.readouts],
        "layers": [_layer_json(layer, scene) for layer in layers],
    }
    text = _spliced(json.dumps(payload, separators=(",", ":"), ensure_ascii=False, allow_nan=False), encoded)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


_MARK = "\ue000"  # a private-use character, in no text: it brackets the number of a table's encoded rows
_PLACEHOLDER = re.compile(f'"{_MARK}(\\d+){_MARK}"')


def _placeholder(text: str, encoded: list[str]) -> str:
    """Stands in the payload for rows already written as JSON (to measure their packed size), not encoded twice."""
    encoded.append(text)
    return f"{_MARK}{len(encoded) - 1}{_MARK}"


def _spliced(text: str, encoded: list[str]) -> str:
    """The payload with each table's JSON in place of its placeholder."""
    return _PLACEHOLDER.sub(lambda m: encoded[int(m[1])], text)


def _readout_json(output) -> dict:
    out = {"out": output.name, "unit": output.unit}
    if output.why_from:
        out["whyOf"] = output.why_from
    elif output.why:
        out["why"] = output.why
    return out


def _axis_json(scene: ResolvedScene, index: int) -> dict:
    """A control's grid for the script: evenly spaced stops as integers of the last digit, else a list."""
    axis = scene.axes[index]
    out = {"param": axis.param, "kind": axis.kind, "count": axis.count, "unit": scene.model.param(axis.param).unit}
    if axis.kind == RANGE:
        out.update(lo=int(axis.lo.scaleb(axis.decimals)), step=int(axis.step.scaleb(axis.decimals)), d=axis.decimals)
    else:
        out.update(
            values=[float(v) for v in axis.stops], texts=[slider_text(scene, index, k) for k in range(axis.count)]
        )
    return out


def _tables_json(tables: dict[str, Table], units: dict[str, str], encoded: list[str]) -> dict:
    """Every table once: an output whose table equals an earlier one's refers to it by name."""
    out, first_of = {}, {}
    for name, table in sorted(tables.items()):
        if isinstance(table, Structured):
            out[name] = _structured_json(table)
            continue
        exponents = b"" if table.exponents is None else table.exponents.tobytes() + units.get(name, "").encode()
        key = (
            table.axes,
            table.decimals,
            table.labels,
            table.quanta.tobytes(),
            table.summed_axes,
            table.raw,
            exponents,
        )
        out[name] = {"same": first_of[key]} if key in first_of else _table_json(table, units.get(name, ""), encoded)
        first_of.setdefault(key, name)
    return out


def _table_json(table: Table, unit: str, encoded: list[str]) -> dict:
    values = table.quanta.reshape(-1, table.width) if table.width else table.quanta
    # The marker becomes null, shown as the output's phrase (within a vector it stays a number).
    nulls = values == SPECIAL if table.special and not table.width else None
    out = {"axes": list(table.axes), "shape": list(table.shape), "d": table.decimals, "q": None}
    if table.digits:  # each entry written to significant digits: its shown digits and how it is written
        values, forms = _written_json(table, unit, nulls)
        out.update(forms)
    if table.summed_axes:  # indexed by the sum of the axes' stops
        out["sum"] = 1
    if table.raw:  # the values themselves (a coordinate of an expression), not counts of a digit
        out["raw"] = 1
    if table.raw or not vlq.fits(values):  # the values themselves, or integers too large: as JSON
        dump = functools.partial(intjson.dumps, lengths=table.lengths)
    else:  # as VLQ text, and a vector's entries (cut to their lengths) in one run, with the lengths beside
        dump = functools.partial(_packed, lengths=table.lengths)
        if values.ndim == 2:
            lengths = np.full(len(values), values.shape[1]) if table.lengths is None else table.lengths
            out["len"] = vlq.dumps(np.asarray(lengths, dtype=np.int64))
    rows = dump(values, nulls=nulls)
    deltas = None if table.special or table.labels or table.raw else dump(_deltas(values))
    if deltas is not None and gzip_bytes(deltas.encode()) < gzip_bytes(rows.encode()):  # the smaller as sent
        out.update(q=_placeholder(deltas, encoded), enc="delta")
    else:
        out["q"] = _placeholder(rows, encoded)
    if table.labels:
        out["labels"] = list(table.labels)
    if table.special:
        out["special"] = table.special
    return out


def _packed(values: np.ndarray, lengths: np.ndarray | None = None, nulls: np.ndarray | None = None) -> str:
    """A table's integers as a JSON string of VLQ text: a vector's rows cut to `lengths`, one after another."""
    if values.ndim == 2 and lengths is not None:
        inside = np.arange(values.shape[1]) < lengths[:, None]
        values = values[inside]
    return f'"{vlq.dumps(values, nulls)}"'


def _written_json(table: Table, unit: str, nulls: np.ndarray | None) -> tuple[np.ndarray, dict]:
    """A table shown to significant digits: the integer shown at each entry (the table's "q"), and ("f") the
    index of how it is written in a short list ("forms": [decimals, suffix, power]; the value is q × 10**power)."""
    zero = written(0, 0, table.digits, unit)  # zero, and a null entry, are written alike whatever the exponent
    forms, indices, shown, by_exponent = {}, [], [], {None: (0, (zero.decimals, zero.suffix, zero.power))}
    blanks = itertools.repeat(False) if nulls is None else nulls.tolist()
    for q, exponent, blank in zip(table.quanta.tolist(), table.exponents.tolist(), blanks):
        # A nonzero mantissa's form depends on its exponent alone, and the number shown is the mantissa scaled.
        found = by_exponent.get(None if blank or not q else exponent)
        if found is None:
            one = written(1, exponent, table.digits, unit)
            found = by_exponent[exponent] = (one.shown, (one.decimals, one.suffix, one.power))
        indices.append(forms.setdefault(found[1], len(forms)))
        shown.append(q * found[0])
    try:
        values = np.array(shown, dtype=np.int64)
    except OverflowError:  # beyond int64: kept as Python's integers
        values = np.array(shown, dtype=object)
    return values, {"f": indices, "forms": [list(key) for key in forms]}


def _structured_json(table: Structured) -> dict:
    """An output the script computes: its expression, digits, and phrases if it is text."""
    out = {"expr": table.expr, "d": table.decimals}
    if table.labels:
        out["labels"] = list(table.labels)
    if table.width:
        out["n"] = table.width
    return out


def _deltas(values: np.ndarray) -> np.ndarray:
    """Differences between neighbours (within each vector, the first against 0), which compress better when smooth."""
    if values.dtype == np.int64 and values.size and not -(2**62) < values.min() <= values.max() < 2**62:
        values = values.astype(object)  # a difference could leave int64: as Python's integers
    out = values.copy()
    out[..., 1:] -= values[..., :-1]
    return out


def _layer_json(layer: Layer, scene: ResolvedScene) -> dict:
    out = {"name": layer.name, "kind": layer.kind}
    if layer.kind == "text":  # phrases, outputs ({"o": name, "u": unit}) and controls ({"i": index})
        out["text"] = [_text_part_json(part, scene) for part in layer.text]
        return out
    if layer.xs is not None:
        out.update(xs=_ref_json(layer.xs, scene), ys=_ref_json(layer.ys, scene))
    else:
        out["pts"] = [[_ref_json(r, scene) for r in xy] for xy in layer.points]
    return out


def _text_part_json(part: str, scene: ResolvedScene):
    kind, _, name = part.partition(":")
    if kind == "out":
        return {"o": name, "u": scene.model.output(name).unit}
    if kind == "in" and scene.axis_index(name) is not None:
        return {"i": scene.axis_index(name)}
    return fixed_text(scene, name) if kind == "in" else part


def _ref_json(ref, scene: ResolvedScene):
    if isinstance(ref, tuple):
        return list(ref)
    if not isinstance(ref, str):
        return ref
    kind, name = ref.split(":", 1)
    if kind == "out":
        return ["o", name]
    index = scene.axis_index(name)
    return ["i", index] if index is not None else scene.base_values()[name]
