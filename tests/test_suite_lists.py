"""The lists the test suite keeps about itself (tests/conftest.py) name tests, files and fixtures that exist: a
rename would otherwise drop out of them without a word (a slow test back in `make check`, a long file scheduled
last, a browser module run without its marker)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from conftest import BROWSER_MODULES, LONGEST_FIRST, SLOW_FIXTURES, SLOW_TESTS

TESTS = Path(__file__).resolve().parent


@pytest.mark.parametrize(
    "listed,name",
    [("LONGEST_FIRST", n) for n in LONGEST_FIRST] + [("BROWSER_MODULES", n) for n in sorted(BROWSER_MODULES)],
)
def test_each_listed_module_is_a_test_file(listed, name):
    assert (TESTS / f"{name}.py").is_file(), f"tests/conftest.py: {listed} names {name!r}, which is not a test file"


def test_longest_first_names_each_file_once():
    assert len(set(LONGEST_FIRST)) == len(LONGEST_FIRST)


@pytest.mark.parametrize("prefix", SLOW_TESTS)
def test_each_slow_prefix_names_a_file_and_a_test_in_it(prefix):
    """A prefix is "tests/<file>.py::" (the whole file) or "tests/<file>.py::<test name>" (or the start of its ids)."""
    path, _, test = prefix.partition("::")
    file = TESTS.parent / path
    assert file.is_file(), f"tests/conftest.py: SLOW_TESTS names {path}, which does not exist"
    name = re.match(r"\w*", test)[0]
    if name:
        assert re.search(rf"^def {name}\w*\(", file.read_text(), re.M), (
            f"tests/conftest.py: SLOW_TESTS names {prefix!r}, not a test of {path}"
        )


@pytest.mark.parametrize("name", sorted(SLOW_FIXTURES))
def test_each_slow_fixture_is_defined(name):
    """A fixture is defined by a function of its name under @pytest.fixture, in conftest.py or a test file."""
    pattern = re.compile(rf"@pytest\.fixture[^\n]*\n(?:@[^\n]*\n)*def {name}\(")
    assert any(pattern.search(path.read_text()) for path in TESTS.glob("*.py")), (
        f"tests/conftest.py: SLOW_FIXTURES names {name!r}, which no fixture in tests/ is called"
    )
