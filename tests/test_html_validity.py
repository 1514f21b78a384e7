"""Every built page is valid HTML, by the Nu HTML Checker (vnu.jar from the npm package vnu-jar,
run offline on Java): no errors, inline SVG and MathML included.

The checker runs once over the whole built site (one JVM start); each page is then one test case.
Warnings and notes are shown when a page fails but do not fail it. `make test` installs Java
(default-jre-headless) when it is missing.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from browser import ROOT

from sitegen.content.pages import discover_pages

VNU = ROOT / "node_modules" / "vnu-jar" / "build" / "dist" / "vnu.jar"
PAGES = [f"{path.stem}.html" for path in discover_pages(ROOT / "content")]


def run_vnu(*targets: Path) -> list[dict]:
    """The checker's messages for every HTML file under `targets` (folders or files), one JVM run."""
    java = shutil.which("java")
    if java is None:
        pytest.fail("java is not installed: `make test` installs default-jre-headless for the HTML checker")
    if not VNU.is_file():
        pytest.fail(f"{VNU} is missing: run `make test` (npm ci installs vnu-jar)")
    # A short run: the quick compiler alone and the serial collector halve the JVM's work (same messages).
    done = subprocess.run(
        [
            java,
            "-Xss8m",
            "-XX:TieredStopAtLevel=1",
            "-XX:+UseSerialGC",
            "-jar",
            str(VNU),
            "--format",
            "json",
            "--skip-non-html",
            *map(str, targets),
        ],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    if done.returncode not in (0, 1):  # 1: the checker found errors
        pytest.fail(f"vnu failed ({done.returncode}): {done.stderr[-2000:]}")
    return json.loads(done.stderr)["messages"]


def _is_error(message: dict) -> bool:
    return message["type"] == "error" or message.get("subType") == "fatal"


def _describe(message: dict) -> str:
    where = f"{message.get('lastLine', '?')}.{message.get('firstColumn', '?')}"
    kind = message["type"] + (f"/{message['subType']}" if "subType" in message else "")
    extract = " ".join(message.get("extract", "").split())[:120]
    return f"{where}: {kind}: {message['message']}  [{extract}]"


# A page the checker must reject, checked in the same run as the site (one JVM start is ~10 s).
INVALID_PAGE = (
    '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>x</title></head>'
    '<body><p id="a">one</p><p id="a">two</p><ul><p>not a list item</p></ul></body></html>'
)


@pytest.fixture(scope="module")
def checker_messages(built_site, tmp_path_factory) -> dict[str, list[dict]]:
    """The checker's messages for the built site and for INVALID_PAGE, by file name."""
    control = tmp_path_factory.mktemp("vnu-control") / "control-invalid.html"
    control.write_text(INVALID_PAGE, encoding="utf-8")
    by_page: dict[str, list[dict]] = {}
    for message in run_vnu(built_site, control):
        name = Path(message.get("url", "unknown").removeprefix("file:")).name
        by_page.setdefault(name, []).append(message)
    return by_page


def test_every_page_is_checked(built_site):
    """The pages parametrized here are exactly the pages built."""
    assert sorted(PAGES) == sorted(p.name for p in built_site.glob("*.html"))


@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_page_is_valid_html(checker_messages, name):
    """The Nu HTML Checker finds no error in the page."""
    messages = checker_messages.get(name, [])
    errors = [m for m in messages if _is_error(m)]
    assert not errors, f"{len(errors)} error(s) in {name}:\n" + "\n".join(_describe(m) for m in messages[:30])


def test_checker_reports_invalid_html(checker_messages):
    """The checker really runs: a page with a duplicate id and a misplaced element fails."""
    errors = [m["message"] for m in checker_messages.get("control-invalid.html", []) if _is_error(m)]
    assert any("Duplicate ID" in e for e in errors) and any("“p” not allowed" in e for e in errors), errors
