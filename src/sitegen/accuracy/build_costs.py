"""What building the book costs: per scene its cold tabulation time, the slider states of its full
cross product, the values it stores and the bytes of its data script; per page its bytes.

"Cold" means no table cache and no model-level memo (the bubble keeps an LRU of solved points):
each timed run tabulates the scene from nothing, as a first build on a fresh checkout would.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from ..build import BuildConfig, build, resolve_book, tabulate_book
from ..compute.cache import compute_now
from ..site.weight import page_weights
from .experiments import clear_model_caches
from .timing import time_medians


def scene_cold_times(root: Path, repeats: int = 3, progress=None) -> dict[str, dict]:
    """Median seconds to tabulate each scene of the book from nothing, serially, with its count of
    slider states (the full cross product) and of the values its tables store."""
    config = BuildConfig.at(root, cache=None)
    book = resolve_book(config)
    jobs = {record.name: (lambda record=record: _tabulate_cold(book.only(record), config)) for record in book.scenes}
    timed = time_medians(jobs, repeats)
    times = {}
    for record in book.scenes:
        name = record.name
        times[name] = {
            "seconds": timed[name].seconds,
            "repeats": timed[name].repeats,
            "model": record.scene.model.name,
            "stops": record.stops,
            "stored_values": timed[name].result,
        }
        if progress:
            progress(f"  {name:<40} {timed[name].seconds:8.3f} s (median of {timed[name].repeats})")
    return times


def _tabulate_cold(book, config: BuildConfig) -> int:
    """Tabulate a book of one scene from nothing; the number of values its tables store."""
    clear_model_caches()
    return sum(record.stored_values for record in tabulate_book(book, config).scenes)


def site_sizes(root: Path) -> tuple[dict[str, dict], dict[str, dict]]:
    """The book built once: raw and gzip bytes of each page (alone and with every asset it loads, as the
    build's summary measured them), and of each scene's data by "page#scene"."""
    with tempfile.TemporaryDirectory() as folder:
        report = build(BuildConfig.at(root, Path(folder) / "build"), progress=None)
        pages = {weight.page: weight.sizes() for weight in report.weights}
        data = {name: {"raw": raw, "gzip": packed} for name, (raw, packed) in report.data_bytes.items()}
        return pages, data


def page_bytes(site: Path, page: Path) -> dict:
    """Raw and gzip bytes of a page of a built site, alone and with every asset it loads (the stylesheet's
    font included), measured as a build's summary measures them."""
    assets = sorted(f for f in (site / "assets").rglob("*") if f.is_file())
    files = {page.name: page.read_bytes()} | {f.relative_to(site).as_posix(): f.read_bytes() for f in assets}
    return page_weights(files, (), compute_now)[0].sizes()
