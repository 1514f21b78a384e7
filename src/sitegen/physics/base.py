"""The small numerical API every model follows: declared parameters, outputs, effects and a
vectorised evaluation. Physics only: nothing here knows about pages or plotting."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar, Iterable, Mapping

import numpy as np


@dataclass(frozen=True)
class Param:
    """A model input: its name, how it is labelled, its unit, default and physical domain."""

    name: str
    symbol: str  # HTML fragment, e.g. "F<sub>pk</sub>"
    unit: str
    default: float
    lo: float = -math.inf
    hi: float = math.inf
    lo_open: bool = False  # True when the domain is lo < x rather than lo <= x
    description: str = ""
    choices: tuple[str, ...] = ()  # a discrete parameter: its value is the index of one of these
    effect: str = ""  # the effect this parameter belongs to; usable only when the scene enables it

    @classmethod
    def choice(cls, name: str, symbol: str, choices: tuple[str, ...], default: str, description: str = "") -> "Param":
        """A parameter that takes one of a few named values, coded 0, 1, ..."""
        return cls(name, symbol, "", float(choices.index(default)), 0.0, float(len(choices) - 1), False, description, choices)

    def with_effect(self, effect: str) -> "Param":
        """The same parameter, marked as belonging to `effect`."""
        return replace(self, effect=effect)

    def contains(self, value):
        """Whether `value` (a number or an array) lies in the model's domain; NaN and ±inf never do."""
        above = np.greater(value, self.lo) if self.lo_open else np.greater_equal(value, self.lo)
        inside = np.isfinite(value) & above & np.less_equal(value, self.hi)
        return inside & np.equal(np.round(value), value) if self.choices else inside

    def domain_text(self) -> str:
        """The domain written for an author, e.g. `m1 > 0` or `0 <= e <= 1`."""
        low = f"{_num(self.lo)} {'<' if self.lo_open else '<='} " if self.lo > -math.inf else ""
        high = f" <= {_num(self.hi)}" if self.hi < math.inf else ""
        if not low and not high:
            return f"{self.name} any real number"
        if low and not high:
            return f"{self.name} {'>' if self.lo_open else '>='} {_num(self.lo)}"
        return f"{low}{self.name}{high}"


@dataclass(frozen=True)
class Output:
    """A computed quantity: its label, unit, the parameters it depends on and how it is shown.

    A number output is shown with `decimals` digits; a text output is an index into `labels`.
    A vector output (`size` > 0) gives `size` numbers per parameter point, e.g. the geometry of a
    curve; a ragged one pads with NaN after its last element. Where the physics is singular (±inf)
    or the quantity does not exist (NaN) an output may be non-finite if it says how to show that in
    words (`special`, e.g. "∞" or "—"); any other non-finite value fails the build.
    """

    name: str
    label: str  # HTML fragment
    unit: str
    deps: tuple[str, ...]
    decimals: int = 3
    labels: tuple[str, ...] = ()
    size: int = 0
    ragged: bool = False
    special: str = ""
    effect: str = ""  # the effect this output belongs to; shown only when the scene enables it

    @property
    def is_text(self) -> bool:
        """Whether the output is a choice among fixed phrases rather than a number."""
        return bool(self.labels)


class Model:
    """Base class: the public `evaluate` validates, the subclass's `_evaluate` computes."""

    name: ClassVar[str]
    title: ClassVar[str]
    params: ClassVar[tuple[Param, ...]]
    outputs: ClassVar[tuple[Output, ...]]
    effects: ClassVar[tuple[str, ...]] = ()
    # Models that are costly per point (an ODE solve each) set this: their grids are split into
    # blocks of at most this many points, so that parallel builds can spread one scene's work.
    chunk_stops: ClassVar[int | None] = None

    @classmethod
    def param(cls, name: str) -> Param:
        """The declared parameter called `name`."""
        return next(p for p in cls.params if p.name == name)

    @classmethod
    def output(cls, name: str) -> Output:
        """The declared output called `name`."""
        return next(o for o in cls.outputs if o.name == name)

    @classmethod
    def defaults(cls) -> dict[str, float]:
        """Every parameter at its default value."""
        return {p.name: p.default for p in cls.params}

    def evaluate(
        self,
        inputs: Mapping[str, object],
        wanted: Iterable[str] | None = None,
        effects: Iterable[str] = (),
    ) -> dict[str, np.ndarray]:
        """Compute the `wanted` outputs (all by default) for broadcastable arrays of inputs."""
        known = {p.name for p in self.params}
        unknown = sorted(set(inputs) - known)
        if unknown:
            raise ValueError(f"unknown parameter(s) {unknown}; {self.name} takes {sorted(known)}")
        values = {**self.defaults(), **inputs}
        arrays = dict(zip(values, np.broadcast_arrays(*(np.asarray(v, float) for v in values.values()))))
        for p in self.params:
            if not np.all(p.contains(arrays[p.name])):
                raise ValueError(f"`{p.name}` must satisfy {p.domain_text()}")
        names = tuple(wanted) if wanted is not None else tuple(o.name for o in self.outputs)
        missing = sorted(set(names) - {o.name for o in self.outputs})
        if missing:
            raise ValueError(f"unknown output(s) {missing} of model {self.name}")
        offered = set(self.effects)
        if set(effects) - offered:
            raise ValueError(f"unknown effect(s) {sorted(set(effects) - offered)} of model {self.name}")
        return self._evaluate(arrays, names, frozenset(effects))

    def _evaluate(
        self, x: Mapping[str, np.ndarray], wanted: tuple[str, ...], effects: frozenset[str]
    ) -> dict[str, np.ndarray]:
        raise NotImplementedError


def _num(value: float) -> str:
    return f"{value:g}"
