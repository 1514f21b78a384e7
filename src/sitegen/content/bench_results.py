"""Where the bench's results live and how they are written and read (strict, sorted JSON)."""

from __future__ import annotations

import json
from pathlib import Path

SCHEMA = 2  # 2: results by model (each its methods and its own experiments)
BENCH_NAME = Path("accuracy") / "bench.json"  # under content/: the accuracy page is rendered from it
BENCH_FILE = Path("content") / BENCH_NAME  # the same, from the project root


def write_results(results: dict, path: Path) -> None:
    """bench.json: sorted keys, one space of indent, no NaN or Infinity (strict JSON), via a temporary file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_suffix(".json.partial")
    partial.write_text(json.dumps(results, indent=1, sort_keys=True, allow_nan=False, ensure_ascii=False) + "\n")
    partial.replace(path)


def load_results(path: Path) -> dict | None:
    """The last bench run's results, or None when there is no bench.json."""
    try:
        return json.loads(path.read_text())
    except FileNotFoundError:
        return None
