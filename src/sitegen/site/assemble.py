"""HTML through jinja2: scenes (controls, readouts, figure, inline tables) and whole pages."""
from __future__ import annotations

import functools
import itertools
import json
import re
from dataclasses import dataclass
from pathlib import Path

import jinja2
import numpy as np

from ..compute.grid import CHOICE, RANGE
from ..compute.quantize import MINUS, SPECIAL, format_quantum, with_unit, written
from ..compute.scenes import ResolvedScene
from ..compute.structure import Structured
from ..compute.table import Table
from ..config import BookConfig
from ..content.pages import Page
from ..render.layers import Layer
from . import intjson, navigation
from .sizes import gzip_bytes

TEMPLATES = Path(__file__).with_name("templates")


@functools.lru_cache(maxsize=8)
def templates(theme: Path | None = None) -> jinja2.Environment:
    """The page and scene templates: a book theme's `templates/` folder first, then the built-in ones."""
    folders = [theme / "templates"] if theme is not None and (theme / "templates").is_dir() else []
    return jinja2.Environment(loader=jinja2.FileSystemLoader([*folders, TEMPLATES]), autoescape=True,
                              keep_trailing_newline=True, trim_blocks=False)


SEARCH_SCRIPT = "assets/search.js"  # the search index and its code, loaded when the search box is first used
_BIG_SVG, _BIG_DATA, _BIG_BODY = (f"\x00sitegen-{name}\x00" for name in ("svg", "data", "body"))


@dataclass(frozen=True)
class RenderedScene:
    """A scene's finished figure: the SVG with layers at the defaults, and the layer specs."""

    svg: str
    layers: tuple[Layer, ...]


def scene_html(scene: ResolvedScene, tables: dict[str, Table], figure: RenderedScene, caption: str, payload: str,
               book: BookConfig | None = None) -> str:
    """The scene element: figure, labelled controls, readouts at the defaults, and its data (`payload`)."""
    stops = scene.default_stops
    sliders = [_slider_view(scene, i, stops[i]) for i in range(len(scene.axes))]
    readouts = [_readout_view(scene, tables, o, stops) for o in scene.readouts]
    notes = [{"name": layer.name, "text": layer_text(layer, scene, tables, stops)} for layer in figure.layers if layer.kind == "text"]
    html = templates(book and book.theme).get_template("scene.html").render(
        id=dom_id(scene),
        model=scene.model.name,
        svg=_BIG_SVG,
        notes=notes,
        sliders=sliders,
        readouts=readouts,
        caption=caption,
        animate=scene.spec.animate,
        data=_BIG_DATA,
    )
    # Large trusted fragments go in after rendering: passing megabytes through jinja2's Markup is slow.
    return html.replace(_BIG_SVG, figure.svg, 1).replace(_BIG_DATA, payload, 1)


def dom_id(scene: ResolvedScene) -> str:
    """The scene element's id (prefixed so it never collides with a heading's id)."""
    return f"scene-{scene.id}"


def readout_text(table: Table, unit: str, stops: tuple[int, ...]) -> str:
    """A readout as the page shows it: a phrase, or the rounded number and its unit (to significant
    digits, with a prefix or a power of ten, for a table that has them)."""
    q = table.at(stops)
    if table.labels:
        return table.labels[q]
    if q == SPECIAL:
        return table.special
    if table.digits:
        form = written(q, int(table.exponents[table.flat_index(stops)]), table.digits, unit)
        return format_quantum(form.shown, form.decimals) + form.suffix
    return with_unit(format_quantum(q, table.decimals), unit)


def _readout_view(scene: ResolvedScene, tables: dict[str, Table], output, stops: tuple[int, ...]) -> dict:
    """A readout at the defaults: label, text, and (where it shows its special words) why."""
    text = readout_text(tables[output.name], output.unit, stops)
    why = why_text(output, tables, stops) if tables[output.name].at(stops) == SPECIAL and not output.is_text else ""
    digits = tables[output.name].digits
    note = f"{digits} significant digits; the unit's prefix follows the value" if digits else ""
    return {"name": output.name, "label": output.label, "is_text": output.is_text, "text": text, "why": why,
            "has_why": bool(output.why or output.why_from), "note": note}


def why_text(output, tables: dict[str, Table], stops: tuple[int, ...]) -> str:
    """Why an output shows its special words here, as its model says."""
    if output.why_from:
        table = tables[output.why_from]
        return table.labels[table.at(stops)]
    return output.why


def layer_text(layer: Layer, scene: ResolvedScene, tables: dict[str, Table], stops: tuple[int, ...]) -> str:
    """A text layer's words at a slider position: outputs written as readouts, parameters as controls."""
    parts = []
    for part in layer.text:
        kind, _, name = part.partition(":")
        if kind == "out":
            parts.append(readout_text(tables[name], scene.model.output(name).unit, stops))
        elif kind == "in":
            index = scene.axis_index(name)
            parts.append(slider_text(scene, index, stops[index]) if index is not None else
                         with_unit(_plain_float(scene.base_values()[name]), scene.model.param(name).unit))
        else:
            parts.append(part)
    return "".join(parts)


def _plain_float(value: float) -> str:
    return f"{value:g}".replace("-", MINUS)


def slider_text(scene: ResolvedScene, index: int, stop: int) -> str:
    """A control's value as shown beside it and announced (aria-valuetext)."""
    axis = scene.axes[index]
    if axis.kind == CHOICE:
        return axis.labels[stop]
    unit = scene.model.param(axis.param).unit
    if axis.kind == RANGE or axis.has_fractions:  # every stop with the same number of decimals
        text = format_quantum(axis.quantum(stop), axis.decimals)
    else:  # listed: each stop as the author wrote it
        text = _plain(axis.stop(stop)).replace("-", MINUS)
    return with_unit(text, unit)


def _slider_view(scene: ResolvedScene, index: int, stop: int) -> dict:
    axis = scene.axes[index]
    param = scene.model.param(axis.param)
    view = {
        "param": axis.param,
        "kind": axis.kind,
        "symbol": param.symbol,
        "unit": param.unit,
        "description": param.description,
        "stop": stop,
        "text": slider_text(scene, index, stop),
        "options": axis.labels,
    }
    if axis.kind == RANGE:
        view.update(min=_plain(axis.lo), max=_plain(axis.hi), step=_plain(axis.step), value=_plain(axis.stop(stop)))
    else:  # a listed slider moves by index; its value text says the stop
        view.update(min="0", max=str(axis.count - 1), step="1", value=str(stop))
    return view


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
        out.update(values=[float(v) for v in axis.stops], texts=[slider_text(scene, index, k) for k in range(axis.count)])
    return out


def _tables_json(tables: dict[str, Table], units: dict[str, str], encoded: list[str]) -> dict:
    """Every table once: an output whose table equals an earlier one's refers to it by name."""
    out, first_of = {}, {}
    for name, table in sorted(tables.items()):
        if isinstance(table, Structured):
            out[name] = _structured_json(table)
            continue
        exponents = b"" if table.exponents is None else table.exponents.tobytes() + units.get(name, "").encode()
        key = (table.axes, table.decimals, table.labels, table.quanta.tobytes(), table.summed_axes, table.raw, exponents)
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
    rows_json = intjson.dumps(values, table.lengths, nulls)
    deltas = None if table.special or table.labels or table.raw else intjson.dumps(_deltas(values), table.lengths)
    if deltas is not None and gzip_bytes(deltas.encode()) < gzip_bytes(rows_json.encode()):  # the smaller as sent
        out.update(q=_placeholder(deltas, encoded), enc="delta")
    else:
        out["q"] = _placeholder(rows_json, encoded)
    if table.labels:
        out["labels"] = list(table.labels)
    if table.special:
        out["special"] = table.special
    return out


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
    if values.dtype == np.int64 and values.size and not -2**62 < values.min() <= values.max() < 2**62:
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
    return with_unit(_plain_float(scene.base_values()[name]), scene.model.param(name).unit) if kind == "in" else part


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


def _plain(value) -> str:
    text = format(value.normalize(), "f")
    return "0" if text == "-0" else text


@dataclass(frozen=True)
class TocEntry:
    """A top-level page in the book's contents, with the pages under it."""

    page: Page
    children: tuple[Page, ...]


def page_html(page: Page, body: str, pages: list[Page], book_title: str, book: BookConfig | None = None) -> str:
    """A whole page: header with the trail of parents and the search box, the book's contents, the
    article with anchored headings and links to the previous and next page, and (on the home page) the
    contents with summaries; its language, author, footer and canonical address from the book's config."""
    by_slug = {p.slug: p for p in pages}
    crumbs, parent = [], page.parent
    while parent and parent in by_slug and len(crumbs) < len(pages):
        crumbs.insert(0, by_slug[parent])
        parent = by_slug[parent].parent
    contents = _contents(pages) if page.slug == "index" else []
    previous, following = navigation.neighbours(page, pages)
    html = templates(book and book.theme).get_template("base.html").render(
        page=page, body=_BIG_BODY, crumbs=crumbs, contents=contents, book_title=book_title,
        outline=navigation.outline(pages), previous=previous, next=following, has_scenes=bool(page.found.scenes),
        search_index=SEARCH_SCRIPT, book=book or BookConfig(Path(".")),
    )
    return html.replace(_BIG_BODY, navigation.with_anchors(body), 1)


def _contents(pages: list[Page]) -> list[TocEntry]:
    ordered = sorted((p for p in pages if p.slug != "index"), key=lambda p: (p.order, p.slug))
    return [TocEntry(p, tuple(c for c in ordered if c.parent == p.slug)) for p in ordered if not p.parent]
