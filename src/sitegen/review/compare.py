"""Two build trees compared: which pages, scenes, figures, tables and other files changed, and how."""

from __future__ import annotations

import difflib
import re
from collections.abc import Mapping
from dataclasses import dataclass, field

from ..site.assemble import SCENE_DATA
from .figures import PixelDiff, SvgChange, svg_change
from .tables import TableChange, compare_table, scene_axes
from .tree import PageDoc, Scene, parse_page, text_lines

CONTEXT = 2  # unchanged lines shown around a change
MARKUP_LINES = 40  # at most this many lines of a markup-only diff


@dataclass(frozen=True)
class DiffLine:
    """One line of a text diff: kind ' ', '-', '+' or '…' (a gap), and its text in (piece, changed) runs."""

    kind: str
    runs: tuple[tuple[str, bool], ...]

    @property
    def text(self) -> str:
        return "".join(piece for piece, _ in self.runs)


@dataclass
class FigureChange:
    """A scene's figure in both builds ('' where absent), what changed in its SVG, and its pixels."""

    old_svg: str
    new_svg: str
    svg: SvgChange | None
    pixels: PixelDiff | None = None  # filled in when the figures are rendered


@dataclass
class SceneChange:
    """A scene that differs between the builds."""

    page: str
    id: str
    model: str
    status: str  # "changed", "added" or "removed"
    figure: FigureChange | None = None
    tables: list[TableChange] = field(default_factory=list)
    table_count: int = 0  # tables the scene has (in the new build, else the old)
    controls: list[str] = field(default_factory=list)  # notes on sliders, readouts and layer recipes
    panel: list[DiffLine] = field(default_factory=list)  # text of controls, readouts (at the defaults), caption
    markup: list[str] = field(default_factory=list)  # a markup diff when no visible text explains the change


@dataclass
class PageChange:
    """A page that differs: its text outside scenes and its scenes that changed."""

    name: str
    title: str
    status: str  # "changed", "added" or "removed"
    text: list[DiffLine] = field(default_factory=list)
    markup: list[str] = field(default_factory=list)
    scenes: list[SceneChange] = field(default_factory=list)


@dataclass(frozen=True)
class FileChange:
    """Any other file (script, stylesheet, font) that differs."""

    name: str
    status: str
    old_size: int
    new_size: int


@dataclass
class Review:
    """Everything that differs between two builds; `changed` is False only for byte-identical trees."""

    old_label: str
    new_label: str
    pages: list[PageChange]
    files: list[FileChange]
    page_count: int
    scene_count: int
    changed: bool
    render_note: str = ""  # why figures were not rendered, if they were not

    def scenes(self) -> list[SceneChange]:
        return [s for p in self.pages for s in p.scenes]

    def figures(self) -> list[SceneChange]:
        return [s for s in self.scenes() if s.figure]

    def tables(self) -> list[tuple[SceneChange, TableChange]]:
        return [(s, t) for s in self.scenes() for t in s.tables]


def compare_trees(old: dict[str, bytes], new: dict[str, bytes], old_label: str, new_label: str) -> Review:
    """Compare two build trees (relative path -> bytes) file by file, pages scene by scene."""
    pages, files, scene_count = [], [], 0
    for name in sorted(set(old) | set(new)):
        a, b = old.get(name), new.get(name)
        if name.endswith(".html"):
            scene_count += len(parse_page(name, (b or a).decode()).scenes)
        if a == b or name.startswith(f"{SCENE_DATA}/"):  # a scene's data is compared with its page
            continue
        if name.endswith(".html"):
            pages.append(compare_pages(name, a, b, old, new))
        else:
            files.append(FileChange(name, _status(a, b), len(a or b""), len(b or b"")))
    page_count = len({n for n in set(old) | set(new) if n.endswith(".html")})
    return Review(old_label, new_label, pages, files, page_count, scene_count, old != new)


def _status(a, b) -> str:
    return "added" if a is None else "removed" if b is None else "changed"


def compare_pages(
    name: str, old: bytes | None, new: bytes | None, old_files: Mapping | None = None, new_files: Mapping | None = None
) -> PageChange:
    """How one page differs: its scenes one by one (their data read from the trees' files), then the rest."""
    doc_a = parse_page(name, old.decode(), old_files) if old is not None else PageDoc(name, "", (), "")
    doc_b = parse_page(name, new.decode(), new_files) if new is not None else PageDoc(name, "", (), "")
    change = PageChange(name, doc_b.title or doc_a.title, _status(old, new))
    by_id_a, by_id_b = {s.id: s for s in doc_a.scenes}, {s.id: s for s in doc_b.scenes}
    for scene_id in [s.id for s in doc_b.scenes] + [s.id for s in doc_a.scenes if s.id not in by_id_b]:
        a, b = by_id_a.get(scene_id), by_id_b.get(scene_id)
        if a is None or b is None or a.html != b.html:
            change.scenes.append(compare_scenes(name, a, b))
    if doc_a.rest != doc_b.rest:
        change.text = text_diff(text_lines(doc_a.rest), text_lines(doc_b.rest))
        if not change.text:
            change.markup = markup_diff(doc_a.rest, doc_b.rest)
    return change


def compare_scenes(page: str, a: Scene | None, b: Scene | None) -> SceneChange:
    """How one scene differs: figure, tables, controls and the text of its panel."""
    some = b or a
    change = SceneChange(page, some.id, some.model, _status(a, b), table_count=len(some.data.get("tables", {})))
    figures_a, figures_b = (a.svg, a.narrow_svg) if a else ("", ""), (b.svg, b.narrow_svg) if b else ("", "")
    if figures_a != figures_b:  # the wide figure shown, or the phone's when only that changed
        which = 0 if figures_a[0] != figures_b[0] else 1
        svg_a, svg_b = figures_a[which], figures_b[which]
        change.figure = FigureChange(svg_a, svg_b, svg_change(svg_a, svg_b) if a and b else None)
    if a is None or b is None:  # a whole scene came or went: its outputs in one line, not one row each
        change.controls = [f"{change.table_count} tables, all {change.status}"]
    elif a.data != b.data:
        change.tables = _table_changes(a.data, b.data)
        change.controls = _control_notes(a.data, b.data)
    panel_a, panel_b = a.panel if a else "", b.panel if b else ""
    if panel_a != panel_b:
        change.panel = text_diff(text_lines(panel_a), text_lines(panel_b))
    explained = change.figure or change.tables or change.controls or change.panel
    if a and b and not explained:
        change.markup = markup_diff(a.html, b.html)
    return change


def _table_changes(old: dict | None, new: dict | None) -> list[TableChange]:
    units = {r["out"]: r.get("unit", "") for d in (old or {}, new or {}) for r in d.get("readouts", [])}
    names = sorted(set((old or {}).get("tables", {})) | set((new or {}).get("tables", {})))
    changes = [compare_table(n, units.get(n, ""), old, new) for n in names]
    return [c for c in changes if c is not None]


def _control_notes(old: dict, new: dict) -> list[str]:
    """Sliders, readouts and layer recipes that differ (tables are compared separately)."""
    notes = []
    axes_a, axes_b = scene_axes(old), scene_axes(new)
    for p in sorted(set(axes_a) | set(axes_b)):
        a, b = axes_a.get(p), axes_b.get(p)
        if a != b:
            notes.append(f"slider {p}: {_axis_text(a)} → {_axis_text(b)}")
    outs_a, outs_b = [r["out"] for r in old.get("readouts", [])], [r["out"] for r in new.get("readouts", [])]
    if outs_a != outs_b:
        notes.append(f"readouts: {' '.join(outs_a) or 'none'} → {' '.join(outs_b) or 'none'}")
    layers_a = {layer["name"]: layer for layer in old.get("layers", [])}
    layers_b = {layer["name"]: layer for layer in new.get("layers", [])}
    moved = [n for n in sorted(set(layers_a) | set(layers_b)) if layers_a.get(n) != layers_b.get(n)]
    if moved:
        notes.append(f"layer recipes changed: {', '.join(moved)}")
    for key in sorted((set(old) | set(new)) - {"sliders", "tables", "readouts", "layers"}):
        if old.get(key) != new.get(key):
            notes.append(f"scene data '{key}' changed")
    return notes


def _axis_text(axis) -> str:
    if axis is None:
        return "none"
    texts = axis.texts
    shown = ", ".join(texts) if len(texts) <= 4 else f"{texts[0]}, {texts[1]} … {texts[-1]}"
    return f"{shown} ({len(texts)} stops)"


def text_diff(old: list[str], new: list[str]) -> list[DiffLine]:
    """Changed lines with a little context; a replaced line marks its changed words."""
    lines = []
    matcher = difflib.SequenceMatcher(None, old, new, autojunk=False)
    for number, group in enumerate(matcher.get_grouped_opcodes(CONTEXT)):
        if number:
            lines.append(DiffLine("…", (("", False),)))
        for tag, i1, i2, j1, j2 in group:
            if tag == "equal":
                lines += [DiffLine(" ", ((t, False),)) for t in old[i1:i2]]
            elif tag == "replace" and i2 - i1 == j2 - j1:
                for a, b in zip(old[i1:i2], new[j1:j2]):
                    lines += _word_diff(a, b)
            else:
                lines += [DiffLine("-", ((t, True),)) for t in old[i1:i2]]
                lines += [DiffLine("+", ((t, True),)) for t in new[j1:j2]]
    return lines


def _word_diff(a: str, b: str) -> list[DiffLine]:
    words_a, words_b = re.split(r"(\s+)", a), re.split(r"(\s+)", b)
    runs_a, runs_b = [], []
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(None, words_a, words_b, autojunk=False).get_opcodes():
        runs_a.append(("".join(words_a[i1:i2]), tag != "equal"))
        runs_b.append(("".join(words_b[j1:j2]), tag != "equal"))
    keep = lambda runs: tuple(r for r in runs if r[0])  # noqa: E731
    return [DiffLine("-", keep(runs_a)), DiffLine("+", keep(runs_b))]


def markup_diff(old: str, new: str) -> list[str]:
    """A unified diff of raw markup, for changes no visible text shows (cut to MARKUP_LINES lines)."""
    lines = list(difflib.unified_diff(old.splitlines(), new.splitlines(), "old", "new", n=1, lineterm=""))[2:]
    lines = [line if len(line) <= 200 else line[:200] + " …" for line in lines]
    if len(lines) > MARKUP_LINES:
        lines = lines[:MARKUP_LINES] + [f"… {len(lines) - MARKUP_LINES} more lines"]
    return lines
