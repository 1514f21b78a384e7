"""Moving layers: shapes whose vertices are looked up from tables or read from sliders."""

from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from pathlib import Path

from ..compute.scenes import ResolvedScene
from ..compute.table import Table
from ..errors import AuthorError, caller_line, code_loc, did_you_mean

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
    # Where the Layer was made (file, line): the figure's own line, named when a reference names nothing.
    where: tuple[str, int] | None = field(default=None, compare=False, repr=False)

    @classmethod
    def note(cls, name: str, *text: str) -> Layer:
        """A text layer: a note under the figure that changes with the sliders."""
        return cls(name, "text", -1, text=text)

    def __post_init__(self):
        if self.where is None:
            object.__setattr__(self, "where", caller_line(inspect.currentframe(), __file__))
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


# --- the figure's contract: every reference names what the scene has ---------------------------------------


def layer_errors(scene: ResolvedScene, layers: list[Layer], view, root: Path | None = None) -> list[AuthorError]:
    """An author error (at the scene's line, naming the layer's file and line) for every reference of
    `layers` that names no parameter or output of the scene, or one of the wrong kind."""
    errors = []
    for layer in layers:
        for ref, wanted in _references(layer):
            problem = _ref_problem(ref, wanted, scene)
            if problem:
                where = _where(layer, view, root)
                errors.append(
                    AuthorError(scene.spec.loc_of("figure"), f"{where}: layer '{layer.name}' {problem}", scene.id)
                )
    return errors


def _references(layer: Layer) -> list[tuple[object, str]]:
    """The layer's references, each with what it must be: "scalar" (a vertex's coordinate), "vector" (xs or
    ys) or "text" (a value a note writes as its readout does)."""
    found = [(r, "scalar") for xy in layer.points for r in xy]
    if layer.kind != "text" and not layer.points:
        found += [(layer.xs, "vector"), (layer.ys, "vector")]
    return found + [(part, "text") for part in layer.text if part.startswith(("out:", "in:"))]


def _ref_problem(ref, wanted: str, scene: ResolvedScene) -> str | None:
    """What is wrong with one reference (said after "layer 'NAME' "), or None."""
    if wanted == "vector" and isinstance(ref, tuple):
        return None if all(isinstance(v, (int, float)) for v in ref) else f"has xs/ys {ref!r} that are not all numbers"
    if isinstance(ref, (int, float)) and not isinstance(ref, bool) and wanted == "scalar":
        return None
    if wanted == "text":  # a phrase, or one number written as its readout is (to significant digits too)
        wanted, written = "scalar", True
    else:
        written = False
    if ref is None:
        return "gives xs or ys without the other (give both, or points)"
    if not isinstance(ref, str) or not ref.startswith(("in:", "out:")):
        what = (
            "a vector output 'out:<name>' or a tuple of numbers"
            if wanted == "vector"
            else "a number, 'in:<parameter>' or 'out:<output>'"
        )
        return f"reads {ref!r}, which is not {what}"
    kind, name = ref.split(":", 1)
    model = scene.model
    if kind == "in":
        params = [p.name for p in model.params]
        if wanted == "vector":
            return f"reads '{ref}' as a vector, but a parameter is one number; give xs/ys a vector output"
        return (
            None
            if name in params
            else f"reads '{ref}', which is no parameter of model "
            f"'{model.name}'{did_you_mean(name, params)} Its parameters: {', '.join(params)}"
        )
    outputs = {o.name: o for o in model.outputs if not o.effect or o.effect in scene.effects}
    fitting = [n for n, o in outputs.items() if bool(o.size) == (wanted == "vector") and (written or not o.digits)]
    what = "vector outputs" if wanted == "vector" else "scalar outputs"
    if name not in outputs:
        return (
            f"reads '{ref}', which is no output of model '{model.name}' in this "
            f"scene{did_you_mean(name, fitting)} Its {what}: {', '.join(fitting) or 'none'}"
        )
    output = outputs[name]
    if output.digits and not written:
        return f"reads '{ref}', which is shown to significant digits; give the layer an output of its own with decimals"
    if bool(output.size) != (wanted == "vector"):
        shape = f"a vector of {output.size}" if output.size else "one number"
        use = "xs/ys" if output.size else "a vertex"
        return (
            f"reads '{ref}' as {'a vector' if wanted == 'vector' else 'one number'}, but it is {shape} "
            f"(for {use}){did_you_mean(name, fitting)} Its {what}: {', '.join(fitting) or 'none'}"
        )
    return None


def _where(layer: Layer, view, root: Path | None) -> str:
    """The layer's line as the author sees it (else the view's class)."""
    try:
        file, line = layer.where or (inspect.getsourcefile(type(view)), inspect.getsourcelines(type(view))[1])
    except (OSError, TypeError):
        return f"figure {type(view).__name__}"
    return str(code_loc(file, line, root))


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
