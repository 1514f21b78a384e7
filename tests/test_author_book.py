"""A book written as a new author would write it (tests/authors/oscillator: a chapter on the basilar membrane
with a model of its own), built unchanged, then broken the way an author breaks one: an output's deps that
leave out a parameter it changes with, a layer reading an output or a parameter the model does not have, a
declared dep that changes nothing. Each must fail the build (or note it) at the author's own line."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest
from scipy.integrate import solve_ivp

from sitegen.build import BuildConfig, build
from sitegen.errors import BuildFailed, SceneCrashed

AUTHOR = Path(__file__).resolve().parent / "authors" / "oscillator"
SCENE = "content/membrane.md:22: scene 'resonance'"  # the scene's fence, where its errors are reported
X_LINE = 46  # models/oscillator/model.py: the `Output("X", ...)` line


@pytest.fixture
def book(tmp_path) -> BuildConfig:
    """A fresh copy of the author's book (its own cache, nothing built)."""
    shutil.copytree(AUTHOR, tmp_path / "book", ignore=shutil.ignore_patterns(".cache", "build", "__pycache__"))
    return BuildConfig.at(tmp_path / "book")


def _edit(book: BuildConfig, name: str, old: str, new: str) -> None:
    path = book.root / name
    text = path.read_text()
    assert old in text, f"{name} no longer holds {old!r}"
    path.write_text(text.replace(old, new))


def _errors(book: BuildConfig) -> list[str]:
    with pytest.raises(BuildFailed) as failure:
        build(book, progress=None)
    return [str(e) for e in failure.value.errors]


def _readout(book: BuildConfig, output: str) -> str:
    html = (book.out / "membrane.html").read_text()
    start = html.index(f'data-out="{output}">') + len(f'data-out="{output}">')
    return html[start : html.index("<", start)]


def test_the_chapter_builds_unchanged_and_shows_the_physics(book):
    """At resonance, ζ = 0.1: X = x_st/2ζ = 125.00 nm, φ = 90.0°; x(5 ms) as the equation of motion gives it."""
    report = build(book, progress=None)
    assert report.notes == [] and report.computed == 1
    assert _readout(book, "X") == "125.00 nm" and _readout(book, "phase") == "90.0°"
    w0 = 2 * math.pi
    run = solve_ivp(
        lambda t, y: (y[1], -0.2 * w0 * y[1] - w0**2 * (y[0] - 25.0 * math.cos(w0 * t))),
        (0, 5.0),
        (0.0, 0.0),
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
    )
    assert _readout(book, "x_now") == f"{run.y[0, -1]:.2f} nm"


def test_deps_leaving_out_zeta_fail_the_build_naming_zeta(book):
    """The amplitude declared without ζ: the page would show 125.00 nm at every ζ. The build says where and why."""
    _edit(
        book,
        "models/oscillator/model.py",
        '("f0", "zeta", "f", "x_st"), decimals=2),',
        '("f0", "f", "x_st"), decimals=2),',
    )
    assert _errors(book) == [
        f"{SCENE}: models/oscillator/model.py:{X_LINE}: output 'X' changes with 'zeta' (125.00 nm → 15.63 nm as "
        "zeta goes 0.1 → 0.8, at f=1, t=5) but its deps leave 'zeta' out; add 'zeta' to its deps"
    ]
    assert not book.out.exists()


def test_the_finding_is_kept_with_the_scene_and_read_back(book, monkeypatch):
    """A second build with the same mistake reports it again from the cache, probing nothing."""
    import sitegen.compute.deps as deps

    _edit(
        book,
        "models/oscillator/model.py",
        '("f0", "zeta", "f", "x_st"), decimals=2),',
        '("f0", "f", "x_st"), decimals=2),',
    )
    first = _errors(book)
    probes = []
    probe_scene = deps.probe_scene
    monkeypatch.setattr(deps, "probe_scene", lambda *args: probes.append(args) or probe_scene(*args))
    assert _errors(book) == first and probes == []
    assert _errors(BuildConfig.at(book.root, cache=None)) == first and len(probes) == 1  # without a cache: probed


def test_a_layer_reading_a_misspelt_output_names_the_figure_and_the_right_name(book):
    """ys="out:gain_curv": an error at the scene naming the figure's line, with "did you mean" and the list."""
    _edit(book, "models/oscillator/figure.py", 'ys="out:gain_curve"', 'ys="out:gain_curv"')
    assert _errors(book) == [
        f"{SCENE}: models/oscillator/figure.py:18: layer 'curve' reads 'out:gain_curv', which is no output of "
        "model 'oscillator' in this scene — did you mean 'gain_curve'? Its vector outputs: gain_curve, ring"
    ]


def test_a_layer_reading_a_missing_parameter_names_the_figure_and_the_parameters(book):
    """ "in:freq" for the drive frequency: an error naming the layer's line and the model's parameters."""
    _edit(book, "models/oscillator/figure.py", '("in:f", "out:X")', '("in:freq", "out:X")')
    assert _errors(book) == [
        f"{SCENE}: models/oscillator/figure.py:19: layer 'here' reads 'in:freq', which is no parameter of model "
        "'oscillator' — did you mean 'f'? Its parameters: f0, zeta, f, x_st, t"
    ]


def test_a_vector_output_read_as_one_number_is_an_error(book):
    """A dot at ("in:f", "out:gain_curve"): the output is a curve of 60 numbers, not a vertex."""
    _edit(book, "models/oscillator/figure.py", '("in:f", "out:X")', '("in:f", "out:gain_curve")')
    assert _errors(book) == [
        f"{SCENE}: models/oscillator/figure.py:19: layer 'here' reads 'out:gain_curve' as one number, but it is "
        "a vector of 60 (for xs/ys). Its scalar outputs: X, phase, x_now"
    ]


def test_a_declared_dep_that_changes_nothing_is_a_note_with_the_factor(book):
    """The phase declared over x_st, which sets only the size of the motion, with x_st on a slider of 4 stops:
    the build goes on and notes that the phase is computed over 4× the stops for nothing."""
    _edit(
        book,
        "models/oscillator/model.py",
        '("f0", "zeta", "f"), decimals=1),',
        '("f0", "zeta", "f", "x_st"), decimals=1),',
    )
    _edit(book, "content/membrane.md", "fix x_st: 25\n", "slider x_st: 10..25 step 5 default 25\n")
    report = build(book, progress=None)
    assert report.notes == [
        f"note: {SCENE}: an output does not change anywhere on this scene's grid with a slider its deps declare, "
        "so it is computed over that many times the stops for nothing: 'phase' (models/oscillator/model.py:47) "
        "with 'x_st' (4×)"
    ]
    assert build(book, progress=None).notes == report.notes  # and again from the cache


@pytest.mark.parametrize(
    "old, new, line, message",
    [
        (
            'table_range(tables["gain_curve"])',
            'table_range(tables["gain_curv"])',
            26,
            "UnknownName: the scene has no table 'gain_curv' — did you mean 'gain_curve'? Its tables (the outputs it "
            "shows: its readouts and what its layers read): X, gain_curve, phase, ring, x_now",
        ),
        (
            'param_range(scene, "t")',
            'param_range(scene, "time")',
            32,
            "UnknownName: model 'oscillator' has no parameter 'time' — did you mean 't'? Its parameters: f0, zeta, f, "
            "x_st, t",
        ),
    ],
    ids=["a-table-it-does-not-show", "a-parameter-it-does-not-have"],
)
def test_a_typo_in_the_figures_draw_names_the_authors_line(book, old, new, line, message):
    """A name the scene has no table or parameter of, asked for in `draw`: the crash names the figure's own line
    and says what the scene has, not a bare KeyError inside sitegen."""
    _edit(book, "models/oscillator/figure.py", old, new)
    with pytest.raises(SceneCrashed) as crash:
        build(book, progress=None)
    assert str(crash.value) == f"{SCENE}: models/oscillator/figure.py:{line}: {message} (while drawing its figure)"
