"""The work–precision experiment of every model that declares numerical methods, read from its declarations.

For each numerically computed scene of the book, each method its model offers (`Model.methods`) runs over a
ladder of its setting — rtol 10⁻³ … 10⁻¹², a resolution (`nodes`) or a step, unless the model declares its
own (`Model.ladders`) — and at the scene's own settings, at the stops the build checks: the error by the
model's `measure_error` against its reference (the largest over the stops), the work in evaluations (summed
over them), and the median wall time of computing the scene's shown outputs at all those stops
(`Model.evaluate`, the model's memos emptied before each call). Errors and evaluations are deterministic;
only the times depend on the machine, which is why this runs in `sitegen bench` and never in a build.

Every run is one dict: its method, the setting it varies ("rtol", "nodes", "step" or None) and the value,
its error, evaluations, median seconds and repeats, and "status" ("ok", or why it has no result). A model's
own experiments (`Model.experiments`) give runs of the same shape.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, replace

import numpy as np

from ..physics.numerics import SETTINGS, BenchScene, Numerics
from .timing import time_medians

RTOLS = tuple(10.0**-k for k in range(3, 13))  # 1e-3 … 1e-12
NODES = tuple(2**k for k in range(2, 11))  # 4 … 1024
STEP_FACTORS = (4.0, 2.0, 1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125)  # times the method's declared step
LADDERED = ("rtol", "nodes", "step")  # the setting a method's ladder varies: the first it takes


@dataclass(frozen=True)
class Plan:
    """How much the bench measures: FULL for `make bench`, QUICK (`--quick`) a smoke test of every part."""

    quick: bool = False
    max_repeats: int = 5  # timed runs of a model's own experiments (fewer for slow calls, timing.py)
    method_repeats: int = 3  # timed runs of each method and setting at a scene's stops
    scene_repeats: int = 3  # cold tabulations per scene (a scene slower than 2 s is timed once)
    ladder_length: int | None = None  # at most this many settings of each ladder (None: all of them)


FULL = Plan()
QUICK = Plan(quick=True, max_repeats=1, method_repeats=1, scene_repeats=1, ladder_length=2)


def finite(value) -> float | None:
    """A float for JSON, or None where the value does not exist (NaN, ±inf)."""
    value = float(value)
    return value if math.isfinite(value) else None


def laddered_setting(taken) -> str | None:
    """The setting a method's ladder varies: rtol, else nodes, else step (None: a method without settings)."""
    return next((key for key in LADDERED if key in taken), None)


def ladder(model, method: str, own: Numerics | None = None) -> tuple:
    """The values of its setting that `method` is measured at: the model's own ladder, or the default one."""
    key = laddered_setting(model.methods[method])
    if key is None:
        return ()
    declared = model.ladders.get(method, {})
    if isinstance(declared, dict) and key in declared:
        return tuple(declared[key])
    if key in model.ladders and not isinstance(model.ladders[key], dict):
        return tuple(model.ladders[key])
    if key == "rtol":
        return RTOLS
    if key == "nodes":
        return NODES
    base = model.methods[method].get("step") or (own.step if own and own.method == method else None)
    return tuple(base * factor for factor in STEP_FACTORS) if base else ()


def settings_at(own: Numerics, model, method: str, value) -> Numerics:
    """The scene's settings switched to `method` (with the settings it declares) and its setting at `value`."""
    start = own if method == own.method else replace(own, **{**dict.fromkeys(SETTINGS), **model.methods[method]})
    key = laddered_setting(model.methods[method])
    return replace(start, method=method, **({key: value} if key else {}))


def trials(item: BenchScene, plan: Plan) -> dict[tuple[str, object], Numerics]:
    """Every (method, value) the scene is measured at, with its settings; the scene's own settings first."""
    model, own = type(item.scene.model), item.scene.model.settings
    own_key = laddered_setting(model.methods.get(own.method, {}))
    found = {(own.method, getattr(own, own_key) if own_key else None): own}
    for method, taken in model.methods.items():
        if laddered_setting(taken) is None:  # a method without settings: measured once, as it is
            found.setdefault((method, None), settings_at(own, model, method, None))
            continue
        values = ladder(model, method, own)
        if plan.ladder_length is not None:
            values = values[: plan.ladder_length]
        for value in values:
            found.setdefault((method, value), settings_at(own, model, method, value))
    return found


def bench_scene(name: str, scene, shown, stops) -> BenchScene:
    """A scene with its stops as parameter values (the scene's fixed values filled in)."""
    base = scene.base_values()
    points = tuple({**base, **{a.param: float(a.stop(k)) for a, k in zip(scene.axes, stop)}} for stop in stops)
    return BenchScene(name, scene, tuple(shown), points)


def method_experiment(items: list[BenchScene], plan: Plan = FULL, progress=None) -> dict:
    """One model's methods at the accuracy stops of each of its scenes: a panel of runs per scene."""
    model = type(items[0].scene.model)
    panels = [_scene_panel(item, plan, progress) for item in items]
    references = sorted({ref for panel in panels for ref in panel.pop("references")})
    skipped = [m for m in model.methods if laddered_setting(model.methods[m]) and not ladder(model, m)]
    return {
        "model": model.name,
        "title": model.title,
        "metric": model.error_metric,
        "reference": "; ".join(references),
        "panels": panels,
        "only_own": skipped,  # methods measured only at the scenes' own settings (their ladder is empty)
    }


def _scene_panel(item: BenchScene, plan: Plan, progress) -> dict:
    """Every trial of one scene: errors first (they fill the model's memos of references), then times."""
    model, own = type(item.scene.model), item.scene.model.settings
    settings = trials(item, plan)
    measured = {key: _measured(model, numerics, item) for key, numerics in settings.items()}
    inputs = {p: np.array([stop[p] for stop in item.stops]) for p in item.stops[0]} if item.stops else {}
    jobs = {
        key: (lambda n=numerics: _evaluate_cold(model, n, item, inputs))
        for key, numerics in settings.items()
        if measured[key]["status"] == "ok"
    }
    timed = time_medians(jobs, plan.method_repeats)
    runs = []
    for (method, value), row in measured.items():
        key = laddered_setting(model.methods.get(method, {}))
        run = {"method": method, "setting": key if value is not None else None, "value": value, **row}
        if (method, value) in timed:
            run.update(time_s=timed[method, value].seconds, repeats=timed[method, value].repeats)
        runs.append(run)
    if progress:
        progress(f"  {item.name:<44} {len(runs)} runs at {len(item.stops)} stops")
    own_key = laddered_setting(model.methods.get(own.method, {}))
    return {
        "scene": item.name,
        "stops": len(item.stops),
        "own": {"method": own.method, "value": getattr(own, own_key) if own_key else None, "text": own.knobs()},
        "tolerance": own.tolerance,
        "runs": runs,
        "references": sorted({ref for row in measured.values() for ref in row.pop("references", ())}),
    }


def _measured(model, numerics: Numerics, item: BenchScene) -> dict:
    """The largest error over the scene's stops, the evaluations spent and the methods that ran, or why not."""
    instance = model(numerics)
    try:
        measurements = [instance.measure_error(stop, item.scene.effects) for stop in item.stops]
    except Exception as error:  # a setting the method cannot run: a result of the experiment, not a crash
        return {"status": f"failed: {type(error).__name__}: {error}".split("\n")[0][:200]}
    errors = [float(m.error) for m in measurements]
    worst = max((math.inf if math.isnan(e) else e for e in errors), default=0.0)
    return {
        "status": "ok" if math.isfinite(worst) else "no finite error (the run and its reference ended differently)",
        "error": finite(worst),
        "evaluations": int(sum(m.evaluations for m in measurements)),
        "solved_by": list(dict.fromkeys(m.method for m in measurements)),
        "references": tuple(dict.fromkeys(m.reference for m in measurements)),
    }


def _evaluate_cold(model, numerics: Numerics, item: BenchScene, inputs: dict):
    """The scene's shown outputs at every stop with `numerics`, the model's memos emptied first."""
    clear_model_caches(model)
    return model(numerics).evaluate(inputs, wanted=item.shown, effects=item.scene.effects)


def clear_model_caches(model=None) -> None:
    """Forget every memo of the physics framework and the built-in models (e.g. the bubble's solved points),
    and of `model`'s own package, so that a run starts cold."""
    prefixes = ("sitegen.physics", "sitegen.models")
    if model is not None:
        prefixes += (model.__module__.rpartition(".")[0] or model.__module__,)  # the model's own package
    for name, module in list(sys.modules.items()):
        if name.startswith(prefixes) and module is not None:
            for value in list(vars(module).values()):
                if callable(getattr(value, "cache_clear", None)):
                    value.cache_clear()
