"""Numerical settings: which method computes a model's numbers, how tightly, and the error it may carry.

A model that computes anything by a numerical method (an ODE solve, a quadrature, a transform)
declares its default `Numerics`, chosen from the measured work–precision front (docs/physics/),
and the methods a scene may choose instead, with the settings each takes. The build checks every
such scene against the model's reference and fails when the measured error exceeds `tolerance`.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, replace

KEYS = ("method", "rtol", "atol", "nodes", "step", "tolerance")  # everything a scene's `numerics:` line may set
SETTINGS = ("rtol", "atol", "nodes", "step")  # the knobs that change the computed numbers
MAX_NODES = 1024


@dataclass(frozen=True)
class Numerics:
    """One choice of numerical settings: the method, its knobs, and the largest error allowed.

    `rtol`/`atol` are an ODE solver's relative and absolute tolerances (None: the method's own
    rule), `nodes` a quadrature's points per smooth piece (or a grid's resolution), `step` a fixed-step
    method's step in the model's own unit; `tolerance` is the declared bound on the error the build
    measures against the model's reference, in the model's `error_metric`.
    """

    method: str
    tolerance: float
    rtol: float | None = None
    atol: float | None = None
    nodes: int | None = None
    step: float | None = None

    def text(self) -> str:
        """The settings as an author writes them, e.g. `method DOP853, rtol 1e-06, tolerance 0.0001`."""
        return f"{self.knobs()}, tolerance {written(self.tolerance)}"

    def knobs(self) -> str:
        """The settings that change the computed numbers (all but the tolerance), as an author writes them."""
        parts = [f"method {self.method}"]
        parts += [f"{key} {written(value)}" for key in SETTINGS if (value := getattr(self, key)) is not None]
        return ", ".join(parts)


@dataclass(frozen=True)
class Measurement:
    """The error of a model's numbers at one parameter point, measured against its reference."""

    error: float  # in the model's error metric; inf when the run and the reference ended differently
    evaluations: int  # right-hand-side or integrand evaluations the settings spent (0 for a transform)
    method: str  # the method that computed the point (after any automatic choice)
    reference: str  # what the point was compared with, e.g. "DOP853 rtol 1e-12"
    # Outputs whose displayed value differs from the reference's: `wrong` ones, and `near` ones, where the
    # reference lies within the tolerance of a rounding boundary (no setting can promise that digit).
    wrong: tuple[str, ...] = ()
    near: tuple[str, ...] = ()


def configure(default: Numerics, methods: Mapping[str, Mapping[str, object]], changes: Mapping[str, str]) -> Numerics:
    """The default settings with an author's changes applied; ValueError saying what is allowed.

    `methods` maps each method a model offers to the settings (besides `tolerance`) it takes, with
    their values when a scene switches to it (None: the method's own rule).
    """
    unknown = [key for key in changes if key not in KEYS]
    if unknown:
        raise ValueError(f"unknown setting '{unknown[0]}'; numerics take {', '.join(KEYS)}")
    method = changes.get("method", default.method)
    if method not in methods:
        raise ValueError(f"unknown method '{method}'; this model offers {', '.join(methods)}")
    taken = methods[method]
    for key in changes:
        if key not in ("method", "tolerance") and key not in taken:
            offers = f"takes {', '.join(taken)} and tolerance" if taken else "takes only tolerance"
            raise ValueError(f"method {method} has no setting '{key}'; it {offers}")
    start = default if method == default.method else replace(default, **{**dict.fromkeys(SETTINGS), **taken})
    return replace(start, method=method, **{key: _value(key, text) for key, text in changes.items() if key != "method"})


def _value(key: str, text: str) -> float | int:
    """A setting's value read from text, or ValueError saying which values it takes."""
    try:
        number = float(text)
    except ValueError:
        number = math.nan
    if key == "nodes":
        if not (number.is_integer() and 1 <= number <= MAX_NODES):
            raise ValueError(f"nodes '{text}' must be a whole number from 1 to {MAX_NODES}")
        return int(number)
    if key == "rtol" and not (1e-14 <= number < 1.0):
        raise ValueError(f"rtol '{text}' must lie in [1e-14, 1)")
    if key in ("atol", "step") and not (0.0 < number < math.inf):
        raise ValueError(f"{key} '{text}' must be a positive number")
    if key == "tolerance" and not (0.0 <= number < math.inf):
        raise ValueError(f"tolerance '{text}' must be a number >= 0")
    return number


def written(value: float, form: str = "g") -> str:
    """A number as an author writes it: 1e-6 rather than 1e-06 (`form` as in format(), e.g. ".1e")."""
    return re.sub(r"e([-+])0*(\d)", r"e\1\2", format(value, form))


@dataclass(frozen=True)
class BenchScene:
    """A scene of the book as `sitegen bench` measures it: "page#id", the resolved scene (its model, axes,
    effects and settings), the outputs it shows, and its parameter values at each stop the build checks."""

    name: str
    scene: object
    shown: tuple[str, ...]
    stops: tuple[Mapping[str, float], ...]


class BenchExperiment:
    """An experiment of a model's own that `sitegen bench` runs beside the generic one (`Model.experiments`).

    `measure` gets the book's scenes of the model, whether the run is quick (a smoke test: a few points, one
    run each) and `timer`, which times a dict of calls and gives each its result and median seconds (the bench
    times, the experiment only declares what to time). It returns JSON-ready data, or None when the book
    gives it nothing to measure. `kind` says how the accuracy page draws it: "work-precision" (panels of runs,
    drawn like the generic experiment) or "digit-sweep" (scenes' shown digits against time).
    """

    kind = "work-precision"

    def measure(self, scenes, quick: bool, timer) -> dict | None:
        """The experiment's results as JSON-ready data."""
        raise NotImplementedError
