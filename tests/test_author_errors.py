"""Broken pages give exact `file:line: message` errors, all of them in one run."""

from __future__ import annotations

import shutil
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from helpers import build_errors, tree, write_book
from test_bad_input import FINITE_HINT

from sitegen.build import build
from sitegen.config import BookConfig
from sitegen.physics import Model, Output, Param
from sitegen.registry import builtin_registry
from sitegen.render.style import new_figure

HERE = Path(__file__).parent
INVALID = HERE / "invalid"
ROOT = HERE.parent
CASES = sorted(p.stem for p in INVALID.glob("*.md"))


def _expected(name: str) -> list[str]:
    """The messages a fixture must produce ({models} and {figures} stand for the registry's names)."""
    text = (INVALID / f"{name}.expected").read_text(encoding="utf-8")
    text = text.replace("{figures}", ", ".join(sorted(builtin_registry().figures)))
    return text.replace("{models}", ", ".join(sorted(builtin_registry().models))).splitlines()


def test_every_invalid_fixture_has_expected_messages():
    """Each broken page in tests/invalid/ comes with the messages it must produce."""
    assert CASES and all((INVALID / f"{name}.expected").is_file() for name in CASES)


@pytest.mark.parametrize("name", CASES)
def test_invalid_page_reports_exact_errors(tmp_path, name):
    """A broken page fails the build with exactly the expected `file:line: message` lines (with the files of
    its folder next to it, and its .bib as the book's bibliography, where it has them)."""
    config = write_book(tmp_path, {name: (INVALID / f"{name}.md").read_text(encoding="utf-8")})
    if (INVALID / name).is_dir():
        shutil.copytree(INVALID / name, config.content, dirs_exist_ok=True)
    if (INVALID / f"{name}.bib").is_file():
        shutil.copy(INVALID / f"{name}.bib", tmp_path / "references.bib")
        book = BookConfig(tmp_path, content=config.content, output=config.out, bibliography=tmp_path / "references.bib")
        config = replace(config, book=book)
    assert build_errors(config) == _expected(name)


def test_errors_from_several_pages_are_reported_together(tmp_path):
    """One run reports every error of every page, sorted by file and line."""
    pages = {name: (INVALID / f"{name}.md").read_text(encoding="utf-8") for name in ("bad-range", "unknown-model")}
    expected = [line for name in ("bad-range", "unknown-model") for line in _expected(name)]
    assert build_errors(write_book(tmp_path, pages)) == expected


def test_failed_build_leaves_previous_build_untouched(tmp_path):
    """A build that fails does not touch the build/ folder of the last good build."""
    config = write_book(tmp_path, {})
    build(config, progress=None)
    before = tree(config.out)
    (config.content / "broken.md").write_text((INVALID / "unknown-model.md").read_text(), encoding="utf-8")
    build_errors(config)
    after = tree(config.out)
    assert after == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["book.toml", "build", "content"]


def test_duplicate_scene_ids_on_one_page(tmp_path):
    """Two scenes with one id on a page: the second is reported at its own line."""
    block = "```scene\nmodel: impulse\n```\n\n"
    config = write_book(tmp_path, {"twice": '+++\ntitle = "Twice"\n+++\n\n' + block + block})
    assert build_errors(config) == [
        "content/twice.md:9: scene 'impulse': another scene on this page has id 'impulse'; add 'id: <unique-name>'"
    ]


def test_unknown_effect_lists_what_the_model_offers(tmp_path):
    """An effect the model does not offer is an error that names the effects it does offer."""
    page = '+++\ntitle = "Effects"\n+++\n\n```scene\nmodel: collision\neffects: restitution_law drag\n```\n'
    assert build_errors(write_book(tmp_path, {"effects": page})) == [
        "content/effects.md:7: scene 'collision': model 'collision' has no effect "
        "'drag'. It offers: restitution_law, contact_spring_dashpot, explosive"
    ]


def test_effect_of_another_model_lists_what_this_model_offers(tmp_path):
    """Naming an effect that exists, but on another model (the chain's boundary on the impulse), is an error at
    the effects line listing the impulse's own effects."""
    page = '+++\ntitle = "Effects"\n+++\n\n```scene\nmodel: impulse\neffects: boundary shape\n```\n'
    assert build_errors(write_book(tmp_path, {"effects": page})) == [
        "content/effects.md:7: scene 'impulse': model 'impulse' has no effect 'boundary'. "
        "It offers: shape, initial_velocity, contact_from_collision"
    ]


def test_parameter_replaced_by_an_enabled_effect_is_an_error_at_its_control(tmp_path):
    """With the spring–dashpot contact, e comes from the contact: a slider on e is an error at its line."""
    page = (
        '+++\ntitle = "Contact"\n+++\n\n```scene\nmodel: collision\neffects: contact_spring_dashpot\n'
        "slider e: 0..1 step 0.5 default 1\n```\n"
    )
    assert build_errors(write_book(tmp_path, {"contact": page})) == [
        "content/contact.md:8: scene 'collision': parameter 'e' is not used with effect 'contact_spring_dashpot', "
        "which takes its place; remove its control"
    ]


def test_restitution_above_one_names_the_effect_that_allows_it(tmp_path):
    """e > 1 is outside the domain unless the scene enables `explosive`; the error says so, and with the effect it
    builds."""
    block = "```scene\nmodel: collision\n{effects}slider e: 0..1.5 step 0.5 default 1\n```\n"
    page = '+++\ntitle = "Explosive"\n+++\n\n' + block.format(effects="")
    (tmp_path / "without").mkdir()
    (tmp_path / "with").mkdir()
    assert build_errors(write_book(tmp_path / "without", {"explosive": page})) == [
        "content/explosive.md:7: scene 'collision': slider 'e' max 1.5 exceeds the model's bound 1.0 "
        "(effect 'explosive' allows larger values)"
    ]
    config = write_book(
        tmp_path / "with",
        {"explosive": page.replace(block.format(effects=""), block.format(effects="effects: explosive\n"))},
    )
    build(config, progress=None)


def test_unknown_parent_page(tmp_path):
    """A parent that is not a page is reported at the page's first line."""
    page = '+++\ntitle = "Orphan"\nparent = "nowhere"\n+++\n\nText.\n'
    assert build_errors(write_book(tmp_path, {"orphan": page})) == [
        "content/orphan.md:1: parent 'nowhere' is not a page; pages: index, orphan"
    ]


class _BareFigure:
    """A figure with axes and no moving layers."""

    label = "empty axes"

    def layers(self, scene):
        return []

    def draw(self, scene, tables):
        return new_figure(2.0)[0]


class _Singular(Model):
    """A model whose output is 1/x: infinite at x = 0."""

    name = "singular"
    title = "Singular"
    params = (Param("x", "x", "", 1.0),)
    outputs = (Output("inverse", "1/x", "", ("x",)),)

    def _evaluate(self, x, wanted, effects):
        with np.errstate(divide="ignore"):
            return {"inverse": 1.0 / x["x"]}


def test_non_finite_output_fails_the_build_naming_the_stop(tmp_path, register):
    """A model returning inf at some stop fails the build, naming the scene and the slider values."""
    register({"singular": _Singular}, {"singular": _BareFigure()})
    page = '+++\ntitle = "Pole"\n+++\n\n```scene\nmodel: singular\nslider x: -1..1 step 0.5 default 1\n```\n'
    assert build_errors(write_book(tmp_path, {"pole": page})) == [
        "content/pole.md:5: scene 'singular': output 'inverse' is not "
        "finite (inf) at x=0.0; the model must return finite numbers" + FINITE_HINT
    ]


def test_project_book_builds_cleanly(built_site):
    """The book in content/ itself has no author errors: the session's build of it succeeded and
    wrote its home page and a page per Markdown file."""
    assert {p.stem for p in built_site.glob("*.html")} == {p.stem for p in (ROOT / "content").glob("*.md")}
