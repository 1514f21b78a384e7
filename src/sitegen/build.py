"""The build, as a short script of named phases: read, resolve, convert math, tabulate, render,
assemble, write. Everything is read and computed before anything is written."""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from .compute.scenes import ResolvedScene, resolve_scene
from .compute.tabulate import Table, tabulate_scene
from .content.markdown_ext import fill_slots, markdown_to_html
from .content.math import convert_math
from .content.pages import Page, discover_pages, read_page
from .errors import AuthorError, ErrorLog, SourceLoc
from .physics import MODELS
from .render.svg import figure_svg
from .render.figures import FIGURES
from .render.layers import layer_points
from .site import assets
from .site.assemble import RenderedScene, dom_id, page_html, scene_html
from .site.writer import write_tree


@dataclass(frozen=True)
class BuildConfig:
    """Where the sources are and where the site goes."""

    root: Path
    content: Path
    out: Path
    node_modules: Path

    @classmethod
    def at(cls, root: Path, out: Path | None = None) -> "BuildConfig":
        """The conventional layout of a project rooted at `root`."""
        root = root.resolve()
        return cls(root, root / "content", (out or root / "build").resolve(), root / "node_modules")


@dataclass
class BuildReport:
    """What a build did: pages, scenes, values stored, and seconds per phase."""

    pages: int = 0
    scenes: int = 0
    stored_values: int = 0
    phases: dict[str, float] = field(default_factory=dict)
    files: dict[str, int] = field(default_factory=dict)


@dataclass(frozen=True)
class PageScene:
    """A resolved scene and the page it sits on."""

    page: Page
    index: int  # position among the page's scenes
    scene: ResolvedScene
    caption: str


def build(config: BuildConfig, progress=print) -> BuildReport:
    """Build the whole site into `config.out`, or raise BuildFailed with every author error."""
    report, log = BuildReport(), ErrorLog()
    clock = _Clock(report, progress)
    pages = clock.phase("read", read_pages, config, log)
    scenes = clock.phase("resolve", resolve_scenes, pages, log)
    mathml = clock.phase("math", convert_page_math, pages, config, log)
    log.raise_if_any()
    tables = clock.phase("tabulate", tabulate_scenes, scenes, log)
    log.raise_if_any()
    figures = clock.phase("render", render_figures, scenes, tables)
    files = clock.phase("assemble", assemble_site, pages, scenes, tables, figures, mathml, config)
    clock.phase("write", write_tree, files, config.out)
    report.pages, report.scenes = len(pages), len(scenes)
    report.stored_values = sum(t.quanta.size for ts in tables.values() for t in ts.values())
    report.files = {name: len(data) for name, data in sorted(files.items())}
    return report


def read_pages(config: BuildConfig, log: ErrorLog) -> list[Page]:
    """Parse every page under content/ (front matter, Markdown, scene blocks, formulas)."""
    pages = []
    for path in discover_pages(config.content):
        page, errors = read_page(path, config.root)
        for error in errors:
            log.add(error)
        if page is not None:
            pages.append(page)
    slugs = {p.slug for p in pages}
    for page in pages:
        if page.parent and page.parent not in slugs:
            log.add(AuthorError(SourceLoc(page.source, 1), f"parent '{page.parent}' is not a page; pages: {', '.join(sorted(slugs))}"))
    if pages and "index" not in slugs:
        log.add(AuthorError(SourceLoc(str(config.content.relative_to(config.root)), 1), "the book needs a home page, content/index.md"))
    return pages


def resolve_scenes(pages: list[Page], log: ErrorLog) -> list[PageScene]:
    """Check every scene block against the models and figures; keep the ones that resolve."""
    resolved = []
    for page in pages:
        seen: set[str] = set()
        for index, spec in enumerate(page.found.scenes):
            if spec.id in seen:
                log.add(AuthorError(spec.loc, f"another scene on this page has id '{spec.id}'; add 'id: <unique-name>'", spec.id))
                continue
            seen.add(spec.id)
            scene, errors = resolve_scene(spec, MODELS)
            figure = spec.figure or spec.model
            if scene is not None and figure not in FIGURES:
                errors.append(AuthorError(spec.loc_of("figure"), f"unknown figure '{figure}'; figures: {', '.join(sorted(FIGURES))}", spec.id))
            for error in errors:
                log.add(error)
            if not errors:
                caption = markdown_to_html(spec.caption, page.source, spec.loc_of("caption").line, page.found, inline=True)
                resolved.append(PageScene(page, index, scene, caption))
    return resolved


def convert_page_math(pages: list[Page], config: BuildConfig, log: ErrorLog) -> dict[str, list[str]]:
    """MathML for every formula of every page (one Temml run for the whole book)."""
    items = [m for page in pages for m in page.found.maths]
    mathml, errors = convert_math(items, config.node_modules)
    for error in errors:
        log.add(error)
    by_page, start = {}, 0
    for page in pages:
        by_page[page.slug] = mathml[start : start + len(page.found.maths)]
        start += len(page.found.maths)
    return by_page


def tabulate_scenes(scenes: list[PageScene], log: ErrorLog) -> dict[str, dict[str, Table]]:
    """Evaluate each scene's readouts and figure outputs over their slider grids."""
    tables = {}
    for item in scenes:
        names = needed_outputs(item.scene)
        try:
            tables[_key(item)] = tabulate_scene(item.scene, names)
        except AuthorError as error:
            log.add(error)
    return tables


def needed_outputs(scene: ResolvedScene) -> list[str]:
    """The outputs a scene shows: its readouts and whatever its figure's layers read."""
    names = [o.name for o in scene.readouts]
    for layer in FIGURES[scene.spec.figure or scene.spec.model].layers(scene):
        names += sorted(layer.outputs() - set(names))
    return names


def render_figures(scenes: list[PageScene], tables) -> dict[str, RenderedScene]:
    """Each scene's static SVG with its moving layers drawn at the default slider values."""
    figures = {}
    for item in scenes:
        scene, scene_tables = item.scene, tables[_key(item)]
        view = FIGURES[scene.spec.figure or scene.spec.model]
        layers = view.layers(scene)
        points = layer_points(layers, scene, scene_tables, scene.default_stops)
        svg = figure_svg(view.draw(scene, scene_tables), layers, points, dom_id(scene), view.label)
        figures[_key(item)] = RenderedScene(svg, tuple(layers))
    return figures


def assemble_site(pages, scenes, tables, figures, mathml, config: BuildConfig) -> dict[str, bytes]:
    """Every output file, in memory: pages, the script, the stylesheet and the math font."""
    book_title = next((p.title for p in pages if p.slug == "index"), "Book")
    files: dict[str, bytes] = {}
    for page in pages:
        html = [
            scene_html(s.scene, tables[_key(s)], figures[_key(s)], fill_slots(s.caption, page.found, mathml[page.slug], []))
            for s in scenes
            if s.page is page
        ]
        body = fill_slots(page.html, page.found, mathml[page.slug], html)
        files[page.output_name] = page_html(page, body, pages, book_title).encode()
    files["assets/sitegen.js"] = assets.script()
    files["assets/sitegen.css"] = assets.stylesheet(config.node_modules)
    files[f"assets/{assets.FONT_FILE}"] = assets.math_font([f.decode() for n, f in files.items() if n.endswith(".html")])
    return files


def _key(item: PageScene) -> str:
    return f"{item.page.slug}#{item.scene.id}"


class _Clock:
    def __init__(self, report: BuildReport, progress):
        self.report, self.progress = report, progress

    def phase(self, name: str, function, *args):
        start = time.perf_counter()
        result = function(*args)
        self.report.phases[name] = time.perf_counter() - start
        if self.progress:
            self.progress(f"{name:<9} {self.report.phases[name]:6.2f} s")
        return result
