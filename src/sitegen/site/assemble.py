"""HTML through jinja2: scenes (controls, readouts, figure; their data, payload.py's, in a script of its own) and
whole pages."""

from __future__ import annotations

import functools
import hashlib
import html as markup
import json
import re
from dataclasses import dataclass
from pathlib import Path

import jinja2

from ..compute.grid import CHOICE, RANGE
from ..compute.quantize import MINUS, SPECIAL, format_quantum, with_unit, written
from ..compute.scenes import ResolvedScene
from ..compute.table import Table
from ..config import BookConfig
from ..content.pages import Page
from ..render.layers import Layer
from . import navigation

TEMPLATES = Path(__file__).with_name("templates")


@functools.lru_cache(maxsize=8)
def templates(theme: Path | None = None) -> jinja2.Environment:
    """The page and scene templates: a book theme's `templates/` folder first, then the built-in ones."""
    folders = [theme / "templates"] if theme is not None and (theme / "templates").is_dir() else []
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader([*folders, TEMPLATES]),
        autoescape=True,
        keep_trailing_newline=True,
        trim_blocks=False,
    )


# The ids the page template gives its own elements (a link may name them too).
TEMPLATE_IDS = ("main-content", "book-contents", "search-box", "search-status", "search-results")
SEARCH_SCRIPT = "assets/search.js"  # the search index and its code, loaded when the search box is first used
_BIG_SVG, _BIG_BODY = (f"\x00sitegen-{name}\x00" for name in ("svg", "body"))


@dataclass(frozen=True)
class RenderedScene:
    """A scene's finished figure: the SVG with layers at the defaults, and the layer specs."""

    svg: str
    layers: tuple[Layer, ...]


def scene_html(
    scene: ResolvedScene,
    tables: dict[str, Table],
    figure: RenderedScene,
    caption: str,
    data_file: str,
    book: BookConfig | None = None,
) -> str:
    """The scene element: figure, labelled controls, readouts at the defaults, and the script that brings its
    data (`data_file`, from `scene_data_file`)."""
    stops = scene.default_stops
    sliders = [_slider_view(scene, i, stops[i]) for i in range(len(scene.axes))]
    readouts = [_readout_view(scene, tables, o, stops) for o in scene.readouts]
    notes = [
        {"name": layer.name, "text": layer_text(layer, scene, tables, stops)}
        for layer in figure.layers
        if layer.kind == "text"
    ]
    html = (
        templates(book and book.theme)
        .get_template("scene.html")
        .render(
            id=dom_id(scene),
            model=scene.model.name,
            svg=_BIG_SVG,
            notes=notes,
            sliders=sliders,
            readouts=readouts,
            caption=caption,
            animate=scene.spec.animate,
            data_file=data_file,
            heights=guessed_heights(figure.svg, sliders, len(readouts), caption),
        )
    )
    # Large trusted fragments go in after rendering: passing megabytes through jinja2's Markup is slow.
    return html.replace(_BIG_SVG, figure.svg, 1)


SCENE_DATA = "assets/scenes"  # the folder of the scenes' data scripts


def scene_data_file(page: Page, scene: ResolvedScene, payload: str) -> tuple[str, bytes]:
    """A scene's data (`payload`, JSON) as a classic script beside the page, and its name in the site: the page
    itself stays small (a phone draws it before the data arrives), and file:// allows classic scripts where it
    blocks fetch. The script only keeps the JSON text, by the scene element's id (parsed when the reader first
    reaches for the scene); its name carries a digest of it, so a host may keep it cached."""
    name = f"{SCENE_DATA}/{page.slug}.{scene.id}.{hashlib.sha256(payload.encode()).hexdigest()[:10]}.js"
    text = (
        f"(window.sitegenScenes = window.sitegenScenes || {{}})[{json.dumps(dom_id(scene))}] = {json.dumps(payload)};\n"
    )
    return name, text.encode()


def scene_data_json(script: bytes) -> str:
    """The JSON a data script of `scene_data_file` keeps."""
    return json.loads(script.decode().split("] = ", 1)[1].rstrip().removesuffix(";"))  # after the element's id


def guessed_heights(svg: str, sliders: list[dict], readouts: int, caption: str) -> tuple[float, float]:
    """A guess, in rem and on the high side, of the scene's height on a phone and in a text column: the page
    holds it for a scene until the scene nears the screen and is laid out (so that what follows does not
    overlap it meanwhile). Fitted to this book's scenes laid out at 320, 412 and 1280 px (within 10 %), plus
    12 % on a phone and 20 % in a column (whose width varies more): the figure's height at its width, a row per
    slider (with the buttons' row), a line per choice and per readout, the caption's lines."""
    shapes = {kind: float(h) / float(w) for w, h, kind in _SVG_SHAPE.findall(svg)}
    wide = shapes.get("wide", 0.6)
    narrow = shapes.get("narrow", wide)
    ranges = sum(s["kind"] != CHOICE for s in sliders) + (1 if sliders else 0)
    options = sum(len(s["options"]) for s in sliders if s["kind"] == CHOICE)
    chars = len(_TAG.sub("", caption))
    phone = narrow * 23.4 + 3.6 * ranges + 0.8 * options + 2.4 * readouts + 0.043 * chars - 3.8
    column = wide * 46 + 0.7 * ranges + 2.24 * readouts + 0.027 * chars - 1.9
    return round(1.12 * phone, 1), round(1.2 * column, 1)


_SVG_SHAPE = re.compile(r'<svg [^>]*?viewBox="0 0 ([\d.]+) ([\d.]+)"[^>]*class="scene-svg (wide|narrow)"')


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
    return {
        "name": output.name,
        "label": output.label,
        "is_text": output.is_text,
        "text": text,
        "why": why,
        "has_why": bool(output.why or output.why_from),
        "note": note,
    }


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
            parts.append(slider_text(scene, index, stops[index]) if index is not None else fixed_text(scene, name))
        else:
            parts.append(part)
    return "".join(parts)


def fixed_text(scene: ResolvedScene, name: str) -> str:
    """A parameter without a slider as a readout writes it: shortest form, a true minus sign, its unit."""
    return with_unit(f"{scene.base_values()[name]:g}".replace("-", MINUS), scene.model.param(name).unit)


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
    html = (
        templates(book and book.theme)
        .get_template("base.html")
        .render(
            page=page,
            body=_BIG_BODY,
            crumbs=crumbs,
            contents=contents,
            book_title=book_title,
            outline=navigation.outline(pages),
            previous=previous,
            next=following,
            has_scenes=bool(page.extracted.scenes),
            has_math="<math" in body,
            description=description(page, body),
            search_index=SEARCH_SCRIPT,
            book=book or BookConfig(Path(".")),
        )
    )
    return html.replace(_BIG_BODY, navigation.with_anchors(body), 1)


_PARAGRAPH = re.compile(r"<p\b[^>]*>(.*?)</p>", re.S)
_TAG = re.compile(r"<[^>]+>")
DESCRIPTION_CHARS = 160  # about what a search engine shows under a result's title


def description(page: Page, body: str) -> str:
    """What a search engine shows for the page: its summary, else the start of its first paragraph."""
    if page.summary:
        return page.summary
    first = _PARAGRAPH.search(body)
    text = " ".join(markup.unescape(_TAG.sub("", first[1])).split()) if first else ""
    if len(text) <= DESCRIPTION_CHARS:
        return text
    return text[: text.rindex(" ", 0, DESCRIPTION_CHARS)].rstrip(",;:") + "\u2026"


def _contents(pages: list[Page]) -> list[TocEntry]:
    ordered = sorted((p for p in pages if p.slug != "index"), key=lambda p: (p.order, p.slug))
    return [TocEntry(p, tuple(c for c in ordered if c.parent == p.slug)) for p in ordered if not p.parent]
