"""Lighthouse on every page of a built site, served compressed on 127.0.0.1, with the mobile and desktop presets.

    .venv/bin/python bench/lighthouse.py --site build [--out build-bench/lighthouse.json] [--runs 1]

A static host sends HTML, CSS and JavaScript gzip-compressed; the server here does the same (level 6, what
most hosts use), so the scores are those of a reader on a real host. Lighthouse (pinned in package.json)
drives Debian's Chromium; its mobile preset simulates a mid-range phone on a throttled mobile network.
Prints, for each page and preset, the four category scores, FCP, LCP, TBT, and where the main thread's time
went; with the page's bytes raw and gzip. Scores vary from run to run on a loaded machine: with --runs N,
each figure is the median of N runs.
"""

from __future__ import annotations

import argparse
import functools
import gzip
import http.server
import io
import json
import os
import statistics
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIGHTHOUSE = ROOT / "node_modules" / ".bin" / "lighthouse"
CHROMIUM = "/usr/bin/chromium"
CHROME_FLAGS = "--headless=new --no-sandbox --disable-gpu --disable-background-networking --disable-extensions"
CATEGORIES = ("performance", "accessibility", "best-practices", "seo")
METRICS = {"fcp": "first-contentful-paint", "lcp": "largest-contentful-paint", "tbt": "total-blocking-time"}
ATTEMPTS = 3
COMPRESSED = (".html", ".css", ".js", ".json", ".svg", ".txt")


class CompressingHandler(http.server.SimpleHTTPRequestHandler):
    """Static files, text ones gzip-compressed for a client that accepts it, as a static host sends them."""

    def log_message(self, format, *args):  # quiet: Lighthouse makes many requests
        pass

    def send_head(self):
        path = self.translate_path(self.path)
        if not path.endswith(COMPRESSED) or "gzip" not in self.headers.get("Accept-Encoding", ""):
            return super().send_head()
        try:
            data = gzip.compress(Path(path).read_bytes(), 6, mtime=0)
        except OSError:
            return super().send_head()
        self.send_response(200)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Content-Encoding", "gzip")
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "max-age=3600")
        self.end_headers()
        return io.BytesIO(data)


def serve(site: Path) -> http.server.ThreadingHTTPServer:
    """A compressing server of `site` on 127.0.0.1 at a free port, running in a thread."""
    handler = functools.partial(CompressingHandler, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def lighthouse(url: str, preset: str, out: Path) -> dict:
    """One Lighthouse run of `url` with the `preset` ("mobile" or "desktop"): its JSON report."""
    command = [
        str(LIGHTHOUSE),
        url,
        "--output=json",
        f"--output-path={out}",
        "--quiet",
        f"--only-categories={','.join(CATEGORIES)}",
        f"--chrome-flags={CHROME_FLAGS}",
    ]
    if preset == "desktop":
        command.append("--preset=desktop")
    for attempt in range(ATTEMPTS):  # on a loaded machine a run may time out: tried again
        run = subprocess.run(command, env={**os.environ, "CHROME_PATH": CHROMIUM}, capture_output=True, text=True)
        if run.returncode == 0:
            return json.loads(out.read_text())
        print(f"lighthouse {preset} {url} failed (attempt {attempt + 1}): {run.stderr.strip()[-500:]}", file=sys.stderr)
    raise SystemExit(f"lighthouse failed {ATTEMPTS} times on {url} ({preset})")


def summary(report: dict) -> dict:
    """Scores (0-100), FCP/LCP/TBT (ms) and the main thread's time by kind of work (ms) of one report."""
    audits = report["audits"]
    out = {name: round(100 * report["categories"][name]["score"]) for name in CATEGORIES}
    out.update({key: audits[audit]["numericValue"] for key, audit in METRICS.items()})
    breakdown = audits["mainthread-work-breakdown"].get("details", {}).get("items", [])
    out["main_thread_ms"] = {item["groupLabel"]: item["duration"] for item in breakdown}
    out["failing"] = sorted(  # the audits that cost points outside performance (whose metrics are shown)
        ref["id"]
        for name in CATEGORIES[1:]
        for ref in report["categories"][name]["auditRefs"]
        if ref["weight"] and audits[ref["id"]]["score"] is not None and audits[ref["id"]]["score"] < 1
    )
    return out


def median_summary(runs: list[dict]) -> dict:
    """Each figure's median over runs (the failing audits of the first run)."""
    keys = [*CATEGORIES, *METRICS]
    out = {key: statistics.median(r[key] for r in runs) for key in keys}
    groups = sorted({g for r in runs for g in r["main_thread_ms"]})
    out["main_thread_ms"] = {g: statistics.median(r["main_thread_ms"].get(g, 0) for r in runs) for g in groups}
    out["failing"] = runs[0]["failing"]
    out["runs"] = len(runs)
    return out


def measure(site: Path, runs: int = 1) -> dict:
    """Lighthouse, mobile and desktop, on every page of `site`, with each page's bytes."""
    sys.path.insert(0, str(ROOT / "src"))
    from sitegen.accuracy.build_costs import page_bytes

    server = serve(site)
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    result = {"lighthouse": subprocess.run([str(LIGHTHOUSE), "--version"], capture_output=True, text=True).stdout}
    result["load_average"] = os.getloadavg()[0]  # scores fall on a busy machine: the load they were taken at
    result["pages"] = {}
    try:
        with tempfile.TemporaryDirectory() as tmp:
            for page in sorted(site.glob("*.html")):
                entry = {"bytes": page_bytes(site, page)}
                for preset in ("mobile", "desktop"):
                    reports = [
                        summary(lighthouse(base + page.name, preset, Path(tmp) / "report.json")) for _ in range(runs)
                    ]
                    entry[preset] = median_summary(reports)
                result["pages"][page.name] = entry
    finally:
        server.shutdown()
    result["lighthouse"] = result["lighthouse"].strip()
    return result


def table(result: dict) -> str:
    """The report as lines of text: one per page and preset, then the main thread's time and failing audits."""
    lines = [
        f"Lighthouse {result['lighthouse']}, served gzip-compressed on 127.0.0.1 "
        f"(load average {result['load_average']:.1f} on {os.cpu_count()} cores at the start)",
        f"{'page':<28} {'preset':<8} {'perf':>4} {'FCP s':>6} {'LCP s':>6} {'TBT ms':>7} "
        f"{'a11y':>4} {'BP':>4} {'SEO':>4} {'html KB':>8} {'gzip KB':>8} {'all KB':>8} {'gzip KB':>8}",
    ]
    for name, entry in result["pages"].items():
        b = entry["bytes"]
        for preset in ("mobile", "desktop"):
            s = entry[preset]
            lines.append(
                f"{name:<28} {preset:<8} {s['performance']:>4.0f} {s['fcp'] / 1000:>6.2f} {s['lcp'] / 1000:>6.2f} "
                f"{s['tbt']:>7.0f} {s['accessibility']:>4.0f} {s['best-practices']:>4.0f} {s['seo']:>4.0f} "
                f"{b['html_raw'] / 1024:>8.1f} {b['html_gzip'] / 1024:>8.1f} "
                f"{b['total_raw'] / 1024:>8.1f} {b['total_gzip'] / 1024:>8.1f}"
            )
    for name, entry in result["pages"].items():
        s = entry["mobile"]
        work = ", ".join(f"{g} {ms:.0f}" for g, ms in sorted(s["main_thread_ms"].items(), key=lambda kv: -kv[1]))
        lines.append(f"{name} mobile main thread (ms): {work}")
        failing = sorted({*entry["mobile"]["failing"], *entry["desktop"]["failing"]})
        if failing:
            lines.append(f"{name} audits below full marks: {', '.join(failing)}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--site", type=Path, default=ROOT / "build", help="the built site (default: build)")
    parser.add_argument("--out", type=Path, default=ROOT / "build-bench" / "lighthouse.json", help="JSON report")
    parser.add_argument("--runs", type=int, default=1, help="runs per page and preset; figures are medians")
    args = parser.parse_args(argv)
    if not LIGHTHOUSE.exists():
        raise SystemExit(f"{LIGHTHOUSE} is missing: run `npm ci` (make bench does)")
    result = measure(args.site, args.runs)
    print(table(result))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(result, indent=2, sort_keys=True) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
