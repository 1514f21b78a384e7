"""`make bench`: build time, page sizes (raw and gzip) and slider-to-DOM latency, printed and saved.

Timings are medians over repeated runs on this machine; treat them as ratios, not absolutes.
"""

from __future__ import annotations

import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build-bench"
sys.path.insert(0, str(ROOT / "src"))

from sitegen.build import BuildConfig, build  # noqa: E402


def build_times(runs: int = 3) -> dict:
    """Median wall time of a full build (and of each phase) over `runs` builds."""
    totals, phases = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(runs):
            start = time.perf_counter()
            report = build(BuildConfig.at(ROOT, Path(tmp) / "build", cache=None), progress=None)
            totals.append(time.perf_counter() - start)
            phases.append(report.phases)
    return {
        "runs": runs,
        "median_s": statistics.median(totals),
        "phases_median_s": {k: statistics.median(p[k] for p in phases) for k in phases[0]},
        "stored_values": report.stored_values,
    }


def rebuild_times(runs: int = 3) -> dict:
    """Cold build, no-op rebuild, one-scene rebuild and a Dask build: seconds and evaluation counts."""
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        shutil.copytree(ROOT / "content", root / "content")
        config = BuildConfig(root, root / "content", root / "build", cache=root / ".cache")

        def timed(cfg):
            start = time.perf_counter()
            report = build(cfg, progress=None)
            return time.perf_counter() - start, report

        colds = []
        for _ in range(runs):
            shutil.rmtree(config.cache, ignore_errors=True)
            colds.append(timed(config))
        noops = [timed(config) for _ in range(runs)]
        page = root / "content" / "newtons-laws.md"
        text = page.read_text()
        assert "slider F_pk: 0..50 step 0.5 default 12" in text, (
            "the impulse scene's F_pk slider changed: update bench/run.py"
        )
        page.write_text(text.replace("slider F_pk: 0..50 step 0.5 default 12", "slider F_pk: 0..50 step 1 default 12"))
        one_scene = timed(config)
        result = {
            "cold_s": statistics.median(t for t, _ in colds),
            "cold_evaluations": colds[-1][1].evaluations,
            "noop_s": statistics.median(t for t, _ in noops),
            "noop_evaluations": noops[-1][1].evaluations,
            "one_scene_s": one_scene[0],
            "one_scene_computed": one_scene[1].computed,
            "one_scene_evaluations": one_scene[1].evaluations,
        }
        try:
            from distributed import LocalCluster
        except ImportError:
            return result
        with LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster:
            dask_config = BuildConfig(
                root, root / "content", root / "build-dask", cache=None, scheduler=cluster.scheduler_address
            )
            seconds, report = timed(dask_config)
        result.update(dask_cold_s=seconds, dask_evaluations=report.evaluations)
        return result


def deps_probe_cost(pairs: int = 3) -> dict:
    """Cold builds of the book with and without the deps probe, in interleaved pairs (so that the machine's load
    falls on both alike; each pair in the other order than the one before, after a build that loads what the
    first build of a process loads): min, median and max seconds of each, and the probe's share of the median.
    In the builds with it, the probe's own CPU seconds (and the page-weight summary's) against the build's: a
    share that the machine's load moves far less than the difference of two builds."""
    import sitegen.build as built
    import sitegen.phases.scenes as scenes

    checked, weighed = scenes.verify_scene_deps, built.page_weights
    seconds, own = {"with": [], "without": []}, []
    with tempfile.TemporaryDirectory() as tmp:
        build(BuildConfig.at(ROOT, Path(tmp) / "warm", cache=None), progress=None)  # imports and compiled code loaded
        for pair in range(pairs):
            for side in ("with", "without") if pair % 2 == 0 else ("without", "with"):
                spent = {"probe": 0.0, "weights": 0.0}
                scenes.verify_scene_deps = _cpu_timed(checked, spent, "probe") if side == "with" else _no_findings
                built.page_weights = _cpu_timed(weighed, spent, "weights")
                try:
                    start, cpu = time.perf_counter(), time.process_time()
                    build(BuildConfig.at(ROOT, Path(tmp) / side, cache=None), progress=None)
                    seconds[side].append(time.perf_counter() - start)
                    if side == "with":
                        own.append({"build_cpu_s": time.process_time() - cpu, **spent})
                finally:
                    scenes.verify_scene_deps, built.page_weights = checked, weighed
    spread = {side: _spread(t) for side, t in seconds.items()}
    share = spread["with"]["median_s"] / spread["without"]["median_s"] - 1
    shares = {part: _spread([run[part] / run["build_cpu_s"] for run in own], "") for part in ("probe", "weights")}
    cpu = {part: _spread([run[part] for run in own]) for part in ("build_cpu_s", "probe", "weights")}
    return {"pairs": pairs, **spread, "share": share, "own_cpu_s": cpu, "own_share": shares}


def _cpu_timed(function, spent: dict, part: str):
    """`function`, adding the CPU seconds of each call to spent[part]."""

    def timed(*args, **kwargs):
        start = time.process_time()
        try:
            return function(*args, **kwargs)
        finally:
            spent[part] += time.process_time() - start

    return timed


def _no_findings(*args, **kwargs) -> list:
    return []


def _spread(values, unit: str = "_s") -> dict:
    return {f"min{unit}": min(values), f"median{unit}": statistics.median(values), f"max{unit}": max(values)}


def page_sizes(report) -> dict:
    """Raw and gzip bytes of each page and of everything it loads, as the build's summary measured them."""
    return {weight.page: weight.sizes() for weight in report.weights}


def main() -> int:
    """Run every benchmark, print a summary and write build-bench/report.json."""
    OUT.mkdir(exist_ok=True)
    site = ROOT / "build"
    built = build(BuildConfig.at(ROOT), progress=None)
    report = {
        "machine": {"python": platform.python_version(), "cpu_count": os.cpu_count(), "platform": platform.platform()},
        "build": build_times(),
        "rebuilds": rebuild_times(),
        "deps_probe": deps_probe_cost(),
        "pages": page_sizes(built),
    }
    latency_file = OUT / "latency.json"
    subprocess.run(
        [sys.executable, str(ROOT / "bench" / "latency.py"), "--site", str(site), "--out", str(latency_file)],
        check=True,
    )
    report["latency"] = json.loads(latency_file.read_text())
    (OUT / "report.json").write_text(json.dumps(report, indent=2, sort_keys=True))
    print(
        f"build: median {report['build']['median_s']:.2f} s over {report['build']['runs']} cold builds, "
        f"{report['build']['stored_values']} stored values"
    )
    r = report["rebuilds"]
    print(
        f"cache: cold {r['cold_s']:.2f} s ({r['cold_evaluations']} evaluations), no-op {r['noop_s']:.2f} s "
        f"({r['noop_evaluations']} evaluations), one scene edited {r['one_scene_s']:.2f} s "
        f"({r['one_scene_computed']} scene, {r['one_scene_evaluations']} evaluations)"
        + (
            f", Dask LocalCluster cold {r['dask_cold_s']:.2f} s ({r['dask_evaluations']} evaluations)"
            if "dask_cold_s" in r
            else ""
        )
    )
    d = report["deps_probe"]
    print(
        f"deps probe: cold build {d['with']['median_s']:.2f} s (min {d['with']['min_s']:.2f}, max "
        f"{d['with']['max_s']:.2f}) with it, {d['without']['median_s']:.2f} s (min {d['without']['min_s']:.2f}, "
        f"max {d['without']['max_s']:.2f}) without, over {d['pairs']} interleaved pairs: {100 * d['share']:+.1f} %"
    )
    for part, what in (("probe", "deps probe"), ("weights", "page weights")):
        s, c = d["own_share"][part], d["own_cpu_s"][part]
        print(
            f"{what}: its own CPU {c['median_s']:.3f} s, {100 * s['median']:.2f} % of the cold build's "
            f"(min {100 * s['min']:.2f} %, max {100 * s['max']:.2f} %)"
        )
    for name, s in report["pages"].items():
        print(
            f"{name:<22} html {s['html_raw'] / 1024:7.1f} KB raw {s['html_gzip'] / 1024:6.1f} KB gzip | "
            f"with assets {s['total_raw'] / 1024:7.1f} KB raw {s['total_gzip'] / 1024:6.1f} KB gzip"
        )
    print(f"wrote {OUT / 'report.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
