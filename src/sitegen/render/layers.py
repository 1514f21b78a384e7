"""Moving layers: shapes whose vertices are looked up from tables or read from sliders."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..compute.scenes import ResolvedScene
from ..compute.table import Table

Ref = float | str  # a number, "out:NAME" (a tabulated output) or "in:NAME" (a parameter's value)
KINDS = ("polyline", "polygon", "dots", "text")


@dataclass(frozen=True)
class Layer:
    """One moving shape drawn over axes `axes`.

    Its vertices are either `points`, pairs of scalar references, or the vectors `xs` and `ys`,
    each a vector output ("out:NAME") or a tuple of fixed numbers. "dots" draws a round dot at
    every vertex, in the colour of its `stroke` and as wide as its `stroke-width` (a `fill` would
    show nothing, so one is an error); a polyline is not filled unless its style gives a `fill`.
    A "text" layer is a note under the figure (e.g. the scale of normalised axes): its `text`
    joins phrases and references, an output written as its readout is, a parameter as its control.
    """

    name: str
    kind: str
    axes: int
    points: tuple[tuple[Ref, Ref], ...] = ()
    xs: str | tuple[float, ...] | None = None
    ys: str | tuple[float, ...] | None = None
    style: dict[str, str] = field(default_factory=dict)
    text: tuple[str, ...] = ()  # a text layer: phrases, and references "out:NAME" or "in:NAME"

    @classmethod
    def note(cls, name: str, *text: str) -> Layer:
        """A text layer: a note under the figure that changes with the sliders."""
        return cls(name, "text", -1, text=text)

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"layer '{self.name}': kind '{self.kind}' is none of {', '.join(KINDS)}")
        if self.kind == "dots" and self.style.get("fill", "none") != "none":
            raise ValueError(
                f"layer '{self.name}': a dots layer draws each dot with its stroke, so a fill shows nothing; "
                f"give the dots' colour as 'stroke' (and their diameter as 'stroke-width'), not as 'fill'"
            )

    def refs(self) -> list:
        """Every reference the layer reads."""
        refs = [r for xy in self.points for r in xy] + [r for r in (self.xs, self.ys) if isinstance(r, str)]
        return refs + [part for part in self.text if part.startswith(("out:", "in:"))]

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
        if table.digits:
            raise ValueError(
                f"a layer reads output '{name}', which is shown to significant digits: give the layer its own output"
            )
        scale = 10.0**-table.decimals
        value = table.at(stops)
        return [float(q) * scale for q in value] if table.width else value * scale
    index = scene.axis_index(name)
    return float(scene.axes[index].stop(stops[index])) if index is not None else scene.base_values()[name]


def layer_points(layers: list[Layer], scene, tables, stops) -> list[list[tuple[float, float]]]:
    """Every layer's vertices at a slider position."""

    def vertices(layer: Layer):
        if layer.kind == "text":  # written by the page (site/assemble.py), not drawn
            return []
        if layer.xs is not None:
            return list(zip(resolve_ref(layer.xs, scene, tables, stops), resolve_ref(layer.ys, scene, tables, stops)))
        return [(resolve_ref(x, scene, tables, stops), resolve_ref(y, scene, tables, stops)) for x, y in layer.points]

    return [vertices(layer) for layer in layers]
