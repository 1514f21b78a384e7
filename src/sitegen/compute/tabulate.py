"""Tabulation: each output evaluated over only the sliders it depends on, quantised for display."""

from __future__ import annotations

import time
from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from ..errors import AuthorError
from ..physics.structure import outputs_read
from .closed_form import require_showable, stop_text
from .quantize import quantize, significant
from .scenes import ResolvedScene
from .structure import compile_structured, structured_pieces
from .table import Table, drop_constant_axes

MAX_POINTS = 20_000_000  # per group of outputs: beyond this a scene would exhaust memory


@dataclass(frozen=True)
class WorkUnit:
    """One piece of a scene's tabulation: some outputs over a block of rows of their grid."""

    scene: ResolvedScene
    axes: tuple[int, ...]  # the sliders the outputs depend on
    names: tuple[str, ...]
    rows: tuple[int, int] | None = None  # a block of stops of the first axis; None for all

    def stops(self) -> int:
        """How many parameter points this unit evaluates."""
        counts = [self.scene.axes[a].count for a in self.axes]
        if self.rows and counts:
            counts[0] = self.rows[1] - self.rows[0]
        return int(np.prod(counts)) if counts else 1


def plan_scene(scene: ResolvedScene, names: list[str], max_stops: int | None = None) -> list[WorkUnit]:
    """The units of work for a scene: one per group of outputs sharing their sliders, split into
    blocks of rows of at most `max_stops` points when given (for models costly per point)."""
    groups: dict[tuple[int, ...], list[str]] = defaultdict(list)
    for name in per_stop_outputs(scene, names):
        deps = scene.model.deps_of(name, scene.effects)
        groups[tuple(i for i, a in enumerate(scene.axes) if a.param in deps)].append(name)
    units = []
    for axes, group in sorted(groups.items()):
        whole = WorkUnit(scene, axes, tuple(group))
        if whole.stops() > MAX_POINTS:
            sliders = ", ".join(scene.axes[a].param for a in axes)
            raise AuthorError(
                scene.spec.loc,
                f"outputs {', '.join(group)} would be tabulated at {whole.stops():,} points "
                f"(sliders {sliders}), more than {MAX_POINTS:,}; use fewer stops",
                scene.id,
            )
        if not max_stops or not axes or whole.stops() <= max_stops:
            units.append(whole)
            continue
        rows = scene.axes[axes[0]].count
        per_row = whole.stops() // rows
        step = max(1, max_stops // per_row)
        units += [WorkUnit(scene, axes, tuple(group), (r, min(r + step, rows))) for r in range(0, rows, step)]
    return units


def evaluate_unit(unit: WorkUnit) -> dict[str, np.ndarray]:
    """The raw values of a unit's outputs over its block of the grid (run anywhere: pure)."""
    scene = unit.scene
    inputs = scene.base_values()
    values = [scene.axes[i].values() for i in unit.axes]
    if unit.rows and values:
        values[0] = values[0][unit.rows[0] : unit.rows[1]]
    grids = np.meshgrid(*values, indexing="ij")
    for i, grid in zip(unit.axes, grids):
        inputs[scene.axes[i].param] = grid
    shape = tuple(len(v) for v in values)
    try:
        results = scene.model.evaluate(inputs, unit.names, scene.effects)
    except (ValueError, ArithmeticError, TimeoutError) as error:  # a model's documented ways to fail
        raise AuthorError(scene.spec.loc, f"model '{scene.model.name}' failed: {error}", scene.id) from None
    out = {}
    for name in unit.names:
        size = scene.model.output(name).size
        out[name] = np.array(np.broadcast_to(np.asarray(results[name], dtype=float), shape + ((size,) if size else ())))
    return out


def evaluate_timed(unit: WorkUnit) -> tuple[dict[str, np.ndarray], float]:
    """`evaluate_unit(unit)` and the seconds it took, wherever it ran."""
    start = time.perf_counter()
    return evaluate_unit(unit), time.perf_counter() - start


def per_stop_outputs(scene: ResolvedScene, names) -> list[str]:
    """The outputs among `names` tabulated at every stop: those without a declared structure, and
    those a structure reads at every stop."""
    pieces = structured_pieces(scene, names)
    read = set().union(*(outputs_read(p) for p in pieces.values())) if pieces else set()
    return [n for n in names if n not in pieces] + sorted(read - set(names))


def assemble_tables(
    scene: ResolvedScene, units: list[WorkUnit], results: list[dict[str, np.ndarray]], names=()
) -> dict:
    """Join the units' blocks (in plan order) into tables, then add the outputs among `names` that
    have a declared structure (compiled here; the check phase verifies them against the model)."""
    blocks: dict[tuple[int, ...], list[dict[str, np.ndarray]]] = defaultdict(list)
    for unit, result in zip(units, results):
        blocks[unit.axes].append(result)
    tables = {}
    for unit in units:
        if unit.names[0] in tables:
            continue
        parts = blocks[unit.axes]
        for name in unit.names:
            array = np.concatenate([p[name] for p in parts], axis=0) if unit.axes else parts[0][name]
            tables[name] = _finish_table(scene, unit.axes, name, array)
    pieces = structured_pieces(scene, names)
    if pieces:
        tables.update(compile_structured(scene, pieces, tables))
    return tables


def tabulate_scene(scene: ResolvedScene, names: list[str]) -> dict[str, Table]:
    """Evaluate the named outputs over their slider grids here and now; fail on any non-finite value."""
    units = plan_scene(scene, names)
    return assemble_tables(scene, units, [evaluate_unit(u) for u in units], names)


def _finish_table(scene: ResolvedScene, axes: tuple[int, ...], name: str, array: np.ndarray) -> Table:
    """Check, quantise and compact one output's raw values into its table."""
    output = scene.model.output(name)
    if output.ragged:
        padding = np.isnan(array)
        lengths = _ragged_lengths(scene, axes, output, ~padding)
        # The padding becomes 0 (the lengths say where rows end), as nan_to_num would make it; that
        # also turns ±inf into the largest floats, so with any of those it is left to nan_to_num.
        padded = np.where(padding, 0.0, array)
        array = padded if np.isfinite(padded).all() else np.nan_to_num(array, nan=0.0)
    else:
        lengths = None
    _require_finite(scene, axes, output, array)
    require_showable(scene, output, array, lambda index: stop_text(scene, axes, index))
    if output.digits and not output.size:  # mantissa and exponent, kept together while axes are dropped
        mantissas, exponents = significant(array, output.digits, special=bool(output.special), floor=output.floor)
        kept, mantissas, exponents = drop_constant_axes(axes, mantissas, exponents)
        return Table(
            name,
            kept,
            mantissas.shape,
            mantissas.reshape(-1),
            0,
            special=output.special,
            exponents=exponents.reshape(-1),
            digits=output.digits,
        )
    quanta = (
        array.astype(np.int64) if output.is_text else quantize(array, output.decimals, special=bool(output.special))
    )
    if lengths is not None:  # drop axes only where the lengths are constant too
        kept, quanta, lengths = drop_constant_axes(axes, quanta, lengths)
    else:
        kept, quanta = drop_constant_axes(axes, quanta)
    grid = quanta.shape[: len(kept)]
    return Table(
        name,
        kept,
        grid,
        quanta.reshape(-1),
        output.decimals,
        output.labels,
        output.size,
        None if lengths is None else lengths.reshape(-1),
        output.special,
    )


def _ragged_lengths(scene: ResolvedScene, axes, output, present: np.ndarray) -> np.ndarray:
    """Length of each vector: its elements before the first NaN (`present` false there), which must be padding to the
    end."""
    lengths = present.sum(axis=-1)
    padded_at_end = np.arange(output.size) < lengths[..., None]
    if not np.array_equal(present, padded_at_end):
        bad = np.argwhere(~np.all(present == padded_at_end, axis=-1))[0]
        raise AuthorError(
            scene.spec.loc, f"output '{output.name}' has NaN inside its values {stop_text(scene, axes, bad)}", scene.id
        )
    return lengths


def _require_finite(scene: ResolvedScene, axes: tuple[int, ...], output, array: np.ndarray) -> None:
    """Fail on a non-finite value, unless the output declares how the page shows it in words."""
    if output.special:  # every value may be non-finite
        return
    finite = np.isfinite(array)
    if not finite.all():
        bad = np.argwhere(~finite)
        element = f" (element {bad[0][-1]})" if output.size else ""
        raise AuthorError(
            scene.spec.loc,
            f"output '{output.name}'{element} is not finite ({array[tuple(bad[0])]}) {stop_text(scene, axes, bad[0])}; "
            "the model must return finite numbers, or, where the physics is singular or the quantity does not exist, "
            'say how the page shows it: special="—" (or "∞") and why="…" (or why_from=) on the Output',
            scene.id,
        )
