"""Wall-clock medians of repeated runs and the machine they ran on: for `sitegen bench` only.

A build never reads a clock into a page: times reach the accuracy page only through the
committed bench.json, so the same sources still give byte-identical builds.
"""

from __future__ import annotations

import datetime
import os
import platform
import statistics
import time
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

SLOW = 2.0  # s: a run this long is timed once (its first run is the measurement)
MEDIUM = 0.5  # s: a run this long is repeated 3 times, a faster one 5 times (a shared machine is noisy)
SAMPLE = 0.02  # s: calls faster than this are timed in loops of several calls per sample


@dataclass(frozen=True)
class Timed:
    """A function's result and the median wall time of one call over `repeats` timed samples."""

    result: object
    seconds: float
    repeats: int


def time_median(function, max_repeats: int = 5) -> Timed:
    """Call `function` once, then again as often as its cost allows; the median seconds per call."""
    return time_medians({0: function}, max_repeats)[0]


def time_medians(functions: dict, max_repeats: int = 5) -> dict:
    """Time several functions in interleaved rounds; for each, its result and median seconds per call.

    Each function is called once first, to warm caches and imports (not counted), except a slow one
    (≥ SLOW s), which is timed once and kept: repeating a 20 s solve would blow the bench's budget.
    The timed repeats then go round all functions in turn, so that a burst of load from another
    process on the machine lands on every function's samples rather than on one function's median.
    """
    first, results = {}, {}
    for key, function in functions.items():
        start = time.perf_counter()
        results[key] = function()
        first[key] = time.perf_counter() - start
    repeats = {key: _repeats(seconds, max_repeats) for key, seconds in first.items()}
    loops = {key: max(1, int(SAMPLE / max(seconds, 1e-7))) for key, seconds in first.items()}
    samples: dict = {key: [] for key in functions}
    for round_ in range(max(repeats.values(), default=0)):
        for key, function in functions.items():
            if repeats[key] > round_:
                start = time.perf_counter()
                for _ in range(loops[key]):
                    function()
                samples[key].append((time.perf_counter() - start) / loops[key])
    return {
        key: Timed(results[key], statistics.median(samples[key]), len(samples[key]))
        if samples[key]
        else Timed(results[key], first[key], 1)
        for key in functions
    }


def _repeats(first: float, max_repeats: int) -> int:
    """How many timed runs a call of `first` seconds gets (0: its first run is the measurement)."""
    if first >= SLOW or max_repeats <= 1:
        return 0
    return min(max_repeats, 3 if first >= MEDIUM else 5)


def machine_info() -> dict:
    """CPU model, cores, the Python and library versions, and the date (UTC) of this run."""
    now = datetime.datetime.now(datetime.UTC)
    return {
        "cpu": _cpu_model(),
        "cores": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": metadata.version("numpy"),
        "scipy": metadata.version("scipy"),
        "matplotlib": metadata.version("matplotlib"),
        "platform": platform.platform(),
        "date": now.strftime("%Y-%m-%d"),
        "time_utc": now.strftime("%H:%M"),
        "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS", "unset"),
    }


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()
