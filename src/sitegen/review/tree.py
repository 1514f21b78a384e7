"""A built site read back for review: its files, and each page split into scenes and the rest."""

from __future__ import annotations

import json
import re
from collections.abc import Mapping
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path

from ..site.assemble import scene_data_json

_FIGURE_OPEN = re.compile(r"<figure\b([^>]*)>")
_ATTR = re.compile(r'([\w:-]+)="([^"]*)"')
_SVG = re.compile(r"<svg\b.*?</svg>", re.S)
_NARROW = re.compile(r'^<svg\b[^>]*\bclass="scene-svg narrow"')
_TITLES = (re.compile(r"<h1\b[^>]*>(.*?)</h1>", re.S), re.compile(r"<title>(.*?)</title>", re.S))


@dataclass(frozen=True)
class Scene:
    """One scene element of a built page: its figure, its data and the rest of its markup."""

    id: str  # the element id without the "scene-" prefix
    model: str
    html: str  # the whole <figure> element
    svg: str  # the inline figure (the wide one), exactly as in the page
    data: dict  # the parsed scene-data JSON
    panel: str  # the element without its figures and data: controls, readouts, caption
    narrow_svg: str = ""  # the phone's figure, if the scene has one


@dataclass(frozen=True)
class PageDoc:
    """A built page: its scenes in order and the page with each scene replaced by a marker."""

    name: str  # path under the build folder, e.g. "newtons-laws.html"
    title: str
    scenes: tuple[Scene, ...]
    rest: str


def read_tree(folder: Path) -> dict[str, bytes]:
    """Every file under `folder` by its relative POSIX path, in sorted order."""
    if not folder.is_dir():
        raise FileNotFoundError(f"no build folder at {folder}")
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def parse_page(name: str, html: str, files: Mapping[str, bytes] | None = None) -> PageDoc:
    """Split a built page into its scenes and the rest (scenes as `[scene: id]` markers); each scene's data is read
    from its script among `files` (the site's, by name), if given."""
    scenes, rest, position = [], [], 0
    for match in _FIGURE_OPEN.finditer(html):
        attrs = dict(_ATTR.findall(match[1]))
        if match.start() < position or "scene" not in attrs.get("class", "").split():
            continue
        end = html.index("</figure>", match.end()) + len("</figure>")
        scene = _scene(attrs, html[match.start() : end], files or {})
        rest += [html[position : match.start()], f"<p>[scene: {scene.id}]</p>"]
        scenes.append(scene)
        position = end
    rest.append(html[position:])
    title = next((found[1] for found in (t.search(html) for t in _TITLES) if found), name)
    return PageDoc(name, _text_of(title), tuple(scenes), "".join(rest))


def _scene(attrs: dict[str, str], block: str, files: Mapping[str, bytes]) -> Scene:
    svgs = [m[0] for m in _SVG.finditer(block)]
    script = files.get(attrs.get("data-src", ""))
    panel = block.replace(f' data-src="{attrs.get("data-src", "")}"', "", 1)  # its digest changes with the data
    for found in svgs:
        panel = panel.replace(found, "", 1)
    scene_id = attrs.get("id", "")
    return Scene(
        scene_id.removeprefix("scene-"),
        attrs.get("data-scene", ""),
        block,
        svgs[0] if svgs else "",
        json.loads(scene_data_json(script)) if script else {},
        panel,
        next((svg for svg in svgs[1:] if _NARROW.search(svg)), ""),
    )


def standalone_svg(svg: str) -> str:
    """The inline figure as a file a browser opens on its own (declares the xlink namespace)."""
    if "xlink:" in svg and "xmlns:xlink" not in svg[: svg.index(">")]:
        svg = svg.replace("<svg ", '<svg xmlns:xlink="http://www.w3.org/1999/xlink" ', 1)
    return svg if svg.endswith("\n") else svg + "\n"


NARROW_SUFFIX = ".narrow"  # "<page>/<scene id>.narrow": the phone's figure of a scene


def page_figures(build: Path) -> dict[str, str]:
    """Every scene figure of a built site, standalone, by name "<page>/<scene id>" (and "….narrow" for a phone's)."""
    figures = {}
    for path in sorted(build.rglob("*.html")):
        name = path.relative_to(build).as_posix()
        for scene in parse_page(name, path.read_text(encoding="utf-8")).scenes:
            figures[f"{name.removesuffix('.html')}/{scene.id}"] = standalone_svg(scene.svg)
            if scene.narrow_svg:
                figures[f"{name.removesuffix('.html')}/{scene.id}{NARROW_SUFFIX}"] = standalone_svg(scene.narrow_svg)
    return figures


# --- visible text -------------------------------------------------------------------------------

_BLOCKS = frozenset(
    "address article aside blockquote br dd div dl dt fieldset figcaption figure footer form h1 h2 h3 h4 h5 "
    "h6 header hr legend li main nav ol p pre section table tbody td th thead title tr ul".split()
)
_HIDDEN = frozenset(("script", "style", "svg", "template"))


class _TextLines(HTMLParser):
    """What a reader sees, one line per block; a range input shows its range, a radio its state."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.lines: list[str] = [""]
        self.hidden = 0

    def handle_starttag(self, tag, attrs):
        if tag in _HIDDEN:
            self.hidden += 1
        if self.hidden:
            return
        if tag in _BLOCKS or (tag == "math" and ("display", "block") in attrs):
            self.lines.append("")
        if tag == "dd":  # a readout reads "label: value" on one line
            self.lines.pop()
            self.lines[-1] += ": "
        if tag == "input":
            self._input(dict(attrs))

    def handle_endtag(self, tag):
        if tag in _HIDDEN:
            self.hidden = max(0, self.hidden - 1)
        elif not self.hidden and tag in _BLOCKS - {"dt"}:
            self.lines.append("")

    def handle_data(self, data):
        if not self.hidden:
            self.lines[-1] += data

    def _input(self, attrs: dict) -> None:
        if attrs.get("type") == "range":
            self.lines[-1] += f" [{attrs.get('min')} … {attrs.get('max')} step {attrs.get('step')}] "
        elif attrs.get("type") == "radio":
            self.lines[-1] += " (•) " if "checked" in attrs else " ( ) "


def text_lines(html: str) -> list[str]:
    """The visible text of an HTML fragment as non-empty lines with collapsed whitespace."""
    parser = _TextLines()
    parser.feed(html)
    parser.close()
    return [line for line in (" ".join(raw.split()) for raw in parser.lines) if line]


def _text_of(html: str) -> str:
    return " ".join(text_lines(f"<p>{html}</p>"))
