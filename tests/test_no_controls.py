"""A scene with no controls (every parameter fixed) has nothing to reset: no Reset button (and no empty column of
controls beside its readouts), and its script runs without one."""

from __future__ import annotations

import pytest
from browser import logged_page
from helpers import write_book

from sitegen.build import build

STILL = '+++\ntitle = "Still"\n+++\n\n```scene\nmodel: impulse\nfix F_pk: 10\n```\n'
MOVING = '+++\ntitle = "Moving"\n+++\n\n```scene\nmodel: impulse\nslider F_pk: 0..20 step 10 default 10\n```\n'


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    config = write_book(tmp_path_factory.mktemp("controls"), {"still": STILL, "moving": MOVING})
    build(config, progress=None)
    return config.out


def test_a_scene_without_controls_has_no_reset_button(site):
    still, moving = (site / "still.html").read_text(), (site / "moving.html").read_text()
    assert "data-reset" not in still and "Reset</button>" not in still
    assert 'class="scene-controls"' not in still  # its readouts take the panel's first column
    assert moving.count("data-reset") == 1  # a scene with a slider keeps its button


def test_its_script_runs_without_the_button(site, chromium):
    """In Chromium the still scene shows its readouts and logs no error."""
    page, errors = logged_page(chromium)
    page.goto((site / "still.html").as_uri())
    assert page.locator("[data-reset]").count() == 0
    assert page.locator('[data-out="J"]').inner_text().endswith("N·s")
    page.close()
    assert errors == []
