"""Structure-aware tabulation: declared exact forms are compiled into small expressions, which the
check phase verifies against the model at sampled stops; a wrong claim fails the build at the scene's line."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import build_errors, resolved_scene, write_book
from test_author_errors import _BareFigure

from sitegen.build import build
from sitegen.compute.closed_form import verified_stops, verify_closed_forms
from sitegen.compute.expression import shown
from sitegen.compute.structure import Structured
from sitegen.compute.tabulate import tabulate_scene
from sitegen.errors import AuthorError, SourceLoc
from sitegen.physics.base import Model, Output, Param
from sitegen.physics.structure import Coord, Poly, param


def _scene(lines: list[str], models=None):
    return resolved_scene(lines, models, where=SourceLoc("try.md", 10))


COLLISION = [
    "model: collision",
    "id: c",
    "slider m1: 0.1..10 step 0.1 default 1",
    "slider m2: 0.1..10 step 0.1 default 2",
    "slider v1i: -5..5 step 0.1 default 3",
    "slider v2i: -5..5 step 0.1 default -1",
    "slider e: 0..1 step 0.01 default 1",
    "readouts: v1f v2f p_before p_after K_before K_after status",
]


def test_full_resolution_collision_ships_a_few_hundred_values():
    """The collision at docs/physics/ resolution (1.03e10 states) ships expressions of at most a few
    hundred node values each and one coordinate table of 199 entries along m1 + m2."""
    scene = _scene(COLLISION)
    assert np.prod([a.count for a in scene.axes]) == 100 * 100 * 101 * 101 * 101
    tables = tabulate_scene(scene, [o.name for o in scene.readouts])
    coordinate = tables["~inv_total_mass"]
    assert coordinate.summed_axes and coordinate.shape == (199,)
    assert all(isinstance(tables[o.name], Structured) for o in scene.readouts)
    assert sum(t.stored_values() for t in tables.values()) < 2000


def test_expression_matches_model_at_many_stops():
    """The script's arithmetic (mirrored in numpy) shows what the model gives at 50 000 random stops
    besides the sampled check's own, except at exact rounding ties."""
    scene = _scene(COLLISION)
    tables = tabulate_scene(scene, ["v1f", "K_after"])
    stops = np.random.default_rng(7).integers(0, [a.count for a in scene.axes], size=(50_000, 5))
    inputs = {a.param: a.values()[stops[:, i]] for i, a in enumerate(scene.axes)}
    direct = scene.model.evaluate(inputs, ["v1f", "K_after"])
    for name, decimals in (("v1f", 3), ("K_after", 2)):
        scaled = direct[name] * 10.0**decimals
        tie = np.abs(np.abs(scaled - np.floor(scaled)) - 0.5) < 1e-9 * np.maximum(1, np.abs(scaled))
        page = shown(tables[name], stops)
        assert np.array_equal(page[~tie], np.rint(scaled[~tie]).astype(np.int64)), name
        assert np.all(np.abs(page[tie] - scaled[tie]) <= 0.5 + 1e-6), name


class _Square(Model):
    """y = x², declared (wrongly, in one output) as linear in x."""

    name = "square"
    title = "square"
    params = (Param("x", "x", "", 1.0), Param("m", "m", "", 1.0, lo=0.0, lo_open=True))
    outputs = (
        Output("right", "right", "", ("x",), structure=Poly(lambda c: c["x"] ** 2, ((param("x"), 2),))),
        Output("wrong", "wrong", "", ("x",), structure=Poly(lambda c: c["x"] ** 2, ((param("x"), 1),))),
        Output(
            "per_mass",
            "per mass",
            "",
            ("x", "m"),
            structure=Poly(
                lambda c: c["x"] * c["inv_m"], ((param("x"), 1), (Coord("inv_m", ("m",), lambda m: 1 / m), 1))
            ),
        ),
    )

    def _evaluate(self, x, wanted, effects):
        values = {"right": x["x"] ** 2, "wrong": x["x"] ** 2, "per_mass": x["x"] / x["m"]}
        return {n: values[n] for n in wanted}


SQUARE = ["model: square", "id: sq", "slider x: -2..2 step 0.01 default 1", "slider m: 0.1..10 step 0.1 default 1"]


@pytest.mark.parametrize("output", ["right", "per_mass"])
def test_true_claims_are_verified(output):
    """A correct degree-2 claim and a reparametrised 1/m axis compile and pass the sampled check."""
    scene = _scene([*SQUARE, f"readouts: {output}"], {"square": _Square})
    table = tabulate_scene(scene, [output])[output]
    assert isinstance(table, Structured)
    assert table.at(scene.default_stops) == 1000
    assert verify_closed_forms(scene, [table]) == []


def test_false_claim_fails_the_build_at_the_scene():
    """Declaring x² linear in x is caught by the sampled check: an author error at the scene's line that names
    the output, a stop, and what the page would show against the model."""
    scene = _scene([*SQUARE, "readouts: wrong"], {"square": _Square})
    errors = verify_closed_forms(scene, [tabulate_scene(scene, ["wrong"])["wrong"]])
    assert len(errors) == 1 and isinstance(errors[0], AuthorError)
    message = str(errors[0])
    assert message.startswith("try.md:10: scene 'sq': output 'wrong'") and "x=" in message and "model gives" in message


def test_sampled_check_covers_corners_edges_and_defaults():
    """The sampled check's stops include every corner, every stop along each edge of the slider box, and the
    defaults."""
    scene = _scene([*SQUARE, "readouts: right"], {"square": _Square})
    stops = {tuple(s) for s in verified_stops(scene).tolist()}
    assert {(0, 0), (0, 99), (400, 0), (400, 99), scene.default_stops} <= stops
    assert all((k, 0) in stops and (k, 99) in stops for k in range(401))


SQUARE_PAGE = (
    '+++\ntitle = "Square"\n+++\n\n```scene\nmodel: square\nid: sq\nslider x: -2..2 step 0.01 default 1\n'
    "readouts: {readout}\n```\n"
)


def test_a_false_claim_fails_each_build_in_the_check_phase(tmp_path, register):
    """A wrong closed form fails the build at the scene's line in the check phase, and again when the scene's tables
    come from the cache (its verdict is cached with them); a true one builds."""
    register({"square": _Square}, {"square": _BareFigure()})
    config = write_book(tmp_path, {"square": SQUARE_PAGE.format(readout="wrong")}, cache=True)
    first = build_errors(config)
    assert len(first) == 1 and first[0].startswith("content/square.md:5: scene 'sq': output 'wrong'")
    assert build_errors(config) == first
    build(write_book(tmp_path, {"square": SQUARE_PAGE.format(readout="right")}, cache=True), progress=None)
