"""The sampled check of closed forms, run in the build's check phase.

An output whose model declares its closed form (a structure: a polynomial, a branch, a ratio; see
physics/structure.py) is shipped as an expression the page's script evaluates. The check compares what
the page will show (the expression evaluated as the script does, compute/expression.py) with a direct
evaluation of the model, at display precision, at every corner of the slider box, at the stops along
its edges (all of them, or EDGE_STOPS spread evenly), at the defaults, and at RANDOM_STOPS stops drawn
from a generator seeded by the scene's id; the build fails at the scene's line on any difference (a
value on an exact rounding tie may round either way).
"""

from __future__ import annotations

import hashlib
import itertools

import numpy as np

from ..errors import AuthorError
from .expression import shown
from .quantize import quantize
from .scenes import ResolvedScene

RANDOM_STOPS = 4000  # sampled stops per scene in the check, beyond corners and edges
EDGE_STOPS = 20_000  # at most this many stops along the box's edges (all of them when fewer)


def verified_stops(scene: ResolvedScene) -> np.ndarray:
    """Every corner and (up to EDGE_STOPS) edge stop of the slider box, the defaults, and a seeded
    random sample: the stops at which a structural claim is checked."""
    counts = [a.count for a in scene.axes]
    if not counts:
        return np.zeros((1, 0), dtype=np.int64)
    ends = [sorted({0, c - 1}) for c in counts]
    rows = [list(corner) for corner in itertools.product(*ends)]
    edges = []  # blocks of stops along one axis from each corner of the others, in that order
    for i, count in enumerate(counts):
        others = [ends[j] for j in range(len(counts)) if j != i]
        for corner in itertools.product(*others):
            block = np.empty((count, len(counts)), dtype=np.int64)
            block[:, [j for j in range(len(counts)) if j != i]] = corner
            block[:, i] = np.arange(count)
            edges.append(block)
    edges = np.concatenate(edges)
    if len(edges) > EDGE_STOPS:
        edges = edges[np.linspace(0, len(edges) - 1, EDGE_STOPS).astype(int)]
    seed = int.from_bytes(hashlib.sha256(scene.spec.id.encode()).digest()[:8], "little")
    sample = np.random.default_rng(seed).integers(0, counts, size=(RANDOM_STOPS, len(counts)))
    return np.unique(np.vstack([rows, edges, [scene.default_stops], sample]).astype(np.int64), axis=0)


def verify_closed_forms(scene: ResolvedScene, forms) -> list[AuthorError]:
    """The sampled check of a scene's closed forms (its `Structured` tables): an author error for the
    first whose page value differs from the model's at a stop of `verified_stops`, else none."""
    stops = verified_stops(scene)
    for form in forms:
        try:
            verify_closed_form(scene, form, stops)
        except AuthorError as error:
            return [error]
    return []


def verify_closed_form(scene: ResolvedScene, table, stops: np.ndarray) -> None:
    """Check that the page shows what the model gives at every row of `stops`; raise an author
    error at the first difference."""
    output = scene.model.output(table.output)
    inputs = scene.base_values()
    for i, axis in enumerate(scene.axes):
        inputs[axis.param] = axis.values()[stops[:, i]]
    direct = np.asarray(scene.model.evaluate(inputs, [table.output], scene.effects)[table.output], dtype=float)
    direct = np.broadcast_to(direct, (len(stops),) + ((output.size,) if output.size else ()))
    deps = scene.model.deps_of(output.name, scene.effects)
    dep_axes = tuple(i for i, a in enumerate(scene.axes) if a.param in deps)
    require_showable(scene, output, direct, lambda index: stop_text(scene, dep_axes, stops[index[0], list(dep_axes)]))
    page = shown(table, stops)
    if output.is_text:
        wrong = page != direct.astype(np.int64)
    else:
        expected = quantize(direct, output.decimals)
        wrong = (page != expected) & ~_ties(direct, output.decimals, page, expected)
    if wrong.ndim > 1:
        wrong = wrong.any(axis=tuple(range(1, wrong.ndim)))
    if wrong.any():
        k = int(np.argmax(wrong))
        raise AuthorError(
            scene.spec.loc,
            f"output '{table.output}': its declared structure gives {_text(page[k], output)} "
            f"{stop_text(scene, tuple(range(len(scene.axes))), stops[k])}, "
            f"but the model gives {_text(direct[k], output, raw=True)}; the structure declared in model "
            f"'{scene.model.name}' is wrong for this scene (remove it to tabulate per stop)",
            scene.id,
        )


def require_showable(scene: ResolvedScene, output, values: np.ndarray, where) -> None:
    """Fail on a number too large to be counted exactly in units of its last digit: the page's
    script reads the counts as JavaScript numbers, exact only up to 2**53 (past 2**63 the count
    would even wrap around). `where(index)` says where the value at that index of `values` is."""
    if output.is_text or output.digits:  # significant digits count no last decimal
        return
    limit = 2.0**53 / 10.0**output.decimals
    too_large = np.abs(values) >= limit  # ±inf too, and only then is the second pass needed to spare them
    if too_large.any() and (too_large := too_large & np.isfinite(values)).any():
        bad = np.argwhere(too_large)
        raise AuthorError(
            scene.spec.loc,
            f"output '{output.name}' is {values[tuple(bad[0])]:.6g} {where(bad[0])}, too large to show "
            f"with {output.decimals} decimals (at most {limit:.6g}); narrow the sliders' ranges",
            scene.id,
        )


def stop_text(scene: ResolvedScene, axes: tuple[int, ...], index) -> str:
    """Where a value is: "at m1=0.1, e=1.00" for the stops `index` of the sliders `axes`."""
    stop = ", ".join(f"{scene.axes[a].param}={scene.axes[a].stop(int(k))}" for a, k in zip(axes, index))
    return f"at {stop}" if stop else "at the scene's fixed values"


def _ties(direct: np.ndarray, decimals: int, page: np.ndarray, expected: np.ndarray) -> np.ndarray:
    """Where the exact value sits on a rounding tie (to the model's own float error), so that
    either neighbour is a correct display."""
    scaled = direct * 10.0**decimals
    off_tie = np.abs(np.abs(scaled - np.floor(scaled)) - 0.5)
    return (np.abs(page - expected) == 1) & (off_tie <= 1e-9 * np.maximum(1.0, np.abs(scaled)))


def _text(value, output, raw: bool = False) -> str:
    if output.is_text:
        return repr(output.labels[int(np.ravel(value)[0])])
    if raw:
        return np.array2string(np.asarray(value), precision=output.decimals + 3)
    return np.array2string(np.asarray(value) * 10.0**-output.decimals, precision=output.decimals)
