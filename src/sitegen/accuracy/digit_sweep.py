"""How the bubble scenes' settings were chosen: every stop of each scene solved at several rtols and its
displayed values compared with a tight reference's, with the time all its solves take.

A value is *wrong* when it shows another digit than the reference and the reference is not within the
run's measured error of a rounding boundary; where it is (and the digits differ), the stop is *near a
boundary*: no solver short of the reference's own accuracy can promise that digit, so such stops are
listed rather than hidden. The reference is the compiled solvers at tight settings (DOP853 at rtol
1e-12; Radau at 1e-10 where the terms are stiff), which the test suite checks against scipy's.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from ..build import BuildConfig, needed_outputs, resolve_book
from ..compute.grid import CHOICE
from ..models.bubble.compare import run_difference, shown_difference
from ..models.bubble.model import ALL, CLOSED_FORMS, PREFIX, Bubble
from ..models.bubble.point import compose, read_run
from ..models.bubble.run import REFERENCE_CAPS
from ..models.bubble.solve import AUTO, EXPLICIT_RTOL, method_for, reference_for, solve, warm_up
from ..physics.numerics import Numerics

RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
NEAR_LISTED = 40  # stops listed by name per scene and setting (the count is always complete)


def digit_sweep(root: Path, rtols=RTOLS, progress=None) -> dict:
    """For every bubble scene of the book: per rtol, its wrong and near-boundary values over all stops and the
    seconds its solves take (one thread, compiled, uncached), against the tight reference."""
    warm_up()  # compiled (or loaded) before any solve is timed
    items = [r for r in resolve_book(BuildConfig.at(root, cache=None)).scenes if r.scene.model.name == "bubble"]
    results = {}
    for item in items:
        name = f"{item.page.slug}#{item.scene.id}"
        results[name] = _scene_sweep(item.scene, rtols)
        if progress:
            runs = ", ".join(
                f"{r['rtol']:.0e}: {r['wrong']} wrong, {r['near']} near, {r['seconds']:.2f} s"
                for r in results[name]["runs"]
            )
            progress(f"  {name:<40} {runs}")
    return results


def _scene_sweep(scene, rtols) -> dict:
    history = next(h for h in PREFIX if h in scene.effects)
    solved_outputs = {o.name for o in Bubble.outputs if o.name not in CLOSED_FORMS and not o.name.endswith("_solver")}
    shown = [n for n in needed_outputs(scene) if n.startswith(PREFIX[history] + "_") and n in solved_outputs]
    points = [(stop, _point(scene, stop)) for stop in np.ndindex(*[a.count for a in scene.axes])]
    problems = [compose({n: point[n] for n in ALL}, scene.effects) for _, point in points]
    references = [_reference(pb) for pb, _ in problems]
    runs = []
    for rtol in rtols:
        settings = Numerics(AUTO, tolerance=1.0, rtol=rtol)
        start = time.perf_counter()
        solved = []
        for pb, scales in problems:
            method, tol, atol = method_for(pb, settings)
            run = solve.__wrapped__(pb, method, tol, atol=atol)
            solved.append((run, read_run(run, pb, scales, scene.effects)))
        seconds = time.perf_counter() - start
        runs.append({"rtol": rtol, "seconds": seconds, **_compare(scene, points, problems, solved, references, shown)})
    return {
        "stops": len(points),
        "shown": shown,
        "runs": runs,
        "chosen": EXPLICIT_RTOL,
        "reference": "compiled DOP853 at rtol 1e-12; Radau at rtol 1e-10 (atol 1e-11) where stiff",
    }


def _reference(pb):
    method, rtol, atol = reference_for(pb, AUTO)
    return solve.__wrapped__(pb, method, rtol, REFERENCE_CAPS, atol=atol)


def _point(scene, stop) -> dict:
    values = {**scene.model.defaults(), **scene.base_values()}
    return {**values, **{a.param: float(a.stop(k)) for a, k in zip(scene.axes, stop)}}


def _compare(scene, points, problems, solved, references, shown) -> dict:
    """Wrong and near-boundary values of one sweep, the largest error in units of the last shown digit."""
    prefix = shown[0].split("_")[0]
    wrong, near, worst = [], [], 0.0
    for (stop, _), (pb, scales), (run, mine), reference in zip(points, problems, solved, references):
        theirs = read_run(reference, pb, scales, scene.effects)
        error = run_difference(run, reference, pb, scales, scene.effects)
        bad, close = shown_difference(mine, theirs, prefix, error, Bubble.outputs)
        wrong += [f"{_stop_text(scene, stop)}: {n}" for n in bad if n in shown]
        near += [f"{_stop_text(scene, stop)}: {n}" for n in close if n in shown]
        worst = max([worst] + [_units(mine, theirs, n) for n in shown])
    return {
        "wrong": len(wrong),
        "near": len(near),
        "max_units": worst if math.isfinite(worst) else None,
        "wrong_stops": wrong[:NEAR_LISTED],
        "near_stops": near[:NEAR_LISTED],
    }


def _units(mine: dict, theirs: dict, name: str) -> float:
    """The largest difference of one shown output in units of its last displayed digit (0 for labels)."""
    output = Bubble.output(name)
    if output.labels:
        return 0.0 if np.array_equal(mine[name.split("_", 1)[1]], theirs[name.split("_", 1)[1]]) else math.inf
    a, b = (
        np.atleast_1d(np.asarray(mine[name.split("_", 1)[1]], float)),
        np.atleast_1d(np.asarray(theirs[name.split("_", 1)[1]], float)),
    )
    both = np.isfinite(a) & np.isfinite(b)
    if not np.array_equal(np.isfinite(a), np.isfinite(b)):
        return math.inf
    return float(np.max(np.abs(a[both] - b[both]), initial=0.0) * 10.0**output.decimals)


def _stop_text(scene, stop) -> str:
    return ", ".join(f"{a.param}={a.labels[k] if a.kind == CHOICE else a.stop(k)}" for a, k in zip(scene.axes, stop))
