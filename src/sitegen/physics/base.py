"""The small numerical API every model follows: declared parameters, outputs, effects and a
vectorised evaluation. Physics only: nothing here knows about pages or plotting."""

from __future__ import annotations

import dataclasses
import inspect
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np

from ..errors import caller_line
from .numerics import Measurement, Numerics


class UnknownName(KeyError):
    """A parameter or output name the model does not declare (its message says which it has)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


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
    replaced_in: tuple[str, ...] = ()  # effects that take this parameter's place: with one on it is unused
    wider: tuple[tuple[str, float], ...] = ()  # (effect, hi): a larger upper bound while that effect is on

    @classmethod
    def choice(cls, name: str, symbol: str, choices: tuple[str, ...], default: str, description: str = "") -> Param:
        """A parameter that takes one of a few named values, coded 0, 1, ..."""
        return cls(
            name, symbol, "", float(choices.index(default)), 0.0, float(len(choices) - 1), False, description, choices
        )

    def with_effect(self, effect: str) -> Param:
        """The same parameter, marked as belonging to `effect`."""
        return replace(self, effect=effect)

    def replaced_by(self, *effects: str) -> Param:
        """The same parameter, unused (and not to be given a control) when one of `effects` is on."""
        return replace(self, replaced_in=self.replaced_in + effects)

    def widened_by(self, effect: str, hi: float) -> Param:
        """The same parameter, allowed up to `hi` when `effect` is on (e.g. e > 1 when explosive)."""
        return replace(self, wider=self.wider + ((effect, hi),))

    def under(self, effects: Iterable[str]) -> Param:
        """The parameter with the domain it has when `effects` are enabled."""
        on = set(effects)
        his = [hi for effect, hi in self.wider if effect in on]
        return replace(self, hi=max(his), wider=()) if his and max(his) > self.hi else self

    def unused_under(self, effects: Iterable[str]) -> str:
        """The enabled effect that replaces this parameter, or "" when the parameter is in use."""
        return next((effect for effect in self.replaced_in if effect in set(effects)), "")

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

    `deps` are the parameters it depends on with no effect enabled (parameters that belong to an
    effect may be listed too: they only get controls when their effect is on). `deps_with` adds
    the parameters an effect brings in, e.g. the bar's mass to the lever's rotation outputs when
    `bar_mass` is on; a parameter `replaced_by` an enabled effect drops out. `Model.deps_of` gives
    the result for a scene's effects.

    A number output is shown with `decimals` digits, or, where its values span decades, with `digits`
    significant digits (chosen from its accuracy) and a unit prefix or power of ten per value; a text
    output is an index into `labels`.
    A vector output (`size` > 0) gives `size` numbers per parameter point, e.g. the geometry of a
    curve; a ragged one pads with NaN after its last element. Where the physics is singular (±inf)
    or the quantity does not exist (NaN) an output may be non-finite if it says how to show that in
    words (`special`, e.g. "∞" or "—"); any other non-finite value fails the build. Where it shows "—"
    the model says why: `why`, one phrase, or `why_from`, a text output whose phrase at the same point
    is the reason.
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
    digits: int = 0  # significant digits (0: `decimals` decimals)
    floor: float = 0.0  # with `digits`: below this magnitude (the output's accuracy) a value shows as 0
    why: str = ""  # why the value does not exist where the output shows `special`
    why_from: str = ""  # a text output giving that reason per point (instead of `why`)
    effect: str = ""  # the effect this output belongs to; shown only when the scene enables it
    deps_with: tuple[tuple[str, tuple[str, ...]], ...] = ()  # (effect, extra deps while it is on)
    # Its exact form (physics/structure.py), or a function of the scene's effects giving it; None:
    # the output is tabulated at every stop of its dependencies.
    structure: object = None
    # Where the Output was declared (file, line): the line of the `Output(...)` call, which the build names
    # when the output breaks its contract (a dep it leaves out). Set by itself; kept through `replace`.
    where: tuple[str, int] | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if self.where is None:
            object.__setattr__(self, "where", caller_line(inspect.currentframe(), __file__))

    def __reduce__(self):
        # Pickled (to a worker process) without its structure, whose kernels are local functions: a
        # worker only evaluates the model; structures are compiled and verified in the build's process.
        fields = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        return _output_from_fields, ({**fields, "structure": None},)

    def structure_for(self, effects: frozenset[str]):
        """The declared exact form of this output under the scene's effects (None: tabulate per stop)."""
        return self.structure(effects) if callable(self.structure) else self.structure

    @property
    def is_text(self) -> bool:
        """Whether the output is a choice among fixed phrases rather than a number."""
        return bool(self.labels)


def _output_from_fields(fields: dict) -> Output:
    return Output(**fields)


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
    # A model that computes by a numerical method declares its default settings (docs/physics/),
    # the methods a scene may choose with the settings each takes, and the error its check measures.
    numerics: ClassVar[Numerics | None] = None
    methods: ClassVar[dict[str, dict[str, object]]] = {}  # method: the settings it takes, at their defaults
    error_metric: ClassVar[str] = ""
    accuracy_stops: ClassVar[int] = 16  # stops its accuracy is measured at (fewer for an ODE solve per point)
    # What `sitegen bench` measures of the methods: each over a ladder of its setting (rtol, nodes or step) at
    # the stops the build checks. A ladder here replaces the default one of a setting for every method
    # (`{"rtol": (1e-4, 1e-6, 1e-8)}`) or for one method (`{"RK45": {"rtol": (1e-4, 1e-6)}}`); an empty ladder
    # measures a method only at the scenes' own settings.
    ladders: ClassVar[dict[str, object]] = {}
    # Experiments of the model's own that the bench runs beside (name: a BenchExperiment, numerics.py); each
    # is a part of the accuracy report under its name.
    experiments: ClassVar[dict[str, object]] = {}

    compares_digits: ClassVar[bool] = False  # whether measure_error also compares the displayed digits

    def __init__(self, settings: Numerics | None = None):
        self.settings = settings if settings is not None else self.numerics

    @classmethod
    def param(cls, name: str) -> Param:
        """The declared parameter called `name` (UnknownName, a KeyError, if there is none)."""
        found = next((p for p in cls.params if p.name == name), None)
        if found is None:
            raise UnknownName(f"model '{cls.name}' has no parameter '{name}'; its parameters: {_names(cls.params)}")
        return found

    @classmethod
    def output(cls, name: str) -> Output:
        """The declared output called `name` (UnknownName, a KeyError, if there is none)."""
        found = next((o for o in cls.outputs if o.name == name), None)
        if found is None:
            raise UnknownName(f"model '{cls.name}' has no output '{name}'; its outputs: {_names(cls.outputs)}")
        return found

    @classmethod
    def deps_of(cls, name: str, effects: Iterable[str] = ()) -> tuple[str, ...]:
        """The parameters output `name` depends on when `effects` are enabled."""
        on = frozenset(effects)
        output = cls.output(name)
        extra = [dep for effect, deps in output.deps_with if effect in on for dep in deps]
        return tuple(d for d in dict.fromkeys((*output.deps, *extra)) if not cls.param(d).unused_under(on))

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
        effects = frozenset(effects)
        offered = set(self.effects)
        if effects - offered:
            raise ValueError(f"unknown effect(s) {sorted(effects - offered)} of model {self.name}")
        values = {**self.defaults(), **inputs}
        arrays = dict(zip(values, np.broadcast_arrays(*(np.asarray(v, float) for v in values.values()))))
        for p in self.params:
            domain = p.under(effects)
            if not np.all(domain.contains(arrays[p.name])):
                raise ValueError(f"`{p.name}` must satisfy {domain.domain_text()}{_unless(p, domain)}")
        names = tuple(wanted) if wanted is not None else tuple(o.name for o in self.outputs)
        missing = sorted(set(names) - {o.name for o in self.outputs})
        if missing:
            raise ValueError(f"unknown output(s) {missing} of model {self.name}")
        return self._evaluate(arrays, names, effects)

    def _evaluate(
        self, x: Mapping[str, np.ndarray], wanted: tuple[str, ...], effects: frozenset[str]
    ) -> dict[str, np.ndarray]:
        raise NotImplementedError

    def is_numerical(self, effects: Iterable[str]) -> bool:
        """Whether, with these effects, some output comes from a numerical method (and is checked)."""
        return self.settings is not None

    def measure_error(self, values: Mapping[str, float], effects: Iterable[str]) -> Measurement:
        """The error of this model's numbers at one point with its settings, against its reference."""
        raise NotImplementedError(f"model {self.name} declares no numerical check")


def _unless(param: Param, domain: Param) -> str:
    """How an effect would widen the domain, e.g. " (up to inf with effect explosive)"."""
    return "".join(f" (up to {_num(hi)} with effect {effect})" for effect, hi in domain.wider)


def _names(declared) -> str:
    return ", ".join(d.name for d in declared)


def _num(value: float) -> str:
    return f"{value:g}"
