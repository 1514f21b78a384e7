"""Effects (docs/physics/README.md): a scene names the effects it shows and the model composes only those.

An effect the scene does not name is never evaluated (spies on the bubble's terms, the chain's damping
and boundary, the collision's contact and the impulse's pulse shapes), effect-dependent dependencies
are what the tabulation uses, and enabling or disabling an effect changes the cache key of that scene
only. The vanishing limits of the effects are in test_properties.py (docs/physics/README.md, effects, rule 2) and in
the models' own test files.
"""

from __future__ import annotations

import inspect
import sys
from pathlib import Path

import numpy as np
import pytest
from helpers import resolved_scene, write_book

from sitegen.build import BuildConfig, build, needed_outputs
from sitegen.compute.cache import scene_key
from sitegen.compute.tabulate import plan_scene, tabulate_scene
from sitegen.errors import SourceLoc
from sitegen.models.bubble import kernel_terms as kernel_terms
from sitegen.models.bubble import model as bubble
from sitegen.models.bubble import point as bubble_point
from sitegen.models.bubble import solve as bubble_solve
from sitegen.models.bubble import terms as bubble_terms
from sitegen.models.bubble.terms import make_rhs
from sitegen.models.chain import motion
from sitegen.models.impulse import pulses
from sitegen.physics import contact
from sitegen.registry import builtin_registry

MODELS = builtin_registry().models

ROOT = Path(__file__).resolve().parents[1]


def _scene(block: str):
    """A resolved scene from the lines of a scene block (no errors allowed), at content/effects.md."""
    return resolved_scene(block.strip(), where=SourceLoc("content/effects.md", 1))


class Counter:
    """Wraps functions and counts the calls of each."""

    def __init__(self):
        self.calls: dict[str, int] = {}

    def wrap(self, name: str, function):
        def counted(*args, **kwargs):
            self.calls[name] = self.calls.get(name, 0) + 1
            return function(*args, **kwargs)

        self.calls.setdefault(name, 0)
        return counted

    def total(self) -> int:
        return sum(self.calls.values())


# --- the impulse's pulse shapes ------------------------------------------------------------------------------

OTHER_SHAPES = [name for name in pulses.SHAPES if name != "triangle"]


@pytest.fixture
def shape_spy(monkeypatch) -> Counter:
    """Counts calls of every shape's force and running integral (the shape effect's terms)."""
    counter = Counter()
    for table, kind in ((pulses.SHAPE_FORCE, "force"), (pulses.SHAPE_RISE, "rise")):
        for name, function in list(table.items()):
            monkeypatch.setitem(table, name, counter.wrap(f"{name}-{kind}", function))
    return counter


def test_pulse_shapes_are_never_evaluated_without_the_shape_effect(shape_spy):
    """Asked for hann through its parameter but without `shape`, the model draws the triangle and never calls another
    shape."""
    model = MODELS["impulse"]()
    out = model.evaluate({"shape": 1.0, "v0": 0.5}, wanted=["J", "pulse_F", "v_curve"], effects=("initial_velocity",))
    assert all(shape_spy.calls[f"{name}-{kind}"] == 0 for name in OTHER_SHAPES for kind in ("force", "rise"))
    assert float(out["J"]) == 0.5 * 12.0 * 0.2  # the triangle's J


def test_pulse_shapes_evaluate_only_the_shapes_present(shape_spy):
    """With `shape` on and a grid of half-sine and rectangle points, only those two shapes are evaluated, once each."""
    model = MODELS["impulse"]()
    model.evaluate(
        {"shape": np.array([2.0, 3.0, 2.0]), "F_pk": np.array([1.0, 2.0, 3.0])}, wanted=["pulse_F"], effects=("shape",)
    )
    evaluated = {name for name, n in shape_spy.calls.items() if n}
    assert evaluated == {"half_sine-force", "rectangle-force"}
    assert shape_spy.calls["half_sine-force"] == 1


def test_impulse_scene_without_effects_never_touches_shapes_or_the_contact(shape_spy, monkeypatch):
    """Tabulating the chapter's impulse scene (no effects) calls no shape function and nothing of the contact."""
    contact_spy = _spy_module(monkeypatch, contact)
    scene = _scene(
        "model: impulse\nslider F_pk: 0..50 step 2 default 12\nslider tau: 0.05..1 step 0.05 default 0.2\n"
        "slider m: 0.5..10 step 0.5 default 2\nreadouts: J dp dv"
    )
    tabulate_scene(scene, needed_outputs(scene))
    assert shape_spy.total() == 0 and contact_spy.total() == 0


# --- the collision's spring–dashpot contact --------------------------------------------------------------------


def _spy_module(monkeypatch, module) -> Counter:
    """Counts calls of every public function of `module` (as the models reach them through the module)."""
    counter = Counter()
    for name, function in inspect.getmembers(module, inspect.isfunction):
        if function.__module__ == module.__name__ and not name.startswith("_"):
            monkeypatch.setattr(module, name, counter.wrap(name, function))
    return counter


COLLISION_BLOCK = "model: collision\nslider m1: 0.5..5 step 0.5 default 1\nslider v1i: -4.5..4.5 step 1 default 2.5\n"


@pytest.mark.parametrize(
    "effects",
    ["", "effects: restitution_law\n", "effects: explosive\n"],
    ids=["no-effects", "restitution_law", "explosive"],
)
def test_collision_contact_is_never_evaluated_unless_named(monkeypatch, effects):
    """A collision scene without `contact_spring_dashpot` calls no function of the contact module."""
    spy = _spy_module(monkeypatch, contact)
    scene = _scene(COLLISION_BLOCK + effects)
    tabulate_scene(scene, needed_outputs(scene))
    assert spy.total() == 0, spy.calls


def test_collision_contact_is_evaluated_when_named(monkeypatch):
    """The same spy sees the contact's restitution and force when the scene names the effect (the spy works)."""
    spy = _spy_module(monkeypatch, contact)
    scene = _scene(COLLISION_BLOCK + "effects: contact_spring_dashpot\n")
    tabulate_scene(scene, needed_outputs(scene))
    assert spy.calls["restitution"] > 0 and spy.calls["force"] > 0


# --- the chain's damping and boundary ------------------------------------------------------------------------------

CHAIN_BLOCK = "model: chain\nslider N: 4, 8 default 8\nslider t: 0..1 step 0.5 default 0.5\n"


@pytest.fixture
def chain_spy(monkeypatch) -> Counter:
    """Counts the damped modal evolution (onsite_damping) and the cosine transforms of free ends (boundary)."""
    counter = Counter()
    monkeypatch.setattr(motion, "_damped_oscillation", counter.wrap("damping", motion._damped_oscillation))
    monkeypatch.setattr(motion.scipy.fft, "dct", counter.wrap("free-ends", motion.scipy.fft.dct))
    return counter


def test_chain_damping_and_free_ends_are_never_evaluated_unless_named(chain_spy):
    """With γ = 2 and free ends given as inputs but neither effect named, the chain is undamped and fixed."""
    model = MODELS["chain"]()
    inputs = {"gamma": 2.0, "ends": 1.0, "N": 8.0, "t": 0.7}
    out = model.evaluate(inputs, wanted=["u_dots", "dev", "E_chain"])
    bare = model.evaluate({"N": 8.0, "t": 0.7}, wanted=["u_dots", "dev", "E_chain"])
    assert chain_spy.total() == 0
    assert all(np.array_equal(out[k], bare[k], equal_nan=True) for k in out)


@pytest.mark.parametrize(
    "effect, fixed, counted",
    [
        ("onsite_damping", "fix gamma: 2\n", "damping"),
        ("boundary", "choice ends: fixed | free default free\n", "free-ends"),
    ],
    ids=["onsite_damping", "boundary"],
)
def test_chain_scene_evaluates_an_effect_only_when_it_names_it(chain_spy, effect, fixed, counted):
    """Tabulating a chain scene: the term is not evaluated without its effect, and is with it."""
    scene = _scene(CHAIN_BLOCK + "readouts: dev")
    tabulate_scene(scene, needed_outputs(scene))
    assert chain_spy.total() == 0
    scene = _scene(CHAIN_BLOCK + f"effects: {effect}\n" + fixed + "readouts: dev")
    tabulate_scene(scene, needed_outputs(scene))
    assert chain_spy.calls[counted] > 0


# --- the bubble's terms
# ------------------------------------------------------------------------------------------------

# The statements that evaluate each term (the start of each, as written there), in scipy's right-hand
# side (make_rhs) and in the compiled one (kernel_terms.rhs).
BUBBLE_TERMS = {
    "gas": "p_gas = gas0 * (gas_volume0 / volume) ** kappa",
    "surface_tension": "p_wall -= two_sigma / r",
    "viscosity": "p_wall -= visc4 * v / r",
    "keller_miksis": "numerator = (1.0 + v / c) * drive",
    "radiation": "return (v, (drive - 1.5 * v * v + r / c * p_gas_rate) / r)",
}
KERNEL_TERMS = {
    "gas": "p_gas = p[GAS] * ((1.0 - p[E3]) / volume) ** p[KAPPA]",
    "surface_tension": "pw -= p[SIGMA2] / r",
    "viscosity": "pw -= p[VISC4] * v / r",
    "keller_miksis": "numerator = (1.0 + v / c) * drive",
    "radiation": "return v, (drive - 1.5 * v * v + r / c * g) / r",
}
DRIVEN = ("gas", "surface_tension", "viscosity", "drive", "keller_miksis")
MILD = {"R0": 10.0, "p_a": 0.4, "f": 50.0}  # a gentle driven bubble: a short, cheap solve


def _term_lines(path: str) -> dict[str, tuple[str, int]]:
    """(function name, line number) of each term's statement, in scipy's or the compiled right-hand side."""
    terms, functions = (BUBBLE_TERMS, [make_rhs]) if path == "scipy" else (KERNEL_TERMS, [kernel_terms.rhs.py_func])
    found = {}
    for function in functions:
        lines, start = inspect.getsourcelines(function)
        name = "rhs" if function is make_rhs else function.__name__
        found.update(
            {
                term: (name, start + i)
                for term, text in terms.items()
                for i, line in enumerate(lines)
                if line.strip().startswith(text)
            }
        )
    assert set(found) == set(terms), "a term's statement changed: update BUBBLE_TERMS or KERNEL_TERMS"
    return found


def _executed_rhs_lines(effects, path: str) -> set[tuple[str, int]]:
    """Solve one driven bubble with `effects` and record which lines of the composed right-hand side ran.

    scipy's path is traced while it solves; the compiled kernels cannot be traced, so the Python source of
    the compiled right-hand side (which numba compiles) is run on the same packed parameters at the states
    of the compiled solve.
    """
    executed: set[tuple[str, int]] = set()
    files = {bubble_terms.__file__} if path == "scipy" else {kernel_terms.__file__}

    def local(frame, event, arg):
        if event == "line":
            executed.add((frame.f_code.co_name, frame.f_lineno))
        return local

    def tracer(frame, event, arg):
        return local if frame.f_code.co_name == "rhs" and frame.f_code.co_filename in files else None

    pb, _ = bubble_point.compose({**MODELS["bubble"].defaults(), **MILD}, effects)
    method = "DOP853" if path == "scipy" else bubble_solve.EXPLICIT
    bubble_solve.solve.cache_clear()  # a cached run would not call the right-hand side at all
    sys.settrace(tracer)
    try:
        run = bubble_solve.solve(pb, method, 1e-6)
        if path == "compiled":
            p = kernel_terms.pack(pb)
            for t, r, v in zip(run.tau[::40], run.r[::40], run.v[::40]):
                kernel_terms.rhs.py_func(p, t, r, v)
    finally:
        sys.settrace(None)
    return executed


@pytest.mark.parametrize("path", ["scipy", "compiled"])
@pytest.mark.parametrize("left_out", ["surface_tension", "viscosity", "keller_miksis"])
def test_bubble_term_left_out_of_the_scene_is_never_evaluated(left_out, path):
    """Line tracing of the right-hand side: without an effect its term's statement never runs; every
    other enabled term's statement does (scipy's right-hand side and the compiled one)."""
    lines = _term_lines(path)
    executed = _executed_rhs_lines(tuple(e for e in DRIVEN if e != left_out), path)
    assert lines[left_out] not in executed
    assert lines["radiation"] not in executed
    for term in DRIVEN:
        if term in BUBBLE_TERMS and term != left_out:
            assert lines[term] in executed, f"{term} should have run"


@pytest.mark.parametrize("path", ["scipy", "compiled"])
def test_bubble_with_every_driven_term_runs_each_of_them(path):
    """The tracing is honest: with all the driven preset's effects on, each of their terms runs."""
    lines = _term_lines(path)
    executed = _executed_rhs_lines(DRIVEN, path)
    assert all(lines[term] in executed for term in DRIVEN if term in BUBBLE_TERMS)


class _RecordingPoint(dict):
    """A point of the grid that records which parameters are read."""

    def __init__(self, values, reads):
        super().__init__(values)
        self.reads = reads

    def __getitem__(self, key):
        self.reads.add(key)
        return super().__getitem__(key)


@pytest.mark.parametrize(
    "effect, param",
    [
        ("vapour", "p_v"),
        ("surface_tension", "sigma"),
        ("viscosity", "mu"),
        ("vdw_hard_core", "h_frac"),
        ("thermal_damping", "D_g"),
    ],
    ids=["vapour", "surface_tension", "viscosity", "vdw_hard_core", "thermal_damping"],
)
def test_bubble_initial_state_never_reads_a_parameter_of_an_effect_left_out(monkeypatch, effect, param):
    """Composing the problem (terms and the equilibrium initial state) reads an effect's parameter only when
    the scene names the effect."""
    reads: set[str] = set()
    original = bubble_point.compose
    monkeypatch.setattr(bubble, "compose", lambda point, effects: original(_RecordingPoint(point, reads), effects))
    model = MODELS["bubble"]()
    model.evaluate(MILD, wanted=["driven_R_max"], effects=("gas", "drive"))
    assert param not in reads
    model.evaluate(MILD, wanted=["driven_R_max"], effects=("gas", "drive", effect))
    assert param in reads  # the spy sees the parameter once the effect is named


# --- effect-dependent dependencies
# -------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "model, output, effects, expected",
    [
        ("lever", "t_stop", (), ("m_L", "m_R", "x_p", "theta_s")),
        ("lever", "t_stop", ("bar_mass",), ("m_L", "m_R", "x_p", "theta_s", "m_b")),
        ("collision", "v1f", (), ("m1", "m2", "v1i", "v2i", "e")),
        ("collision", "v1f", ("contact_spring_dashpot",), ("m1", "m2", "v1i", "v2i", "k_c", "c_d")),
        ("impulse", "J", (), ("F_pk", "tau")),
        ("impulse", "J", ("shape",), ("F_pk", "tau", "shape")),
        ("impulse", "J", ("contact_from_collision",), ("m", "m_hit", "v_rel", "k_c", "c_d")),
    ],
    ids=[
        "lever-plain",
        "lever-bar_mass",
        "collision-law",
        "collision-contact",
        "impulse-plain",
        "impulse-shape",
        "impulse-contact",
    ],
)
def test_deps_follow_the_scene_effects(model, output, effects, expected):
    """deps_of adds what an effect brings in (m_b, k_c, c_d, shape) and drops what it replaces (e, F_pk, τ)."""
    assert MODELS[model].deps_of(output, effects) == expected


def test_tabulation_groups_outputs_by_their_deps_under_the_effects():
    """A lever scene with bar_mass and rotation_dynamics tabulates t_stop over m_b too; without bar_mass, not."""
    block = (
        "model: lever\nslider m_L: 1..3 step 1 default 2\nslider x_p: 0..2 step 0.5 default 1.5\n"
        "slider m_b: 0..2 step 1 default 1\n"
    )
    with_bar = _scene(block + "effects: bar_mass rotation_dynamics\nreadouts: t_stop")
    units = plan_scene(with_bar, ["t_stop"])
    assert {with_bar.axes[a].param for unit in units for a in unit.axes} == {"m_L", "x_p", "m_b"}
    without = _scene(
        block.replace("slider m_b: 0..2 step 1 default 1\n", "") + "effects: rotation_dynamics\nreadouts: t_stop"
    )
    assert {without.axes[a].param for unit in plan_scene(without, ["t_stop"]) for a in unit.axes} == {"m_L", "x_p"}


# --- the cache key follows a scene's effects, and only that scene's -------------------------------------------------

PAGE = """+++
title = "Two scenes"
+++

```scene
model: collision
id: first
slider m1: 0.5..5 step 0.5 default 1
slider v1i: -4.5..4.5 step 1 default 2.5
{effects}
```

```scene
model: impulse
id: second
slider F_pk: 0..50 step 10 default 10
slider tau: 0.1..1 step 0.3 default 0.4
```
"""
TOGGLES = ["", "effects: explosive", "effects: contact_spring_dashpot", "effects: contact_spring_dashpot\nfix c_d: 20"]


def _keys(effects: str) -> dict[str, str]:
    """Each scene's cache key digest for the page with the first scene's effects line."""
    keys = {}
    text = PAGE.format(effects=effects)
    for block in text.split("```scene\n")[1:]:
        scene = _scene(block.split("```")[0])
        keys[scene.id] = scene_key(scene, needed_outputs(scene)).digest
    return keys


def test_toggling_an_effect_changes_the_key_of_that_scene_only():
    """Every effects line of the first scene gives it a different key; the second scene's key never moves."""
    keys = [_keys(toggle) for toggle in TOGGLES]
    assert len({k["first"] for k in keys}) == len(TOGGLES)
    assert len({k["second"] for k in keys}) == 1


@pytest.fixture
def book(tmp_path) -> BuildConfig:
    """A small book with the two-scene page and its own cache."""
    return write_book(tmp_path, {"page": PAGE.format(effects="")}, cache=True)


def test_enabling_an_effect_recomputes_only_that_scene(book):
    """A rebuild after adding `effects: contact_spring_dashpot` to one scene computes that scene and takes
    the other from the cache."""
    build(book, progress=None)
    page = book.content / "page.md"
    page.write_text(PAGE.format(effects="effects: contact_spring_dashpot"))
    report = build(book, progress=None)
    statuses = {line.split()[1]: line.rsplit("s  ", 1)[1] for line in report.scene_lines if line.startswith("[")}
    assert statuses == {"page#first": "computed: spec changed", "page#second": "cached"}
