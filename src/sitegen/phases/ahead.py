"""The work that starts before the pages: in one process forked beside the build, the scenes of models
with compiled code are tabulated and the accuracy report's diagrams are drawn, while this process builds
the pages that need neither; the pages with those scenes, then those with report parts, come last.

Compiled solves and the report's diagrams are the heaviest work of a cold build that does not depend on
the pages built before it, and they keep the machine's other core busy. Their results are the same bytes
wherever they are made. Nothing is forked with --jobs or a scheduler (they spread the tabulating already),
nor where forking is unsafe (see `Beside`): then everything is done here, as it is needed.
"""

from __future__ import annotations

from ..compute.executors import Beside
from ..compute.tabulate import evaluate_unit
from ..content.bench_results import BENCH_NAME, load_results
from ..errors import AuthorError
from ..site.report import bench_figures, bench_figures_cached
from .record import Book
from .run import Ahead, BuildRun
from .scenes import planned, timed


def work_ahead(book: Book, run: BuildRun) -> Book:
    """Start the compiled scenes' tabulating and the report's diagrams in a process beside the build."""
    if run.failed or not run.may_fork:
        return book
    scenes = _in_writing_order(
        [
            r
            for r in book.scenes
            if r.scene.model.name in run.kernels_loaded and not (run.cache and run.cache.has(r.key))
        ],
        book,
        run,
    )
    parts = [block.part for page in book.pages for block in page.found.reports]
    bench = load_results(run.config.content / BENCH_NAME) if parts else None
    if bench and run.cache and bench_figures_cached(bench, parts, run.models, run.registry.reports, run.cache):
        bench = None  # nothing to draw
    if not scenes and not bench:
        return book
    run.beside = Beside.start()
    if run.beside is None:
        return book
    for record in scenes:
        try:
            units = tuple(planned(record))
        except AuthorError:  # reported when the scene is tabulated
            continue
        futures = tuple(run.beside.submit(timed, evaluate_unit, unit) for unit in units)
        run.ahead[record.name] = Ahead(record.scene.model.name, units, futures)
    for model in sorted({a.model for a in run.ahead.values()}):
        count = sum(a.model == model for a in run.ahead.values())
        run.say(
            f"ahead     {model}: {count} scene{'s' * (count != 1)} tabulating in a process beside the build; "
            f"pages with them are built last"
        )
    if bench:  # after the scenes: the report's page is written last
        run.drawn_ahead = run.beside.submit(bench_figures, bench, parts, run.models, run.registry.reports, run.cache)
        run.say("ahead     the accuracy report's diagrams that the cache lacks: drawing in the same process")
    return book


def _in_writing_order(records: list, book: Book, run: BuildRun) -> list:
    """The records in the order the build takes them (their pages' writing order), each table once where a cache
    keeps it: the build takes a second scene of the same table from the cache, where the first put it."""
    late = run.late_models() | {r.scene.model.name for r in records}  # as it will be: these go ahead, so are late
    rank = {page.slug: n for n, page in enumerate(book.writing_order(late=late))}
    records = sorted(records, key=lambda r: rank[r.page.slug])  # stable: a page's scenes keep their order
    if not run.cache:
        return records
    seen = set()
    return [r for r in records if not (r.key.digest in seen or seen.add(r.key.digest))]
