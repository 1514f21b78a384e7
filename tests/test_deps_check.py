"""The deps check on models written here, for what the oscillator book does not show: effects that bring a
parameter (`deps_with`) or take one's place (`replaced_by`), a vector output changing in one element, a parameter
without a slider moved across its domain, and the same check called from a book's tests (`sitegen.testing`)."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import build_errors, write_book
from test_author_errors import _BareFigure

from sitegen.build import build
from sitegen.physics import Model, Output, Param
from sitegen.render.layers import Layer
from sitegen.testing import deps_problems

HERE = __file__.rsplit("/", 1)[0]


class Lamp(Model):
    """A lamp: brightness y = a (+ b when it glows); c sets the base level unless the glow takes its place."""

    name = "lamp"
    title = "Lamp"
    effects = ("glow",)
    params = (
        Param("a", "a", "", 1.0, 0.0, 10.0),
        Param("b", "b", "", 1.0, 0.0, 10.0).with_effect("glow"),
        Param("c", "c", "", 2.0, 0.0, 10.0).replaced_by("glow"),
        Param("d", "d", "", 3.0, 0.0, 10.0),
    )
    outputs = (
        Output("y", "y", "", ("a",), deps_with=(("glow", ("b",)),)),  # right: b only while glowing
        Output("z", "z", "", ("a",)),  # wrong with the glow on: it reads b then
        Output("w", "w", "", ("a", "c")),  # wrong with the glow on: c is replaced, yet w still reads it
        Output("v", "v", "", ("a",), size=3),  # wrong in its last element, which reads d
    )

    def _evaluate(self, x, wanted, effects):
        glow = "glow" in effects
        a, b, c, d = x["a"], x["b"], x["c"], x["d"]
        values = {
            "y": lambda: a + (b if glow else 0.0),
            "z": lambda: a + (b if glow else 0.0),
            "w": lambda: a + c if glow else a + c,
            "v": lambda: np.stack([a, 2 * a, a + d], axis=-1),
        }
        return {name: values[name]() for name in wanted}


PAGE = (
    '+++\ntitle = "Lamp"\n+++\n\n```scene\nmodel: lamp\n{effects}slider '
    "a: 0..2 step 1 default 1\n{more}readouts: {readouts}\n```\n"
)
LINES = {o.name: o.where[1] for o in Lamp.outputs}


@pytest.fixture
def lamp(register):
    register({"lamp": Lamp}, {"lamp": _BareFigure()})


def _page(readouts: str, effects: str = "", more: str = "") -> str:
    return PAGE.format(effects=f"effects: {effects}\n" if effects else "", more=more, readouts=readouts)


def test_right_deps_build_with_and_without_the_effect(tmp_path, lamp):
    """y declares b only while the glow is on, and c is left alone: both scenes build."""
    (tmp_path / "off").mkdir()
    (tmp_path / "on").mkdir()
    build(write_book(tmp_path / "off", {"lamp": _page("y")}), progress=None)
    build(write_book(tmp_path / "on", {"lamp": _page("y", "glow", "slider b: 0..2 step 1 default 1\n")}), progress=None)


def test_a_parameter_an_effect_brings_must_be_declared_for_that_effect(tmp_path, lamp):
    """With the glow on, z reads b, which its deps leave out (it would need deps_with=(("glow", ("b",)),))."""
    page = _page("z", "glow", "slider b: 0..2 step 1 default 1\n")
    assert build_errors(write_book(tmp_path, {"lamp": page})) == [
        f"content/lamp.md:5: scene 'lamp': {HERE}/test_deps_check.py:{LINES['z']}: output 'z' changes with 'b' "
        "(2.000 → 1.000 as b goes 1 → 0, at a=1) but its deps leave 'b' out; add 'b' to its deps"
    ]


def test_a_parameter_an_effect_replaces_must_not_change_the_output(tmp_path, lamp):
    """With the glow on, c is replaced (its deps drop it) but w still reads it: moved across its domain
    (it has no slider), it changes w."""
    assert build_errors(write_book(tmp_path, {"lamp": _page("w", "glow")})) == [
        f"content/lamp.md:5: scene 'lamp': {HERE}/test_deps_check.py:{LINES['w']}: output 'w' changes with 'c' "
        "(3.000 → 3.164 as c goes 2 → 2.16418, at a=1) but its deps leave 'c' out; add 'c' to its deps"
    ]


class _CurveFigure(_BareFigure):
    """A figure with one curve: the lamp's v."""

    def layers(self, scene):
        return [Layer("curve", "polyline", 0, xs=(0.0, 1.0, 2.0), ys="out:v")]


def test_a_vector_output_names_the_element_that_changed(tmp_path, register):
    """v's last element reads d, a parameter without a slider, moved across its domain: the error names element 2."""
    register({"lamp": Lamp}, {"lamp": _CurveFigure()})
    assert build_errors(write_book(tmp_path, {"lamp": _page("y")})) == [
        f"content/lamp.md:5: scene 'lamp': {HERE}/test_deps_check.py:{LINES['v']}: output 'v' (element 2) changes "
        "with 'd' (4.000 → 2.536 as d goes 3 → 1.53588, at a=1) but its deps leave 'd' out; add 'd' to its deps"
    ]


def test_a_books_test_finds_the_same_mistakes(lamp):
    """deps_problems over the domain: z and w with the glow on, v with or without it."""
    off = deps_problems(Lamp(), points=4)
    on = deps_problems(Lamp(), {"glow"}, points=4)
    assert [p.split(": ", 1)[1].split(" (")[0] for p in off] == ["output 'v'"]
    assert sorted(p.split(": ", 1)[1].split(" (")[0].split(" changes")[0] for p in on) == [
        "output 'v'",
        "output 'w'",
        "output 'z'",
    ]


def test_a_parameter_one_output_declares_is_still_moved_for_another(tmp_path, lamp):
    """y declares b under the glow and z does not: shown together, b is still moved, and z is caught."""
    page = _page("y, z", "glow", "slider b: 0..2 step 1 default 1\n")
    assert [e.split(": ", 3)[3].split(" (")[0] for e in build_errors(write_book(tmp_path, {"lamp": page}))] == [
        "output 'z' changes with 'b'"
    ]


class _SolvedLamp(Lamp):
    """The lamp as if each of its stops were an ODE solve (it declares chunk_stops): fewer moves, the same finding."""

    chunk_stops = 64


def test_a_model_solved_per_stop_still_has_its_fixed_parameters_moved(tmp_path, register):
    """With one value from each stop for a parameter without a slider, w's reading of c is still found."""
    register({"lamp": _SolvedLamp}, {"lamp": _BareFigure()})
    assert build_errors(write_book(tmp_path, {"lamp": _page("w", "glow")})) == [
        f"content/lamp.md:5: scene 'lamp': {HERE}/test_deps_check.py:{LINES['w']}: output 'w' changes with 'c' "
        "(3.000 → 3.164 as c goes 2 → 2.16418, at a=1) but its deps leave 'c' out; add 'c' to its deps"
    ]
