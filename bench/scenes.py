"""Per scene: the states of the full cross product of its controls, the values the page actually
stores, the bytes of its inline data (raw and gzip) and its cold tabulation time (median).

Run by bench/run.py (`make bench`) in a fresh process, so that no solve is reused from an earlier
build in the same process (the bubble model memoises its solves); also runnable alone:
`python bench/scenes.py [--site build] [--out scenes.json]`.
"""
from __future__ import annotations

import gzip
import os
import re
import statistics
import sys
import time
from math import prod
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from sitegen.build import BuildConfig, needed_outputs, read_pages, resolve_scenes  # noqa: E402
from sitegen.compute.tabulate import tabulate_scene  # noqa: E402
from sitegen.errors import ErrorLog  # noqa: E402

SCENE_DATA = re.compile(r'<figure class="scene" id="scene-([\w-]+)".*?<script type="application/json" class="scene-data">(.*?)</script>', re.S)


def scene_payloads(site: Path) -> dict[str, bytes]:
    """Each scene's inline JSON in the built site, by "page#scene"."""
    found = {}
    for page in sorted(site.glob("*.html")):
        for scene_id, data in SCENE_DATA.findall(page.read_text()):
            found[f"{page.stem}#{scene_id}"] = data.encode()
    return found


def scene_figures(site: Path, runs: int = 3) -> list[dict]:
    """One row per scene of the book (tabulation timed `runs` times, cold, in this process)."""
    log = ErrorLog()
    items = resolve_scenes(read_pages(BuildConfig.at(ROOT), log), log)
    log.raise_if_any()
    payloads = scene_payloads(site)
    rows = []
    for item in items:
        scene, names = item.scene, needed_outputs(item.scene)
        seconds = []
        for _ in range(runs if scene.model.chunk_stops is None else 1):  # ODE models: one run (tens of seconds)
            start = time.perf_counter()
            tables = tabulate_scene(scene, names)
            seconds.append(time.perf_counter() - start)
        payload = payloads.get(f"{item.page.slug}#{scene.id}", b"")
        rows.append({
            "scene": f"{item.page.slug}#{scene.id}",
            "model": scene.model.name,
            "full_product_states": prod(a.count for a in scene.axes),
            "outputs": len(names),
            "stored_values": sum(t.stored_values() for t in tables.values()),
            "structured_outputs": sum(1 for n in names if hasattr(tables.get(n), "expr")),
            "payload_raw": len(payload),
            "payload_gzip": len(gzip.compress(payload, 9, mtime=0)) if payload else 0,
            "tabulate_s_median": statistics.median(seconds),
            "runs": len(seconds),
        })
    return rows


def print_rows(rows: list[dict]) -> None:
    """A readable table of `scene_figures`."""
    print(f"{'scene':<40} {'states':>16} {'stored':>9} {'exact':>6} {'JSON raw':>10} {'gzip':>9} {'tabulate':>9}")
    for r in rows:
        print(f"{r['scene']:<40} {r['full_product_states']:>16,} {r['stored_values']:>9,} "
              f"{r['structured_outputs']:>2}/{r['outputs']:<3} {r['payload_raw'] / 1024:>8.1f}KB {r['payload_gzip'] / 1024:>7.1f}KB "
              f"{r['tabulate_s_median']:>8.2f}s")


def main() -> int:
    """Print the rows for the site in build/ (or --site DIR) and write them as JSON when --out is given."""
    import argparse
    import json

    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--site", type=Path, default=ROOT / "build")
    parser.add_argument("--out", type=Path)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    rows = scene_figures(args.site, args.runs)
    print_rows(rows)
    if args.out:
        args.out.write_text(json.dumps(rows, indent=1, sort_keys=True))
    return 0


if __name__ == "__main__":
    sys.exit(main())
