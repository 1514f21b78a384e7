"""The tables the pages ship are exact to the displayed digit at every stop, against exact rationals."""
from __future__ import annotations

from fractions import Fraction
from itertools import product
from pathlib import Path

import numpy as np
import pytest

from sitegen.build import BuildConfig, needed_outputs, read_pages, resolve_scenes
from sitegen.compute.tabulate import tabulate_scene
from sitegen.errors import ErrorLog

ROOT = Path(__file__).resolve().parents[1]


def _exact_impulse(F_pk, tau, m):
    J = F_pk * tau / 2
    return {"J": J, "dp": J, "dv": J / m, "t_apex": tau / 2}


def _exact_collision(m1, m2, v1i, v2i, e):
    M = m1 + m2
    if v1i > v2i:
        V = (m1 * v1i + m2 * v2i) / M
        v1f, v2f = V - e * (m2 / M) * (v1i - v2i), V + e * (m1 / M) * (v1i - v2i)
    else:
        V, v1f, v2f = (m1 * v1i + m2 * v2i) / M, v1i, v2i
    K_before = (m1 * v1i**2 + m2 * v2i**2) / 2
    K_after = (m1 * v1f**2 + m2 * v2f**2) / 2
    return {
        "v1f": v1f, "v2f": v2f, "v_cm": V,
        "p_before": m1 * v1i + m2 * v2i, "p_after": m1 * v1f + m2 * v2f,
        "K_before": K_before, "K_after": K_after, "K_lost": K_before - K_after,
        "K_kept_pct": 100 * K_after / K_before if K_before else Fraction(100),
        "status": 0 if v1i > v2i else 1,
    }


EXACT = {"impulse": _exact_impulse, "collision": _exact_collision}


def _book_scenes():
    log = ErrorLog()
    config = BuildConfig.at(ROOT)
    scenes = resolve_scenes(read_pages(config, log), log)
    log.raise_if_any()
    return [s.scene for s in scenes]


# Scenes whose models have an exact rational reference here; the others are checked against their
# models' own reference tests and, through the page, by the browser suite.
SCENES = [s for s in _book_scenes() if s.model.name in EXACT]


@pytest.mark.parametrize("scene", SCENES, ids=[s.id for s in SCENES])
def test_every_stop_is_exact_to_the_displayed_digit(scene):
    """At every slider stop each shipped value is within half a unit of its last digit of the exact value."""
    tables = tabulate_scene(scene, needed_outputs(scene))
    exact = EXACT[scene.model.name]
    base = {k: Fraction(v) for k, v in scene.base_values().items()}
    names = [p.name for p in scene.model.params]
    worst = {}
    for stops in product(*(range(a.count) for a in scene.axes)):
        values = dict(base)
        for axis, k in zip(scene.axes, stops):
            values[axis.param] = Fraction(axis.stop(k))  # the slider's exact decimal value
        reference = exact(*(values[n] for n in names))
        for name, table in tables.items():
            shown = Fraction(table.at(stops), 10**table.decimals)
            if table.labels:
                assert shown * 10**table.decimals == reference[name], (name, stops)
                continue
            # Correct rounding: |shown - exact| <= half a unit (a tie may round either way).
            error = abs(shown - reference[name]) * 10**table.decimals
            worst[name] = max(worst.get(name, 0), error)
    assert all(error <= Fraction(1, 2) for error in worst.values()), {k: float(v) for k, v in worst.items()}


def test_collision_defaults_reproduce_the_seed():
    """At the defaults the collision shows −2.333, 1.667, 1.00/1.00, 5.50/5.50."""
    scene = next(s for s in SCENES if s.model.name == "collision")
    tables = tabulate_scene(scene, needed_outputs(scene))
    at = {n: tables[n].at(scene.default_stops) for n in ("v1f", "v2f", "p_before", "p_after", "K_before", "K_after")}
    assert at == {"v1f": -2333, "v2f": 1667, "p_before": 100, "p_after": 100, "K_before": 550, "K_after": 550}


def test_tables_cover_only_their_dependencies():
    """Each table spans only sliders its output depends on; no table is the full cross product needlessly."""
    for scene in SCENES:
        for name, table in tabulate_scene(scene, needed_outputs(scene)).items():
            deps = scene.model.output(name).deps
            assert {scene.axes[a].param for a in table.axes} <= set(deps), (scene.id, name)
            assert table.quanta.size == int(np.prod(table.shape))
