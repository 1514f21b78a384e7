"""The build's accuracy measurement: declared numerical settings, measured errors, tolerances that fail the build."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest
from helpers import resolved_scene, write_book

from sitegen.build import build
from sitegen.compute.measure import caption_sentence, measure_accuracy, measured_stops
from sitegen.errors import BuildFailed, SourceLoc
from sitegen.models.bubble.model import Bubble
from sitegen.models.bubble.point import SOLVER_LABELS
from sitegen.models.bubble.presets import PRESETS
from sitegen.physics.numerics import Numerics, configure
from sitegen.registry import builtin_registry

MODELS = builtin_registry().models

ROOT = Path(__file__).resolve().parents[1]

# Small grids of the book's three bubble scenes (presets A with gas, B and C), two stops each.
COLLAPSE = """model: bubble
id: collapse
slider R0: 100, 1000 default 1000
fix gas_content: 0.01
effects: inertia, vapour, step, gas
fix kappa: 1.4
readouts: collapse_R_min"""
DRIVEN = """model: bubble
id: driven
slider p_a: 1.2, 1.3 default 1.3
effects: gas, vdw_hard_core, surface_tension, viscosity, drive, keller_miksis
readouts: driven_R_min"""
BLAKE = """model: bubble
id: blake
slider depth: 0.9, 0.99 default 0.99
effects: gas, vapour, surface_tension, viscosity, ramp
fix kappa: 1
fix R0: 1
readouts: ramp_R_max"""
BUBBLE_SCENES = [
    pytest.param(COLLAPSE, id="collapse-DOP853"),
    pytest.param(DRIVEN, id="driven-DOP853"),
    pytest.param(BLAKE, id="blake-LSODA"),
]


def _scene(text: str):
    """A scene block resolved against the registry (it must be valid), at content/t.md."""
    return resolved_scene(text, where=SourceLoc("content/t.md", 1))


def _record(text: str):
    """The accuracy record of one scene, checked afresh (no cache)."""
    records, errors = measure_accuracy([SimpleNamespace(page=SimpleNamespace(slug="t"), scene=_scene(text))])
    return records[0], errors


@pytest.mark.parametrize("text", BUBBLE_SCENES)
def test_bubble_scene_error_is_measured_and_within_its_default_tolerance(text):
    """At the default settings each preset's measured error is a real, nonzero number below the declared tolerance."""
    record, errors = _record(text)
    assert 0.0 < record.error <= record.tolerance == Bubble.numerics.tolerance
    assert not errors and record.stops_measured == 2 and record.evaluations > 0


@pytest.mark.parametrize("text", BUBBLE_SCENES)
def test_loosening_rtol_raises_the_measured_error(text):
    """rtol 1e-2 instead of 1e-6 makes the measured error at least ten times larger."""
    tight, _ = _record(text)
    loose, _ = _record(text + "\nnumerics: rtol 1e-2, tolerance 1")
    assert loose.error > 10 * tight.error and loose.settings == "rtol 0.01"


def test_tolerance_below_the_error_is_reported_with_the_worst_stop():
    """A tolerance under the measured error is an error at the numerics line naming the stop and both numbers."""
    record, errors = _record(COLLAPSE + "\nnumerics: method DOP853, rtol 1e-2, tolerance 1e-8")
    assert record.error > 1e-8 and len(errors) == 1
    message = str(errors[0])
    assert message.startswith("content/t.md:9: scene 'collapse': measured error ")
    assert "at R0=1000 exceeds" in message or "at R0=100 exceeds" in message
    assert "exceeds the declared tolerance 1e-8" in message and "tighten rtol (now 0.01)" in message


def test_loosened_tolerance_fails_the_build(tmp_path):
    """A throwaway book whose scene declares rtol 1e-2 with tolerance 1e-8 fails, naming file:line, scene and stop."""
    page = (
        '+++\ntitle = "Loose"\n+++\n\nText.\n\n```scene\n'
        + COLLAPSE
        + "\nnumerics: method DOP853, rtol 1e-2, tolerance 1e-8\n```\n"
    )
    config = write_book(tmp_path, {"loose": page}, cache=True)
    with pytest.raises(BuildFailed) as failure:
        build(config, progress=None)
    (error,) = failure.value.errors
    assert str(error).startswith("content/loose.md:15: scene 'collapse': measured error ")
    assert " at R0=" in str(error) and "exceeds the declared tolerance 1e-8" in str(error)
    assert not config.out.exists()


def test_checked_scene_caption_states_the_error_and_links_only_when_the_page_exists(tmp_path):
    """The caption ends with the measured error; the link to its row appears once content/accuracy.md exists."""
    page = '+++\ntitle = "Chain"\n+++\n\n```scene\nmodel: chain\nslider N: 4, 8 default 8\ncaption: Beads.\n```\n'
    config = write_book(tmp_path, {"beads": page}, cache=True)
    report = build(config, progress=None)
    (record,) = report.accuracy
    assert (record.page, record.scene, record.method, record.model) == ("beads", "chain", "exact DST", "chain")
    html = (config.out / "beads.html").read_text()
    assert "Beads. Measured error " in html and "accuracy.html" not in html
    (config.content / "accuracy.md").write_text('+++\ntitle = "Accuracy and cost"\n+++\n\nRows.\n')
    build(config, progress=None)
    assert f'href="accuracy.html#{record.anchor}"' in (config.out / "beads.html").read_text()


def test_no_op_rebuild_runs_no_accuracy_solves(tmp_path):
    """With a cache the second check measures nothing: every record comes from the cached result."""
    from sitegen.compute.cache import TableCache

    cache, calls = TableCache(tmp_path), []

    def cached(kind, key, compute):
        return cache.cached(kind, key, lambda: calls.append(kind) or compute())

    items = [SimpleNamespace(page=SimpleNamespace(slug="t"), scene=_scene(DRIVEN))]
    first, _ = measure_accuracy(items, cached)
    second, _ = measure_accuracy(items, cached)
    assert calls == ["accuracy"] and first == second


def test_sample_is_deterministic_and_holds_defaults_and_corners():
    """The sampled stops are the same on every call and include the defaults and both extreme corners."""
    scene = _scene(
        "model: chain\nslider N: 1, 2, 4, 8, 16 default 8\nslider t: 0..2 step "
        "0.1 default 0.5\nchoice launch: right-moving | split default split"
    )
    stops = measured_stops(scene)
    assert stops == measured_stops(scene) and len(stops) == len(set(stops)) == 16
    assert stops[:3] == [scene.default_stops, (0, 0, 0), (4, 20, 1)]


@pytest.mark.parametrize(
    "model, effects",
    [
        pytest.param("chain", (), id="chain-DST"),
        pytest.param("work", (), id="work-closed-form"),
        pytest.param("kinetic", (), id="kinetic-counting"),
        pytest.param("lever", ("rotation_dynamics",), id="lever-elliptic"),
    ],
)
def test_every_numerical_model_meets_its_declared_tolerance_at_its_defaults(model, effects):
    """Chain, work, kinetic and lever (rotating) each measure an error within their declared tolerance."""
    instance = MODELS[model]()
    assert instance.is_numerical(effects)
    assert instance.measure_error({}, effects).error <= instance.numerics.tolerance


@pytest.mark.parametrize(
    "preset, rtol, label",
    [
        pytest.param("stiff", None, SOLVER_LABELS[2], id="stiff-default"),
        pytest.param("stiff", "1e-10", "compiled-Radau, at the scene's rtol", id="stiff-rtol-1e-10"),
        pytest.param("B", None, SOLVER_LABELS[1], id="driven-default"),
        pytest.param("A", None, "analytic (betaincinv)", id="rayleigh-analytic"),
    ],
)
def test_automatic_method_switches_to_implicit_for_stiff_terms(preset, rtol, label):
    """`method auto` picks the compiled Radau where 4µT/ρR0² > 10³, the compiled DOP853 for the driven bubble, the
    closed form for Rayleigh; the labels name the method and its rtol."""
    effects, values = PRESETS[preset]
    settings = configure(Bubble.numerics, Bubble.methods, {"rtol": rtol} if rtol else {})
    prefix = {"drive": "driven", "step": "collapse"}[next(e for e in effects if e in ("drive", "step"))]
    out = Bubble(settings).evaluate(values, [f"{prefix}_solver"], effects)
    assert SOLVER_LABELS[int(out[f"{prefix}_solver"])] == label


@pytest.mark.parametrize(
    "changes, message",
    [
        (
            {"method": "Euler"},
            "unknown method 'Euler'; this model offers auto, RK45, "
            "DOP853, Radau, BDF, LSODA, compiled-DOP853, compiled-Radau",
        ),
        ({"steps": "10"}, "unknown setting 'steps'; numerics take method, rtol, atol, nodes, step, tolerance"),
        ({"nodes": "32"}, "method auto has no setting 'nodes'; it takes rtol, atol and tolerance"),
        ({"rtol": "2"}, "rtol '2' must lie in [1e-14, 1)"),
        ({"tolerance": "-1"}, "tolerance '-1' must be a number >= 0"),
    ],
    ids=["method", "key", "not-taken", "rtol-range", "negative-tolerance"],
)
def test_invalid_settings_say_what_is_allowed(changes, message):
    """configure rejects what a model does not take, listing what it does."""
    with pytest.raises(ValueError) as problem:
        configure(Bubble.numerics, Bubble.methods, changes)
    assert str(problem.value) == message


def test_switching_method_takes_the_new_methods_defaults():
    """A scene that names another method gets that method's own defaults for the settings it did not give."""
    methods = {"stepper": {"rtol": 1e-3}, "quadrature": {"nodes": 32}}
    default = Numerics("stepper", tolerance=1.0, rtol=1e-3)
    assert configure(default, methods, {"method": "quadrature"}) == Numerics("quadrature", tolerance=1.0, nodes=32)
    assert (
        configure(Bubble.numerics, Bubble.methods, {"method": "Radau", "atol": "1e-9"}).text()
        == "method Radau, rtol 1e-6, atol 1e-9, tolerance 1e-5"
    )


def test_settings_take_part_in_the_cache_key():
    """Changing rtol changes the scene's key; changing only the tolerance does not (the tables are the same)."""
    from sitegen.compute.cache import scene_key

    keys = [
        scene_key(_scene(COLLAPSE + extra), ["collapse_R_min"]).spec
        for extra in ("", "\nnumerics: rtol 1e-8", "\nnumerics: tolerance 1e-2")
    ]
    assert keys[0] != keys[1] and keys[0] == keys[2]


@pytest.mark.parametrize(
    "error, expected",
    [
        (3.1e-8, "Measured error 3.1\u00a0×\u00a010<sup>−8</sup>"),
        (1e-12, "Measured error 10<sup>−12</sup>"),
        (0.0, "Measured error 0 "),
    ],
    ids=["mantissa", "power", "zero"],
)
def test_caption_sentence_writes_powers_of_ten(error, expected):
    """The caption's number and the reference's tolerance are written as powers of ten."""
    record = SimpleNamespace(error=error, metric="max |ΔR|/R₀", reference="Radau at rtol 1e-12", anchor="acc-p-s")
    sentence = caption_sentence(record, link=False)
    assert sentence.startswith(expected) and "Radau at rtol\u00a010<sup>−12</sup>." in sentence
