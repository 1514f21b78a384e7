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

import numpy as np

from ...compute.grid import CHOICE
from ...physics.numerics import BenchExperiment, Numerics
from .compare import run_difference, shown_difference
from .point import ALL, PREFIX, compose, read_run
from .run import REFERENCE_CAPS
from .solve import AUTO, EXPLICIT_RTOL, method_for, reference_for, solve, warm_up

RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
NEAR_LISTED = 40  # stops listed by name per scene and setting (the count is always complete)


class DigitSweep(BenchExperiment):
    """Every stop of each bubble scene at several rtols, its shown digits against a tight reference's."""

    kind = "digit-sweep"

    def measure(self, scenes, quick: bool, timer) -> dict | None:
        """Per scene and rtol: its wrong and near-boundary values over all stops and the seconds its solves
        take (compiled, uncached, timed once), against the tight reference."""
        if not scenes:
            return None
        warm_up()  # compiled (or loaded) before any solve is timed
        rtols = RTOLS[2:3] if quick else RTOLS
        sweeps = {item.name: _scene_sweep(item, rtols, timer) for item in scenes}
        return {
            "scenes": sweeps,
            "title": "bubble scenes, every stop",
            "ringed": max(sweeps, key=lambda name: (sweeps[name]["stops"], name)),  # the ring: on the largest scene
            "label": "Time per solve against the largest error in units of the last shown digit, every stop of "
            "each bubble scene.",
        }


def _scene_sweep(item, rtols, timer) -> dict:
    scene = item.scene
    history = next(h for h in PREFIX if h in scene.effects)
    points = [(stop, _point(scene, stop)) for stop in np.ndindex(*[a.count for a in scene.axes])]
    problems = [compose({n: point[n] for n in ALL}, scene.effects) for _, point in points]
    references = [_reference(pb) for pb, _ in problems]
    read = read_run(references[0], *problems[0], scene.effects)  # what a solve gives: the outputs to compare
    shown = [
        n
        for n in item.shown
        if n.startswith(PREFIX[history] + "_") and n.split("_", 1)[1] in read and not n.endswith("_solver")
    ]

    def solve_all(rtol: float) -> list:
        settings = Numerics(AUTO, tolerance=1.0, rtol=rtol)
        solved = []
        for pb, scales in problems:
            method, tol, atol = method_for(pb, settings)
            run = solve.__wrapped__(pb, method, tol, atol=atol)
            solved.append((run, read_run(run, pb, scales, scene.effects)))
        return solved

    runs = []
    for rtol in rtols:  # one rtol at a time: the solved runs of every stop are many
        timed = timer({rtol: lambda rtol=rtol: solve_all(rtol)}, 1)[rtol]  # timed once: it is thousands of solves
        runs.append(
            {
                "rtol": rtol,
                "seconds": timed.seconds,
                **_compare(scene, points, problems, timed.result, references, shown),
            }
        )
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
        bad, close = shown_difference(mine, theirs, prefix, error, type(scene.model).outputs)
        wrong += [f"{_stop_text(scene, stop)}: {n}" for n in bad if n in shown]
        near += [f"{_stop_text(scene, stop)}: {n}" for n in close if n in shown]
        worst = max([worst] + [_units(type(scene.model), mine, theirs, n) for n in shown])
    return {
        "wrong": len(wrong),
        "near": len(near),
        "max_units": worst if math.isfinite(worst) else None,
        "wrong_stops": wrong[:NEAR_LISTED],
        "near_stops": near[:NEAR_LISTED],
    }


def _units(model, mine: dict, theirs: dict, name: str) -> float:
    """The largest difference of one shown output in units of its last displayed digit (0 for labels)."""
    output = model.output(name)
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
