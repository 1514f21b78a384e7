"""The browser engines in the test log: a run that drives a browser ends with one line naming each engine and
its version (conftest.py's `engines_line`), with pytest-xdist's workers too; a run that drives none has no such
line."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import engines_line
from engines import installed_versions

TESTS = Path(__file__).resolve().parent
LINE = re.compile(r"^browser engines: Chromium .+, Firefox ESR .+, WebKitGTK .+$", re.M)


def _report(keywords: dict) -> pytest.TestReport:
    return pytest.TestReport("t.py::test", ("t.py", 0, "test"), keywords, "passed", None, "call")


def test_no_line_without_a_browser_test():
    """Reports of tests that drove no browser (and things that are no test's report) make no line."""
    assert engines_line([_report({"test": 1, "slow": 1}), object()]) is None


def test_a_browser_test_makes_the_line():
    """One report of a test marked `browser` makes the line, every engine named in it, in order."""
    assert LINE.match(engines_line([_report({"test": 1}), _report({"test": 1, "browser": 1})]))


@pytest.mark.browser
def test_each_engine_tells_its_version():
    """Each installed engine's version is read from its binary or library: a number with dots."""
    versions = installed_versions()
    assert [re.sub(r" [\d.]+$", "", v) for v in versions] == ["Chromium", "Firefox ESR", "WebKitGTK"], versions


def _run(folder: Path, marked: bool) -> str:
    """What a run in two pytest-xdist workers prints of a test file with four tests, `browser` ones if `marked`."""
    (folder / "pytest.ini").write_text("[pytest]\nmarkers =\n    browser: drives a browser\n")
    mark = "pytestmark = pytest.mark.browser\n" if marked else ""
    tests = "".join(f"def test_{n}():\n    pass\n" for n in range(4))
    (folder / "test_some.py").write_text(f"import pytest\n{mark}{tests}")
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "conftest", "-n", "2", "-p", "no:cacheprovider", "test_some.py"],
        cwd=folder,
        env={**os.environ, "PYTHONPATH": str(TESTS)},
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


@pytest.mark.slow
@pytest.mark.parametrize("marked", [True, False], ids=["browser", "no-browser"])
def test_the_line_ends_a_run_in_several_processes(tmp_path, marked):
    """Run with pytest-xdist, the browser tests' marks come back from the workers: one line, only after them."""
    printed = _run(tmp_path, marked)
    assert len(LINE.findall(printed)) == (1 if marked else 0), printed
