"""Slider-input -> DOM-updated latency of the built pages, in headless Chromium.

    .venv/bin/python bench/latency.py --site build [--out build-bench/latency.json]

Every page of the site that has scenes is opened from file://. For each scene, an in-page loop
puts random sliders at random stops and times `dispatchEvent(new Event("input"))` with
performance.now(); the page script's handler updates the readouts, slider texts and figure
layers synchronously, so when dispatchEvent returns the DOM is up to date (style and layout are
not included: they happen at the next frame, outside the script). A second loop times the same
number of inputs as one batch, which gives a mean below the timer's resolution: Chromium coarsens
performance.now() to 100 µs on pages that are not cross-origin isolated (file:// never is), so
per-input percentiles are multiples of about 0.1 ms.

Prints p50 / p95 / max per scene in milliseconds and writes them as JSON to --out.
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

from sitegen.review.figures import CHROMIUM, LAUNCH_ARGS

# In the page: time `samples` inputs of random sliders at random stops (after `warmup` untimed
# ones), then the same number again as one batch. Stops are written exactly from the attributes
# (integers of 10^-d), so every value set is one the slider really has.
_MEASURE_JS = r"""
({sceneId, samples, warmup, seed}) => {
  const root = document.getElementById("scene-" + sceneId);
  const decimals = (text) => (text.split(".")[1] || "").length;
  const sliders = [...root.querySelectorAll('input[type="range"][data-param]')].map((el) => {
    const d = Math.max(decimals(el.getAttribute("min")), decimals(el.getAttribute("step")));
    const scale = 10 ** d;
    const lo = Math.round(parseFloat(el.getAttribute("min")) * scale);
    const step = Math.round(parseFloat(el.getAttribute("step")) * scale);
    const hi = Math.round(parseFloat(el.getAttribute("max")) * scale);
    return {el, d, lo, step, count: Math.round((hi - lo) / step) + 1};
  });
  let state = seed >>> 0;
  const random = () => {  // mulberry32
    state = (state + 0x6d2b79f5) >>> 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
  const pick = () => {
    const s = sliders[Math.floor(random() * sliders.length)];
    const k = Math.floor(random() * s.count);
    return [s.el, ((s.lo + k * s.step) / 10 ** s.d).toFixed(s.d)];
  };
  const readouts = [...root.querySelectorAll("[data-out]")];
  const changed = new Set();
  for (let i = 0; i < warmup; i++) {
    const [el, value] = pick();
    el.value = value;
    el.dispatchEvent(new Event("input", {bubbles: true}));
  }
  const times = [];
  for (let i = 0; i < samples; i++) {
    const [el, value] = pick();
    el.value = value;
    const event = new Event("input", {bubbles: true});
    const t0 = performance.now();
    el.dispatchEvent(event);
    const t1 = performance.now();
    times.push(t1 - t0);
    changed.add(readouts.map((r) => r.textContent).join("|"));
  }
  const batch = [];
  for (let i = 0; i < samples; i++) batch.push(pick());
  const b0 = performance.now();
  for (const [el, value] of batch) {
    el.value = value;
    el.dispatchEvent(new Event("input", {bubbles: true}));
  }
  const b1 = performance.now();
  // The smallest step performance.now() takes on this page.
  let resolution = Infinity;
  for (let i = 0; i < 50; i++) {
    const a = performance.now();
    let b = performance.now();
    while (b === a) b = performance.now();
    resolution = Math.min(resolution, b - a);
  }
  return {
    sliders: sliders.length, times, batch_ms: b1 - b0, resolution_ms: resolution,
    distinct_readout_states: changed.size,
  };
}
"""


def percentile(values: list[float], q: float) -> float:
    """The q-th percentile (0..100) by linear interpolation between order statistics."""
    ordered = sorted(values)
    position = (len(ordered) - 1) * q / 100
    low = int(position)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (position - low)


def measure(site: Path, samples: int, warmup: int, seed: int) -> dict:
    pages = sorted(site.glob("*.html"))
    if not pages:
        raise SystemExit(f"no pages in {site}; build the site first (sitegen build)")
    report = {"site": str(site), "samples_per_scene": samples, "warmup": warmup, "seed": seed, "scenes": {}}
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
        report["browser"] = f"Chromium {browser.version}"
        report["machine"] = {"python": platform.python_version(), "platform": platform.platform()}
        try:
            for path in pages:
                page = browser.new_page()
                errors: list[str] = []
                page.on("pageerror", lambda e: errors.append(str(e)))
                page.goto(path.resolve().as_uri(), wait_until="load")
                scene_ids = page.eval_on_selector_all(
                    "figure.scene[id^='scene-']", "els => els.map(e => e.id.slice(6))"
                )
                for index, scene_id in enumerate(scene_ids):
                    result = page.evaluate(
                        _MEASURE_JS, {"sceneId": scene_id, "samples": samples, "warmup": warmup, "seed": seed + index}
                    )
                    times = result["times"]
                    if result["distinct_readout_states"] < 2:
                        raise SystemExit(
                            f"{path.name}#{scene_id}: the readouts never changed; is the page script running?"
                        )
                    report["scenes"][f"{path.name}#{scene_id}"] = {
                        "sliders": result["sliders"],
                        "samples": len(times),
                        "p50_ms": percentile(times, 50),
                        "p95_ms": percentile(times, 95),
                        "max_ms": max(times),
                        "mean_ms": statistics.fmean(times),
                        "batch_mean_ms": result["batch_ms"] / samples,
                        "timer_resolution_ms": result["resolution_ms"],
                        "distinct_readout_states": result["distinct_readout_states"],
                    }
                if errors:
                    raise SystemExit(f"{path.name}: page errors while measuring: {errors}")
                page.close()
        finally:
            browser.close()
    if not report["scenes"]:
        raise SystemExit(f"no scenes on any page of {site}")
    return report


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--site", type=Path, default=Path("build"), help="the built site (default: build)")
    parser.add_argument("--out", type=Path, default=Path("build-bench/latency.json"), help="JSON report path")
    parser.add_argument("--samples", type=int, default=500, help="timed inputs per scene (default: 500)")
    parser.add_argument("--warmup", type=int, default=100, help="untimed inputs first (default: 100)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the random stops (default: 1)")
    args = parser.parse_args(argv)

    report = measure(args.site, args.samples, args.warmup, args.seed)
    print(f"{report['browser']}, {args.samples} random slider inputs per scene, input event -> DOM updated")
    print(f"{'scene':<32} {'p50 ms':>8} {'p95 ms':>8} {'max ms':>8} {'batch mean ms':>14}")
    resolution = max(s["timer_resolution_ms"] for s in report["scenes"].values())

    def ms(value: float) -> str:  # a time that read 0 only means "below the timer's resolution"
        return f"{value:8.3f}" if value > 0 else f"{'<' + format(resolution, '.3f'):>8}"

    for name, s in report["scenes"].items():
        print(f"{name:<32} {ms(s['p50_ms'])} {ms(s['p95_ms'])} {ms(s['max_ms'])} {s['batch_mean_ms']:14.4f}")
    print(
        f"(performance.now() resolution here: {resolution:.3f} ms; per-input times are multiples of it,"
        " the batch mean is not)"
    )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=2, sort_keys=True) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
