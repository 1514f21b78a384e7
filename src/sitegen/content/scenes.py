"""Scene blocks: the author's declaration of an interactive figure, parsed line by line.

```scene
model: collision
id: collision
slider m1: 0.5..5 step 0.5 default 1
fix e: 1
effects: restitution_law
readouts: v1f v2f
caption: Two carts meet on a frictionless track.
```
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from fractions import Fraction

from ..errors import AuthorError, SourceLoc, did_you_mean

KEYS = ("model", "id", "slider", "choice", "fix", "effects", "readouts", "figure", "caption", "animate", "numerics")
_LINE = re.compile(r"^(?P<key>[A-Za-z_]+)(?:\s+(?P<name>[A-Za-z_][A-Za-z0-9_]*))?\s*:\s*(?P<value>.*?)\s*$")
# A number, or NaN/infinity, which are read as numbers so that the error can say what is wrong with them.
_NUMBER = r"[-+]?(?:(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?|(?i:nan|inf(?:inity)?)(?!\w))"
_SLIDER = re.compile(
    rf"^(?P<lo>{_NUMBER})\s*\.\.\s*(?P<hi>{_NUMBER})\s+step\s+(?P<step>{_NUMBER}(?:\s*/\s*\d+)?)\s+default\s+(?P<default>{_NUMBER})$"
)
_LIST = re.compile(rf"^(?P<values>{_NUMBER}(?:\s*,\s*{_NUMBER})+)\s+default\s+(?P<default>{_NUMBER})$")
_CHOICE = re.compile(r"^(?P<options>[\w-]+(?:\s*\|\s*[\w-]+)+)\s+default\s+(?P<default>[\w-]+)$")
_ID = re.compile(r"^[a-z][a-z0-9-]*$")
SLIDER_FORM = (
    "slider NAME: MIN..MAX step STEP default VALUE, e.g. 'slider m1: 0.5..5 step 0.5 default 1' "
    "(a step may be a fraction: 'step 1/60'), or slider NAME: V1, V2, ... default VALUE"
)
CHOICE_FORM = "choice NAME: OPTION | OPTION ... default OPTION, e.g. 'choice force: spring | drag default spring'"
NUMERICS_FORM = "numerics: KEY VALUE, KEY VALUE ..., e.g. 'numerics: method DOP853, rtol 1e-8, tolerance 1e-6'"
_SETTING = re.compile(r"^(?P<key>[A-Za-z_]+)\s+(?P<value>[\w.+-]+)$")


@dataclass(frozen=True)
class SliderSpec:
    """One slider as the author wrote it: evenly spaced (lo..hi step) or a list of stops."""

    param: str
    lo: Decimal
    hi: Decimal
    step: Decimal | Fraction  # a Fraction when the author wrote one, e.g. 1/60 (frames of an animation)
    default: Decimal
    loc: SourceLoc
    listed: tuple[Decimal, ...] = ()  # the stops, when the author listed them


@dataclass(frozen=True)
class ChoiceSpec:
    """A radio group: the options offered (names of the model's choices) and the default."""

    param: str
    options: tuple[str, ...]
    default: str
    loc: SourceLoc


@dataclass(frozen=True)
class FixedSpec:
    """A parameter held at one value in this scene."""

    param: str
    value: Decimal
    loc: SourceLoc


@dataclass(frozen=True)
class SceneSpec:
    """A scene block as written: what to compute, which sliders, what to show."""

    loc: SourceLoc
    id: str
    model: str
    sliders: tuple[SliderSpec | ChoiceSpec, ...] = ()  # in the order written
    fixed: tuple[FixedSpec, ...] = ()
    effects: tuple[str, ...] = ()
    readouts: tuple[str, ...] = ()
    figure: str | None = None
    caption: str = ""
    animate: str | None = None  # a slider stepped by a play button
    numerics: tuple[tuple[str, str], ...] = ()  # (setting, value) as written, checked against the model later
    lines: tuple[tuple[str, SourceLoc], ...] = ()  # (key, place) of every line, to point errors at
    unread: tuple[str, ...] = ()  # parameters of control lines that could not be read (already errors)

    def loc_of(self, key: str) -> SourceLoc:
        """Where the author wrote `key` (the block's opening line if nowhere)."""
        return next((loc for k, loc in self.lines if k == key), self.loc)


def parse_scene_block(body: list[str], fence: SourceLoc) -> tuple[SceneSpec | None, list[AuthorError]]:
    """Parse the lines between the fences; return the spec (None if unusable) and every error."""
    errors: list[AuthorError] = []
    fields: dict[str, object] = {"sliders": [], "fixed": [], "lines": []}
    for offset, text in enumerate(body, start=1):
        loc = SourceLoc(fence.path, fence.line + offset)
        if not text.strip() or text.lstrip().startswith("#"):
            continue
        try:
            _parse_line(text.strip(), loc, fields)
        except AuthorError as error:
            errors.append(error)
            line = _LINE.match(text.strip())
            if line and line["name"]:  # a control already reported: nothing else is said of its parameter
                fields.setdefault("unread", []).append(line["name"])
    if "model" not in fields:
        errors.append(AuthorError(fence, "scene block has no 'model:' line; add e.g. 'model: collision'"))
        return None, errors
    scene_id = str(fields.get("id", fields["model"]))
    errors = [AuthorError(e.loc, e.message, scene_id) for e in errors]
    spec = SceneSpec(
        loc=fence,
        id=scene_id,
        model=str(fields["model"]),
        sliders=tuple(fields["sliders"]),
        fixed=tuple(fields["fixed"]),
        effects=tuple(fields.get("effects", ())),
        readouts=tuple(fields.get("readouts", ())),
        figure=fields.get("figure"),
        caption=str(fields.get("caption", "")),
        animate=fields.get("animate"),
        numerics=fields.get("numerics", ()),
        lines=tuple(fields["lines"]),
        unread=tuple(fields.get("unread", ())),
    )
    return spec, errors


def _parse_line(text: str, loc: SourceLoc, fields: dict) -> None:
    match = _LINE.match(text)
    if not match:
        raise AuthorError(loc, f"cannot read '{text}'; a scene line is 'KEY: VALUE' with KEY one of {', '.join(KEYS)}")
    key, name, value = match["key"], match["name"], match["value"]
    if key not in KEYS:
        raise AuthorError(
            loc, f"unknown directive '{key}'{did_you_mean(key, KEYS)} A scene block takes {', '.join(KEYS)}"
        )
    needs_name = key in ("slider", "choice", "fix")
    if needs_name != bool(name):
        forms = {"slider": SLIDER_FORM, "choice": CHOICE_FORM, "fix": "fix NAME: VALUE"}
        form = forms.get(key, f"{key}: VALUE")
        raise AuthorError(loc, f"malformed '{key}' line; write {form}")
    fields["lines"].append((f"{key} {name}" if name else key, loc))
    if key == "slider":
        fields["sliders"].append(_parse_slider(name, value, loc))
    elif key == "choice":
        fields["sliders"].append(_parse_choice(name, value, loc))
    elif key == "fix":
        fields["fixed"].append(FixedSpec(name, _decimal(value, loc, f"fixed value of '{name}'"), loc))
    elif key in ("effects", "readouts"):
        fields[key] = tuple(value.replace(",", " ").split())
    elif key == "id" and not _ID.match(value):
        raise AuthorError(loc, f"scene id '{value}' must be lower-case letters, digits and '-', starting with a letter")
    elif key in fields:
        raise AuthorError(loc, f"'{key}' is given twice in one scene block")
    elif key == "numerics":
        fields[key] = _parse_numerics(value, loc)
    else:
        fields[key] = value


def _parse_slider(name: str, value: str, loc: SourceLoc) -> SliderSpec:
    listed = _LIST.match(value)
    if listed:
        stops = tuple(_decimal(v.strip(), loc, f"slider '{name}' stop") for v in listed["values"].split(","))
        return SliderSpec(
            name,
            min(stops),
            max(stops),
            Decimal(0),
            _decimal(listed["default"], loc, f"slider '{name}' default"),
            loc,
            stops,
        )
    match = _SLIDER.match(value)
    if not match:
        raise AuthorError(loc, f"malformed slider '{name}': '{value}'; write {SLIDER_FORM}")
    words = {"lo": "min", "hi": "max", "default": "default"}
    lo, hi, default = (_decimal(match[k], loc, f"slider '{name}' {words[k]}") for k in words)
    return SliderSpec(name, lo, hi, _step(match["step"], name, loc), default, loc)


def _step(text: str, name: str, loc: SourceLoc) -> Decimal | Fraction:
    """A slider's step: a decimal, or a fraction such as 1/60 whose stops no decimal can hold."""
    number, _, divisor = text.partition("/")
    step = _decimal(number.strip(), loc, f"slider '{name}' step")
    if not divisor:
        return step
    if int(divisor) == 0:
        raise AuthorError(loc, f"slider '{name}' step '{text}' divides by zero")
    return Fraction(step) / int(divisor)


def _parse_numerics(value: str, loc: SourceLoc) -> tuple[tuple[str, str], ...]:
    """(setting, value) pairs of a `numerics:` line, in the order written; the model checks them."""
    pairs: list[tuple[str, str]] = []
    for item in value.split(","):
        match = _SETTING.match(item.strip())
        if not match:
            raise AuthorError(loc, f"malformed numerics setting '{item.strip()}'; write {NUMERICS_FORM}")
        if match["key"] in dict(pairs):
            raise AuthorError(loc, f"numerics setting '{match['key']}' is given twice")
        pairs.append((match["key"], match["value"]))
    return tuple(pairs)


def _parse_choice(name: str, value: str, loc: SourceLoc) -> ChoiceSpec:
    match = _CHOICE.match(value)
    if not match:
        raise AuthorError(loc, f"malformed choice '{name}': '{value}'; write {CHOICE_FORM}")
    return ChoiceSpec(name, tuple(o.strip() for o in match["options"].split("|")), match["default"], loc)


def _decimal(text: str, loc: SourceLoc, what: str) -> Decimal:
    try:
        number = Decimal(text)
    except InvalidOperation:
        raise AuthorError(loc, f"{what} '{text}' is not a number") from None
    if not number.is_finite():
        raise AuthorError(loc, f"{what} must be a finite number, not '{text}'")
    return number
