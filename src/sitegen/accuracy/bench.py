"""`sitegen bench`: run every accuracy–cost experiment, write bench.json, print a readable summary."""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path

from ..content.bench_results import SCHEMA
from ..site.report import summary
from .build_costs import scene_cold_times, site_sizes
from .digit_sweep import digit_sweep
from .experiments import FULL, Plan, bubble_experiment, chain_experiment
from .resolution import resolution_experiment
from .timing import MEDIUM, SAMPLE, SLOW, machine_info

REPEATS = (
    f"a warm-up call, then the median of 5 timed runs for calls under {MEDIUM:g} s, 3 under {SLOW:g} s; "
    f"a call of {SLOW:g} s or more is timed once; calls under {SAMPLE * 1e3:g} ms are timed in loops"
)


def run_bench(root: Path, plan: Plan = FULL, progress=print) -> dict:
    """Every experiment of the plan on this machine, as one JSON-ready dict."""
    start = time.perf_counter()
    results = {"schema": SCHEMA, "machine": machine_info(), "plan": {**_plain(asdict(plan)), "repeats": REPEATS}}
    sections = {}
    with _section(sections, "chain", progress, "velocity Verlet, RK45, DOP853 against the exact DST solution"):
        results["chain"] = chain_experiment(plan)
    results["bubble"] = {}
    for case in plan.cases:
        with _section(
            sections,
            f"bubble {case}",
            progress,
            f"{', '.join(plan.bubble_methods)} over {len(plan.bubble_rtols)} tolerances",
        ):
            results["bubble"][case] = bubble_experiment(case, plan)
    with _section(
        sections, "digits", progress, "every stop of each bubble scene at several rtols against a tight reference"
    ):
        results["digits"] = digit_sweep(root, plan.sweep_rtols, progress)
    with _section(sections, "resolution", progress, "interpolation error against bytes"):
        results["resolution"] = resolution_experiment()
    with _section(
        sections, "build", progress, "per scene: cold tabulation time, states, stored values, bytes; bytes per page"
    ):
        pages, data = site_sizes(root)
        scenes = scene_cold_times(root, plan.scene_repeats, progress)
        results["build"] = {
            "scenes": {name: {**row, "data": data.get(name)} for name, row in scenes.items()},
            "pages": pages,
        }
    results["section_seconds"] = sections
    results["seconds"] = time.perf_counter() - start
    return results


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
    """The readable summary: machine, chain, each bubble case, resolution and build costs."""
    m = results["machine"]
    lines = [
        f"machine: {m['cpu']}, {m['cores']} cores, Python {m['python']}, NumPy {m['numpy']}, SciPy {m['scipy']}, "
        f"{m['date']} {m['time_utc']} UTC; bench took {results['seconds']:.0f} s"
    ]
    lines += _chain_lines(results["chain"])
    for case, data in results["bubble"].items():
        lines += _bubble_lines(case, data)
    lines.append("bubble scenes, every stop against the tight reference (rtol: wrong, near a boundary, ms per solve):")
    for name, sweep in results.get("digits", {}).items():
        lines.append(
            f"  {name:<40} "
            + ", ".join(
                f"{r['rtol']:.0e}: {r['wrong']}, {r['near']}, {r['seconds'] / sweep['stops'] * 1e3:.2f} ms"
                for r in sweep["runs"]
            )
        )
    lines.append("resolution (max interpolation error / display resolution, float32 bytes):")
    for row in results["resolution"]:
        lines.append(
            f"  {row['output']:<24} {row['axis_text']:<18} {row['nodes']:>4} nodes  "
            f"{row['error'] / row['display_resolution']:9.3g}×  {row['bytes_float32']:>5} B"
        )
    lines.append("build, per scene: cold tabulation (median), full-product slider states, stored values, inline data:")
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
    return lines


def _chain_lines(chain: dict) -> list[str]:
    lines = ["chain (error = max|u − u_DST|/A at t = 2L/c):"]
    for n in sorted({r["N"] for r in chain["runs"]}):
        head = summary.chain_headlines(chain, n)
        dst = head["dst"]
        lines.append(f"  N = {n}: exact DST {dst['time_s'] * 1e3:.3f} ms (vs eigh {dst['error']:.1e})")
        if head["halving"]:
            h = head["halving"]
            lines.append(f"    Verlet ν {h['from']:g} → {h['to']:g}: error ÷{h['error']:.2f}, time ×{h['time']:.2f}")
        if head["cheapest_1e-6"]:
            c = head["cheapest_1e-6"]
            lines.append(
                f"    cheapest integrator to 1e-6: {summary.label(c)}, {c['time_s'] * 1e3:.2f} ms = "
                f"{head['dst_advantage']:.0f}× the DST"
            )
        lines.append("    time per extra digit: " + _digits(head["per_digit"]))
    return lines


def _bubble_lines(case: str, data: dict) -> list[str]:
    head = summary.bubble_headlines(data)
    lines = [
        f"bubble {data['title']}; error = {data['metric']}; reference {data['reference']} "
        f"(check {data['reference_check'].get('agreement')})"
    ]
    for run in data["runs"]:
        if "skipped" in run:
            continue
        error = f"{run['error']:.2e}" if run.get("error") is not None else "   —    "
        lines.append(
            f"  {summary.label(run):<22} nfev {run['nfev']:>8}  {run['time_s'] * 1e3:9.2f} ms  err {error}  "
            f"{run['status']}"
        )
    skipped = [r for r in data["runs"] if "skipped" in r]
    if skipped:
        lines.append(f"  skipped {len(skipped)}: " + "; ".join(sorted({r["skipped"] for r in skipped})))
    lines.append("  time per extra digit: " + _digits(head["per_digit"]))
    lines.append("  Pareto front: " + ", ".join(summary.label(r) for r in head["pareto"]))
    lines.append(
        "  cheapest within "
        + "; ".join(
            f"{target:.0e}: {summary.label(run)} ({run['time_s'] * 1e3:.1f} ms)"
            for target, run in head["cheapest"].items()
            if run
        )
    )
    if head["chosen"]:
        c = head["chosen"]
        lines.append(f"  chosen: {summary.label(c)}: {c['time_s'] * 1e3:.2f} ms, error {c['error']:.1e}")
    return lines


def _digits(per_digit: dict) -> str:
    return ", ".join(f"{m} ×{f:.2f}" if f else f"{m} —" for m, f in per_digit.items())
