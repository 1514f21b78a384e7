"""The compiled bubble solver against scipy's: right-hand side, Jacobian, steppers, events and statuses.

scipy's solvers stay the reference; the compiled DOP853 and Radau follow the same algorithms, so on the
same problem at the same rtol they must end the same way and agree far below the tolerance.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from sitegen.build import BuildConfig, resolve_book
from sitegen.models.bubble import kernel_terms as kernel
from sitegen.models.bubble.model import ALL
from sitegen.models.bubble.point import compose, read_run
from sitegen.models.bubble.presets import preset_problem
from sitegen.models.bubble.solve import COMPILED, EXPLICIT, IMPLICIT, STIFF, integrate, method_for
from sitegen.models.bubble.terms import RADIATION, make_rhs
from sitegen.physics import compiled

ROOT = Path(__file__).resolve().parents[1]
PRESETS = ["A", "B", "C", "stiff"]
STATES = [(0.3, 1.0, 0.0), (5.0, 0.7, -0.3), (2.0, 2.5, 0.4), (1.0, 0.3, -2.0), (7.0, 0.05, 30.0)]


def _problem(preset: str, radiation: bool = False):
    pb, _ = preset_problem(preset, gas_content=0.01) if preset == "A" else preset_problem(preset)
    if preset == "A":
        pb = dataclasses.replace(pb, gas=0.01, kappa=1.4)
    return dataclasses.replace(pb, compressible=RADIATION) if radiation else pb


@pytest.mark.parametrize("radiation", [False, True], ids=["as-composed", "radiation"])
@pytest.mark.parametrize("preset", PRESETS)
def test_compiled_right_hand_side_equals_scipys_to_the_last_bit(preset, radiation):
    """The compiled terms do the same operations in the same order as make_rhs: equal floats."""
    pb = _problem(preset, radiation)
    rhs, p = make_rhs(pb), kernel.pack(pb)
    for t, r, v in STATES:
        assert kernel.rhs(p, t, r, v) == tuple(rhs(t, [r, v]))


@pytest.mark.parametrize("radiation", [False, True], ids=["as-composed", "radiation"])
@pytest.mark.parametrize("preset", PRESETS)
def test_analytic_jacobian_matches_central_differences(preset, radiation):
    """∂r̈/∂r and ∂r̈/∂ṙ against central differences of the right-hand side (relative 1e-6)."""
    pb = _problem(preset, radiation)
    p, step = kernel.pack(pb), 1e-6
    for t, r, v in STATES:
        d_r, d_v = kernel.jacobian(p, t, r, v)
        fd_r = (kernel.rhs(p, t, r * (1 + step), v)[1] - kernel.rhs(p, t, r * (1 - step), v)[1]) / (2 * r * step)
        fd_v = (kernel.rhs(p, t, r, v + step)[1] - kernel.rhs(p, t, r, v - step)[1]) / (2 * step)
        assert d_r == pytest.approx(fd_r, rel=1e-6, abs=1e-6)
        assert d_v == pytest.approx(fd_v, rel=1e-6, abs=1e-6)


def _agreement(mine, theirs) -> float:
    both = np.isfinite(mine.r) & np.isfinite(theirs.r)
    assert np.array_equal(np.isfinite(mine.r), np.isfinite(theirs.r))
    return float(np.max(np.abs(mine.r[both] - theirs.r[both])))


@pytest.mark.parametrize(
    "preset, scipy_method, compiled_method, rtol, bound",
    [
        ("A", "DOP853", EXPLICIT, 1e-8, 1e-12),
        ("B", "DOP853", EXPLICIT, 1e-8, 1e-9),
        ("C", "DOP853", EXPLICIT, 1e-8, 1e-8),
        ("A", "Radau", IMPLICIT, 1e-8, 1e-9),
        ("stiff", "Radau", IMPLICIT, 1e-8, 1e-8),
        ("C", "Radau", IMPLICIT, 1e-8, 1e-7),
    ],
)
def test_compiled_stepper_follows_scipys(preset, scipy_method, compiled_method, rtol, bound):
    """Same algorithm, same problem, same rtol: the same status and the sampled curves within `bound`
    (far below rtol's error; scipy's Radau differentiates numerically, the compiled one analytically)."""
    pb = _problem(preset)
    theirs = integrate(pb, (1.0, 0.0), scipy_method, rtol)
    mine = integrate(pb, (1.0, 0.0), compiled_method, rtol)
    assert mine.status == theirs.status
    assert _agreement(mine, theirs) < bound
    assert len(mine.maxima) == len(theirs.maxima) or preset == "C"  # C's quasi-static hold has spurious extrema


@functools.cache  # the book is read once for every scene's test
def _book_scenes() -> dict:
    return {record.scene.id: record.scene for record in resolve_book(BuildConfig.at(ROOT, cache=None)).scenes}


def _scene_stops(scene_id: str, count: int = 5):
    """`count` stops of a book scene (its defaults, corners and seeded random ones) as model points."""
    scene = _book_scenes()[scene_id]
    rng = np.random.default_rng(15)
    stops = [scene.default_stops, tuple(0 for _ in scene.axes), tuple(a.count - 1 for a in scene.axes)]
    stops += [tuple(int(rng.integers(a.count)) for a in scene.axes) for _ in range(count - 3)]
    defaults = {**scene.model.defaults(), **scene.base_values()}
    return scene, [{**defaults, **{a.param: float(a.stop(k)) for a, k in zip(scene.axes, stop)}} for stop in stops]


SCIPY_OF = {EXPLICIT: "DOP853", IMPLICIT: "Radau"}


@pytest.mark.parametrize("scene_id", ["rayleigh-collapse", "driven-bubble", "driven-map", "blake-threshold"])
def test_compiled_path_agrees_with_scipy_at_sampled_stops_of_every_bubble_scene(scene_id):
    """At sampled stops of each bubble scene, the scene's compiled solve and scipy's same method at the same
    rtol end with the same status, flag and growth, and R_max, R_min, ... agree to 1e-6 (1e-4 where stiff)."""
    scene, points = _scene_stops(scene_id)
    for point in points:
        pb, scales = compose({name: point[name] for name in ALL}, scene.effects)
        method, rtol, atol = method_for(pb, scene.model.settings)
        if method not in COMPILED:
            continue
        mine = integrate(pb, (1.0, 0.0), method, rtol, atol=atol)
        theirs = integrate(pb, (1.0, 0.0), SCIPY_OF[method], rtol, atol=atol)
        assert mine.status == theirs.status, point
        a, b = read_run(mine, pb, scales, scene.effects), read_run(theirs, pb, scales, scene.effects)
        for key in ("R_max", "R_min", "R_max2", "R_min2", "mach", "flag", "growth"):
            assert a[key] == pytest.approx(b[key], rel=1e-4 if pb.stiffness > STIFF else 1e-6), (point, key)


def _kernel_modules() -> list[str]:
    """The modules of the files the compiled code's key digests (the kernel_*.py files of the models)."""
    package = Path(compiled.__file__).parents[1]
    return [
        "sitegen." + ".".join(f.relative_to(package).with_suffix("").parts)
        for f in compiled.KERNEL_FILES
        if "models" in f.parts
    ]


def test_every_kernel_of_the_bubble_is_in_a_file_the_compiled_key_digests():
    """A kernel defined outside the digested files could change without a fresh cache folder."""
    import sitegen.models.bubble.model  # noqa: F401  (imports every module of the bubble's solver)

    digested = {str(f) for f in compiled.KERNEL_FILES}
    found = {
        value.py_func.__code__.co_filename
        for name, module in sys.modules.items()
        if name.startswith("sitegen.models.bubble")
        for value in vars(module).values()
        if hasattr(value, "py_func")
    }
    assert found and found <= digested, sorted(found - digested)


@pytest.mark.parametrize("module_name", _kernel_modules())
def test_every_constant_a_kernel_reads_is_in_a_file_the_compiled_key_digests(module_name):
    """A kernel bakes the module constants it reads into its compiled code, which is cached under a digest of
    the kernel files: a constant imported from another file (terms.py, say) could change without a recompile."""
    module, files = importlib.import_module(module_name), {str(f) for f in compiled.KERNEL_FILES}
    imported = {}  # name -> the module it is imported from
    for node in ast.walk(ast.parse(Path(module.__file__).read_text())):
        if isinstance(node, ast.ImportFrom):
            source = importlib.util.resolve_name("." * node.level + (node.module or ""), module.__package__)
            imported.update({alias.asname or alias.name: source for alias in node.names})
    for value in vars(module).values():
        if getattr(value, "py_func", None) is None or value.py_func.__module__ != module_name:
            continue
        for name in value.py_func.__code__.co_names:
            source = imported.get(name)
            if source and isinstance(value.py_func.__globals__.get(name), (int, float, np.ndarray)):
                assert sys.modules[source].__file__ in files, f"{value.py_func.__name__} reads {name} from {source}"


def test_the_dop853_tableau_meets_its_order_conditions():
    """The coefficients as published: each node is its row's sum, the weights sum to one and meet the conditions
    of order up to four on their own, and the error estimators are differences of weights (they sum to zero)."""
    from sitegen.models.bubble import kernel_dop853 as t

    steps = range(t.STAGES)
    assert np.allclose(t.A.sum(axis=1), t.C, atol=1e-15)
    for k in range(1, 5):  # Σ b_i c_i^(k-1) = 1/k
        assert sum(t.B[i] * t.C[i] ** (k - 1) for i in steps) == pytest.approx(1 / k, abs=1e-15)
    assert sum(t.B[i] * t.C[i] * t.A[i, j] * t.C[j] for i in steps for j in steps) == pytest.approx(1 / 8, abs=1e-15)
    assert t.E5.sum() == pytest.approx(0.0, abs=1e-15) and t.E3.sum() == pytest.approx(0.0, abs=1e-15)
