"""The bubble's presets (docs/physics/bubble.md), for the tests and the accuracy report."""

from __future__ import annotations

import time

from .model import Bubble
from .point import Scales, compose
from .run import Run
from .solve import solve
from .terms import Problem

PRESETS = {  # name: (effects, parameters that differ from the defaults), docs/physics/bubble.md
    "A": (("inertia", "vapour", "step"), {"R0": 1000.0, "p_inf": 1.0}),
    "B": (
        ("gas", "vdw_hard_core", "surface_tension", "viscosity", "drive", "keller_miksis"),
        {"R0": 4.5, "p_a": 1.3, "f": 26.5},
    ),
    "C": (("gas", "vapour", "surface_tension", "viscosity", "ramp"), {"R0": 1.0, "kappa": 1.0, "depth": 0.99}),
    "stiff": (
        ("gas", "surface_tension", "viscosity", "drive"),
        {"R0": 1.0, "mu": 1.0, "rho": 1260.0, "p_a": 0.5, "f": 20.0, "kappa": 1.4},
    ),
}


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
