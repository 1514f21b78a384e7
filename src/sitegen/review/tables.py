"""Two versions of a scene's table compared stop by stop (decode.py reads them back from the pages)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..compute.quantize import format_quantum
from .decode import Axis, Decoded, decode, expression, scene_axes, with_unit


@dataclass(frozen=True)
class Extreme:
    """The largest change of one kind: how big, from what to what, and at which stop."""

    size: str
    old: str
    new: str
    where: str


@dataclass(frozen=True)
class TableChange:
    """How one output's table changed between two builds."""

    output: str
    unit: str
    status: str  # "changed", "added" or "removed"
    stops: int = 0  # stops compared (those both grids share)
    changed: int = 0  # stops whose shown value changed
    largest_abs: Extreme | None = None
    largest_rel: Extreme | None = None
    where: str = ""  # the stops that changed, in short
    notes: tuple[str, ...] = ()


def compare_table(name: str, unit: str, old: dict | None, new: dict | None) -> TableChange | None:
    """How output `name` changed between two versions of a scene's data (None when it did not)."""
    if old is None or name not in old.get("tables", {}):
        return TableChange(name, unit, "added", notes=(_describe_new(new, name),))
    if new is None or name not in new.get("tables", {}):
        return TableChange(name, unit, "removed")
    expressions = expression(old, name), expression(new, name)
    if expressions[0] == expressions[1] and expressions[0] is not None:
        return None
    a, b = decode(old, name), decode(new, name)
    if a is None or b is None:  # an expression over too many stops to evaluate them all
        return _compare_expressions(name, unit, *expressions)
    axes_old, axes_new = scene_axes(old), scene_axes(new)
    params, index_old, index_new, texts = _common_stops(a.params, b.params, axes_old, axes_new)
    va, vb = _expand(a, params, index_old), _expand(b, params, index_new)
    notes = _grid_notes(a, b, axes_old, axes_new)
    if a.is_text != b.is_text:
        return TableChange(name, unit, "changed", notes=(*notes, "changed between a phrase and a number"))
    va, vb = _same_width(va, vb, len(params))
    same = (va == vb) if a.is_text else ((va == vb) | (np.isnan(va) & np.isnan(vb)))
    stop_same = same.reshape(same.shape[: len(params)] + (-1,)).all(axis=-1)
    changed = int((~stop_same).sum())
    if not changed and not notes:
        return None
    change = TableChange(
        name, unit, "changed", int(stop_same.size), changed, notes=tuple(notes), where=_where(~stop_same, params, texts)
    )
    if changed and not a.is_text:
        change = _with_extremes(change, va, vb, params, texts, a.decimals, b.decimals, a.is_vector)
    elif changed:
        first = tuple(int(i) for i in np.argwhere(~stop_same)[0])
        example = Extreme("", str(va[first]), str(vb[first]), _stop_text(first, params, texts))
        change = replace(change, largest_abs=example)
    return change


def _compare_expressions(name: str, unit: str, old: dict | None, new: dict | None) -> TableChange | None:
    """An output computed by the page from a verified expression: changed when the expression (its
    nodes, node values or digits) changed; the coordinate tables it reads ("~…") are compared as
    tables of their own."""
    if old == new:
        return None
    if old is None or new is None:
        was, now = ("a table", "an expression") if old is None else ("an expression", "a table")
        return TableChange(name, unit, "changed", notes=(f"now computed from {now} (was {was})",))
    return TableChange(name, unit, "changed", notes=("its exact expression changed (nodes, values or digits)",))


def _common_stops(pa, pb, axes_old: dict[str, Axis], axes_new: dict[str, Axis]):
    """The union of both tables' sliders, and for each the stops both builds share (by value)."""
    params = tuple(pb) + tuple(p for p in pa if p not in pb)
    index_old, index_new, texts = {}, {}, {}
    for p in params:
        ao, an = axes_old.get(p), axes_new.get(p)
        if ao and an:
            shared = set(ao.keys)
            keys = [k for k in an.keys if k in shared]
            index_old[p] = [ao.keys.index(k) for k in keys]
            index_new[p] = [an.keys.index(k) for k in keys]
            texts[p] = [an.texts[i] for i in index_new[p]]
        else:  # a slider only one build has: the other's table is constant along it
            axis = an or ao
            index_old[p] = index_new[p] = list(range(len(axis.keys)))
            texts[p] = list(axis.texts)
    return params, index_old, index_new, texts


def _expand(table: Decoded, params: tuple[str, ...], index: dict[str, list[int]]) -> np.ndarray:
    """The table's values at the shared stops, on axes in `params` order (broadcast along absent ones)."""
    values = table.values
    for position, p in enumerate(table.params):
        values = np.take(values, index[p], axis=position)
    order = [table.params.index(p) for p in params if p in table.params]
    values = np.transpose(values, order + list(range(len(table.params), values.ndim)))
    tail = values.shape[len(order) :]
    values = values.reshape(tuple(len(index[p]) if p in table.params else 1 for p in params) + tail)
    return np.broadcast_to(values, tuple(len(index[p]) for p in params) + tail)


def _same_width(va: np.ndarray, vb: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    if va.ndim == n or vb.ndim == n or va.shape[-1] == vb.shape[-1]:
        return va, vb
    width = max(va.shape[-1], vb.shape[-1])
    pad = lambda v: np.concatenate([v, np.full(v.shape[:-1] + (width - v.shape[-1],), np.nan)], axis=-1)  # noqa: E731
    return pad(va), pad(vb)


def _grid_notes(a: Decoded, b: Decoded, axes_old, axes_new) -> list[str]:
    notes = []
    if a.decimals != b.decimals and not (a.is_text or b.is_text):
        notes.append(f"shown to {b.decimals} decimals (was {a.decimals})")
    if a.params != b.params:
        notes.append(f"depends on {_names(b.params)} (was {_names(a.params)})")
    for p in sorted(set(a.params) | set(b.params)):
        ao, an = axes_old.get(p), axes_new.get(p)
        if ao and an and ao.keys != an.keys:
            notes.append(
                f"stops of {p} changed ({len(ao.keys)} → {len(an.keys)}); "
                f"compared at the {len(set(ao.keys) & set(an.keys))} both have"
            )
    return notes


def _names(params) -> str:
    return ", ".join(params) if params else "no slider"


def _with_extremes(change, va, vb, params, texts, d_old, d_new, vector) -> TableChange:
    finite = np.isfinite(va) & np.isfinite(vb)
    diff = np.where(finite, np.abs(vb - va), -1.0)
    notes = list(change.notes)
    special = int((np.isinf(va) != np.isinf(vb)).sum())
    if special:
        notes.append(f"{special} value(s) changed to or from the special phrase")
    largest_abs = largest_rel = None
    if diff.max() > 0:
        at = np.unravel_index(int(np.argmax(diff)), diff.shape)
        size = format_quantum(round(float(diff[at]) * 10**d_new), d_new)
        largest_abs = _extreme(size, va, vb, at, params, texts, d_old, d_new, change.unit, vector)
        relative = np.where(finite & (va != 0), diff / np.where(va != 0, np.abs(va), 1.0), -1.0)
        if relative.max() > 0:
            at = np.unravel_index(int(np.argmax(relative)), relative.shape)
            largest_rel = _extreme(_percent(float(relative[at])), va, vb, at, params, texts, d_old, d_new, "", vector)
        if ((va == 0) & (vb != 0) & finite).any():
            notes.append("some values changed from exactly 0 (no relative change)")
    return replace(change, largest_abs=largest_abs, largest_rel=largest_rel, notes=tuple(notes))


def _extreme(size, va, vb, at, params, texts, d_old, d_new, unit, vector) -> Extreme:
    where = _stop_text(at[: len(params)], params, texts)
    if vector:
        where = f"{where}, element {at[len(params)]}" if where else f"element {at[len(params)]}"
    old = format_quantum(round(float(va[at]) * 10**d_old), d_old)
    new = format_quantum(round(float(vb[at]) * 10**d_new), d_new)
    return Extreme(with_unit(size, unit) if unit else size, old, new, where)


def _percent(ratio: float) -> str:
    percent = 100.0 * ratio
    return f"{percent:.3g} %" if percent < 1000 else f"{ratio:.3g}×"


def _stop_text(index, params, texts) -> str:
    return ", ".join(f"{p} = {texts[p][int(k)]}" for p, k in zip(params, index))


def _where(changed: np.ndarray, params, texts) -> str:
    """The changed stops in short: all of them, a few listed, or the span along each slider."""
    count = int(changed.sum())
    if not params:
        return "the only value" if count else ""
    if count == changed.size:
        return "every stop"
    if count <= 3:
        return "; ".join(_stop_text(tuple(i), params, texts) for i in np.argwhere(changed))
    spans = []
    for position, p in enumerate(params):
        hit = np.flatnonzero(changed.any(axis=tuple(i for i in range(changed.ndim) if i != position)))
        if len(hit) < changed.shape[position]:
            first, last = texts[p][hit[0]], texts[p][hit[-1]]
            spans.append(f"{p} = {first}" if first == last else f"{p} from {first} to {last}")
    return ", ".join(spans) if spans else "spread over the whole range of every slider"


def _describe_new(data: dict | None, name: str) -> str:
    if not data:
        return "new output"
    table = decode(data, name)
    return f"new output over {_names(table.params)}" if table is not None else "new output, computed from an expression"
