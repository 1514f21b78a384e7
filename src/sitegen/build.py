"""The build, as a short script of named phases: read, resolve, convert math, tabulate, check, render,
assemble, report (the accuracy page's blocks), write. Everything is read and computed before anything is written."""
from __future__ import annotations

import time
from math import prod
from dataclasses import dataclass, field
from pathlib import Path

from .accuracy.check import caption_sentence, check_scenes
from .accuracy.page import fill_reports
from .accuracy.records import SceneAccuracy
from .accuracy.results import BENCH_NAME
from .compute.scenes import ResolvedScene, resolve_scene
from .compute.cache import TableCache, compute_now, digest, forget_sources, library_version, scene_key, source_digest
from .compute.executors import executor_for
from .compute.tabulate import Table, assemble_tables, evaluate_unit, plan_scene
from .content.markdown_ext import fill_slots, markdown_to_html
from .content.math import convert_math
from .content.pages import Page, discover_pages, read_page
from .errors import AuthorError, ErrorLog, SourceLoc
from .physics import MODELS, compiled
from .render.svg import figure_svg
from .render.figures import FIGURES
from .render.figures.base import figure_label
from .render.layers import layer_points
from .site import assets
from .site.assemble import RenderedScene, dom_id, page_html, scene_html, scene_payload
from .site.writer import write_tree


@dataclass(frozen=True)
class BuildConfig:
    """Where the sources are, where the site goes, the cache, and where the work runs."""

    root: Path
    content: Path
    out: Path
    node_modules: Path
    cache: Path | None = None  # None: compute everything, remember nothing
    jobs: int = 1
    scheduler: str | None = None  # address of a Dask scheduler, e.g. tcp://127.0.0.1:8786

    @classmethod
    def at(cls, root: Path, out: Path | None = None, **options) -> "BuildConfig":
        """The conventional layout of a project rooted at `root` (cache in ROOT/.cache)."""
        root = root.resolve()
        options.setdefault("cache", root / ".cache")
        return cls(root, root / "content", (out or root / "build").resolve(), root / "node_modules", **options)


@dataclass
class BuildReport:
    """What a build did: pages, scenes, values stored, and seconds per phase."""

    pages: int = 0
    scenes: int = 0
    stored_values: int = 0
    computed: int = 0  # scenes evaluated by their models in this build
    cached: int = 0  # scenes taken from the cache
    evaluations: int = 0  # work units run (model evaluations over blocks of stops)
    phases: dict[str, float] = field(default_factory=dict)
    files: dict[str, int] = field(default_factory=dict)
    scene_lines: list[str] = field(default_factory=list)  # one line per scene: cached or computed and why
    accuracy: list[SceneAccuracy] = field(default_factory=list)  # numerically computed scenes, in page/scene order


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
    forget_sources()  # a long-lived process (tests, a watcher) must see edited model code
    cache = TableCache(config.cache) if config.cache else None
    remember = cache.remember if cache else compute_now
    pages = clock.phase("read", read_pages, config, log)
    scenes = clock.phase("resolve", resolve_scenes, pages, log)
    mathml = clock.phase("math", convert_page_math, pages, config, log, remember)
    log.raise_if_any()
    clock.phase("compile", compile_kernels, scenes, cache, config, progress)
    tables = clock.phase("tabulate", tabulate_scenes, scenes, cache, config, report, log, progress)
    log.raise_if_any()
    report.accuracy = clock.phase("check", check_accuracy, scenes, log, remember, progress)
    log.raise_if_any()
    figures = clock.phase("render", render_figures, scenes, tables, remember)
    files = clock.phase("assemble", assemble_site, pages, scenes, tables, figures, mathml, config, remember, report.accuracy)
    files = clock.phase("report", fill_reports, files, pages, scenes, report.accuracy, config.content / BENCH_NAME, remember)
    if cache:
        report.scene_lines += cache.problems
    clock.phase("write", write_tree, files, config.out)
    report.pages, report.scenes = len(pages), len(scenes)
    report.stored_values = sum(t.stored_values() for ts in tables.values() for t in ts.values())
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


def convert_page_math(pages: list[Page], config: BuildConfig, log: ErrorLog, remember=compute_now) -> dict[str, list[str]]:
    """MathML for every formula of every page (one Temml run for the whole book, or none if cached)."""
    items = [m for page in pages for m in page.found.maths]
    mathml, errors = convert_math(items, config.node_modules, remember)
    for error in errors:
        log.add(error)
    by_page, start = {}, 0
    for page in pages:
        by_page[page.slug] = mathml[start : start + len(page.found.maths)]
        start += len(page.found.maths)
    return by_page


def compile_kernels(scenes: list[PageScene], cache: TableCache | None, config: BuildConfig, progress=None) -> None:
    """Compile the kernels of the models that have scenes to tabulate, or load them from .cache/compiled/
    (kept even without a table cache); a build with every table cached loads none."""
    compiled.use_cache(config.root / ".cache" / "compiled")
    pending = [item for item in scenes if not cache or not cache.has(scene_key(item.scene, needed_outputs(item.scene)))]
    models = {item.scene.model.name: item.scene.model for item in pending}
    for name, model in sorted(models.items()):
        prepared = model.prepare_kernels()
        if prepared and progress:
            seconds, fresh = prepared
            progress(f"compile   {name}: {'compiled' if fresh else 'loaded from the cache'} in {seconds:.2f} s")


def tabulate_scenes(scenes, cache: TableCache | None, config: BuildConfig, report: BuildReport, log: ErrorLog,
                    progress=None) -> dict[str, dict[str, Table]]:
    """Each scene's tables: from the cache when its key matches, else computed by the executor."""
    tables, pending = {}, []
    for item in scenes:
        names = needed_outputs(item.scene)
        key = scene_key(item.scene, names)
        found = cache.load(key) if cache else None
        if found is not None:
            tables[_key(item)] = found
            _note_scene(report, item, cache, key, cached=True, seconds=0.0, progress=progress, total=len(scenes))
        else:
            try:
                pending.append((item, names, key, plan_scene(item.scene, names, item.scene.model.chunk_stops)))
            except AuthorError as error:  # a grid too large to tabulate
                log.add(error)
    with executor_for(config.jobs, config.scheduler) as executor:
        submitted = [[executor.submit(_timed, evaluate_unit, unit) for unit in units] for *_, units in pending]
        for (item, names, key, units), futures in zip(pending, submitted):
            try:
                results, seconds = _collect(futures)
                computed = assemble_tables(item.scene, units, results, names)
            except AuthorError as error:
                log.add(error)
                continue
            tables[_key(item)] = computed
            report.evaluations += len(units)
            if cache:
                cache.store(key, tables[_key(item)])
            _note_scene(report, item, cache, key, cached=False, seconds=seconds, progress=progress, total=len(scenes))
    return tables


def check_accuracy(scenes: list[PageScene], log: ErrorLog, remember=compute_now, progress=None) -> list[SceneAccuracy]:
    """Each numerically computed scene measured against its model's reference (a scene over its tolerance is an error)."""
    records, errors = check_scenes(scenes, remember, progress, shown=needed_outputs)
    for error in errors:
        log.add(error)
    return records


def _timed(function, *args):
    start = time.perf_counter()
    return function(*args), time.perf_counter() - start


def _collect(futures) -> tuple[list, float]:
    """Results of a scene's units in plan order, and the seconds they took in all."""
    pairs = [future.result() for future in futures]
    return [result for result, _ in pairs], sum(seconds for _, seconds in pairs)


def _note_scene(report: BuildReport, item: PageScene, cache, key, cached: bool, seconds: float, progress, total: int) -> None:
    """Count the scene and log one line: name, stops, seconds, cached or computed and why."""
    stops = prod(axis.count for axis in item.scene.axes)
    status = cache.explain(_key(item), key, cached) if cache else "computed: no cache"
    report.cached += cached
    report.computed += not cached
    line = f"[{report.cached + report.computed}/{total}] {_key(item):<36} {stops:>14,} stops {seconds:7.2f} s  {status}"
    report.scene_lines.append(line)
    if progress:
        progress(line)


def needed_outputs(scene: ResolvedScene) -> list[str]:
    """The outputs a scene shows: its readouts and whatever its figure's layers read."""
    names = [o.name for o in scene.readouts]
    for layer in FIGURES[scene.spec.figure or scene.spec.model].layers(scene):
        names += sorted(layer.outputs() - set(names))
    return names


def render_figures(scenes: list[PageScene], tables, remember=compute_now) -> dict[str, RenderedScene]:
    """Each scene's static SVG with its moving layers drawn at the default slider values."""
    figures = {}
    for item in scenes:
        scene, scene_tables = item.scene, tables[_key(item)]
        view = FIGURES[scene.spec.figure or scene.spec.model]
        layers = view.layers(scene)
        points = layer_points(layers, scene, scene_tables, scene.default_stops)

        def draw(view=view, scene=scene, scene_tables=scene_tables, layers=layers, points=points) -> bytes:
            return figure_svg(view.draw(scene, scene_tables), layers, points, dom_id(scene), figure_label(view, scene)).encode()

        # The layers are drawn at the defaults, so the defaults (through the points) belong in the key.
        key = digest(_scene_digest(item), source_digest(FIGURE_MODULES | {type(view).__module__}), repr(points), "figure")
        figures[_key(item)] = RenderedScene(remember("figures", key, draw).decode(), tuple(layers))
    return figures


def assemble_site(pages, scenes, tables, figures, mathml, config: BuildConfig, remember=compute_now,
                  accuracy: list[SceneAccuracy] = ()) -> dict[str, bytes]:
    """Every output file, in memory: pages, the script, the stylesheet and the math font."""
    book_title = next((p.title for p in pages if p.slug == "index"), "Book")
    checked = {(record.page, record.scene): record for record in accuracy}
    linked = any(p.slug == "accuracy" for p in pages)  # the rows exist only on the accuracy page
    files: dict[str, bytes] = {}
    payload_code = source_digest(frozenset({"sitegen.site.assemble"}))
    for page in pages:
        html = []
        for s in (s for s in scenes if s.page is page):
            figure = figures[_key(s)]
            payload = remember("payloads", digest(_scene_digest(s), payload_code),
                               lambda s=s, figure=figure: scene_payload(s.scene, tables[_key(s)], figure.layers).encode())
            caption = fill_slots(s.caption, page.found, mathml[page.slug], [])
            if (page.slug, s.scene.id) in checked:
                caption = f"{caption} {caption_sentence(checked[(page.slug, s.scene.id)], linked)}".strip()
            html.append(scene_html(s.scene, tables[_key(s)], figure, caption, payload.decode()))
        body = fill_slots(page.html, page.found, mathml[page.slug], html)
        files[page.output_name] = page_html(page, body, pages, book_title).encode()
    files["assets/sitegen.js"] = assets.script()
    files["assets/sitegen.css"] = assets.stylesheet(config.node_modules)
    files[f"assets/{assets.FONT_FILE}"] = assets.math_font([f.decode() for n, f in files.items() if n.endswith(".html")], remember)
    return files


FIGURE_MODULES = frozenset({"sitegen.render.svg", "sitegen.render.style", "sitegen.render.layers", "sitegen.render.figures.base"})


def _scene_digest(item: PageScene) -> str:
    """What a scene's figure and data depend on: its tables' key, its place and the matplotlib version."""
    return digest(scene_key(item.scene, needed_outputs(item.scene)).digest, _key(item), f"matplotlib {library_version('matplotlib')}")


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
