"""The accuracy page's report blocks, filled into the assembled HTML.

Numbers come from two places only: bench.json (times, measured on the machine named on the
page) and this build's own deterministic data (the scenes' accuracy records and table bytes).
No clock is read here, so the same sources and the same bench.json give the same bytes.
"""
from __future__ import annotations

import gzip
import hashlib
import json
import math
import re
from dataclasses import dataclass
from html import escape
from pathlib import Path

from ..compute.cache import compute_now, digest, library_version, source_digest
from ..render.svg import figure_svg
from ..render.work_precision import Panel, Point, Series, resolution_figure, work_precision_figure
from . import summary
from .results import load_results
from .records import SceneAccuracy
from .sweep_report import near_listing, sweep_panel, sweep_rows

_SLOT = re.compile(r'<div data-report-slot="(\d+)"></div>')
_SCENE_DATA = re.compile(rb'<script type="application/json" class="scene-data">(.*?)</script>', re.S)
_CODE = frozenset({"sitegen.accuracy.page", "sitegen.accuracy.sweep_report", "sitegen.render.work_precision", "sitegen.render.svg"})
MISSING = ('<p class="report-missing">No benchmark results yet: run <code>make bench</code> (or '
           '<code>sitegen bench</code>) to measure them.</p>')


@dataclass(frozen=True)
class ReportContext:
    """Everything a report block may show: the bench run, this build's records, pages and scenes."""

    bench: dict | None
    records: tuple[SceneAccuracy, ...]
    pages: tuple  # the book's Pages
    scenes: tuple  # the build's PageScenes
    table_bytes: dict  # "page#scene" -> (raw, gzip) bytes of the scene's inline tables in this build
    remember: object = compute_now


def fill_reports(files: dict[str, bytes], pages, scenes, records, bench_file: Path, remember=compute_now) -> dict[str, bytes]:
    """The assembled files with every accuracy-report slot replaced by its part of the report."""
    if not any(page.found.reports for page in pages):
        return files
    sizes = {f"{item.page.slug}#{item.scene.id}": _scene_bytes(files, item.page.slug, item.scene.id, remember)
             for item in scenes}
    context = ReportContext(load_results(bench_file), tuple(records or ()), tuple(pages), tuple(scenes), sizes, remember)
    filled = dict(files)
    for page in pages:
        if page.found.reports:
            parts = [PARTS[block.part](context) for block in page.found.reports]
            html = files[page.output_name].decode()
            filled[page.output_name] = _SLOT.sub(lambda m: parts[int(m[1])], html).encode()
    return filled


# --- numbers as the page writes them ------------------------------------------------------------------------


def sci(value: float | None, digits: int = 2) -> str:
    """2.1 × 10<sup>−7</sup> as the captions write numbers; 0.083, 1.3 or 270 between 0.01 and 10⁴; "—" if none."""
    if value is None or not math.isfinite(value):
        return "—"
    if value == 0:
        return "0"
    if 0.01 <= abs(value) < 1e4:
        rounded = float(f"{value:.{digits}g}")
        return f"{rounded:.{max(0, digits - 1 - math.floor(math.log10(abs(rounded))))}f}".replace("-", "−")
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    power = f"10<sup>{int(exponent)}</sup>".replace("-", "−")
    return power if float(mantissa) == 1.0 else f"{mantissa} × {power}"


def duration(seconds: float | None) -> str:
    """0.052 ms, 5.6 ms, 3.2 s."""
    if seconds is None:
        return "—"
    if seconds >= 1.0:
        return f"{seconds:.1f} s" if seconds < 100 else f"{seconds:.0f} s"
    ms = seconds * 1e3
    return f"{ms:.3f} ms" if ms < 1 else f"{ms:.2g} ms" if ms < 10 else f"{ms:.0f} ms"


def kib(size: int) -> str:
    """Bytes in KiB with one decimal (or bytes under 1 KiB)."""
    return f"{size} B" if size < 1024 else f"{size / 1024:.1f} KiB"


def factor(value: float | None) -> str:
    """×3.2 (or "—")."""
    return "—" if value is None else f"×{value:.2g}" if value < 10 else f"×{value:.0f}"


def rtol_exponent(rtol: float) -> str:
    """1e-06 -> "6": the label beside a point of a work–precision line."""
    return str(-int(round(math.log10(rtol))))


# --- the figures ---------------------------------------------------------------------------------------------


def _figure(context: ReportContext, name: str, data, label: str, draw) -> str:
    """A diagram's inline SVG, remembered by its data and the drawing code (same data, same bytes)."""
    key = digest(name, json.dumps(data, sort_keys=True), source_digest(_CODE), f"matplotlib {library_version('matplotlib')}")
    svg = context.remember("report-figures", key, lambda: figure_svg(draw(), [], [], f"acc-{name}", label).encode())
    return svg.decode()


def _figure_html(name: str, svg: str, label: str, caption: str, data_table: str) -> str:
    """The diagram on a white card that scrolls on a phone, its caption, and its numbers behind a disclosure."""
    return (f'<figure class="report-figure" id="fig-{name}">\n<div class="report-scroll report-card" tabindex="0" '
            f'role="region" aria-label="{escape(label)}">\n{svg}</div>\n<figcaption>{caption}</figcaption>\n</figure>\n'
            f'<details class="report-data">\n<summary>The numbers behind this diagram</summary>\n{data_table}</details>\n')


def _table(head: list[str], rows: list[list[str]], caption: str = "", row_ids: list[str] | None = None,
           text: tuple[int, ...] = ()) -> str:
    """A table in a scrolling box (wide tables scroll sideways on a phone, not the page); `text` columns wrap."""
    ids = row_ids or [""] * len(rows)
    body = "\n".join(_row(row, row_id, text) for row, row_id in zip(rows, ids))
    cap = f"<caption>{caption}</caption>\n" if caption else ""
    label = escape(re.sub(r"<[^>]+>", "", caption) or "table")
    heads = "".join(f'<th scope="col">{h}</th>' for h in head)
    return (f'<div class="report-scroll" tabindex="0" role="region" aria-label="{label}">\n<table class="report">\n{cap}'
            f"<thead><tr>{heads}</tr></thead>\n<tbody>\n{body}\n</tbody>\n</table>\n</div>\n")


def _row(cells: list[str], row_id: str, text: tuple[int, ...]) -> str:
    attribute = f' id="{row_id}"' if row_id else ""
    return f"<tr{attribute}>" + "".join(f'<td class="text">{c}</td>' if i in text else f"<td>{c}</td>"
                                        for i, c in enumerate(cells)) + "</tr>"


def chain_part(context: ReportContext) -> str:
    """The chain's work–precision diagram (one panel per N) and its numbers."""
    if not context.bench:
        return MISSING
    chain = context.bench["chain"]
    sizes = sorted({run["N"] for run in chain["runs"]})
    label = "Work–precision diagram of the chain of masses: error against time for each method, one panel per chain size."

    def draw():
        return work_precision_figure([_chain_panel(chain, n) for n in sizes], "median wall time per run (ms)",
                                     "max |u − u_DST| / A", "labels: ν = cΔt/a for Verlet, rtol = 10⁻ⁿ for RK45 and DOP853")

    svg = _figure(context, "chain", chain, label, draw)
    caption = ("One round trip (t = 2L/c) of the Gaussian pulse, σ = 0.05 L. Each line is a method; the number "
               "beside a point is its Courant number ν (velocity Verlet) or n in rtol = 10⁻ⁿ (RK45, DOP853). "
               "The ringed point is what the page uses: the exact DST solution, whose own error is its "
               "disagreement with a dense eigendecomposition.")
    rows = [[str(r["N"]), r["method"], f"rtol {summary.exponent_text(r['rtol'])}" if r["rtol"] else escape(r["setting"]),
             f"{r['steps']:,}", f"{r['evaluations']:,}", sci(r["error"]), duration(r["time_s"]), str(r["repeats"])]
            for r in chain["runs"]]
    table = _table(["N", "method", "setting", "steps", "force evaluations", "error", "median time", "runs"], rows,
                   "Every run of the chain experiment")
    return _figure_html("chain", svg, label, caption, table)


def _chain_panel(chain: dict, n: int) -> Panel:
    runs = [r for r in chain["runs"] if r["N"] == n and summary.usable(r)]
    series = [Series(method, tuple(_run_point(r) for r in group)) for method, group in summary.methods(runs).items()]
    dst = summary.find(runs, "exact DST")
    chosen = Point(dst["time_s"] * 1e3, dst["error"], "chosen: exact DST") if dst else None
    return Panel(f"chain of N = {n} masses", tuple(series), chosen=chosen, floor=1e-16, ceiling=10.0)


def bubble_part(case: str):
    """The report block of one bubble case: its work–precision diagram and its numbers."""

    def render(context: ReportContext) -> str:
        if not context.bench or case not in context.bench.get("bubble", {}):
            return MISSING
        data = context.bench["bubble"][case]
        label = f"Work–precision diagram of bubble case {case}: error against time for five solvers over rtol 10⁻³ to 10⁻¹²."

        def draw():
            return work_precision_figure([_bubble_panel(data)], "median wall time per solve (ms)", data["metric"].split(" over")[0],
                                         "labels: rtol = 10⁻ⁿ; ▲: error above the plot")

        svg = _figure(context, f"bubble-{case}", data, label, draw)
        return _figure_html(f"bubble-{case}", svg, label, _bubble_caption(data), _bubble_table(case, data))

    return render


def _bubble_panel(data: dict) -> Panel:
    runs = [r for r in data["runs"] if summary.usable(r)]
    series = [Series(m, tuple(_run_point(r) for r in group)) for m, group in summary.methods(runs).items()
              if m not in summary.EXACT]
    chosen_run = summary.bubble_headlines(data)["chosen"]
    exact = summary.find(runs, "analytic")
    chosen = None
    if chosen_run:
        text = f"chosen: {summary.label(chosen_run)}" + (" (exact)" if chosen_run.get("exact") else "")
        chosen = Point(chosen_run["time_s"] * 1e3, chosen_run["error"], text)
    return Panel(data.get("short", data["title"]), tuple(series), chosen=chosen, floor=1e-15, ceiling=10.0,
                 exact=Point(exact["time_s"] * 1e3, 0.0, "") if exact else None)


def _run_point(run: dict) -> Point:
    """A run as a point (time in ms, error) labelled by its Courant number or its rtol exponent."""
    if run.get("courant") is not None:
        return Point(run["time_s"] * 1e3, run["error"], f"{run['courant']:g}")
    if run.get("rtol"):
        exponent = rtol_exponent(run["rtol"])
        return Point(run["time_s"] * 1e3, run["error"], exponent, major=int(exponent) % 3 == 0)
    return Point(run["time_s"] * 1e3, run["error"])


def _bubble_caption(data: dict) -> str:
    check = data["reference_check"]
    agreement = f" (they agree to {sci(check['agreement'])})" if check.get("agreement") is not None else ""
    return (f"{escape(data['title'])}. Error: {escape(data['metric'])}; reference: {escape(data['reference'])}{agreement}. "
            "The number beside a point is n in rtol = 10⁻ⁿ (atol = 10⁻³ rtol, nondimensional); the ringed point is "
            "the setting the model chooses for this case.")


def _bubble_table(case: str, data: dict) -> str:
    front = {id(r) for r in summary.bubble_headlines(data)["pareto"]}
    rows = []
    for r in data["runs"]:
        tol = summary.exponent_text(r["rtol"]) if r.get("rtol") else "—"
        if "skipped" in r:
            rows.append([r["method"], tol, "—", "—", "—", "", f"not run: {escape(r['skipped'])}"])
        else:
            status = "" if r["status"] == data["expected_status"] else f"ended: {escape(r['status'])}"
            rows.append([r["method"], tol, f"{r['nfev']:,}", sci(r["error"]), duration(r["time_s"]),
                         "yes" if id(r) in front else "", f"{r['repeats']} run(s) {status}".strip()])
    return _table(["method", "rtol", "evaluations", "error", "median time", "Pareto front", "notes"], rows,
                  f"Every run of bubble case {case}", text=(6,))


def resolution_part(context: ReportContext) -> str:
    """Interpolation error against bytes for the §12 outputs, and what the page ships instead."""
    if not context.bench:
        return MISSING
    rows = context.bench["resolution"]
    label = "Interpolation error against stored bytes for four outputs, by choice of axis and number of nodes."

    def draw():
        xlim = (min(r["bytes_float32"] for r in rows) / 2.5, max(r["bytes_float32"] for r in rows) * 2.5)
        panels = [_resolution_panel([r for r in rows if r["line"] == key], xlim) for key in dict.fromkeys(r["line"] for r in rows)]
        return resolution_figure(panels, "labels: number of nodes; dashed: half of the last displayed digit")

    svg = _figure(context, "resolution", rows, label, draw)
    caption = ("Each output is stored at a few nodes and interpolated back to every slider stop; the error is the "
               "largest difference from the model, in units of half the last digit the page shows (below the dashed "
               "line an interpolated readout would round correctly). A coordinate in which the output is exactly "
               "affine or quadratic (w₁ = m₁/(m₁+m₂), 1/m, quadratic in e) needs two or three nodes; the pole of "
               "MA(x_p) defeats interpolation. The page ships every stop, rounded: no interpolation error at all.")
    table = _table(["output", "axis", "nodes", "max error", "÷ ½ digit", "float32", "JSON gzip"],
                   [[escape(r["output"]), escape(r["axis_text"]), str(r["nodes"]), sci(r["error"]),
                     sci(r["error"] / r["display_resolution"]), f"{r['bytes_float32']} B", f"{r['bytes_json_gzip']} B"]
                    for r in rows], "Every axis choice and node count")
    return _figure_html("resolution", svg, label, caption, table)


AXIS_GROUPS = {"linear": "linear axis", "log": "log axis", "w1": "exact coordinate", "inverse": "exact coordinate",
               "quadratic": "exact coordinate", "per stop": "every stop"}


def _resolution_panel(rows: list[dict], xlim: tuple[float, float]) -> Panel:
    series = []
    for group in dict.fromkeys(AXIS_GROUPS.values()):
        members = [r for r in rows if AXIS_GROUPS[r["axis"]] == group]
        points = tuple(Point(r["bytes_float32"], r["error"] / r["display_resolution"], str(r["nodes"])) for r in members)
        series.append(Series(group, points))
    return Panel(rows[0]["output"], tuple(series), floor=1e-13, ceiling=1e6, line=(1.0, "½ digit"), xlim=xlim, ylim=(1e-14, 1e6))


# --- tables and text -----------------------------------------------------------------------------------------


def machine_part(context: ReportContext) -> str:
    """Where and when the timings were measured, and how they were repeated."""
    if not context.bench:
        return MISSING
    m, plan = context.bench["machine"], context.bench["plan"]
    return (f'<p class="report-machine">The timings on this page were measured on <strong>{m["date"]}</strong>, '
            f'on a machine with {m["cores"]} cores ({escape(m["cpu"])}; Python {m["python"]}, NumPy {m["numpy"]}, '
            f'SciPy {m["scipy"]}, one BLAS thread), in one run of <code>sitegen bench</code> that took '
            f'{duration(context.bench["seconds"])}. Each time is a median: {escape(plan["repeats"])}. Read them '
            f"as ratios: on another machine every time scales, the comparisons mostly do not.</p>\n")


def digits_part(context: ReportContext) -> str:
    """What one more correct digit costs, per method, and the headline ratios of the run."""
    if not context.bench:
        return MISSING
    items = [_chain_sentence(context.bench["chain"], n) for n in sorted({r["N"] for r in context.bench["chain"]["runs"]})]
    items += [_bubble_sentence(case, data) for case, data in context.bench["bubble"].items()]
    rows = _per_digit_rows(context.bench)
    table = _table(["problem"] + list(rows["methods"]), rows["rows"], "Time multiplier per extra correct digit "
                   "(least-squares slope of log time against −log error)")
    return "<ul class=\"report-findings\">\n" + "\n".join(f"<li>{item}</li>" for item in items if item) + "\n</ul>\n" + table


def _per_digit_rows(bench: dict) -> dict:
    names = ["velocity Verlet", "RK45", "DOP853", "Radau", "BDF", "LSODA", "compiled-DOP853", "compiled-Radau"]
    rows = []
    for n in sorted({r["N"] for r in bench["chain"]["runs"]}):
        costs = summary.chain_headlines(bench["chain"], n)["per_digit"]
        rows.append([f"chain, N = {n}"] + [factor(costs.get(m)) for m in names])
    for case, data in bench["bubble"].items():
        costs = summary.bubble_headlines(data)["per_digit"]
        rows.append([f"bubble {case}"] + [factor(costs.get(m)) for m in names])
    return {"methods": names, "rows": rows}


def _chain_sentence(chain: dict, n: int) -> str:
    head = summary.chain_headlines(chain, n)
    parts = [f"<strong>Chain, N = {n}.</strong>"]
    if head["dst"]:
        parts.append(f"The exact DST solution takes {duration(head['dst']['time_s'])} per frame and agrees with a "
                     f"dense eigendecomposition to {sci(head['dst']['error'])}.")
    if head["halving"]:
        h = head["halving"]
        parts.append(f"Halving Verlet's step (ν {h['from']:g} → {h['to']:g}) divides its error by {h['error']:.1f} "
                     f"and multiplies its time by {h['time']:.1f}.")
    if head["cheapest_1e-6"]:
        c = head["cheapest_1e-6"]
        parts.append(f"The cheapest integrator within {sci(1e-6)} is {label_html(c)}: {duration(c['time_s'])}, "
                     f"{head['dst_advantage']:.0f} times the DST's time for a worse answer.")
    return " ".join(parts)


def _bubble_sentence(case: str, data: dict) -> str:
    head = summary.bubble_headlines(data)
    runs = data["runs"]
    parts = [f"<strong>Bubble {case}.</strong>"]
    if head["chosen"]:
        c = head["chosen"]
        parts.append(f"The chosen setting, {label_html(c)}, takes {duration(c['time_s'])} "
                     + ("and is exact." if c.get("exact") else f"with error {sci(c['error'])} ({c['nfev']:,} evaluations)."))
    step = summary.tighter(runs, "DOP853", 1e-6, 1e-9)
    if case != "C" and step and step["digits"] is not None:
        parts.append(f"Tightening DOP853 from rtol {sci(1e-6)} to {sci(1e-9)} buys {step['digits']:.1f} digits "
                     f"for {factor(step['time'])} the time.")
    if case == "A":
        dop = summary.find(runs, "DOP853", rtol=1e-6)
        ratio = summary.ratio(dop, head["chosen"])
        if ratio:
            parts.append(f"DOP853 at rtol {sci(1e-6)} takes {ratio:.0f} times as long as the closed form.")
    if case == "C":
        fast, slow = summary.find(runs, "LSODA", rtol=1e-6), summary.find(runs, "RK45", rtol=1e-6)
        ratio = summary.ratio(slow, fast)
        if ratio:
            parts.append(f"RK45 at the same rtol needs {slow['nfev']:,} evaluations and {ratio:.0f} times LSODA's time: "
                         "its step is held down by stability, not accuracy.")
    cheapest = [f"within {sci(target)}, {label_html(run)} ({duration(run['time_s'])})"
                for target, run in head["cheapest"].items() if run]
    if cheapest:
        parts.append("Cheapest solver run " + "; ".join(cheapest) + ".")
    return " ".join(parts)


def label_html(run: dict) -> str:
    """A run as the page's prose names it: "DOP853 at rtol 10<sup>−6</sup>", "velocity Verlet at ν = 0.1"."""
    if run.get("rtol"):
        return f"{escape(run['method'])} at rtol {sci(run['rtol'])}"
    if run.get("courant") is not None:
        return f"velocity Verlet at ν = {run['courant']:g}"
    return escape(run["method"])


def settings_part(context: ReportContext) -> str:
    """The bubble scenes' settings, chosen: time per solve against the largest error in shown digits, every stop."""
    sweep = (context.bench or {}).get("digits")
    if not sweep:
        return MISSING
    label = "Time per solve against the largest error in units of the last shown digit, every stop of each bubble scene."

    def draw():
        return work_precision_figure([sweep_panel(sweep)], "time per solve, all stops (ms)", "largest error (last shown digits)",
                                     "labels: rtol = 10⁻ⁿ; below 0.5 every shown digit can be right")

    table = _table(["scene", "rtol", "ms per solve", "wrong values", "near a boundary", "largest error (digits)"], sweep_rows(sweep),
                   "Every stop of every bubble scene against the tight reference", text=(0,))
    caption = (f"{label} Reference: {escape(next(iter(sweep.values()))['reference'])}. The number beside a point is n in rtol = 10⁻ⁿ; "
               "the ringed point is the setting the scenes use.")
    return _figure_html("settings", _figure(context, "settings", sweep, label, draw), label, caption, table) + near_listing(sweep)


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
        rows.append([_scene_link(context, record.page, record.scene), f"{escape(record.method)}{settings}",
                     f"{sci(record.error)} <span class=\"report-note\">{within} {sci(record.tolerance)}; "
                     f"{escape(record.metric)}</span>", escape(record.reference),
                     f"{record.stops_checked:,} stops<span class=\"report-note\">{record.evaluations:,} evaluations</span>",
                     duration(cold["seconds"]) if cold else "—", f"{kib(packed)}<span class=\"report-note\">{kib(raw)} raw</span>" if raw else "—"])
        ids.append(record.anchor)
    head = ["scene", "method", "measured error", "reference", "checked", "cold build", "tables (gzip)"]
    return _table(head, rows, "Numerically computed scenes of this build", ids, text=(0, 1, 2, 3, 4))


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
        rows.append([_scene_link(context, item.page.slug, item.scene.id), escape(item.scene.model.name),
                     f"{math.prod(axis.count for axis in item.scene.axes):,}",
                     f"{duration(cold['seconds'])} ({cold['repeats']})" if cold else "—", kib(raw), kib(packed)])
    scenes = _table(["scene", "model", "slider stops", "cold build (runs)", "tables", "gzip"], rows,
                    "Cold build cost of every scene", text=(0,))
    pages = _table(["page", "HTML gzip", "with script, stylesheet and font, gzip"],
                   [[f'<a href="{escape(name)}">{escape(name)}</a>', kib(p["html_gzip"]), kib(p["total_gzip"])]
                    for name, p in context.bench["build"]["pages"].items()], "Bytes per page (as of the bench run)")
    return scenes + pages


def _scene_link(context: ReportContext, slug: str, scene: str) -> str:
    """The scene's id, linked to it, with its page's title under it."""
    title = next((p.title for p in context.pages if p.slug == slug), slug)
    return (f'<a href="{escape(slug)}.html#scene-{escape(scene)}">{escape(scene)}</a>'
            f'<span class="report-note">{escape(title)}</span>')


def scene_data(html: bytes, scene: str) -> bytes | None:
    """The inline tables (JSON) of scene `scene` in a built page, or None when it is not there."""
    start = html.find(f'id="scene-{scene}"'.encode())
    found = _SCENE_DATA.search(html, start) if start >= 0 else None
    return found[1] if found else None


def _scene_bytes(files: dict, slug: str, scene: str, remember) -> tuple[int, int]:
    """Raw and gzip bytes of a scene's inline tables in this build (0, 0 when not found)."""
    payload = scene_data(files.get(f"{slug}.html", b""), scene)
    if payload is None:
        return 0, 0
    packed = remember("report-gzip", hashlib.sha256(payload).hexdigest(), lambda: str(len(gzip.compress(payload, 9, mtime=0))).encode())
    return len(payload), int(packed)


PARTS = {
    "machine": machine_part,
    "chain": chain_part,
    "bubble-A": bubble_part("A"),
    "bubble-B": bubble_part("B"),
    "bubble-C": bubble_part("C"),
    "settings": settings_part,
    "digits": digits_part,
    "resolution": resolution_part,
    "scenes": scenes_part,
    "build": build_part,
}
