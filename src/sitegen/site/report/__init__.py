"""The accuracy page's report blocks, filled in while the page is assembled.

Numbers come from two places only: bench.json (times, measured on the machine named on the
page) and this build's own deterministic data (the scenes' accuracy records and table bytes, which
the build hands over: nothing is read back from built HTML). No clock is read here, so the same
sources and the same bench.json give the same bytes.

The parts every book has are below; every numerical model has a part under its name (methods.py), and each
experiment a model declares of its own (`Model.experiments`) a part under the experiment's name, drawn by the
experiment's kind: this module names no model.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from html import escape

from ...compute.accuracy import SceneAccuracy
from ...compute.cache import compute_now
from ...render.work_precision import Panel, Point, Series, resolution_figure
from . import summary
from .html import FIGURES_KIND, MISSING, duration, factor, figure, figure_html, kib, sci, table
from .methods import experiment_part, finding, model_part, powers
from .sweep import sweep_part

DRAWN_BY_KIND = {"work-precision": experiment_part, "digit-sweep": sweep_part}


@dataclass(frozen=True)
class ReportContext:
    """Everything a report block may show: the bench run, this build's records, pages and scenes."""

    bench: dict | None
    records: tuple[SceneAccuracy, ...]
    pages: tuple  # the book's Pages
    scenes: tuple  # the build's scene records (each with .page and .scene)
    table_bytes: Mapping  # "page#scene" -> (raw, gzip) bytes of the scene's inline tables in this build
    cached: object = compute_now
    models: Mapping = None  # the models of the build, by name
    reports: Mapping = None  # the registry's REPORTS (unused: every part is drawn from bench.json by its kind)


def report_parts(models: Mapping) -> list[str]:
    """Every part a block may show: the book's own, one per numerical model (by its name), and the
    experiments the models declare of their own."""
    numerical = [name for name, model in models.items() if model.numerics is not None]
    declared = [part for model in models.values() for part in model.experiments]
    return ["machine", *numerical, *declared, "digits", "resolution", "scenes", "build"]


def report_part(part: str, context: ReportContext) -> str:
    """The HTML of one report block."""
    if part in BOOK_PARTS:
        return BOOK_PARTS[part](context)
    if part in context.models:
        return model_part(part, context)
    model = next(model for model in context.models.values() if part in model.experiments)
    found = ((context.bench or {}).get("models") or {}).get(model.name, {}).get("experiments", {}).get(part)
    return DRAWN_BY_KIND.get(model.experiments[part].kind, experiment_part)(part, found, context)


def bench_figures(bench: dict, parts: list[str], models: Mapping, reports: Mapping, cache=None) -> dict[str, bytes]:
    """Every diagram that the report `parts` draw from bench.json alone, by the key `figure` caches it under
    (but those `cache`, a TableCache, holds already).

    Drawn before the build's own work: a part is rendered as if the build had no scenes, and only
    its diagrams are kept. A diagram drawn from the build's data has another key then (or its part fails), and
    is drawn with the part, later."""
    drawn: dict[str, bytes] = {}

    def keep(kind: str, key: str, compute) -> bytes:
        if kind != FIGURES_KIND:
            return compute()
        if cache is not None and cache.holds(kind, key):
            return b""  # drawn before: what the part writes with it is thrown away
        drawn[key] = compute()
        return drawn[key]

    _parts_from_bench(bench, parts, models, reports, keep)
    return drawn


def bench_figures_cached(bench: dict, parts: list[str], models: Mapping, reports: Mapping, cache) -> bool:
    """Whether `cache` holds every diagram that `bench_figures` would draw (found without drawing any)."""
    keys = set()

    def note(kind: str, key: str, compute) -> bytes:
        if kind != FIGURES_KIND:
            return compute()
        keys.add(key)
        return b""

    _parts_from_bench(bench, parts, models, reports, note)
    return all(cache.holds(FIGURES_KIND, key) for key in keys)


def _parts_from_bench(bench: dict, parts: list[str], models: Mapping, reports: Mapping, cached) -> None:
    """Render the report `parts` as if the build had no scenes, with `cached` for what they keep."""
    context = ReportContext(bench, (), (), (), {}, cached, models, reports)
    for part in parts:
        try:
            report_part(part, context)
        except Exception:  # a part that needs the build's own data: drawn with it, later
            continue


def resolution_part(context: ReportContext) -> str:
    """Interpolation error against bytes for the outputs of the resolution table (docs/physics/README.md), and what the
    page ships instead."""
    if not context.bench:
        return MISSING
    rows = context.bench["resolution"]
    if not rows:
        return '<p class="report-missing">No scene of this book shows an output of the interpolation experiment.</p>\n'
    label = "Interpolation error against stored bytes for four outputs, by choice of axis and number of nodes."

    def draw(narrow):
        xlim = (min(r["bytes_float32"] for r in rows) / 2.5, max(r["bytes_float32"] for r in rows) * 2.5)
        panels = [
            _resolution_panel([r for r in rows if r["line"] == key], xlim)
            for key in dict.fromkeys(r["line"] for r in rows)
        ]
        return resolution_figure(panels, "labels: number of nodes; dashed: half of the last displayed digit", narrow)

    svg = figure(context, "resolution", rows, label, draw)
    caption = (
        "Each output is stored at a few nodes and interpolated back to every slider stop; the error is the "
        "largest difference from the model, in units of half the last digit the page shows (below the dashed "
        "line an interpolated readout would round correctly). A coordinate in which the output is exactly "
        "affine or quadratic (w₁ = m₁/(m₁+m₂), 1/m, quadratic in e) needs two or three nodes; the pole of "
        "MA(x_p) defeats interpolation. The page ships every stop, rounded: no interpolation error at all."
    )
    numbers = table(
        ["output", "axis", "nodes", "max error", "÷ ½ digit", "float32", "JSON gzip"],
        [
            [
                escape(r["output"]),
                escape(r["axis_text"]),
                str(r["nodes"]),
                sci(r["error"]),
                sci(r["error"] / r["display_resolution"]),
                f"{r['bytes_float32']} B",
                f"{r['bytes_json_gzip']} B",
            ]
            for r in rows
        ],
        "Every axis choice and node count",
    )
    return figure_html("resolution", svg, label, caption, numbers)


AXIS_GROUPS = {
    "linear": "linear axis",
    "log": "log axis",
    "w1": "exact coordinate",
    "inverse": "exact coordinate",
    "quadratic": "exact coordinate",
    "per stop": "every stop",
}


def _resolution_panel(rows: list[dict], xlim: tuple[float, float]) -> Panel:
    series = []
    for group in dict.fromkeys(AXIS_GROUPS.values()):
        members = [r for r in rows if AXIS_GROUPS[r["axis"]] == group]
        points = tuple(
            Point(r["bytes_float32"], r["error"] / r["display_resolution"], str(r["nodes"])) for r in members
        )
        series.append(Series(group, points))
    return Panel(
        rows[0]["output"], tuple(series), floor=1e-13, ceiling=1e6, line=(1.0, "½ digit"), xlim=xlim, ylim=(1e-14, 1e6)
    )


# --- tables and text -----------------------------------------------------------------------------------------


def machine_part(context: ReportContext) -> str:
    """Where and when the timings were measured, and how they were repeated."""
    if not context.bench:
        return MISSING
    m, plan = context.bench["machine"], context.bench["plan"]
    return (
        f'<p class="report-machine">The timings on this page were measured on <strong>{m["date"]}</strong>, '
        f"on a machine with {m['cores']} cores ({escape(m['cpu'])}; Python {m['python']}, NumPy {m['numpy']}, "
        f"SciPy {m['scipy']}, one BLAS thread), in one run of <code>sitegen bench</code> that took "
        f"{duration(context.bench['seconds'])}. Each time is a median: {escape(plan['repeats'])}. Read them "
        f"as ratios: on another machine every time scales, the comparisons mostly do not.</p>\n"
    )


def digits_part(context: ReportContext) -> str:
    """What one more correct digit costs, per method of every experiment, and the headline of each panel."""
    if not context.bench:
        return MISSING
    found = summary.experiments(context.bench)
    items = [finding(panel) for _, _, data in found for panel in data["panels"]]
    items += [powers(escape(text)) for _, _, data in found for text in data.get("findings", [])]
    costs = [
        (summary.panel_title(panel), summary.headlines(panel)["per_digit"])
        for _, _, data in found
        for panel in data["panels"]
    ]
    methods = list(dict.fromkeys(m for _, per in costs for m, f in per.items() if f))
    numbers = table(
        ["problem", *map(escape, methods)],
        [[escape(title)] + [factor(per.get(m)) for m in methods] for title, per in costs if any(per.values())],
        "Time multiplier per extra correct digit (least-squares slope of log time against −log error)",
    )
    return (
        '<ul class="report-findings">\n'
        + "\n".join(f"<li>{item}</li>" for item in items if item)
        + "\n</ul>\n"
        + numbers
    )


def scenes_part(context: ReportContext) -> str:
    """One row per numerically checked scene of this build: settings, measured error, cost."""
    if not context.records:
        return '<p class="report-missing">No numerical scenes were checked in this build.</p>\n'
    rows, ids = [], []
    for record in sorted(context.records, key=lambda r: (r.page, r.scene)):
        key = f"{record.page}#{record.scene}"
        cold = (context.bench or {}).get("build", {}).get("scenes", {}).get(key)
        raw, packed = context.table_bytes.get(key, (0, 0))
        within = "within" if record.error <= record.tolerance else "EXCEEDS"
        settings = "" if record.settings in ("", "—") else f'<span class="report-note">{escape(record.settings)}</span>'
        rows.append(
            [
                _scene_link(context, record.page, record.scene),
                f"{escape(record.method)}{settings}",
                f'{sci(record.error)} <span class="report-note">{within} {sci(record.tolerance)}; '
                f"{escape(record.metric)}</span>",
                escape(record.reference),
                f'{record.stops_measured:,} stops<span class="report-note">{record.evaluations:,} evaluations</span>',
                duration(cold["seconds"]) if cold else "—",
                f'{kib(packed)}<span class="report-note">{kib(raw)} raw</span>' if raw else "—",
            ]
        )
        ids.append(record.anchor)
    head = ["scene", "method", "measured error", "reference", "checked", "cold build", "tables (gzip)"]
    return table(head, rows, "Numerically computed scenes of this build", ids, text=(0, 1, 2, 3, 4))


def build_part(context: ReportContext) -> str:
    """Every scene's cold tabulation time and table bytes, and every page's bytes."""
    if not context.bench:
        return MISSING
    timed = context.bench["build"]["scenes"]
    rows = []
    for item in context.scenes:
        key = f"{item.page.slug}#{item.scene.id}"
        raw, packed = context.table_bytes.get(key, (0, 0))
        cold = timed.get(key)
        rows.append(
            [
                _scene_link(context, item.page.slug, item.scene.id),
                escape(item.scene.model.name),
                f"{math.prod(axis.count for axis in item.scene.axes):,}",
                f"{duration(cold['seconds'])} ({cold['repeats']})" if cold else "—",
                kib(raw),
                kib(packed),
            ]
        )
    scenes = table(
        ["scene", "model", "slider stops", "cold build (runs)", "tables", "gzip"],
        rows,
        "Cold build cost of every scene",
        text=(0,),
    )
    pages = table(
        ["page", "HTML gzip", "with script, stylesheet and font, gzip"],
        [
            [f'<a href="{escape(name)}">{escape(name)}</a>', kib(p["html_gzip"]), kib(p["total_gzip"])]
            for name, p in context.bench["build"]["pages"].items()
        ],
        "Bytes per page (as of the bench run)",
    )
    return scenes + pages


def _scene_link(context: ReportContext, slug: str, scene: str) -> str:
    """The scene's id, linked to it, with its page's title under it."""
    title = next((p.title for p in context.pages if p.slug == slug), slug)
    return (
        f'<a href="{escape(slug)}.html#scene-{escape(scene)}">{escape(scene)}</a>'
        f'<span class="report-note">{escape(title)}</span>'
    )


BOOK_PARTS = {
    "machine": machine_part,
    "digits": digits_part,
    "resolution": resolution_part,
    "scenes": scenes_part,
    "build": build_part,
}
