"""The models' reference, written from the same declarations the build checks scenes against:
each model's parameters (symbol, unit, domain, default), outputs (unit, what they depend on),
effects, numerical settings and figures. `sitegen models` prints it; docs/models.md is its text
for the built-in models (`sitegen models --builtin > docs/models.md`)."""

from __future__ import annotations

import math
import re
from html import unescape

from .physics.base import Model, Output, Param
from .registry import Registry

HEADER = (
    "# Models\n\nEvery model a scene may name (`model: NAME`), from its declarations. This file is written by\n"
    "`sitegen models --builtin > docs/models.md`; a test checks that it is up to date.\n"
)


def models_reference(registry: Registry, names: list[str] | None = None, header: bool = True) -> str:
    """Markdown (readable as plain text) for the models `names` (default: all, by name)."""
    chosen = sorted(registry.models) if names is None else names
    parts = [HEADER] if header and names is None else []
    parts += [model_section(registry, name) for name in chosen]
    return "\n".join(parts)


def model_section(registry: Registry, name: str) -> str:
    """One model's section: what it is, where it comes from, its effects, numerics, parameters, outputs."""
    model = registry.models[name]
    origin = registry.origins.get(f"model {name}", "")
    figures = [f for f in sorted(registry.figures) if registry.origins.get(f"figure {f}") == origin]
    lines = [f"## {name}: {plain(model.title)}", ""]
    lines.append(f"- source: {origin}")
    lines.append(f"- figures: {', '.join(figures) if figures else 'none'}")
    lines.append(f"- effects: {', '.join(model.effects) if model.effects else 'none'}")
    lines.append(f"- numerical settings: {_numerics(model)}")
    if model.chunk_stops:
        lines.append(f"- work is split into blocks of at most {model.chunk_stops:,} stops")
    lines += ["", "| parameter | symbol | unit | domain | default | effect |", "|---|---|---|---|---|---|"]
    lines += [_param_row(p) for p in model.params]
    lines += ["", "| output | label | unit | depends on | shown as | effect |", "|---|---|---|---|---|---|"]
    lines += [_output_row(o) for o in model.outputs]
    return "\n".join(lines) + "\n"


def _numerics(model: type[Model]) -> str:
    if model.numerics is None:
        return "none (closed forms: exact to the shown digit)"
    methods = "; ".join(f"{m} ({_settings(taken)})" for m, taken in model.methods.items())
    metric = f"; error measured as {model.error_metric}" if model.error_metric else ""
    return f"{model.numerics.text()}{metric}; a scene may choose: {methods or model.numerics.method}"


def _settings(taken: dict) -> str:
    """The settings a method takes, at the values a scene switching to it starts from."""
    parts = [f"{key} {value}" if value is not None else f"{key}: the method's own rule" for key, value in taken.items()]
    return ", ".join(parts) or "tolerance only"


def _param_row(p: Param) -> str:
    if p.choices:
        domain, default = "one of " + ", ".join(p.choices), p.choices[int(p.default)]
    else:
        domain = p.domain_text() + "".join(f" (up to {_num(hi)} with {effect})" for effect, hi in p.wider)
        default = _num(p.default)
    effect = "; ".join(filter(None, [p.effect, f"unused with {', '.join(p.replaced_in)}" if p.replaced_in else ""]))
    return _row(p.name, plain(p.symbol), p.unit, domain, default, effect)


def _output_row(o: Output) -> str:
    deps = ", ".join(o.deps) or "nothing"
    deps += "".join(f"; with {effect} also {', '.join(extra)}" for effect, extra in o.deps_with)
    if o.labels:
        shown = f"one of {len(o.labels)} phrases"
    elif o.size:
        shown = f"{'up to ' if o.ragged else ''}{o.size} numbers, {o.decimals} decimals"
    elif o.digits:
        shown = f"{o.digits} significant digits, unit prefix per value" + (f" (0 below {o.floor:g})" if o.floor else "")
    else:
        shown = f"{o.decimals} decimals"
    if o.special:
        shown += f"; {plain(o.special)} where it does not exist or is infinite"
        why = o.why or (f"why: {o.why_from}" if o.why_from else "")
        shown += f" ({why})" if why else ""
    return _row(o.name, plain(o.label), o.unit, deps, shown, o.effect)


def _row(*cells: str) -> str:
    return "| " + " | ".join(c.replace("|", "\\|") if c else "" for c in cells) + " |"


def plain(html: str) -> str:
    """An HTML fragment (a symbol, a label) as text: v<sub>1</sub> -> v_1, 10<sup>3</sup> -> 10^3."""
    text = re.sub(r"<sub>(.*?)</sub>", r"_\1", html)
    text = re.sub(r"<sup>(.*?)</sup>", r"^\1", text)
    return unescape(re.sub(r"<[^>]+>", "", text))


def _num(value: float) -> str:
    return "∞" if value == math.inf else "−∞" if value == -math.inf else f"{value:g}"
