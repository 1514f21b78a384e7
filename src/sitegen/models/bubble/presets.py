"""The bubble's presets (docs/physics/bubble.md), for the tests and the accuracy report."""

from __future__ import annotations

import time

from .bench import PRESETS
from .model import Bubble
from .point import Scales, compose
from .run import Run
from .solve import solve
from .terms import Problem

__all__ = ["PRESETS", "preset_problem", "run_preset"]


def preset_problem(preset: str, **changes) -> tuple[Problem, Scales]:
    """The nondimensional problem of a preset at its defaults (or with some parameters changed)."""
    effects, values = PRESETS[preset]
    return compose({**Bubble.defaults(), **values, **changes}, effects)


def run_preset(preset: str, method: str, rtol: float, **changes) -> tuple[Run, int, float]:
    """One preset solved with a given method and rtol: (run, nfev, wall seconds), uncached."""
    pb, _ = preset_problem(preset, **changes)
    start = time.perf_counter()
    run = solve.__wrapped__(pb, method, rtol)
    return run, run.nfev, time.perf_counter() - start
