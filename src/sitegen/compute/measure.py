"""The check phase's accuracy measurement: every numerically computed scene against its model's reference.

At a small deterministic sample of slider stops (the defaults, corners of the grid and seeded
random stops) the scene's model measures the error of its own numbers, with the scene's numerical
settings, against a closed form or a tight solution by a second method. The largest error becomes
the scene's `SceneAccuracy` record; a scene whose error exceeds its declared tolerance is an author
error naming the worst stop. Results are cached under the scene's key, so a rebuild with nothing
changed solves nothing; records hold no times (those go to the progress lines only).
"""

from __future__ import annotations

import hashlib
import json
import math
import re
import time
from dataclasses import dataclass
from html import escape

import numpy as np

from ..errors import AuthorError
from ..physics.numerics import written
from .accuracy import SceneAccuracy
from .cache import compute_now, scene_key
from .grid import CHOICE
from .scenes import ResolvedScene
from .sources import digest, source_digest

MEASURE_MODULES = frozenset({"sitegen.compute.measure", "sitegen.compute.accuracy"})


@dataclass(frozen=True)
class Measured:
    """A scene's record and the slider values of its worst stop (for the error message)."""

    record: SceneAccuracy
    worst: str


def measure_accuracy(
    items, cached=compute_now, progress=None, shown=None
) -> tuple[list[SceneAccuracy], list[AuthorError]]:
    """Records of every numerically computed scene, in the order given, and an error per scene over its
    tolerance or showing a digit the reference does not.

    `items` are the build's page scenes (each with `.page.slug` and `.scene`); `shown(scene)` names the
    outputs a scene displays (its readouts when not given).
    """
    records, errors = [], []
    for item in items:
        scene = item.scene
        if scene.model.settings is None or not scene.model.is_numerical(scene.effects):
            continue
        start = time.perf_counter()
        key = digest(scene_key(scene, []).digest, item.page.slug, source_digest(MEASURE_MODULES), "accuracy")
        names = sorted(shown(scene) if shown else (o.name for o in scene.readouts))
        key = digest(key, *names)
        measured = json.loads(cached("accuracy", key, lambda scene=scene, names=names: _measure(scene, names).encode()))
        measured_scene = _measured(item.page.slug, scene, measured)
        records.append(measured_scene.record)
        if measured_scene.record.error > measured_scene.record.tolerance:
            errors.append(tolerance_error(scene, measured_scene))
        if measured_scene.record.digits_wrong:
            errors.append(digits_error(scene, measured_scene.record))
        if progress:
            progress(_progress_line(item.page.slug, measured_scene.record, time.perf_counter() - start))
    return records, errors


def _progress_line(page: str, record: SceneAccuracy, seconds: float) -> str:
    """One line of the build's log for a measured scene (the only place its time appears)."""
    error = written(record.error, ".1e") if record.error else "0"
    digits = (
        f"; digits: {len(record.digits_wrong)} wrong, {len(record.near_boundary)} near a rounding boundary"
        if record.digits_compared
        else ""
    )
    return (
        f"check     {page + '#' + record.scene:<44} {record.stops_measured:>3} stops {seconds:7.2f} s  "
        f"error {error} (tolerance {written(record.tolerance)}){digits}"
    )


def _measure(scene: ResolvedScene, shown: list[str]) -> str:
    """What the settings achieve at the sampled stops, as JSON: the error, and the displayed outputs
    (of `shown`) that differ from the reference's, wrong or near a rounding boundary."""
    rows, wrong, near = [], [], []
    for stop in measured_stops(scene):
        values = {**scene.base_values(), **{a.param: float(a.stop(k)) for a, k in zip(scene.axes, stop)}}
        measurement = scene.model.measure_error(values, scene.effects)
        error = float(measurement.error)
        rows.append((math.inf if math.isnan(error) else error, measurement, stop_text(scene, stop)))
        wrong += [f"{stop_text(scene, stop)}: {name}" for name in measurement.wrong if name in shown]
        near += [f"{stop_text(scene, stop)}: {name}" for name in measurement.near if name in shown]
    worst = max(rows, key=lambda row: row[0])
    methods = list(dict.fromkeys(m.method for _, m, _ in rows))
    references = list(dict.fromkeys(m.reference for _, m, _ in rows))
    return json.dumps(
        {
            "error": repr(worst[0]),
            "worst": worst[2],
            "stops": len(rows),
            "evaluations": sum(m.evaluations for _, m, _ in rows),
            "methods": methods,
            "references": references,
            "wrong": wrong,
            "near": near,
        },
        sort_keys=True,
    )


def _measured(page: str, scene: ResolvedScene, measured: dict) -> Measured:
    """The record of a scene from its measurements and its current settings."""
    settings = scene.model.settings
    knobs = settings.knobs().removeprefix(f"method {settings.method}").lstrip(", ")
    methods = measured["methods"]
    method = f"{settings.method}: {', '.join(methods)}" if settings.method == "auto" else methods[0]
    record = SceneAccuracy(
        page=page,
        scene=scene.id,
        model=scene.model.name,
        method=method,
        settings=knobs or "—",
        tolerance=settings.tolerance,
        error=float(measured["error"]),
        metric=scene.model.error_metric,
        reference="; ".join(measured["references"]),
        stops_measured=measured["stops"],
        evaluations=measured["evaluations"],
        digits_compared=scene.model.compares_digits,
        digits_wrong=tuple(measured["wrong"]),
        near_boundary=tuple(measured["near"]),
    )
    return Measured(record, measured["worst"])


def tolerance_error(scene: ResolvedScene, measured_scene: Measured) -> AuthorError:
    """The author error of a scene whose measured error exceeds its declared tolerance, with what to do."""
    record, settings = measured_scene.record, scene.model.settings
    taken = scene.model.methods.get(settings.method, {})
    if "rtol" in taken:
        remedy = f"tighten rtol (now {written(settings.rtol)})" if settings.rtol is not None else "set a smaller rtol"
    elif "nodes" in taken:
        remedy = f"raise nodes (now {settings.nodes})"
    else:
        remedy = "choose another method"
    where = scene.spec.loc_of("numerics")
    message = (
        f"measured error {written(record.error, '.1e')} ({record.metric}, "
        f"against {record.reference}) at {measured_scene.worst} "
        f"exceeds the declared tolerance {written(settings.tolerance)} of '{settings.text()}'; "
        f"{remedy} or loosen the tolerance on the scene's 'numerics:' line"
    )
    return AuthorError(where, message, scene.id)


def digits_error(scene: ResolvedScene, record: SceneAccuracy) -> AuthorError:
    """The author error of a scene that shows a digit its reference does not, away from any rounding boundary."""
    shown = "; ".join(record.digits_wrong[:3]) + (
        f" and {len(record.digits_wrong) - 3} more" if len(record.digits_wrong) > 3 else ""
    )
    message = (
        f"displayed values differ from {record.reference} at {shown}; tighten rtol on the scene's 'numerics:' "
        f"line (a value within the tolerance {written(record.tolerance)} of a rounding boundary is only listed)"
    )
    return AuthorError(scene.spec.loc_of("numerics"), message, scene.id)


def measured_stops(scene: ResolvedScene) -> list[tuple[int, ...]]:
    """The stops a scene is measured at: its defaults, the lowest and highest corners, then other
    corners and random stops from a generator seeded by the scene's own key (deterministic)."""
    counts = [axis.count for axis in scene.axes]
    budget = min(scene.model.accuracy_stops, math.prod(counts))
    rng = np.random.default_rng(int(hashlib.sha256(scene_key(scene, []).spec.encode()).hexdigest()[:16], 16))
    highest = tuple(count - 1 for count in counts)
    corners = [
        tuple(int(c) for c in np.multiply(highest, rng.integers(2, size=len(counts)))) for _ in range((budget - 3) // 2)
    ]
    chosen = list(dict.fromkeys([scene.default_stops, (0,) * len(counts), highest, *corners]))[:budget]
    while len(chosen) < budget:
        stop = tuple(int(rng.integers(count)) for count in counts)
        if stop not in chosen:
            chosen.append(stop)
    return chosen


def stop_text(scene: ResolvedScene, stop: tuple[int, ...]) -> str:
    """A stop as an author reads it, e.g. `R0=4.5, p_a=1.3, f=26.5` (choices by name)."""
    parts = [f"{a.param}={a.labels[k] if a.kind == CHOICE else a.stop(k)}" for a, k in zip(scene.axes, stop)]
    return ", ".join(parts) or "the scene's fixed values"


def caption_sentence(record: SceneAccuracy, link: bool, methods: bool = False) -> str:
    """The caption's closing sentence (HTML): the measured error, against what, a link to the row and (`methods`:
    the accuracy page shows the model's part) one to what each of the model's methods costs at the scene's stops."""
    see = f', see <a href="accuracy.html#{record.anchor}">accuracy and cost</a>' if link else ""
    if link and methods:
        see += f' and <a href="accuracy.html#{record.methods_anchor}">what each method costs</a>'
    return (
        f"Measured error {_number_html(record.error)} ({escape(record.metric)}) against "
        f"{_exponents_html(escape(record.reference))}{see}."
    )


def _number_html(value: float) -> str:
    """3.1 × 10<sup>−8</sup>, or 0, for the caption."""
    if value == 0.0:
        return "0"
    if not math.isfinite(value):
        return "∞"
    mantissa, exponent = f"{value:.1e}".split("e")
    power = f"10<sup>{int(exponent)}</sup>".replace("-", "−")
    return power if mantissa == "1.0" else f"{mantissa}\u00a0×\u00a0{power}"  # no line break inside a number


def _exponents_html(text: str) -> str:
    """Numbers like 1e-12 written as 10<sup>−12</sup>, kept on the line of the word before them."""

    def power(match: re.Match) -> str:
        mantissa, exponent = match[1], int(match[2])
        shown = f"10<sup>{exponent}</sup>".replace("-", "−")
        return shown if mantissa in ("1", "1.0") else f"{mantissa}\u00a0×\u00a0{shown}"

    return re.sub(r" (\d+(?:\.\d+)?)e([-+]?\d+)\b", lambda m: "\u00a0" + power(m), text)
