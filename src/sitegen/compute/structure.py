"""Structure-aware tabulation: an output declared as a polynomial, a branch or a ratio of a few
exact pieces is shipped as that expression, and the page's script evaluates it.

The expression is plain JSON that knows slider values, tables, polynomial nodes, branches and
thresholds, and nothing of physics. `evaluate` below is the script's arithmetic in numpy, in the
same order of operations, so that what the build proves is what the page shows. `prove` compares
it with a direct evaluation of the model at every corner and edge of the slider box and at a
seeded random sample of stops, and the build fails on any displayed difference.
"""
from __future__ import annotations

import hashlib
import itertools
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import AuthorError
from ..physics.structure import ChoiceOf, Choose, Coord, Log10, OutputOf, Poly, Ratio, Threshold
from .grid import CHOICE, LIST
from .quantize import quantize
from .scenes import ResolvedScene
from .table import Table, grid_table

RANDOM_STOPS = 4000  # sampled stops per scene in the proof, beyond corners and edges
EDGE_STOPS = 20_000  # at most this many stops along the box's edges (all of them when fewer)


@dataclass(frozen=True)
class Structured:
    """An output the page computes from an expression over slider values and small tables."""

    output: str
    expr: dict  # what the script evaluates (JSON)
    decimals: int
    labels: tuple[str, ...] = ()
    width: int = 0
    special: str = ""
    parts: dict[str, Table] = field(default_factory=dict)  # the tables the expression reads
    sliders: tuple[np.ndarray, ...] = ()  # each slider's value at each stop, as the script computes it
    bounds: tuple[float, float] = (0.0, 0.0)  # smallest and largest shown value over the proof's stops

    def at(self, stops: tuple[int, ...]):
        """The quantum (or quanta of a vector) shown at a full slider position."""
        value = shown(self, np.asarray([stops], dtype=np.int64))[0]
        return value.tolist() if self.width else int(value)

    def value_range(self) -> tuple[float, float]:
        """Smallest and largest value the page can show (for a figure's axis limits)."""
        return self.bounds

    def stored_values(self) -> int:
        """How many numbers the expression ships (its tables are counted on their own)."""
        return _count_numbers(self.expr)


def _count_numbers(node) -> int:
    if isinstance(node, dict):
        return sum(_count_numbers(v) for k, v in node.items() if k not in ("x", "t"))
    if isinstance(node, list):
        return sum(_count_numbers(v) for v in node)
    return 1 if isinstance(node, (int, float)) else 0


def slider_values(scene: ResolvedScene) -> tuple[np.ndarray, ...]:
    """Each slider's value at each stop, computed as the page's script computes it."""
    values = []
    for axis in scene.axes:
        if axis.kind == CHOICE:
            values.append(np.arange(axis.count, dtype=float))
        elif axis.kind == LIST:
            values.append(np.array([float(s) for s in axis.stops]))
        else:  # the script: (lo + k step) / 10^d with integers lo and step, one correctly rounded division
            d = axis.decimals
            lo, step = int(axis.lo.scaleb(d)), int(axis.step.scaleb(d))
            values.append(np.array([(lo + k * step) / 10.0**d for k in range(axis.count)]))
    return tuple(values)


# --- compiling a declaration into an expression --------------------------------------------


class _Compiler:
    """Turns one scene's declared pieces into expressions and the coordinate tables they read."""

    def __init__(self, scene: ResolvedScene, per_stop: dict[str, Table]):
        self.scene, self.per_stop = scene, per_stop
        self.sliders = slider_values(scene)
        self.parts: dict[str, Table] = {}

    def compile(self, piece) -> dict:
        if isinstance(piece, Poly):
            return self._poly(piece)
        if isinstance(piece, Choose):
            return {"sel": self.compile(piece.by), "of": [self.compile(b) for b in piece.branches]}
        if isinstance(piece, Threshold):
            return {"cut": self.compile(piece.value), "edges": [float(e) for e in piece.edges], "map": list(piece.labels)}
        if isinstance(piece, Ratio):
            return {"ratio": [self.compile(piece.numerator), self.compile(piece.denominator)],
                    "k": float(piece.scale), "zero": float(piece.when_zero)}
        if isinstance(piece, Log10):
            return {"log10": self.compile(piece.value), "k": float(piece.scale)}
        if isinstance(piece, ChoiceOf):
            return self._param(piece.name)
        if isinstance(piece, OutputOf):
            self.parts[piece.name] = self.per_stop[piece.name]
            return {"t": piece.name}
        raise TypeError(f"unknown structure piece {piece!r}")

    def _param(self, name: str) -> dict:
        index = self.scene.axis_index(name)
        return {"x": index} if index is not None else {"c": float(self.scene.base_values()[name])}

    def _coordinate(self, coord: Coord) -> tuple[dict, np.ndarray] | None:
        """The coordinate's expression and its values over the slider box (None: fixed here)."""
        sliders = [self.scene.axis_index(p) for p in coord.of]
        if all(i is None for i in sliders):
            return None
        if coord.is_param:
            values = self.sliders[sliders[0]]
            return {"x": sliders[0]}, values
        name = f"~{coord.name}"
        if name not in self.parts:
            self.parts[name] = coordinate_table(self.scene, coord)
        return {"t": name}, table_values(self.parts[name])

    def _poly(self, poly: Poly) -> dict:
        base = dict(self.scene.base_values())
        coords, nodes, names = [], [], []
        for coord, degree in poly.degrees:
            found = self._coordinate(coord)
            if found is None:  # fixed in this scene: the kernel sees its one value
                if not coord.is_param:
                    base[coord.name] = coord.fn(**{p: base[p] for p in coord.of})
                continue
            expr, values = found
            lo, hi = float(values.min()), float(values.max())
            count = degree + 1 if hi > lo else 1
            coords.append(expr)
            nodes.append([lo + (hi - lo) * j / (count - 1) for j in range(count)] if count > 1 else [lo])
            names.append(coord.name)
        grids = np.meshgrid(*[np.array(n) for n in nodes], indexing="ij") if nodes else []
        inputs = {**base, **dict(zip(names, grids))}
        values = np.asarray(poly.kernel(inputs), dtype=float)
        shape = tuple(len(n) for n in nodes) + ((poly.size,) if poly.size else ())
        values = np.broadcast_to(values, shape).reshape((-1, poly.size) if poly.size else -1)
        if not np.all(np.isfinite(values)):
            raise ValueError("a polynomial's kernel is not finite at its nodes")
        return {"poly": coords, "nodes": nodes, "v": values.tolist()}


def coordinate_table(scene: ResolvedScene, coord: Coord) -> Table:
    """A derived coordinate (e.g. 1/(m1 + m2)) at every stop of its sliders, with `coord.decimals`
    digits; stored along one summed index when it depends only on the sum of the stop indices."""
    axes = tuple(i for i in (scene.axis_index(p) for p in coord.of) if i is not None)
    inputs = dict(scene.base_values())
    grids = np.meshgrid(*[scene.axes[i].values() for i in axes], indexing="ij")
    inputs.update({scene.axes[i].param: g for i, g in zip(axes, grids)})
    values = np.asarray(coord.fn(**{p: inputs[p] for p in coord.of}), dtype=float)
    values = np.broadcast_to(values, tuple(scene.axes[i].count for i in axes))
    if not np.all(np.isfinite(values)):
        raise ValueError(f"coordinate '{coord.name}' is not finite at every stop")
    raw = coord.decimals is None
    entries = np.array(values, dtype=float) if raw else quantize(values, coord.decimals)
    summed = _along_index_sum(entries)
    if summed is not None:
        return Table(f"~{coord.name}", axes, (len(summed),), summed, coord.decimals or 0, summed_axes=True, raw=raw)
    table = grid_table(f"~{coord.name}", axes, entries, coord.decimals or 0)
    return Table(table.output, table.axes, table.shape, table.quanta, table.decimals, raw=raw)


def table_values(table: Table, rows=slice(None)) -> np.ndarray:
    """A scalar table's values (at `rows`): doubles as stored, or quanta scaled to their digits."""
    entries = table.quanta[rows]
    if table.raw:
        return entries.astype(float)
    return entries.astype(float) if table.labels else entries / 10.0**table.decimals


def _along_index_sum(entries: np.ndarray) -> np.ndarray | None:
    """The values by i + j + ... when they depend only on that sum (e.g. a function of m1 + m2 on
    two sliders with the same grid), else None. The sum of two floats can differ in its last bit
    between 0.1 + 0.3 and 0.2 + 0.2, so values along one sum may differ by a few units in the last
    place (or one unit of the last stored digit): far below what any output shows, and the proof
    checks the outputs."""
    if entries.ndim < 2:
        return None
    total = sum(np.indices(entries.shape))
    by_sum = np.zeros(int(total.max()) + 1, dtype=entries.dtype)
    by_sum[total.ravel()[::-1]] = entries.ravel()[::-1]  # the first stop of each sum wins
    spread = np.abs(by_sum[total] - entries)
    allowed = 8 * np.finfo(float).eps * np.abs(entries) if entries.dtype.kind == "f" else 1
    return by_sum if np.all(spread <= allowed) else None


# --- the script's arithmetic, over many stops at once ---------------------------------------


def evaluate(expr: dict, parts: dict[str, Table], sliders, stops: np.ndarray) -> np.ndarray:
    """The expression's value at each row of `stops` (n × sliders), as the page's script computes it."""
    n = len(stops)
    if "c" in expr:
        return np.full(n, expr["c"])
    if "x" in expr:
        return sliders[expr["x"]][stops[:, expr["x"]]]
    if "t" in expr:
        table = parts[expr["t"]]
        return table_values(table, table.flat_indices(stops))
    if "poly" in expr:
        return _poly_value(expr, parts, sliders, stops)
    if "sel" in expr:
        which = evaluate(expr["sel"], parts, sliders, stops).astype(np.int64)
        branches = [evaluate(b, parts, sliders, stops) for b in expr["of"]]
        return np.choose(which[(...,) + (None,) * (branches[0].ndim - 1)], branches)
    if "cut" in expr:
        value = evaluate(expr["cut"], parts, sliders, stops)
        count = sum((value > edge).astype(np.int64) for edge in expr["edges"])
        return np.asarray(expr["map"], dtype=float)[count]
    if "log10" in expr:
        return expr["k"] * np.log10(evaluate(expr["log10"], parts, sliders, stops))
    if "ratio" in expr:
        top, bottom = (evaluate(e, parts, sliders, stops) for e in expr["ratio"])
        safe = np.where(bottom == 0, 1.0, bottom)
        return np.where(bottom == 0, expr["zero"], expr["k"] * top / safe)
    raise ValueError(f"unknown expression {sorted(expr)}")


def _poly_value(expr: dict, parts, sliders, stops: np.ndarray) -> np.ndarray:
    """Tensor-product Lagrange interpolation, in the script's order of operations."""
    weights = []
    for coord, nodes in zip(expr["poly"], expr["nodes"]):
        c = evaluate(coord, parts, sliders, stops)
        per_node = []
        for j, xj in enumerate(nodes):
            w = np.ones(len(stops))
            for m, xm in enumerate(nodes):
                if m != j:
                    w = w * (c - xm) / (xj - xm)
            per_node.append(w)
        weights.append(per_node)
    values = np.asarray(expr["v"], dtype=float)
    total = np.zeros((len(stops),) + values.shape[1:])
    for flat, index in enumerate(itertools.product(*[range(len(n)) for n in expr["nodes"]])):
        product = np.ones(len(stops))
        for i, j in enumerate(index):
            product = product * weights[i][j]
        total = total + (values[flat] * product[:, None] if values.ndim > 1 else values[flat] * product)
    return total


def shown(table: Structured, stops: np.ndarray) -> np.ndarray:
    """What the page shows at each row of `stops`: a label index, or integers of the last digit
    (rounded half up: floor(x·10^d + 0.5), as the script rounds)."""
    value = evaluate(table.expr, table.parts, table.sliders, stops)
    if table.labels:
        return value.astype(np.int64)
    return np.floor(value * 10.0**table.decimals + 0.5).astype(np.int64) + 0


# --- proving a declaration against the model ------------------------------------------------


def proof_stops(scene: ResolvedScene) -> np.ndarray:
    """Every corner and (up to EDGE_STOPS) edge stop of the slider box, the defaults, and a seeded
    random sample: the stops at which a structural claim is checked."""
    counts = [a.count for a in scene.axes]
    if not counts:
        return np.zeros((1, 0), dtype=np.int64)
    ends = [sorted({0, c - 1}) for c in counts]
    rows = [list(corner) for corner in itertools.product(*ends)]
    edges = []
    for i, count in enumerate(counts):
        others = [ends[j] for j in range(len(counts)) if j != i]
        for corner in itertools.product(*others):
            for k in range(count):
                edges.append([*corner[:i], k, *corner[i:]])
    if len(edges) > EDGE_STOPS:
        edges = [edges[i] for i in np.linspace(0, len(edges) - 1, EDGE_STOPS).astype(int)]
    seed = int.from_bytes(hashlib.sha256(scene.spec.id.encode()).digest()[:8], "little")
    sample = np.random.default_rng(seed).integers(0, counts, size=(RANDOM_STOPS, len(counts)))
    return np.unique(np.vstack([rows, edges or np.zeros((0, len(counts)), int), [scene.default_stops], sample]).astype(np.int64), axis=0)


def prove(scene: ResolvedScene, table: Structured, stops: np.ndarray) -> tuple[float, float]:
    """Check that the page shows what the model gives at every row of `stops`; raise an author
    error at the first difference. Returns the smallest and largest value shown."""
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
    scale = 10.0**-output.decimals
    return float(page.min()) * scale, float(page.max()) * scale


def require_showable(scene: ResolvedScene, output, values: np.ndarray, where) -> None:
    """Fail on a number too large to be counted exactly in units of its last digit: the page's
    script reads the counts as JavaScript numbers, exact only up to 2**53 (past 2**63 the count
    would even wrap around). `where(index)` says where the value at that index of `values` is."""
    if output.is_text:
        return
    limit = 2.0**53 / 10.0**output.decimals
    bad = np.argwhere(np.isfinite(values) & (np.abs(values) >= limit))
    if len(bad):
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


# --- a scene's structured outputs ------------------------------------------------------------


def structured_pieces(scene: ResolvedScene, names) -> dict[str, object]:
    """The outputs among `names` with a declared structure under the scene's effects."""
    pieces = {}
    for name in names:
        piece = scene.model.output(name).structure_for(scene.effects)
        if piece is not None:
            pieces[name] = piece
    return pieces


def compile_structured(scene: ResolvedScene, pieces: dict[str, object], per_stop: dict[str, Table]) -> dict[str, object]:
    """Each declared output as a proven expression, plus the coordinate tables they read (named "~…")."""
    compiler = _Compiler(scene, per_stop)
    stops = proof_stops(scene) if pieces else None
    out: dict[str, object] = {}
    for name, piece in pieces.items():
        output = scene.model.output(name)
        try:
            expr = compiler.compile(piece)
        except ValueError as error:
            raise AuthorError(scene.spec.loc, f"output '{name}': {error}", scene.id) from None
        table = Structured(name, expr, output.decimals, output.labels, output.size, output.special,
                           dict(compiler.parts), compiler.sliders)
        bounds = prove(scene, table, stops)
        out[name] = replace(table, bounds=bounds)
    out.update({n: t for n, t in compiler.parts.items() if n not in out})
    return out
