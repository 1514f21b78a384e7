"""Bad input never crashes the build or the command: the cases tests/invalid/ cannot hold
(a model that raises, returns non-finite values or runs out of time; a file that is not UTF-8), and how
`sitegen build` reports each kind of failure — file:line errors, an exit status, and no Python traceback unless --debug.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from helpers import build_errors, write_book

from sitegen import cli
from sitegen.build import build
from sitegen.physics import Model, Output, Param
from sitegen.render.layers import Layer
from sitegen.render.style import new_figure

ROOT = Path(__file__).resolve().parents[1]
# What a non-finite error suggests after "the model must return finite numbers".
FINITE_HINT = (
    ', or, where the physics is singular or the quantity does not exist, say how the page shows it: special="—" '
    '(or "∞") and why="…" (or why_from=) on the Output'
)


class _Figure:
    label = "empty axes"

    def layers(self, scene):
        return []

    def draw(self, scene, tables):
        return new_figure(2.0)[0]


def _model(name: str, evaluate) -> type[Model]:
    """A one-parameter model whose evaluation is `evaluate(x)`."""
    return type(
        name.title(),
        (Model,),
        {
            "name": name,
            "title": name,
            "params": (Param("x", "x", "", 1.0, 0.0, 10.0),),
            "outputs": (Output("y", "y", "", ("x",)),),
            "_evaluate": lambda self, x, wanted, effects: {"y": evaluate(x["x"])},
        },
    )


def _raise(error):
    def evaluate(x):
        raise error

    return evaluate


def _capped(x):
    """A solve with a budget that ran out at x >= 2: it says so by returning NaN there."""
    return np.where(x >= 2, np.nan, x)


SCENE = '+++\ntitle = "Model"\n+++\n\n```scene\nmodel: {name}\nslider x: 0..3 step 1 default 1\n```\n'


@pytest.fixture
def register_model(register):
    """register_model(name, evaluate): a model and a bare figure in the registry of the test's builds."""

    def _register(name: str, evaluate) -> None:
        register({name: _model(name, evaluate)}, {name: _Figure()})

    return _register


def test_model_that_raises_a_numerical_error(tmp_path, register_model):
    """A model failing with ValueError/ArithmeticError (its documented way) is an author error at the scene."""
    register_model("fragile", _raise(ValueError("the integral diverges")))
    register_model("divider", _raise(ZeroDivisionError("division by zero")))
    config = write_book(tmp_path, {"a": SCENE.format(name="fragile"), "b": SCENE.format(name="divider")})
    assert build_errors(config) == [
        "content/a.md:5: scene 'fragile': model 'fragile' failed: the integral diverges",
        "content/b.md:5: scene 'divider': model 'divider' failed: division by zero",
    ]


def test_solve_out_of_time_reports_the_stop(tmp_path, register_model):
    """A solve whose time or evaluation budget ran out returns NaN (failure as data); the build
    fails naming the scene and the first slider value where it happened."""
    register_model("capped", _capped)
    config = write_book(tmp_path, {"slow": SCENE.format(name="capped")})
    assert build_errors(config) == [
        "content/slow.md:5: scene 'capped': output 'y' is not finite (nan) at x=2; the model must return finite numbers"
        + FINITE_HINT
    ]


def test_solve_that_exceeds_its_time_limit_is_an_author_error(tmp_path, register_model):
    """A solver that raises TimeoutError at its wall-time cap fails the build at the scene, saying so."""
    register_model("stalled", _raise(TimeoutError("the solve exceeded its 10 s wall-time limit")))
    config = write_book(tmp_path, {"stall": SCENE.format(name="stalled")})
    assert build_errors(config) == [
        "content/stall.md:5: scene 'stalled': model 'stalled' failed: the solve exceeded its 10 s wall-time limit"
    ]


def test_model_returning_infinity_reports_the_stop(tmp_path, register_model):
    """A model returning ±inf where its output declares no words for it fails the build at that stop."""
    register_model("blowup", lambda x: np.where(x == 3, np.inf, x))
    config = write_book(tmp_path, {"pole": SCENE.format(name="blowup")})
    assert build_errors(config) == [
        "content/pole.md:5: scene 'blowup': output 'y' is not finite (inf) at x=3; the model must return finite numbers"
        + FINITE_HINT
    ]


class _Curve(Model):
    """A curve of four points whose third is NaN at x = 3 (a quantity that does not exist there)."""

    name = "curve"
    title = "Curve"
    params = (Param("x", "x", "", 1.0, 0.0, 3.0),)
    outputs = (Output("ys", "curve", "", ("x",), size=4),)

    def _evaluate(self, x, wanted, effects):
        x = x["x"]
        return {"ys": np.stack([x, 2 * x, np.where(x == 3, np.nan, x), x], axis=-1)}


class _CurveFigure(_Figure):
    def layers(self, scene):
        return [Layer("curve", "polyline", 0, xs=(0.0, 1.0, 2.0, 3.0), ys="out:ys")]


def test_a_vector_output_that_is_not_finite_names_the_element(tmp_path, register):
    """The error names the element of the vector and the stop, and says how to show it in words instead."""
    register({"curve": _Curve}, {"curve": _CurveFigure()})
    config = write_book(tmp_path, {"curve": SCENE.format(name="curve")})
    assert build_errors(config) == [
        "content/curve.md:5: scene 'curve': output 'ys' (element 2) is not finite (nan) at x=3; the model must "
        "return finite numbers" + FINITE_HINT
    ]


def test_value_too_large_to_show_exactly(tmp_path):
    """A finite value too large to count in units of its last digit (exactly, in the page's
    JavaScript) fails the build at the stop, instead of showing a wrapped-around number."""
    page = (
        '+++\ntitle = "Huge"\n+++\n\n```scene\nmodel: collision\n'
        "slider m1: 1e20..3e20 step 1e20 default 1e20\nreadouts: p_before\n```\n"
    )
    assert build_errors(write_book(tmp_path, {"huge": page})) == [
        "content/huge.md:5: scene 'collision': output 'p_before' is 3e+20 at m1=1E+20, too large to show "
        "with 2 decimals (at most 9.0072e+13); narrow the sliders' ranges"
    ]


def test_file_that_is_not_utf8(tmp_path):
    """A page saved in another encoding is an error at the line of the first bad byte."""
    page = '+++\ntitle = "Caf\xe9"\n+++\n'.encode("latin-1")
    assert build_errors(write_book(tmp_path, {"latin": page})) == [
        "content/latin.md:2: the file is not UTF-8 text (byte 0xe9); save it as UTF-8"
    ]


def test_byte_order_mark_is_ignored(tmp_path):
    """A UTF-8 byte-order mark (some editors write one) does not hide the front matter."""
    config = write_book(tmp_path, {"bom": "\ufeff" + '+++\ntitle = "BOM"\n+++\n\nText.\n'})
    assert build(config, progress=None).pages == 2


# --- the command ------------------------------------------------------------------------------------


def run_cli(root: Path, capsys, *extra: str) -> tuple[int, str]:
    """`sitegen build --root ROOT --no-cache ...` (in this process, as the command runs it): its exit
    status and what it printed on stderr. An exception it let out would fail the test."""
    capsys.readouterr()
    status = cli.main(["build", "--root", str(root), "--no-cache", *extra])
    return status, capsys.readouterr().err


def test_every_error_of_every_page_in_one_run(tmp_path, capsys):
    """The command prints every author error of the book, sorted, then a summary; exit 1."""
    pages = {
        name: (ROOT / "tests" / "invalid" / f"{name}.md").read_text(encoding="utf-8")
        for name in ("not-finite-or-reversed", "front-matter-types", "bad-tex")
    }
    write_book(tmp_path, pages)
    status, err = run_cli(tmp_path, capsys)
    expected = [
        line
        for name in sorted(pages)
        for line in (ROOT / "tests" / "invalid" / f"{name}.expected").read_text().splitlines()
    ]
    assert status == 1
    assert err.splitlines() == [
        *expected,
        f"build failed: {len(expected)} error(s); {tmp_path / 'build'} was left as it was",
    ]


def test_missing_content_folder(tmp_path, capsys):
    """A book without content/ is one line and exit 2, not an empty site."""
    (tmp_path / "book.toml").write_text("")
    status, err = run_cli(tmp_path, capsys)
    assert status == 2 and "no folder content in" in err and "Traceback" not in err


def test_output_that_cannot_be_written(tmp_path, capsys):
    """An output folder that cannot be made (here: under a file) is one line and exit 2."""
    write_book(tmp_path, {})
    (tmp_path / "file").write_text("not a folder")
    status, err = run_cli(tmp_path, capsys, "--out", str(tmp_path / "file" / "build"))
    assert status == 2 and "Traceback" not in err, err
    assert err.startswith("sitegen: ") and "holds the last complete build" in err


def test_internal_error_is_reported_without_traceback(tmp_path, register_model, capsys):
    """A bug (an exception no author can cause) is one line naming it and where it struck (page, line,
    scene, phase), exit 3; --debug shows the traceback."""
    register_model("buggy", _raise(KeyError("oops")))
    write_book(tmp_path, {"bug": SCENE.format(name="buggy")})
    assert cli.main(["build", "--root", str(tmp_path), "--no-cache"]) == 3
    err = capsys.readouterr().err
    assert (
        "sitegen: content/bug.md:5: scene 'buggy': " in err
        and "KeyError: 'oops' (while tabulating)" in err
        and "internal error" not in err
    )
    assert "--debug" in err and "Traceback" not in err
    assert not (tmp_path / "build").exists()


def test_debug_shows_the_traceback_and_keeps_the_exit_status(tmp_path, register_model, capsys):
    """--debug adds the traceback (ending in the exception and the line that raised it) to the same one-line
    report, and the build still exits 3, as a script or a CI job reading the status expects."""
    register_model("buggy", _raise(KeyError("oops")))
    write_book(tmp_path, {"bug": SCENE.format(name="buggy")})
    assert cli.main(["build", "--root", str(tmp_path), "--no-cache", "--debug"]) == 3
    err = capsys.readouterr().err
    assert err.startswith("Traceback (most recent call last):") and "KeyError: 'oops'\n" in err
    assert err.rstrip().endswith("holds the last complete build") and "sitegen: content/bug.md:5: scene 'buggy'" in err
