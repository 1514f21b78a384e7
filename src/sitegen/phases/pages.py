"""The phases that make files: each scene's element and data script, each page (its accuracy-report
parts filled from the build's records, not read back from HTML), and the shared assets."""

from __future__ import annotations

import hashlib
from dataclasses import replace

from ..compute.executors import result_here_if_waiting
from ..compute.measure import caption_sentence
from ..compute.sources import digest, source_digest
from ..content.bench_results import BENCH_NAME, load_results
from ..content.markdown_ext import fill_slots
from ..site import assets, search
from ..site.assemble import page_html, scene_data_file, scene_html
from ..site.payload import scene_payload
from ..site.report import ReportContext, bench_figures, bench_figures_cached, report_part
from ..site.sizes import gzip_bytes
from .record import Book, SceneRecord, Written
from .run import BuildRun
from .scenes import scene_digest

PAYLOAD_CODE = frozenset({scene_payload.__module__})
SIZE_CODE = frozenset({gzip_bytes.__module__})


def send_diagrams(book: Book, run: BuildRun) -> Book:
    """Send the drawing of the accuracy report's diagrams that come from bench.json alone (those the cache
    lacks) to the executor, a unit per report part, after the tables: a pool's workers draw them while this
    process finishes the other pages, and the report's page folds them in (the same bytes as drawn here)."""
    bench = load_results(run.config.content / BENCH_NAME)
    if run.failed or bench is None:
        return book
    models, reports = run.registry.models, run.registry.reports
    parts = dict.fromkeys(block.part for page in book.pages for block in page.extracted.reports)
    if run.cache:
        parts = [part for part in parts if not bench_figures_cached(bench, [part], models, reports, run.cache)]
    drawings = [(bench, [part], models, reports) for part in parts]
    return replace(book, diagrams=tuple((args, run.executor.submit(bench_figures, *args)) for args in drawings))


def _drawn_diagrams(book: Book, executor) -> dict[str, bytes]:
    """The diagrams sent out by `send_diagrams`, by their cache key (drawn here if no worker has started them); a
    part whose drawing failed is left out (it is drawn with its page, where a failure is reported)."""
    drawn = {}
    for args, future in book.diagrams:
        try:
            drawn.update(result_here_if_waiting(executor, future, bench_figures, *args))
        except Exception:
            continue
    return drawn


def assemble_scenes(book: Book, run: BuildRun) -> Book:
    """Each scene's element: figure, controls, readouts at the defaults, caption, and its data script."""
    if run.failed:
        return book
    accuracy = next((p for p in book.pages if p.slug == "accuracy"), None)  # the rows exist only on that page
    parts = {block.part for block in accuracy.extracted.reports} if accuracy else set()
    records = []
    for record in book.current():
        with run.scene(record, "assembling its element"):
            records.append(_assembled(record, book, run, accuracy is not None, parts))
    return book.with_records(records)


def _assembled(record: SceneRecord, book: Book, run: BuildRun, linked: bool, parts: set) -> SceneRecord:
    scene, tables, figure, page = record.scene, record.tables, record.figure, record.page
    # The figure's layers go into the payload: a change to the view's layers is a new payload.
    key = digest(scene_digest(record), source_digest(PAYLOAD_CODE), repr(figure.layers))
    payload = run.cached("payloads", key, lambda: scene_payload(scene, tables, figure.layers).encode())
    cited = book.citations.get(page.slug)
    caption = fill_slots(
        record.caption, page.extracted, book.mathml[page.slug], [], (), cited and cited.citations, book.reference(page)
    )
    number = f'<span class="caption-label">Figure\u00a0{page.extracted.scene_number(record.index)}</span>'
    caption = f"{number} {caption}".strip()
    if record.accuracy is not None:
        methods = record.accuracy.model in parts  # the accuracy page shows the model's part
        caption = f"{caption} {caption_sentence(record.accuracy, linked, methods)}".strip()
    data_file = scene_data_file(page, scene, payload.decode())
    html = scene_html(scene, tables, figure, caption, data_file[0], run.config.book)
    sizes = _data_bytes(payload, run) if book.has_reports else (len(payload), 0)
    return replace(record, html=html, data_file=data_file, data_bytes=sizes)


def _data_bytes(payload: bytes, run: BuildRun) -> tuple[int, int]:
    """Raw and gzip bytes of a scene's inline tables (what the accuracy report lists)."""
    key = digest(hashlib.sha256(payload).hexdigest(), source_digest(SIZE_CODE))  # how sizes are measured is part of one
    packed = run.cached("report-gzip", key, lambda: str(gzip_bytes(payload)).encode())
    return len(payload), int(packed)


def write_page(book: Book, run: BuildRun) -> Book:
    """The current page as HTML, written into the new tree; its scenes then keep only what the accuracy report reads."""
    if run.failed:
        return book
    page, records = book.page, book.current()
    context = _report_context(book, run, _drawn_diagrams(book, run.executor)) if page.extracted.reports else None
    reports = [report_part(block.part, context) for block in page.extracted.reports]
    cited = book.citations.get(page.slug)
    scenes = [r.html for r in records]
    body = fill_slots(
        page.html,
        page.extracted,
        book.mathml[page.slug],
        scenes,
        reports,
        cited and cited.citations,
        book.reference(page),
    )
    html = page_html(page, body, list(book.pages), run.config.book.title or book.title, run.config.book)
    written = _write(run, page.output_name, html.encode(), assets.math_characters(html), search.page_sections(html))
    data = tuple(_write(run, *r.data_file) for r in records if r.data_file)
    finished = book.with_records(r.finished() for r in records)
    return replace(finished, written=(*book.written, written, *data), diagrams=() if context else book.diagrams)


def _report_context(book: Book, run: BuildRun, drawn: dict[str, bytes]) -> ReportContext:
    """What the report's parts show; a diagram in `drawn` (by its key) is taken from there (and cached)."""
    records = tuple(r.accuracy for r in book.scenes if r.accuracy is not None)
    sizes = {r.name: r.data_bytes for r in book.scenes}
    bench = load_results(run.config.content / BENCH_NAME)

    def cached(kind: str, key: str, compute) -> bytes:
        return run.cached(kind, key, (lambda: drawn[key]) if key in drawn else compute)

    return ReportContext(
        bench, records, book.pages, book.scenes, sizes, cached, run.registry.models, run.registry.reports
    )


def write_assets(book: Book, run: BuildRun) -> Book:
    """The script, the stylesheet (with the theme's CSS), the math font (cut down to the characters the
    pages use), the search index of every page with its code, and the files the pages name, as they are."""
    if run.failed:
        return book
    pages = [w for w in book.written if w.name.endswith(".html")]  # the pages, all written by now
    characters = set().union(*(w.characters for w in pages))
    files = [(name, (run.config.content / name).read_bytes()) for name in book.files]
    files += [
        ("assets/sitegen.js", assets.script()),
        (search.SEARCH_SCRIPT, search.search_script({w.name: list(w.sections) for w in pages}, list(book.pages))),
        ("assets/sitegen.css", assets.stylesheet(assets.theme_css(run.config.book.theme))),
        (f"assets/{assets.FONT_FILE}", assets.math_font(characters, run.cached)),
    ]
    return replace(book, written=(*book.written, *(_write(run, name, data) for name, data in files)))


def _write(run: BuildRun, name: str, data: bytes, characters=frozenset(), sections=()) -> Written:
    """Write one file of the site into the staging folder; what the shared assets need of it."""
    run.tree.write(name, data)
    return Written(name, len(data), frozenset(characters), tuple(sections))
