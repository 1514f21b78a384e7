"""Grid resolution against interpolation error against bytes (docs/physics/README.md).

For a few outputs of the tabulated scenes, each along one slider with the others at their
defaults: store the output at a few nodes of some axis (linear, logarithmic, or a coordinate in
which the output is exactly affine or quadratic), interpolate back to every slider stop, and
measure the largest error against the model itself. The page ships every stop instead; its
bytes are the last row of each group.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from ..compute.quantize import quantize
from ..registry import builtin_registry
from ..site.sizes import gzip_bytes

FLOAT32 = 4  # bytes per stored value as float32


@dataclass(frozen=True)
class Line:
    """One output along one slider: the model, the slider's stops and the digits the page shows."""

    name: str  # e.g. "I2 v₁f(m₁)"
    model: str
    output: str
    param: str
    stops: np.ndarray
    decimals: int
    fixed: tuple[tuple[str, float], ...] = ()
    scene: str = ""  # the scene of the book that shows this output (page#id), if any

    def exact(self, x) -> np.ndarray:
        """The model's value at x (the other parameters at their defaults and `fixed`)."""
        inputs = {**dict(self.fixed), self.param: np.asarray(x, float)}
        return np.asarray(
            builtin_registry().models[self.model]().evaluate(inputs, wanted=[self.output])[self.output], float
        )


def _stops(lo: float, hi: float, step: float) -> np.ndarray:
    return np.round(lo + step * np.arange(round((hi - lo) / step) + 1), 10)


# docs/physics/README.md, on the slider ranges of the impulse, collision and lever scenes.
LINES = {
    "v1f": Line(
        "I2 v₁f(m₁), m₂ = 2 kg",
        "collision",
        "v1f",
        "m1",
        _stops(0.1, 10.0, 0.1),
        3,
        (("m2", 2.0), ("v1i", 3.0), ("v2i", -1.0), ("e", 1.0)),
        "newtons-laws#collision",
    ),
    "K_after": Line(
        "I2 K_after(e)",
        "collision",
        "K_after",
        "e",
        _stops(0.0, 1.0, 0.01),
        2,
        (("m1", 1.0), ("m2", 2.0), ("v1i", 3.0), ("v2i", -1.0)),
        "newtons-laws#collision",
    ),
    "dv": Line(
        "I1 Δv(m)",
        "impulse",
        "dv",
        "m",
        _stops(0.1, 10.0, 0.1),
        3,
        (("F_pk", 12.0), ("tau", 0.2)),
        "newtons-laws#impulse",
    ),
    "MA": Line("I4 MA(x_p)", "lever", "MA", "x_p", _stops(0.0, 2.0, 0.01), 2, (), "newtons-laws#lever"),
}


def interpolation_error(line: Line, axis: str, count: int) -> tuple[float, np.ndarray]:
    """Largest |interpolated − model| over the finite stops, and the stored node values."""
    x = line.stops[np.isfinite(line.exact(line.stops))]
    coordinate, nodes = AXES[axis](line, x, count)
    values = line.exact(nodes)
    if axis == "quadratic":
        interpolated = _lagrange(coordinate(nodes), values, coordinate(x))
    else:
        order = np.argsort(coordinate(nodes))  # np.interp wants rising nodes; 1/m falls
        interpolated = np.interp(coordinate(x), coordinate(nodes)[order], values[order])
    return float(np.max(np.abs(interpolated - line.exact(x)))), values


def _lagrange(nodes: np.ndarray, values: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The polynomial through (nodes, values), evaluated at x (Lagrange form; a few nodes only)."""
    total = np.zeros_like(x)
    for i, (node, value) in enumerate(zip(nodes, values)):
        others = np.delete(nodes, i)
        total += value * np.prod([(x - o) / (node - o) for o in others], axis=0)
    return total


def _mass_fraction(line: Line):
    m2 = dict(line.fixed)["m2"]
    return lambda m1: m1 / (m1 + m2)


# axis name -> (line, finite stops, node count) -> (coordinate function, node positions in the slider's value)
AXES = {
    "linear": lambda line, x, n: (lambda v: v, np.linspace(x[0], x[-1], n)),
    "log": lambda line, x, n: (np.log, np.geomspace(x[0], x[-1], n)),
    "w1": lambda line, x, n: (_mass_fraction(line), np.array([x[0], x[-1]])),
    "inverse": lambda line, x, n: (lambda v: 1.0 / v, np.array([x[0], x[-1]])),
    "quadratic": lambda line, x, n: (lambda v: v, np.linspace(x[0], x[-1], n)),
}
AXIS_TEXT = {
    "linear": "linear {p}",
    "log": "log {p}",
    "w1": "w₁ = m₁/(m₁+m₂)",
    "inverse": "1/{p}",
    "quadratic": "quadratic in {p}",
    "per stop": "every stop",
}

# (line, axis, node counts): the rows of the table in docs/physics/README.md.
CASES = (
    ("v1f", "linear", (17, 33, 65)),
    ("v1f", "log", (17, 33, 65)),
    ("v1f", "w1", (2,)),
    ("K_after", "linear", (2, 3, 5, 9, 17)),
    ("K_after", "quadratic", (3,)),
    ("dv", "linear", (17, 33, 65)),
    ("dv", "log", (17, 33, 65)),
    ("dv", "inverse", (2,)),
    ("MA", "linear", (65,)),
)


def json_gzip_bytes(values: np.ndarray, decimals: int) -> int:
    """Bytes of the values as our pages store them (integers of the last shown digit, JSON, gzip)."""
    quanta = quantize(values, decimals).tolist()
    return gzip_bytes(json.dumps(quanta, separators=(",", ":")).encode())


def resolution_experiment(scenes=None) -> list[dict]:
    """Every row of the resolution table (docs/physics/README.md), then one 'every stop' row per output (what
    the page ships, no interpolation); only the outputs of `scenes` ("page#id") when given (a book without those
    scenes has no rows)."""
    lines = {key: line for key, line in LINES.items() if scenes is None or line.scene in scenes}
    rows = []
    for key, axis, counts in CASES:
        if key not in lines:
            continue
        line = LINES[key]
        for count in counts:
            error, values = interpolation_error(line, axis, count)
            rows.append(_row(key, line, axis, count, error, values))
    for key, line in lines.items():
        values = line.exact(line.stops)
        finite = values[np.isfinite(values)]
        rows.append(_row(key, line, "per stop", len(line.stops), 0.0, finite))
    return rows


def _row(key: str, line: Line, axis: str, count: int, error: float, values: np.ndarray) -> dict:
    return {
        "line": key,
        "output": line.name,
        "scene": line.scene,
        "axis": axis,
        "axis_text": AXIS_TEXT[axis].format(p=line.param),
        "nodes": count,
        "stops": len(line.stops),
        "error": error,
        "display_resolution": 0.5 * 10.0**-line.decimals,
        "decimals": line.decimals,
        "bytes_float32": FLOAT32 * count,
        "bytes_json_gzip": json_gzip_bytes(values, line.decimals),
    }
