"""Structure-aware tabulation: an output declared as a polynomial, a branch or a ratio of a few
exact pieces is shipped as that expression, and the page's script evaluates it.

The expression is plain JSON that knows slider values, tables, polynomial nodes, branches and
thresholds, and nothing of physics. expression.py is the script's arithmetic in numpy, in the
same order of operations, so that what the build verifies is what the page shows: the check phase
compares it with a direct evaluation of the model at every corner and edge of the slider box and at
a seeded random sample of stops (closed_form.py), and fails on any displayed difference.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import AuthorError
from ..physics.structure import ChoiceOf, Choose, Coord, Log10, OutputOf, Poly, Ratio, Threshold
from .closed_form import verified_stops
from .expression import shown, table_values
from .grid import CHOICE, LIST
from .quantize import quantize
from .scenes import ResolvedScene
from .table import Table, grid_table


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
    bounds: tuple[float, float] = (0.0, 0.0)  # smallest and largest shown value over the sampled stops
    digits = 0  # an expression is shown to its decimals, never to significant digits

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
            return {
                "cut": self.compile(piece.value),
                "edges": [float(e) for e in piece.edges],
                "map": list(piece.labels),
            }
        if isinstance(piece, Ratio):
            return {
                "ratio": [self.compile(piece.numerator), self.compile(piece.denominator)],
                "k": float(piece.scale),
                "zero": float(piece.when_zero),
            }
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


def _along_index_sum(entries: np.ndarray) -> np.ndarray | None:
    """The values by i + j + ... when they depend only on that sum (e.g. a function of m1 + m2 on
    two sliders with the same grid), else None. The sum of two floats can differ in its last bit
    between 0.1 + 0.3 and 0.2 + 0.2, so values along one sum may differ by a few units in the last
    place (or one unit of the last stored digit): far below what any output shows, and the sampled
    check verifies the outputs."""
    if entries.ndim < 2:
        return None
    total = sum(np.indices(entries.shape))
    by_sum = np.zeros(int(total.max()) + 1, dtype=entries.dtype)
    by_sum[total.ravel()[::-1]] = entries.ravel()[::-1]  # the first stop of each sum wins
    spread = np.abs(by_sum[total] - entries)
    allowed = 8 * np.finfo(float).eps * np.abs(entries) if entries.dtype.kind == "f" else 1
    return by_sum if np.all(spread <= allowed) else None


def shown_bounds(table: Structured, stops: np.ndarray) -> tuple[float, float]:
    """The smallest and largest value the page shows at `stops` (for a figure's axis limits)."""
    with np.errstate(invalid="ignore"):  # a value too large to show: the check phase's error (require_showable)
        page = shown(table, stops)
    scale = 10.0**-table.decimals
    return float(page.min()) * scale, float(page.max()) * scale


# --- a scene's structured outputs ------------------------------------------------------------


def structured_pieces(scene: ResolvedScene, names) -> dict[str, object]:
    """The outputs among `names` with a declared structure under the scene's effects."""
    pieces = {}
    for name in names:
        output = scene.model.output(name)
        piece = output.structure_for(scene.effects)
        if piece is not None and not output.digits:  # significant digits are looked up, never computed
            pieces[name] = piece
    return pieces


def compile_structured(
    scene: ResolvedScene, pieces: dict[str, object], per_stop: dict[str, Table]
) -> dict[str, object]:
    """Each declared output as an expression, plus the coordinate tables they read (named "~…"). The check
    phase verifies each against the model (closed_form.py)."""
    compiler = _Compiler(scene, per_stop)
    stops = verified_stops(scene) if pieces else None
    out: dict[str, object] = {}
    for name, piece in pieces.items():
        output = scene.model.output(name)
        try:
            expr = compiler.compile(piece)
        except ValueError as error:
            raise AuthorError(scene.spec.loc, f"output '{name}': {error}", scene.id) from None
        table = Structured(
            name,
            expr,
            output.decimals,
            output.labels,
            output.size,
            output.special,
            dict(compiler.parts),
            compiler.sliders,
        )
        out[name] = replace(table, bounds=shown_bounds(table, stops))
    out.update({n: t for n, t in compiler.parts.items() if n not in out})
    return out
