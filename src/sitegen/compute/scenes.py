"""Resolving a scene block against the model registry: every author mistake becomes an error."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

from ..content.scenes import CHOICE_FORM, ChoiceSpec, SceneSpec, SliderSpec
from ..errors import AuthorError, SourceLoc, did_you_mean
from ..physics import Model, Output
from ..physics.numerics import configure
from .grid import CHOICE, LIST, Axis, as_decimal

MAX_STOPS = 100_001  # per slider; more is almost certainly a typo in the step


@dataclass(frozen=True)
class ResolvedScene:
    """A scene ready to compute: its model, slider axes, fixed values, effects and readouts."""

    spec: SceneSpec
    model: Model
    axes: tuple[Axis, ...]
    default_stops: tuple[int, ...]
    fixed: tuple[tuple[str, float], ...]
    effects: frozenset[str]
    readouts: tuple[Output, ...]

    @property
    def id(self) -> str:
        """The scene's id, unique on its page."""
        return self.spec.id

    def axis_index(self, param: str) -> int | None:
        """Position of the slider for `param`, or None when it has no slider."""
        return next((i for i, a in enumerate(self.axes) if a.param == param), None)

    def base_values(self) -> dict[str, float]:
        """Every parameter at the value the scene starts from (sliders at their defaults)."""
        values = {**self.model.defaults(), **dict(self.fixed)}
        for axis, stop in zip(self.axes, self.default_stops):
            values[axis.param] = float(axis.stop(stop))
        return values


def resolve_scene(
    spec: SceneSpec, models: Mapping[str, type[Model]], broken: Mapping[str, SourceLoc] | None = None
) -> tuple[ResolvedScene | None, list[AuthorError]]:
    """Check a scene block against its model; return the resolved scene or every error found.

    `broken`: plugins that failed to load, by name (a scene naming one is told where it failed)."""
    if spec.model not in models and spec.model in (broken or {}):
        message = f"model '{spec.model}' could not be loaded: see the error at {broken[spec.model]}"
        return None, [AuthorError(spec.loc_of("model"), message, spec.id)]
    if spec.model not in models:
        message = (
            f"unknown model '{spec.model}'{_suggest(spec.model, models)} Known models: {', '.join(sorted(models))}"
        )
        return None, [AuthorError(spec.loc_of("model"), message, spec.id)]
    model = models[spec.model]()
    errors: list[AuthorError] = []

    def error(key: str, message: str) -> None:
        errors.append(AuthorError(spec.loc_of(key), message, spec.id))

    effects = frozenset(spec.effects) & frozenset(model.effects)  # the scene's effects that the model offers
    axes, stops = _controls(spec, model, effects, errors)
    reported = set(spec.unread) | {c.param for c in spec.sliders} - {a.param for a in axes}
    _check_animation(spec, axes, error, reported)
    fixed = _fixed_values(spec, model, {a.param for a in axes}, effects, error)
    _check_effects_offered(spec, model, error)
    _check_params_need_their_effects(model, [a.param for a in axes] + [name for name, _ in fixed], effects, error)
    _check_params_not_replaced(spec, model, effects, errors)
    settings = _settings(spec, model, effects, error)
    known = {o.name: o for o in model.outputs if not o.effect or o.effect in effects}
    _check_readouts(spec, model, known, error)
    if errors:
        return None, errors
    readouts = (
        tuple(known[n] for n in spec.readouts) if spec.readouts else tuple(o for o in known.values() if not o.size)
    )
    scene = ResolvedScene(spec, type(model)(settings), tuple(axes), tuple(stops), tuple(fixed), effects, readouts)
    return scene, []


def _controls(spec: SceneSpec, model: Model, effects: frozenset[str], errors: list) -> tuple[list[Axis], list[int]]:
    """Each slider's and choice's grid and default stop (an error for each control that is wrong)."""
    axes, stops = [], []
    seen: set[str] = set()
    for control in spec.sliders:
        if isinstance(control, ChoiceSpec):
            axis, problem = _choice_axis(control, model, seen)
            what = "choice"
        else:
            axis, problem = _slider_axis(control, model, seen, effects)  # (an effect may widen a domain)
            what = "slider"
        seen.add(control.param)
        if problem:
            errors.append(AuthorError(control.loc, f"{what} '{control.param}' {problem}", spec.id))
            continue
        axes.append(axis)
        stops.append(axis.index_of(_default_code(control, model)))
    return axes, stops


def _check_animation(spec: SceneSpec, axes: list[Axis], error, reported: set[str]) -> None:
    """What `animate:` names must be one of the scene's sliders (unless its control is `reported` already)."""
    sliders = [a.param for a in axes if a.kind != CHOICE]
    if spec.animate is not None and spec.animate not in sliders and spec.animate not in reported:
        error("animate", f"animate '{spec.animate}' is not one of the scene's sliders: {', '.join(sliders) or 'none'}")


def _fixed_values(
    spec: SceneSpec, model: Model, controlled: set[str], effects: frozenset[str], error
) -> list[tuple[str, float]]:
    """The `fix` lines that name a parameter without a control, at a value in its domain."""
    fixed = []
    for item in spec.fixed:
        if item.param not in {p.name for p in model.params}:
            problem = _no_such_param(item.param, model)
        elif item.param in controlled:
            problem = "also has a slider; keep the slider or the fixed value"
        else:
            problem = _domain_problem(model, item.param, item.value, "value", effects)
        if problem:
            error(f"fix {item.param}", f"fixed '{item.param}' {problem}")
        else:
            fixed.append((item.param, float(item.value)))
    return fixed


def _check_effects_offered(spec: SceneSpec, model: Model, error) -> None:
    """Every effect the scene asks for is one the model offers."""
    offered = set(model.effects)
    for effect in spec.effects:
        if effect not in offered:
            what = f"offers: {', '.join(model.effects)}" if model.effects else "offers no effects"
            error("effects", f"model '{model.name}' has no effect '{effect}'{_suggest(effect, offered)} It {what}")


def _check_params_need_their_effects(model: Model, names: list[str], effects: frozenset[str], error) -> None:
    """A parameter that belongs to an effect may be set only when the scene shows that effect."""
    for name in names:
        needs = model.param(name).effect
        if needs and needs not in effects:
            error("effects", f"parameter '{name}' belongs to effect '{needs}'; add it to the scene's 'effects:' line")


def _check_params_not_replaced(spec: SceneSpec, model: Model, effects: frozenset[str], errors: list) -> None:
    """No control for a parameter that one of the scene's effects takes the place of."""
    for control in [*spec.sliders, *spec.fixed]:
        if control.param in {p.name for p in model.params} and (
            replacing := model.param(control.param).unused_under(effects)
        ):
            errors.append(
                AuthorError(
                    control.loc,
                    f"parameter '{control.param}' is not used with effect '{replacing}', which "
                    "takes its place; remove its control",
                    spec.id,
                )
            )


def _check_readouts(spec: SceneSpec, model: Model, known: dict[str, Output], error) -> None:
    """Every readout is an output of the model under the scene's effects."""
    for name in spec.readouts:
        if name not in known:
            error(
                "readouts",
                f"model '{model.name}' has no output '{name}'{_suggest(name, known)} Its outputs: {', '.join(known)}",
            )


def _settings(spec: SceneSpec, model: Model, effects: frozenset[str], error):
    """The model's numerical settings with the scene's `numerics:` line applied (errors reported)."""
    if not spec.numerics:
        return model.settings
    if model.numerics is None or not model.is_numerical(effects):
        what = "this scene, with these effects," if model.numerics is not None else "everything"
        error("numerics", f"model '{model.name}' computes {what} in closed form; remove the 'numerics:' line")
        return model.settings
    try:
        return configure(model.numerics, model.methods, dict(spec.numerics))
    except ValueError as problem:
        error("numerics", f"numerics: {problem}")
        return model.settings


def _slider_axis(
    s: SliderSpec, model: Model, seen: set[str], effects: frozenset[str]
) -> tuple[Axis | None, str | None]:
    """The slider's grid, or what is wrong with it (said after "slider 'NAME' ")."""
    problem = (
        _control_problem(s.param, model, seen)
        or ("is a choice of the model; write it as " + CHOICE_FORM if model.param(s.param).choices else None)
        or (_list_problem(s, model, effects) if s.listed else _range_problem(s, model, effects))
    )
    if problem:
        return None, problem
    if s.listed:
        return Axis(s.param, s.listed, LIST), None
    return Axis.evenly(s.param, s.lo, s.step, int((Fraction(s.hi) - Fraction(s.lo)) / Fraction(s.step)) + 1), None


def _choice_axis(c: ChoiceSpec, model: Model, seen: set[str]) -> tuple[Axis | None, str | None]:
    """The radio group's grid (codes of the chosen options), or what is wrong with it."""
    problem = _control_problem(c.param, model, seen)
    if problem:
        return None, problem
    offered = model.param(c.param).choices
    if not offered:
        return None, f"is not a choice of model '{model.name}'; give it a slider"
    for option in (*c.options, c.default):
        if option not in offered:
            return None, f"has no option '{option}'{_suggest(option, offered)} Options: {' | '.join(offered)}"
    if c.default not in c.options:
        return None, f"default '{c.default}' is not among the options offered: {' | '.join(c.options)}"
    if len(set(c.options)) != len(c.options):
        return None, "lists an option twice"
    codes = tuple(Decimal(offered.index(o)) for o in c.options)
    return Axis(c.param, codes, CHOICE, c.options), None


def _default_code(control: SliderSpec | ChoiceSpec, model: Model) -> Decimal:
    if isinstance(control, ChoiceSpec):
        return Decimal(model.param(control.param).choices.index(control.default))
    return control.default


def _control_problem(name: str, model: Model, seen: set[str]) -> str | None:
    if name not in {p.name for p in model.params}:
        return _no_such_param(name, model)
    if name in seen:
        return "appears twice; keep one control per parameter"
    return None


def _list_problem(s: SliderSpec, model: Model, effects: frozenset[str]) -> str | None:
    if list(s.listed) != sorted(set(s.listed)):
        return "stops must be listed in increasing order, each once"
    for value in s.listed:
        if problem := _domain_problem(model, s.param, value, "stop", effects):
            return problem
    if s.default not in s.listed:
        return f"default {s.default} is not one of the listed stops"
    if len(s.listed) > MAX_STOPS:
        return f"has {len(s.listed)} stops, more than {MAX_STOPS}"
    return None


def _range_problem(s: SliderSpec, model: Model, effects: frozenset[str]) -> str | None:
    """What is wrong with an evenly spaced slider (said after "slider 'NAME' "), or None."""
    if s.step <= 0:
        return f"step {s.step} must be positive"
    if s.lo >= s.hi:
        return f"min {s.lo} must be below max {s.hi}"
    lo, step = Fraction(s.lo), Fraction(s.step)  # exact, whether the step is a decimal or a fraction like 1/60
    count = (Fraction(s.hi) - lo) / step
    if count.denominator != 1:
        return f"range {s.lo}..{s.hi} is not a whole number of steps of {s.step}; max {_stop(s, int(count))} would be"
    if count + 1 > MAX_STOPS:  # (the count itself can have hundreds of digits: not worth printing)
        return f"has more than {MAX_STOPS} stops from {s.lo} to {s.hi} in steps of {s.step}; use a larger step"
    for bound, value in (("min", s.lo), ("max", s.hi)):
        if problem := _domain_problem(model, s.param, value, bound, effects):
            return problem
    k = (Fraction(s.default) - lo) / step
    if not (s.lo <= s.default <= s.hi) or k.denominator != 1:
        below = max(0, min(int(k), int(count)))
        near = sorted({below, min(below + 1, int(count))})
        return (
            f"default {s.default} is not a stop of {s.lo}..{s.hi} step "
            f"{s.step}; nearest stops: {', '.join(_stop(s, n) for n in near)}"
        )
    return None


def _stop(s: SliderSpec, k: int) -> str:
    """Stop k of an evenly spaced slider as an author would write it (to 6 decimals and '…' if no decimal holds it)."""
    if isinstance(s.step, Decimal):
        return str(s.lo + s.step * k)
    exact = as_decimal(Fraction(s.lo) + s.step * k)
    return str(exact) if isinstance(exact, Decimal) else f"{float(exact):.6f}…"


def _no_such_param(name: str, model: Model) -> str:
    names = [p.name for p in model.params]
    return f"names no parameter of model '{model.name}'{_suggest(name, names)} Its parameters: {', '.join(names)}"


def _domain_problem(
    model: Model, name: str, value: Decimal, what: str, effects: frozenset[str] = frozenset()
) -> str | None:
    """What is wrong with `value` for parameter `name` under the scene's effects (said after the subject), or None."""
    param = model.param(name).under(effects)
    if param.contains(float(value)):
        return None
    widen = "".join(
        f" (effect '{effect}' allows {'larger values' if hi == float('inf') else f'up to {_bound(hi)}'})"
        for effect, hi in param.wider
        if float(value) <= hi
    )
    if float(value) > param.hi:
        return f"{what} {value} exceeds the model's bound {_bound(param.hi)}{widen}"
    return f"{what} {value} is outside the model's domain {param.domain_text()}"


def _bound(value: float) -> str:
    return f"{value:.1f}" if value == int(value) else f"{value:g}"


def _suggest(name: str, choices) -> str:
    """A " — did you mean 'x'?" for a near miss, else just the end of the sentence."""
    return did_you_mean(name, choices)
