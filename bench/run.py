"""`make bench`: build time, page sizes (raw and gzip) and slider-to-DOM latency, printed and saved.

Timings are medians over repeated runs on this machine; treat them as ratios, not absolutes.
"""
from __future__ import annotations

import gzip
import json
import os
import platform
import re
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
            report = build(BuildConfig.at(ROOT, Path(tmp) / "build"), progress=None)
            totals.append(time.perf_counter() - start)
            phases.append(report.phases)
    return {
        "runs": runs,
        "median_s": statistics.median(totals),
        "phases_median_s": {k: statistics.median(p[k] for p in phases) for k in phases[0]},
        "stored_values": report.stored_values,
    }


def page_sizes(site: Path) -> dict:
    """Raw and gzip bytes of each page and of everything it loads."""
    sizes = {}
    for page in sorted(site.glob("*.html")):
        html = page.read_text()
        assets = sorted(set(re.findall(r'(?:href|src)="(assets/[^"]+)"', html)) | {"assets/latinmodern-math.woff2"})
        files = [page, *(site / a for a in assets)]
        sizes[page.name] = {
            "html_raw": page.stat().st_size,
            "html_gzip": len(gzip.compress(page.read_bytes(), 9, mtime=0)),
            "total_raw": sum(f.stat().st_size for f in files),
            "total_gzip": sum(len(gzip.compress(f.read_bytes(), 9, mtime=0)) for f in files),
        }
    return sizes


def main() -> int:
    """Run every benchmark, print a summary and write build-bench/report.json."""
    OUT.mkdir(exist_ok=True)
    site = ROOT / "build"
    build(BuildConfig.at(ROOT), progress=None)
    report = {
        "machine": {"python": platform.python_version(), "cpu_count": os.cpu_count(), "platform": platform.platform()},
        "build": build_times(),
        "pages": page_sizes(site),
    }
    latency_file = OUT / "latency.json"
    subprocess.run([sys.executable, str(ROOT / "bench" / "latency.py"), "--site", str(site), "--out", str(latency_file)], check=True)
    report["latency"] = json.loads(latency_file.read_text())
    (OUT / "report.json").write_text(json.dumps(report, indent=2, sort_keys=True))
    print(f"build: median {report['build']['median_s']:.2f} s over {report['build']['runs']} cold builds, "
          f"{report['build']['stored_values']} stored values")
    for name, s in report["pages"].items():
        print(f"{name:<22} html {s['html_raw'] / 1024:7.1f} KB raw {s['html_gzip'] / 1024:6.1f} KB gzip | "
              f"with assets {s['total_raw'] / 1024:7.1f} KB raw {s['total_gzip'] / 1024:6.1f} KB gzip")
    print(f"wrote {OUT / 'report.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
