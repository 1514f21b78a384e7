"""The build, as a short script of named phases over one record per scene.

read, resolve and math run over the whole book, and every author error they find is reported
before anything is computed. Then the work of every table the cache lacks is sent to the executor (in this
process, local processes or a Dask cluster: compute.executors), and, a page at a time, its scenes' tables
are taken from the cache or folded from that work in plan order and checked, and its figures sent out to be
drawn; then the page before it takes in its figures, is assembled and written into a staging folder, and
the garbage its work left is collected. The staging folder replaces
build/ only when every page is written: the previous build/ stays intact on any failure. Pages that show
accuracy-report parts come last, as those list every scene.
"""

from __future__ import annotations

from dataclasses import replace

from .compute.executors import executor_for
from .compute.sources import forget_sources
from .phases.collect import collect_garbage, collecting_per_page
from .phases.link import link_book
from .phases.pages import assemble_scenes, send_diagrams, write_assets, write_page
from .phases.read import convert_math, figure_name, read_pages, resolve_scenes
from .phases.read import needed_outputs as _needed_outputs
from .phases.record import Book
from .phases.run import BuildConfig, BuildReport, BuildRun
from .phases.scenes import check_scenes, compile_first_stops, render_figures, send_figures, send_work, tabulate_scenes
from .registry import BookModels, Registry, builtin_registry, load_registry
from .site.weight import page_weights, weight_lines, weight_warnings
from .site.writer import staged_tree

__all__ = ["BuildConfig", "BuildReport", "build", "needed_outputs", "resolve_book", "tabulate_book"]

BOOK_PHASES = (
    ("read", read_pages),
    ("link", link_book),
    ("resolve", resolve_scenes),
    ("math", convert_math),
    ("compile", compile_first_stops),
    ("send", send_work),
    ("diagrams", send_diagrams),
)
# A page's phases in two halves: while the executor's workers draw a page's figures, this process goes on to
# the next page's tables (a build holds two pages' tables at most), then finishes the page.
PAGE_PHASES = (
    ("send", send_work),
    ("tabulate", tabulate_scenes),
    ("check", check_scenes),
    ("figures", send_figures),
)
FINISH_PHASES = (
    ("render", render_figures),
    ("assemble", assemble_scenes),
    ("write", write_page),
    ("collect", collect_garbage),
)


def build(config: BuildConfig, progress=print, registry: Registry | None = None) -> BuildReport:
    """Build the whole site into `config.out`, or raise BuildFailed with every author error.

    `registry`: the models and figures to use (default: the book's, found by `load_registry`)."""
    forget_sources()  # a long-lived process (tests, a watcher) must see edited model code
    registry = registry or load_registry(config.book)
    setup = BookModels.of(config.book)  # the book's own models, for workers to import
    modules = sorted({model.__module__ for model in registry.models.values()})  # what workers import first
    with executor_for(config.jobs, config.scheduler, setup, modules) as executor, collecting_per_page():
        run = BuildRun.of(config, registry, progress, executor)
        book = Book()
        for name, phase in BOOK_PHASES:
            book = _timed(run, name, phase, book)
        run.log.raise_if_any()
        with staged_tree(config.out) as tree:
            pages = replace(run, tree=tree)
            order = book.writing_order()
            for page, before in zip([*order, None], [None, *order]):
                if page is not None:
                    for name, phase in PAGE_PHASES:
                        book = pages.phase(name, phase, book.at(page))
                if before is not None:
                    for name, phase in FINISH_PHASES:
                        book = pages.phase(name, phase, book.at(before))
            book = pages.phase("write", write_assets, book.at(None))
            run.log.raise_if_any()
    for name in (n for n, _ in PAGE_PHASES + FINISH_PHASES):
        run.say(f"{name:<9} {run.seconds[name]:6.2f} s")
    return _finish(run, book)


def _timed(run: BuildRun, name: str, phase, book: Book) -> Book:
    book = run.phase(name, phase, book)
    run.say(f"{name:<9} {run.seconds[name]:6.2f} s")
    return book


def _finish(run: BuildRun, book: Book) -> BuildReport:
    """What the build did, from the book it made and the run's log; the pages' weights said."""
    tabulated = [r for r in book.in_writing_order() if r.status]
    files = dict(sorted({w.name: w.size for w in book.written}.items()))
    weights = page_weights(_site_files(run.config.out, files), book.scenes, run.cached)
    warnings = weight_warnings(weights, run.config.book.page_budget_kb, book.scenes)
    for line in weight_lines(weights) + warnings:
        run.say(line)
    return BuildReport(
        pages=len(book.pages),
        scenes=len(book.scenes),
        stored_values=sum(r.stored_values for r in book.scenes),
        computed=sum(not r.cached for r in tabulated),
        cached=sum(r.cached for r in tabulated),
        evaluations=sum(r.evaluations for r in book.scenes),
        phases=dict(run.seconds),
        files=files,
        scene_lines=[line for r in tabulated for line in r.lines] + (run.cache.problems if run.cache else []),
        weights=weights,
        warnings=warnings,
        accuracy=[r.accuracy for r in book.scenes if r.accuracy is not None],
        data_bytes={r.name: r.data_bytes for r in book.scenes},
    )


def _site_files(out, names) -> dict[str, bytes]:
    """The pages and assets of the site just written (what a reader downloads)."""
    return {n: (out / n).read_bytes() for n in names if n.endswith(".html") or n.startswith("assets/")}


def needed_outputs(scene, registry: Registry | None = None) -> list[str]:
    """The outputs a scene shows: its readouts and whatever its figure's layers read (figures of
    `registry`, default the built-in ones)."""
    return _needed_outputs(scene, (registry or builtin_registry()).figures[figure_name(scene.spec)])


def resolve_book(config: BuildConfig, registry: Registry | None = None) -> Book:
    """The book read and its scenes resolved (the first phases of a build; BuildFailed on author errors)."""
    run = BuildRun.of(config, registry or load_registry(config.book))
    book = resolve_scenes(read_pages(Book(), run), run)
    run.log.raise_if_any()
    return book


def tabulate_book(book: Book, config: BuildConfig, registry: Registry | None = None) -> Book:
    """The book's scenes tabulated, as a build would (its cache, if any; nothing checked, drawn or written)."""
    run = BuildRun.of(config, registry or load_registry(config.book))
    book = tabulate_scenes(book.at(None), run)
    run.log.raise_if_any()
    return book
