"""Moving layers: shapes whose vertices are looked up from tables or read from sliders."""
from __future__ import annotations

from dataclasses import dataclass, field

from ..compute.scenes import ResolvedScene
from ..compute.table import Table

Ref = float | str  # a number, "out:NAME" (a tabulated output) or "in:NAME" (a parameter's value)
KINDS = ("polyline", "polygon", "dots")


@dataclass(frozen=True)
class Layer:
    """One moving shape drawn over axes `axes`.

    Its vertices are either `points`, pairs of scalar references, or the vectors `xs` and `ys`,
    each a vector output ("out:NAME") or a tuple of fixed numbers. "dots" draws a round dot at
    every vertex.
    """

    name: str
    kind: str
    axes: int
    points: tuple[tuple[Ref, Ref], ...] = ()
    xs: str | tuple[float, ...] | None = None
    ys: str | tuple[float, ...] | None = None
    style: dict[str, str] = field(default_factory=dict)

    def refs(self) -> list:
        """Every reference the layer reads."""
        return [r for xy in self.points for r in xy] + [r for r in (self.xs, self.ys) if isinstance(r, str)]

    def outputs(self) -> set[str]:
        """The tabulated outputs this layer reads."""
        return {r[4:] for r in self.refs() if isinstance(r, str) and r.startswith("out:")}


def resolve_ref(ref, scene: ResolvedScene, tables: dict[str, Table], stops: tuple[int, ...]):
    """The value a layer reference takes at a slider position (a number, or a list for a vector)."""
    if isinstance(ref, tuple):
        return [float(v) for v in ref]
    if not isinstance(ref, str):
        return float(ref)
    kind, name = ref.split(":", 1)
    if kind == "out":
        table = tables[name]
        scale = 10.0**-table.decimals
        value = table.at(stops)
        return [float(q) * scale for q in value] if table.width else value * scale
    index = scene.axis_index(name)
    return float(scene.axes[index].stop(stops[index])) if index is not None else scene.base_values()[name]


def layer_points(layers: list[Layer], scene, tables, stops) -> list[list[tuple[float, float]]]:
    """Every layer's vertices at a slider position."""
    def vertices(layer: Layer):
        if layer.xs is not None:
            return list(zip(resolve_ref(layer.xs, scene, tables, stops), resolve_ref(layer.ys, scene, tables, stops)))
        return [(resolve_ref(x, scene, tables, stops), resolve_ref(y, scene, tables, stops)) for x, y in layer.points]

    return [vertices(layer) for layer in layers]
