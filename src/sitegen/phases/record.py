"""The records the build carries through its phases: one per scene, and the book that holds them.

Each phase returns a new book whose records have the phase's part filled in (MkDocs' `Page`
goes through its build the same way); nothing travels in dicts keyed by "page#scene".
"""

from __future__ import annotations

from collections.abc import Mapping
from concurrent.futures import Future
from dataclasses import dataclass, field, replace

from ..compute.accuracy import SceneAccuracy
from ..compute.cache import CacheKey
from ..compute.scenes import ResolvedScene
from ..compute.table import Table
from ..content.bibliography import PageCitations
from ..content.labels import Target, reference_html
from ..content.pages import Page
from ..render.figures.base import FigureView
from ..site.assemble import RenderedScene


@dataclass(frozen=True)
class SceneRecord:
    """One scene through the build: its block, then what each phase made of it."""

    page: Page
    index: int  # position among the page's scenes
    scene: ResolvedScene  # resolve: the block against its model (its `spec` is the block as written)
    view: FigureView  # resolve: the figure that draws it
    caption: str = ""  # resolve: the caption's HTML (math still as slots)
    outputs: tuple[str, ...] = ()  # resolve: what it shows (readouts and what its layers read)
    key: CacheKey | None = None  # resolve: the key of its tables
    tables: Mapping[str, Table] | None = None  # tabulate
    status: str = ""  # tabulate: "cached", or "computed: why"
    cached: bool = False  # tabulate: the tables came from the cache
    evaluations: int = 0  # tabulate: units of work run for them (none when cached)
    lines: tuple[str, ...] = ()  # tabulate: its lines of the build's log (cached or computed and why, notes)
    accuracy: SceneAccuracy | None = None  # check: numerically computed scenes only
    drawing: FigureWork | None = None  # figures: its figure sent out to be drawn (until render takes it)
    figure: RenderedScene | None = None  # render
    html: str = ""  # assemble: the scene element
    data_file: tuple[str, bytes] | None = None  # assemble: its data script, (name in the site, bytes)
    data_bytes: tuple[int, int] = (0, 0)  # assemble: raw and gzip bytes of its data (for the report)
    stored_values: int = 0  # tabulate: numbers its tables ship

    @property
    def name(self) -> str:
        """How the build's log and the accuracy report name the scene: "page#scene"."""
        return f"{self.page.slug}#{self.scene.spec.id}"

    @property
    def stops(self) -> int:
        """Slider states of the scene (the full cross product)."""
        count = 1
        for axis in self.scene.axes:
            count *= axis.count
        return count

    def finished(self) -> SceneRecord:
        """The record once its page is written: what the accuracy report reads is kept; the tables, figure and
        HTML are let go."""
        return replace(self, tables=None, drawing=None, figure=None, html="", data_file=None)


@dataclass(frozen=True)
class FigureWork:
    """A scene's figure sent out to be drawn: its cache key, its moving layers, what its drawing is made of (view,
    scene, tables, layers, their points at the defaults, the ids' prefix) and the future of its SVG bytes (None
    when the cache holds them)."""

    key: str
    layers: tuple
    drawing: tuple
    future: Future | None


@dataclass(frozen=True)
class Written:
    """One file the write phases put into the site, and what a page's leaves for the shared assets: the
    characters its formulas show (the math font's subset) and its sections (the search index)."""

    name: str
    size: int
    characters: frozenset[str] = frozenset()
    sections: tuple = ()


@dataclass(frozen=True)
class Book:
    """The pages, a record per resolved scene (page and scene order), the MathML of each page, the book's
    labels, each citing page's citations and the files the pages name; while it is built, the work sent out
    for its tables and the files written."""

    pages: tuple[Page, ...] = ()
    scenes: tuple[SceneRecord, ...] = ()
    mathml: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    labels: Mapping[str, Target] = field(default_factory=dict)  # link: every label, by name
    citations: Mapping[str, PageCitations] = field(default_factory=dict)  # link: by page slug
    files: tuple[str, ...] = ()  # link: the files under content/ the pages name, copied into the site
    page: Page | None = None  # the page the scene phases are working on (None: every page)
    work: Mapping[str, tuple] = field(default_factory=dict)  # send: a table key's digest -> units, futures
    diagrams: tuple = ()  # diagrams: the report's diagrams sent out, (arguments, future of {cache key: SVG bytes})
    written: tuple[Written, ...] = ()  # write: the site's files so far, in the order written

    def current(self) -> tuple[SceneRecord, ...]:
        """The records the scene phases work on now: the current page's, or all."""
        return tuple(s for s in self.scenes if self.page is None or s.page is self.page)

    def with_records(self, records) -> Book:
        """The book with some records replaced (matched by page and position)."""
        new = {(r.page.slug, r.index): r for r in records}
        return replace(self, scenes=tuple(new.get((s.page.slug, s.index), s) for s in self.scenes))

    def only(self, record: SceneRecord) -> Book:
        """The book with one scene (to work on it alone)."""
        return replace(self, scenes=(record,), page=None)

    def at(self, page: Page | None) -> Book:
        """The book with the scene phases pointed at `page`."""
        return replace(self, page=page)

    def writing_order(self) -> list[Page]:
        """Pages in the order they are finished: pages with accuracy reports last, as they read every scene."""
        return sorted(self.pages, key=lambda p: bool(p.extracted.reports))

    def in_writing_order(self) -> list[SceneRecord]:
        """The records in the order their pages are finished (`writing_order`), each page's in scene order."""
        return sorted(self.scenes, key=lambda r: bool(r.page.extracted.reports))

    def reference(self, page: Page):
        """How a reference on `page` is written: label -> the link to it, with its number."""
        return lambda name: reference_html(self.labels[name], page)

    @property
    def has_reports(self) -> bool:
        """Whether a page shows accuracy-report parts (which list every scene's data bytes)."""
        return any(p.extracted.reports for p in self.pages)

    @property
    def title(self) -> str:
        """The book's title: its home page's."""
        return next((p.title for p in self.pages if p.slug == "index"), "Book")
