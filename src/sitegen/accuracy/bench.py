"""`sitegen bench`: measure what the book's numerical choices cost, write bench.json, print a summary.

Every numerically computed scene's model gets the work–precision experiment of its declared methods
(experiments.py) and the experiments it declares of its own (`Model.experiments`); then the interpolation
experiment and the build's costs. Nothing here names a model: the book's scenes say which are measured.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path

from ..build import BuildConfig, needed_outputs, resolve_book
from ..compute.measure import measured_stops
from ..content.bench_results import SCHEMA
from ..registry import load_registry
from ..site.report import summary
from .build_costs import scene_cold_times, site_sizes
from .experiments import FULL, Plan, bench_scene, method_experiment
from .resolution import resolution_experiment
from .timing import MEDIUM, SAMPLE, SLOW, machine_info, time_medians

REPEATS = (
    f"a warm-up call, then the median of 5 timed runs for calls under {MEDIUM:g} s, 3 under {SLOW:g} s; "
    f"a call of {SLOW:g} s or more is timed once; calls under {SAMPLE * 1e3:g} ms are timed in loops; "
    "each method and setting at a scene's stops: the median of 3"
)


def numerical_scenes(root: Path) -> tuple[dict[str, list], set[str]]:
    """The book's numerically computed scenes as the bench measures them, by model name (in the book's order),
    and the names ("page#id") of all its scenes."""
    config = BuildConfig.at(root, cache=None)
    registry = load_registry(config.book)
    records = resolve_book(config, registry).scenes
    found: dict[str, list] = {}
    for record in records:
        scene = record.scene
        if scene.model.settings is None or not scene.model.is_numerical(scene.effects):
            continue
        item = bench_scene(record.name, scene, needed_outputs(scene, registry), measured_stops(scene))
        found.setdefault(scene.model.name, []).append(item)
    return found, {record.name for record in records}


def run_bench(root: Path, plan: Plan = FULL, progress=print) -> dict:
    """Every experiment of the plan on this machine, as one JSON-ready dict."""
    start = time.perf_counter()
    results = {"schema": SCHEMA, "machine": machine_info(), "plan": {**_plain(asdict(plan)), "repeats": REPEATS}}
    sections: dict[str, float] = {}
    scenes, names = numerical_scenes(root)
    results["models"] = {name: _model_results(items, plan, sections, progress) for name, items in scenes.items()}
    with _section(sections, "resolution", progress, "interpolation error against bytes"):
        results["resolution"] = resolution_experiment(names)
    with _section(
        sections, "build", progress, "per scene: cold tabulation time, states, stored values, bytes; bytes per page"
    ):
        pages, data = site_sizes(root)
        costs = scene_cold_times(root, plan.scene_repeats, progress)
        results["build"] = {
            "scenes": {name: {**row, "data": data.get(name)} for name, row in costs.items()},
            "pages": pages,
        }
    results["section_seconds"] = sections
    results["seconds"] = time.perf_counter() - start
    return results


def _model_results(items: list, plan: Plan, sections: dict, progress) -> dict:
    """One model's generic experiment over its scenes, and the experiments it declares of its own."""
    model = type(items[0].scene.model)
    with _section(sections, model.name, progress, f"{', '.join(model.methods)} at {len(items)} scene(s)' stops"):
        methods = method_experiment(items, plan, progress)
    own = {}

    def timer(jobs: dict, repeats: int = plan.max_repeats) -> dict:
        return time_medians(jobs, repeats)

    for name, experiment in model.experiments.items():
        with _section(sections, name, progress, f"{model.name}'s own experiment {name}"):
            data = experiment.measure(items, plan.quick, timer)
        if data is not None:
            own[name] = {"kind": experiment.kind, **data}
    return {"title": model.title, "methods": methods, "experiments": own}


@contextmanager
def _section(sections: dict, name: str, progress, what: str):
    """Time one part of the bench and say what it is doing."""
    if progress:
        progress(f"{name}: {what}")
    start = time.perf_counter()
    yield
    sections[name] = time.perf_counter() - start


def _plain(data: dict) -> dict:
    return {k: list(v) if isinstance(v, tuple) else v for k, v in data.items()}


def summary_lines(results: dict) -> list[str]:
    """The readable summary: machine, each experiment's runs and headlines, dominated settings, resolution, build."""
    m = results["machine"]
    lines = [
        f"machine: {m['cpu']}, {m['cores']} cores, Python {m['python']}, NumPy {m['numpy']}, SciPy {m['scipy']}, "
        f"{m['date']} {m['time_utc']} UTC; bench took {results['seconds']:.0f} s"
    ]
    for part, title, data in summary.experiments(results):
        lines.append(f"{part}: {title}; error = {data['metric']}; reference {data['reference']}")
        for panel in data["panels"]:
            lines += _panel_lines(panel)
    for results_of in results["models"].values():
        for part, data in results_of["experiments"].items():
            if data["kind"] == "digit-sweep":
                lines += _sweep_lines(part, data)
    lines.append("resolution (max interpolation error / display resolution, float32 bytes):")
    for row in results["resolution"]:
        lines.append(
            f"  {row['output']:<24} {row['axis_text']:<18} {row['nodes']:>4} nodes  "
            f"{row['error'] / row['display_resolution']:9.3g}×  {row['bytes_float32']:>5} B"
        )
    lines.append("build, per scene: cold tabulation (median), full-product slider states, stored values, data bytes:")
    for name, scene in results["build"]["scenes"].items():
        data = scene.get("data") or {"raw": 0, "gzip": 0}
        lines.append(
            f"  {name:<40} {scene['seconds']:8.3f} s over {scene['repeats']} run(s), {scene['stops']:>17,} states, "
            f"{scene.get('stored_values', 0):>10,} values, "
            f"{data['raw'] / 1024:7.1f} KiB raw {data['gzip'] / 1024:6.1f} KiB gzip"
        )
    for name, page in results["build"]["pages"].items():
        lines.append(
            f"  {name:<28} {page['html_gzip'] / 1024:7.1f} KiB gzip, with assets {page['total_gzip'] / 1024:7.1f} KiB"
        )
    dominated = summary.dominated_lines(results)  # last, where an author sees it
    lines.append(f"scenes whose settings another setting beats: {len(dominated) or 'none'}")
    return lines + [f"  {line}" for line in dominated]


def _panel_lines(panel: dict) -> list[str]:
    """One panel's runs, its cost per digit, its Pareto front and its chosen run."""
    head = summary.headlines(panel)
    lines = [f"  {summary.panel_title(panel)}:"]
    for run in panel["runs"]:
        if run.get("status", "ok") != "ok":
            lines.append(f"    {summary.label(run):<28} {run.get('skipped') or run['status']}")
            continue
        error = f"{run['error']:.2e}" if run.get("error") is not None else "   —    "
        lines.append(
            f"    {summary.label(run):<28} {run.get('evaluations', 0):>9,} evaluations {run['time_s'] * 1e3:10.3f} ms  "
            f"err {error}"
        )
    lines.append("    time per extra digit: " + _digits(head["per_digit"]))
    lines.append("    Pareto front: " + ", ".join(summary.label(r) for r in head["pareto"]))
    if head["chosen"]:
        c = head["chosen"]
        lines.append(f"    chosen: {summary.label(c)}: {c['time_s'] * 1e3:.3f} ms, error {c['error']:.1e}")
    return lines


def _sweep_lines(part: str, data: dict) -> list[str]:
    lines = [f"{part}: every stop of each scene at several rtols (rtol: wrong, near a boundary, ms per solve):"]
    for name, sweep in data["scenes"].items():
        lines.append(
            f"  {name:<40} "
            + ", ".join(
                f"{r['rtol']:.0e}: {r['wrong']}, {r['near']}, {r['seconds'] / sweep['stops'] * 1e3:.2f} ms"
                for r in sweep["runs"]
            )
        )
    return lines


def _digits(per_digit: dict) -> str:
    return ", ".join(f"{m} ×{f:.2f}" if f else f"{m} —" for m, f in per_digit.items())
