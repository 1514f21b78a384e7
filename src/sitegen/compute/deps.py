"""Verifying what an output declares it depends on (its `deps`) against what the model computes.

A scene tabulates each output only over the sliders in its deps, so a parameter missing from them would
freeze that slider's effect and ship a wrong number at every other stop. When a scene is tabulated, each
output is evaluated at the scene's defaults and at a stop seeded from the scene's key, and again with each
parameter of the scene moved — to both ends of its slider and a seeded stop, or to seeded values of its
domain near its fixed value — all in one call of the model. An output that changes with a parameter its deps leave out
is an error naming its `Output(...)` line, the parameter and the values. The finding is cached under the scene's
key: a warm build reads it back and evaluates nothing.

The other way round is read from the tables themselves, at no cost: a declared dep whose slider leaves a
table the same at every stop (at the digits shown) is a note with the factor of stops it costs. A book's
tests run the same probe across the model's whole domain (`probe_model`, through sitegen.testing), where a
declared dep that never changed the output is reported too.
"""

from __future__ import annotations

import hashlib
import inspect
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import AuthorError, code_loc
from .cache import compute_now, scene_key
from .quantize import fmt, significant_text, with_unit
from .scenes import ResolvedScene
from .sources import digest, source_digest

BASE_STOPS = 2  # stops a scene is probed at: its defaults and a seeded other
MOVES = 3  # values each parameter is moved to from each of them (a slider: both ends and a seeded stop)
RELATIVE = 1e-12  # a change smaller than this (relative) is float noise no page shows
NOTED = 4  # outputs a scene's note names (then how many more)
DEPS_MODULES = frozenset({__name__})


@dataclass(frozen=True)
class Probe:
    """The points a model is evaluated at: `values` per parameter (one entry per point); point 0..K-1 are
    the base points, every other one is base point `base[j]` with parameter `moved[j]` changed."""

    values: dict[str, np.ndarray]
    base: np.ndarray  # per point: the base point it moved from (itself for a base point)
    moved: tuple[str, ...]  # per point: the parameter moved ("" for a base point)
    noted: frozenset[str] = frozenset()  # the declared deps to note when they never changed an output


@dataclass(frozen=True)
class DepsFindings:
    """What the probe found: an error text per undeclared dependency, a note text per declared dep that never
    changed an output (for the deps the probe notes)."""

    errors: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


def verify_scene_deps(scene: ResolvedScene, names, cached=compute_now, root: Path | None = None):
    """An author error for each output among `names` that changes with a parameter its deps leave out
    (cached under the scene's key: a rebuild reads the finding back and evaluates nothing)."""
    names = list(dict.fromkeys(names))
    key = digest(scene_key(scene, names).digest, source_digest(DEPS_MODULES), str(root), "deps")

    def probe() -> bytes:
        return json.dumps(list(probe_scene(scene, names, root).errors)).encode()

    return [AuthorError(scene.spec.loc, text, scene.id) for text in json.loads(cached("deps", key, probe))]


def probe_scene(scene: ResolvedScene, names, root: Path | None = None) -> DepsFindings:
    """Probe a scene's outputs `names` at seeded stops of its sliders."""
    probe = scene_probe(scene, _seed(scene, names))
    return probe_outputs(scene.model, names, scene.effects, probe, root, _stop_text(scene))


def inert_deps_note(scene: ResolvedScene, tables, root: Path | None = None) -> str | None:
    """A note naming the tabulated outputs whose table stays the same along a slider their deps declare
    (checked at every stop, at the digits shown): the scene computes them over that many times the stops
    for nothing. None when there is none."""
    found = []
    for name, table in sorted(tables.items()):
        if name.startswith("~") or not hasattr(table, "axes") or name not in {o.name for o in scene.model.outputs}:
            continue
        output = type(scene.model).output(name)
        deps = type(scene.model).deps_of(name, scene.effects)
        idle = [a for i, a in enumerate(scene.axes) if a.param in deps and a.count > 1 and i not in table.axes]
        if idle:
            sliders = ", ".join(f"'{a.param}' ({a.count}×)" for a in idle)
            found.append(f"'{name}' ({_declared_at(scene.model, output, root)}) with {sliders}")
    if not found:
        return None
    shown = "; ".join(found[:NOTED]) + (f"; and {len(found) - NOTED} more" if len(found) > NOTED else "")
    note = AuthorError(
        scene.spec.loc,
        f"{'an output does' if len(found) == 1 else f'{len(found)} outputs do'} not change anywhere on this "
        f"scene's grid with a slider its deps declare, so it is computed over that many times the stops for "
        f"nothing: {shown}",
        scene.id,
    )
    return f"note: {note}"


def probe_model(
    model, effects=frozenset(), points: int = 16, seed: int = 0, root: Path | None = None, moves: int = MOVES
) -> DepsFindings:
    """Probe every output of `model` under `effects` at `points` seeded points of its domain, each parameter
    moved `moves` times from each (for a book's tests)."""
    effects = frozenset(effects)
    names = [o.name for o in model.outputs if not o.effect or o.effect in effects]
    probe = model_probe(model, effects, points, seed, moves)
    return probe_outputs(model, names, effects, probe, root, where=_point_text(model))


def probe_outputs(model, names, effects, probe: Probe, root=None, where=None) -> DepsFindings:
    """Errors and notes for outputs `names` of `model` from one evaluation at the probe's points."""
    try:
        results = _evaluate(model, names, effects, probe)
    except (ValueError, ArithmeticError, TimeoutError) as error:  # a model's documented ways to fail
        return DepsFindings(
            (f"model '{model.name}' failed at a point of its domain while its deps were checked: {error}",)
        )
    errors, notes = [], []
    for name in names:
        output = type(model).output(name)
        deps = set(type(model).deps_of(name, effects))
        changes = _changes(output, results[name], probe)
        declared = _declared_at(model, output, root)
        for param in (p.name for p in model.params):
            change = changes.get(param)
            if param not in deps and change is not None:
                errors.append(f"{declared}: {_undeclared(output, param, change, probe, where)}")
            elif param in deps and change is None and param in probe.noted:
                notes.append(f"{declared}: {_inert(output, param, probe)}")
    return DepsFindings(tuple(errors), tuple(notes))


# --- the points ----------------------------------------------------------------------------------------------


def scene_probe(scene: ResolvedScene, seed: int) -> Probe:
    """The scene's defaults and seeded stops, each with every parameter of the scene moved: to other stops of
    its slider, or to values near its fixed value in its domain (a parameter replaced by one of the scene's
    effects too: it must change nothing)."""
    rng = np.random.default_rng(seed)
    counts = [axis.count for axis in scene.axes]
    stops = [scene.default_stops]
    for _ in range(4 * BASE_STOPS):
        stop = tuple(int(rng.integers(count)) for count in counts)
        if len(stops) < BASE_STOPS and stop not in stops:
            stops.append(stop)
    bases = []
    for stop in stops:
        values = scene.base_values()
        values.update({a.param: float(a.stop(k)) for a, k in zip(scene.axes, stop)})
        bases.append(values)
    points, base_of, moved = list(bases), list(range(len(bases))), [""] * len(bases)
    for param in scene.model.params:
        if param.effect and param.effect not in scene.effects:
            continue  # a parameter of an effect the scene leaves out: no control can set it here
        index = scene.axis_index(param.name)
        for b, values in enumerate(bases):
            if index is not None:
                axis = scene.axes[index]
                others = _other_stops(axis.count, stops[b][index], rng)
                new = [float(axis.values()[k]) for k in others]
            else:
                new = _near(param.under(scene.effects), values[param.name], rng)
            for value in new:
                points.append({**values, param.name: value})
                base_of.append(b)
                moved.append(param.name)
    return _probe(scene.model, points, base_of, moved)  # (an idle dep of a scene is read from its tables)


def model_probe(model, effects: frozenset[str], points: int, seed: int, moves: int = MOVES) -> Probe:
    """`points` seeded points across the model's domain, each with every parameter moved to `moves` other values."""
    rng = np.random.default_rng(seed)
    bases = [{p.name: _anywhere(p.under(effects), rng) for p in model.params} for _ in range(points)]
    every, base_of, moved = list(bases), list(range(points)), [""] * points
    for param in model.params:
        for b, values in enumerate(bases):
            for _ in range(moves):
                value = _anywhere(param.under(effects), rng, avoid=values[param.name])
                every.append({**values, param.name: value})
                base_of.append(b)
                moved.append(param.name)
    return _probe(model, every, base_of, moved, frozenset(p.name for p in model.params))


def _probe(model, points: list[dict], base_of: list[int], moved: list[str], noted=frozenset()) -> Probe:
    values = {p.name: np.array([point[p.name] for point in points], dtype=float) for p in model.params}
    return Probe(values, np.array(base_of), tuple(moved), noted)


def _other_stops(count: int, own: int, rng) -> list[int]:
    """Up to MOVES stops of a slider other than `own`: both ends, then seeded others."""
    chosen = [k for k in dict.fromkeys((0, count - 1)) if k != own]
    spare = [k for k in range(count) if k != own and k not in chosen]
    extra = rng.choice(len(spare), size=min(len(spare), MOVES - len(chosen)), replace=False) if spare else []
    return chosen + [spare[int(i)] for i in sorted(extra)]


def _near(param, value: float, rng) -> list[float]:
    """Values a parameter without a slider is moved to: its other options, or seeded values in its domain
    within max(|value|, 1) of `value`."""
    if param.choices:
        return [float(k) for k in range(len(param.choices)) if k != value][:MOVES]
    reach = max(abs(value), 1.0)
    lo, hi = max(param.lo, value - reach), min(param.hi, value + reach)
    return [_inside(param, float(v)) for v in rng.uniform(lo, hi, 2) if _inside(param, float(v)) != value]


def _anywhere(param, rng, avoid: float | None = None) -> float:
    """A seeded value in the parameter's domain (a stretch of ±5 where it is unbounded), other than `avoid`."""
    for _ in range(8):
        if param.choices:
            value = float(rng.integers(len(param.choices)))
        elif param.lo >= 0 and np.isfinite(param.hi) and param.hi - param.lo > 1e5:  # e.g. a count up to 1e6: decades
            value = param.lo + 10.0 ** rng.uniform(-1.0, 2.5)
        else:
            lo = param.lo if np.isfinite(param.lo) else -5.0
            hi = param.hi if np.isfinite(param.hi) else max(lo, 0.0) + 5.0
            value = float(rng.uniform(lo, hi))
        value = _inside(param, value)
        if value != avoid:
            return value
    return value


def _inside(param, value: float) -> float:
    """The value, kept off an open lower bound."""
    return float(np.nextafter(param.lo, np.inf)) if param.lo_open and value <= param.lo else value


# --- what changed ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Change:
    point: int  # the moved point
    element: int | None  # the element of a vector output that changed
    before: float
    after: float


def _evaluate(model, names, effects, probe: Probe) -> dict[str, np.ndarray]:
    """Every output at every point of the probe, in one call of the model."""
    results = model.evaluate(probe.values, names, effects)
    count = len(probe.moved)
    out = {}
    for name in names:
        size = type(model).output(name).size
        out[name] = np.broadcast_to(np.asarray(results[name], dtype=float), (count,) + ((size,) if size else ()))
    return out


def _changes(output, values: np.ndarray, probe: Probe) -> dict[str, _Change]:
    """For each moved parameter, the first point where moving it changed the output."""
    before, after = values[probe.base], values
    with np.errstate(invalid="ignore"):
        same = (before == after) | (np.isnan(before) & np.isnan(after))
        same |= np.abs(after - before) <= RELATIVE * np.maximum(np.abs(before), np.abs(after))
    changed = ~same if same.ndim == 1 else ~same.all(axis=1)
    found = {}
    for j in np.flatnonzero(changed):
        param = probe.moved[j]
        if param and param not in found:
            element = int(np.argmin(same[j])) if same.ndim > 1 else None
            pick = (lambda v: v[j, element]) if element is not None else (lambda v: v[j])
            found[param] = _Change(int(j), element, float(pick(before)), float(pick(after)))
    return found


# --- messages --------------------------------------------------------------------------------------------------


def _undeclared(output, param: str, change: _Change, probe: Probe, where) -> str:
    base = int(probe.base[change.point])
    was, now = probe.values[param][base], probe.values[param][change.point]
    element = f" (element {change.element})" if change.element is not None else ""
    at = f", at {where(probe, base, param)}" if where else ""
    return (
        f"output '{output.name}'{element} changes with '{param}' ({_value(output, change.before)} → "
        f"{_value(output, change.after)} as {param} goes {_number(was)} → {_number(now)}{at}) but its deps "
        f"leave '{param}' out; add '{param}' to its deps"
    )


def _inert(output, param: str, probe: Probe) -> str:
    moves = sum(1 for m in probe.moved if m == param)
    return f"output '{output.name}' declares '{param}' in its deps but did not change when it moved ({moves} probes)"


def _value(output, value: float) -> str:
    """A value as its readout writes it (a phrase, or the number to its decimals with its unit)."""
    if not np.isfinite(value):
        return str(value)
    if output.labels:
        index = int(value)
        return repr(output.labels[index]) if 0 <= index < len(output.labels) else str(value)
    if output.digits:
        return significant_text(value, output.digits, output.unit)
    return with_unit(fmt(value, output.decimals), output.unit)


def _number(value: float) -> str:
    return f"{value:g}"


def _stop_text(scene: ResolvedScene):
    def where(probe: Probe, base: int, moved: str) -> str:
        others = [a.param for a in scene.axes if a.param != moved]
        return ", ".join(f"{p}={_number(probe.values[p][base])}" for p in others) or "the scene's fixed values"

    return where


def _point_text(model):
    def where(probe: Probe, base: int, moved: str) -> str:
        return ", ".join(f"{p.name}={_number(probe.values[p.name][base])}" for p in model.params if p.name != moved)

    return where


def _declared_at(model, output, root: Path | None) -> str:
    """Where the output was declared, as the author sees it: its `Output(...)` line, else the model's class."""
    try:
        file, line = output.where or (inspect.getsourcefile(type(model)), inspect.getsourcelines(type(model))[1])
    except (OSError, TypeError):
        return f"model '{model.name}'"
    return str(code_loc(file, line, root))


def _seed(scene: ResolvedScene, names) -> int:
    """The probe's seed: from the scene's request (its sliders, values, effects and outputs), never the clock."""
    return int(hashlib.sha256(scene_key(scene, list(names)).spec.encode()).hexdigest()[:16], 16)
