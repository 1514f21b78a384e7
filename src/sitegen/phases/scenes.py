"""The phases that work on scenes, a page at a time: tabulate (from the cache or by the executor),
check the numerics against each model's reference, and render each figure."""

from __future__ import annotations

import pickle
import time
from dataclasses import replace
from functools import partial

from ..compute.check import check_scenes as check_accuracy
from ..compute.deps import inert_deps_note, verify_scene_deps
from ..compute.executors import Background, executor_for, results_in_order
from ..compute.sources import digest, library_version, source_digest
from ..compute.tabulate import assemble_tables, evaluate_unit, per_stop_outputs, plan_scene
from ..render.figures.base import scene_figures
from ..render.layers import layer_points
from ..render.style import laid_out
from ..render.svg import figure_svg
from ..site.assemble import RenderedScene, dom_id
from .record import Book, SceneRecord
from .run import PROGRESS_EVERY, BuildRun

# The code that turns a view's drawing into the page's SVG (followed through its imports, with the view's module).
DRAWING = frozenset(f.__module__ for f in (figure_svg, laid_out, layer_points, scene_figures))


def compile_kernels(book: Book, run: BuildRun) -> Book:
    """Compile the kernels of the models that have scenes to tabulate, or load them from .cache/compiled/
    (kept even without a table cache); a build with every table cached loads none."""
    if run.failed:  # an author error stops the build before anything is computed
        return book
    pending = {r.scene.model.name: r.scene.model for r in book.scenes if not run.cache or not run.cache.has(r.key)}
    for name, model in sorted(pending.items()):
        if not model.kernels_cached(run.compiled_cache) and _other_pages(book, name) and _compiling_beside(model, run):
            run.say(
                f"compile   {name}: compiling in {len(run.compiling[name])} processes beside the build; "
                f"pages with its scenes are built last"
            )
            continue
        prepared = model.prepare_kernels(run.compiled_cache)
        if prepared:
            run.kernels_loaded.add(name)
            seconds, fresh = prepared
            run.say(f"compile   {name}: {'compiled' if fresh else 'loaded from the cache'} in {seconds:.2f} s")
    return book


def _compiling_beside(model, run: BuildRun) -> bool:
    """Start compiling `model`'s kernels beside the build, a process per part; False (nothing started) for a
    model that cannot be handed to another process, which compiles here instead.

    Compiling takes many seconds of one core: it runs beside the pages that need no compiled code, which
    are built first (the machine's other core does the compiling)."""
    parts = []
    try:  # every part hands over the same call, so one that cannot be pickled fails at the first, before any starts
        for part in model.kernel_parts or (None,):
            parts.append(Background(model.prepare_kernels, run.compiled_cache, part))
    except (pickle.PicklingError, TypeError, AttributeError, OSError):  # OSError: no process could start
        for started in parts:
            started.stop()
        return False
    run.compiling[model.name] = parts
    return True


def _other_pages(book: Book, model: str) -> bool:
    """Whether some page has no scene of `model` (and so could be built while its kernels compile)."""
    return len(book.pages_with({model})) < len(book.pages)


def tabulate_scenes(book: Book, run: BuildRun) -> Book:
    """Each scene's tables: from the cache when its key matches, else computed by the executor."""
    if run.config.jobs > 1 or run.config.scheduler:  # worker processes start with the kernels this one has loaded
        for record in book.current():
            run.await_kernels(record.scene.model)
    records = []
    with executor_for(run.config.jobs, run.config.scheduler) as executor:
        for record in book.current():
            with run.scene(record, "tabulating"):
                records.append(_checked_deps(_tabulated(record, run, executor), run))
    return book.with_records(records)


def _checked_deps(record: SceneRecord, run: BuildRun) -> SceneRecord:
    """The record, once its outputs are found to change only with what their deps declare (probed, or read
    back with its tables); each that does not is an author error, and the record keeps no tables."""
    errors = verify_scene_deps(record.scene, planned_outputs(record), run.remember, run.config.root)
    for error in errors:
        run.error(error)
    return replace(record, tables=None) if errors else record


def _tabulated(record: SceneRecord, run: BuildRun, executor) -> SceneRecord:
    found = run.cache.load(record.key) if run.cache else None
    if found is not None:
        return _noted(replace(record, tables=found), run, cached=True, seconds=0.0)
    run.await_kernels(record.scene.model)
    ahead = run.ahead.pop(record.name, None)
    units = list(ahead.units) if ahead else planned(record)

    def here():
        return _evaluated(record, units, results_in_order(executor, partial(timed, evaluate_unit), units), run)

    if ahead is None:
        results, seconds = here()
    else:
        try:
            results, seconds = _evaluated(record, units, (future.result() for future in ahead.futures), run)
        except Exception:  # computed again here, where an error names the model's file and line
            results, seconds = here()
    tables = assemble_tables(record.scene, units, results, list(record.outputs))
    run.report.evaluations += len(units)
    if run.cache:
        run.cache.store(record.key, tables)
    return _noted(replace(record, tables=tables), run, cached=False, seconds=seconds)


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


def timed(function, *args):
    """`function(*args)` and the seconds it took."""
    start = time.perf_counter()
    return function(*args), time.perf_counter() - start


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


def _noted(record: SceneRecord, run: BuildRun, cached: bool, seconds: float) -> SceneRecord:
    """Count the scene and log its line: name, stops, seconds, cached or computed and why."""
    report = run.report
    status = run.cache.explain(record.name, record.key, cached) if run.cache else "computed: no cache"
    report.cached += cached
    report.computed += not cached
    line = f"[{report.cached + report.computed}/{report.scenes}] {record.name:<36} {record.stops:>14,} stops {seconds:7.2f} s  {status}"
    report.scene_lines.append(line)
    run.say(line)
    stored = sum(t.stored_values() for t in record.tables.values())
    if note := inert_deps_note(record.scene, record.tables, run.config.root):
        report.scene_lines.append(note)
        run.say(note)
    return replace(record, status=status, stored_values=stored)


def check_scenes(book: Book, run: BuildRun) -> Book:
    """Each numerically computed scene measured against its model's reference (over its tolerance: an error)."""
    records = []
    for record in book.current():
        if record.tables is None:
            continue
        with run.scene(record, "checking its numerics"):
            run.await_kernels(record.scene.model)
            found, errors = check_accuracy([record], run.remember, run.progress, shown=lambda _: record.outputs)
            for error in errors:
                run.error(error)
            records.append(replace(record, accuracy=found[0] if found else None))
    return book.with_records(records)


def render_figures(book: Book, run: BuildRun) -> Book:
    """Each scene's static SVG with its moving layers drawn at the default slider values."""
    if run.failed:
        return book
    records = []
    for record in book.current():
        with run.scene(record, "drawing its figure"):
            records.append(replace(record, figure=_figure(record, run)))
    return book.with_records(records)


def _figure(record: SceneRecord, run: BuildRun) -> RenderedScene:
    scene, tables, view = record.scene, record.tables, record.view
    layers = view.layers(scene)
    points = layer_points(layers, scene, tables, scene.default_stops)

    def draw() -> bytes:  # the wide figure, then (if the view draws one) the phone's
        return "".join(scene_figures(view, scene, tables, layers, points, dom_id(scene))).encode()

    # The layers are drawn at the defaults, so the defaults (through the points) belong in the key.
    key = digest(scene_digest(record), source_digest(DRAWING | {type(view).__module__}), repr(points), "figure")
    return RenderedScene(run.remember("figures", key, draw).decode(), tuple(layers))


def scene_digest(record: SceneRecord) -> str:
    """What a scene's figure and data depend on: its tables' key, its place and the matplotlib version."""
    return digest(record.key.digest, record.name, f"matplotlib {library_version('matplotlib')}")
