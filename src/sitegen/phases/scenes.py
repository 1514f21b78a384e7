"""The phases that work on scenes, a page at a time: tabulate (from the cache or by the executor),
check (each closed form against its model at sampled stops, the numerics against each model's
reference), and render each figure."""

from __future__ import annotations

import json
import time
from dataclasses import replace

from ..compute.closed_form import verify_closed_forms
from ..compute.deps import inert_deps_note, verify_scene_deps
from ..compute.executors import result_here_if_waiting
from ..compute.measure import measure_accuracy
from ..compute.sources import digest, library_version, source_digest
from ..compute.structure import Structured
from ..compute.tabulate import assemble_tables, evaluate_timed, per_stop_outputs, plan_scene
from ..errors import AuthorError
from ..render.figures.base import scene_figures
from ..render.layers import layer_points
from ..render.style import laid_out
from ..render.svg import figure_svg
from ..site.assemble import RenderedScene, dom_id
from .record import Book, FigureWork, SceneRecord
from .run import PROGRESS_EVERY, BuildRun

SEND_AHEAD = 1  # pages past the one being tabulated whose tables' work is sent out
SAID_FROM = 0.1  # seconds: a model whose first stop takes this long (compiled code, mostly) gets a line
# The code that turns a view's drawing into the page's SVG (followed through its imports, with the view's module).
DRAWING = frozenset(f.__module__ for f in (figure_svg, laid_out, layer_points, scene_figures))
CLOSED_FORM_CODE = frozenset({verify_closed_forms.__module__})


def compile_first_stops(book: Book, run: BuildRun) -> Book:
    """Evaluate the first scene of each model that has work to send out at its default stop, here: a model's
    compiled code is compiled (or loaded from its cache) once, in this process, before workers load it."""
    if run.failed:  # an author error stops the build before anything is computed
        return book
    first = {}
    for record in book.scenes:
        if not (run.cache and run.cache.has(record.key)):
            first.setdefault(record.scene.model.name, record)
    for name, record in sorted(first.items()):
        start = time.perf_counter()
        try:
            scene = record.scene
            scene.model.evaluate(scene.base_values(), per_stop_outputs(scene, list(record.outputs)), scene.effects)
        except Exception:  # reported where the scene is tabulated, with its place
            continue
        seconds = time.perf_counter() - start
        if seconds >= SAID_FROM:
            run.say(f"compile   {name}: its first stop in {seconds:.2f} s (compiled code compiled or loaded)")
    return book


def send_work(book: Book, run: BuildRun) -> Book:
    """Send the work of the tables the cache lacks to the executor, each table once, in plan order: those of the
    page being tabulated and of the SEND_AHEAD pages after it (from the first page, before any is). Enough to keep
    a pool's workers busy, while the results waiting to be folded stay a few pages' worth."""
    if run.failed:
        return book
    order = [page.slug for page in book.writing_order()]
    start = order.index(book.page.slug) if book.page is not None else 0
    window = set(order[start : start + SEND_AHEAD + 1])
    work = dict(book.work)
    for record in book.scenes:
        digest = record.key.digest
        if record.page.slug not in window or digest in work or (run.cache and run.cache.has(record.key)):
            continue
        try:
            work[digest] = _submitted(planned(record), run.executor)
        except AuthorError:  # reported when the scene is tabulated
            continue
    return replace(book, work=work)


def _submitted(units: list, executor) -> tuple[list, list]:
    """The units and the futures of their results (with their seconds)."""
    return units, [executor.submit(evaluate_timed, unit) for unit in units]


def tabulate_scenes(book: Book, run: BuildRun) -> Book:
    """Each scene's tables: from the cache when its key matches, else from the work sent out for it (which
    the book then no longer holds)."""
    records, work = [], dict(book.work)
    done = sum(1 for r in book.scenes if r.status)  # scenes tabulated before this page
    for record in book.current():
        with run.scene(record, "tabulating"):
            record, seconds = _tabulated(record, work.pop(record.key.digest, None), run)
            record = _noted(record, seconds, f"[{done + len(records) + 1}/{len(book.scenes)}]", run)
            records.append(_verified_deps(record, run))
    return replace(book.with_records(records), work=work)


def _verified_deps(record: SceneRecord, run: BuildRun) -> SceneRecord:
    """The record, once its outputs are found to change only with what their deps declare (probed, or read
    back with its tables); each that does not is an author error, and the record keeps no tables."""
    errors = verify_scene_deps(record.scene, planned_outputs(record), run.cached, run.config.root)
    for error in errors:
        run.error(error)
    return replace(record, tables=None) if errors else record


def _tabulated(record: SceneRecord, work: tuple | None, run: BuildRun) -> tuple[SceneRecord, float]:
    """The record with its tables, from the cache or folded from `work` (its units and their futures; sent
    now when None), and the seconds the work took."""
    tables = run.cache.load(record.key) if run.cache else None
    if tables is not None:
        return replace(record, tables=tables, cached=True), 0.0
    units, futures = work or _submitted(planned(record), run.executor)
    results, seconds = _evaluated(record, units, (_result(u, f, run.executor) for u, f in zip(units, futures)), run)
    tables = assemble_tables(record.scene, units, results, list(record.outputs))
    if run.cache:
        run.cache.store(record.key, tables)
    return replace(record, tables=tables, evaluations=len(units)), seconds


def _result(unit, future, executor) -> tuple:
    """A unit's result and seconds (worked out here if no worker has started it). Should its work have failed but
    for an author error (a crash, whose line is best named from a traceback of this process; or a worker lost), it
    is done again here."""
    try:
        return result_here_if_waiting(executor, future, evaluate_timed, unit)
    except AuthorError:
        raise
    except Exception:
        return evaluate_timed(unit)


def planned_outputs(record: SceneRecord) -> list[str]:
    """The outputs a scene evaluates: those it shows and those their exact forms read at every stop."""
    return list(dict.fromkeys([*record.outputs, *per_stop_outputs(record.scene, list(record.outputs))]))


def planned(record: SceneRecord) -> list:
    """The scene's units of work (`plan_scene` for the outputs it needs, in blocks its model asks for)."""
    return plan_scene(record.scene, list(record.outputs), record.scene.model.chunk_stops)


def _evaluated(record: SceneRecord, units, timed_results, run: BuildRun) -> tuple[list, float]:
    """The units' results (taken from `timed_results` in order, each with its seconds) and their seconds in all,
    with progress inside a long scene."""
    results, seconds = [], 0.0
    pace = _Pace(record, sum(unit.stops() for unit in units), run)
    for unit, (result, took) in zip(units, timed_results):
        results.append(result)
        seconds += took
        pace.done(unit.stops())
    return results, seconds


class _Pace:
    """Progress inside a long scene: stops done, total and rate, at most every PROGRESS_EVERY seconds."""

    def __init__(self, record: SceneRecord, total: int, run: BuildRun):
        self.record, self.total, self.run = record, total, run
        self.start = self.last = time.perf_counter()
        self.stops = 0

    def done(self, stops: int) -> None:
        self.stops += stops
        now = time.perf_counter()
        if now - self.last >= PROGRESS_EVERY and self.stops < self.total:
            self.last = now
            rate = self.stops / (now - self.start)
            self.run.say(f"  {self.record.name:<40} {self.stops:>12,} of {self.total:,} stops, {rate:,.0f} stops/s")


def _noted(record: SceneRecord, seconds: float, number: str, run: BuildRun) -> SceneRecord:
    """The record with its status, the numbers its tables ship and its lines of the log (said): name, stops,
    seconds, cached or computed and why, and a note on each declared dep that changes nothing."""
    status = run.cache.explain(record.name, record.key, record.cached) if run.cache else "computed: no cache"
    lines = [f"{number} {record.name:<36} {record.stops:>14,} stops {seconds:7.2f} s  {status}"]
    run.say(lines[0])
    if note := inert_deps_note(record.scene, record.tables, run.config.root):
        lines.append(note)
        run.say(note)
    stored = sum(t.stored_values() for t in record.tables.values())
    return replace(record, status=status, lines=tuple(lines), stored_values=stored)


def check_scenes(book: Book, run: BuildRun) -> Book:
    """Each scene's closed forms verified against its model at sampled stops, then each numerically computed
    scene measured against its model's reference (a wrong closed form, or an error over the tolerance: an
    author error)."""
    records = []
    for record in book.current():
        if record.tables is None:
            continue
        with run.scene(record, "checking its closed forms and numerics"):
            if errors := _closed_form_errors(record, run):
                for error in errors:
                    run.error(error)
                records.append(replace(record, tables=None))
                continue
            measured, errors = measure_accuracy([record], run.cached, run.progress, shown=lambda _: record.outputs)
            for error in errors:
                run.error(error)
            records.append(replace(record, accuracy=measured[0] if measured else None))
    return book.with_records(records)


def _closed_form_errors(record: SceneRecord, run: BuildRun) -> list[AuthorError]:
    """The sampled check of the scene's closed forms (`verify_closed_forms`), its verdict cached under the key of
    the scene's tables: a rebuild with the tables cached evaluates nothing."""
    forms = [table for table in record.tables.values() if isinstance(table, Structured)]
    if not forms:
        return []
    scene = record.scene
    key = digest(record.key.digest, source_digest(CLOSED_FORM_CODE), "closed-forms")

    def verify() -> bytes:
        return json.dumps([error.message for error in verify_closed_forms(scene, forms)]).encode()

    return [AuthorError(scene.spec.loc, text, scene.id) for text in json.loads(run.cached("closed-forms", key, verify))]


def send_figures(book: Book, run: BuildRun) -> Book:
    """Send the drawing of each figure the cache lacks to the executor (the static SVG, with the moving layers at
    the default slider values): a pool's workers draw a page's figures while this process goes on to the next
    page's tables, and `render_figures` takes each drawing in."""
    records = []
    for record in book.current():
        if record.tables is None:  # its tabulating or check failed, and is reported
            continue
        with run.scene(record, "drawing its figure"):
            records.append(replace(record, drawing=_sent_figure(record, run)))
    return book.with_records(records)


def _sent_figure(record: SceneRecord, run: BuildRun) -> FigureWork:
    scene, tables, view = record.scene, record.tables, record.view
    layers = view.layers(scene)
    points = layer_points(layers, scene, tables, scene.default_stops)
    # The layers are drawn at the defaults, so the defaults (through the points) belong in the key.
    key = digest(scene_digest(record), source_digest(DRAWING | {type(view).__module__}), repr(points), "figure")
    drawing = (view, scene, tables, layers, points, dom_id(scene))
    future = None if run.cache and run.cache.holds("figures", key) else run.executor.submit(drawn_figure, *drawing)
    return FigureWork(key, tuple(layers), drawing, future)


def drawn_figure(view, scene, tables, layers, points, prefix: str) -> bytes:
    """A scene's figure as inline SVG: the wide one, then (if the view draws one) the phone's."""
    return "".join(scene_figures(view, scene, tables, layers, points, prefix)).encode()


def render_figures(book: Book, run: BuildRun) -> Book:
    """Each scene's figure: from the cache, or the drawing sent out for it (drawn here should its unit have failed
    but for an author error, so that a crash is named from this process's traceback)."""
    records = []
    for record in book.current():
        if record.drawing is None:
            continue
        with run.scene(record, "drawing its figure"):
            work = record.drawing
            svg = run.cached("figures", work.key, lambda: _drawing(work, run.executor))
            records.append(replace(record, figure=RenderedScene(svg.decode(), work.layers), drawing=None))
    return book.with_records(records)


def _drawing(work: FigureWork, executor) -> bytes:
    try:
        return result_here_if_waiting(executor, work.future, drawn_figure, *work.drawing)
    except AuthorError:
        raise
    except Exception:
        return drawn_figure(*work.drawing)


def scene_digest(record: SceneRecord) -> str:
    """What a scene's figure and data depend on: its tables' key, its place and the matplotlib version."""
    return digest(record.key.digest, record.name, f"matplotlib {library_version('matplotlib')}")
