"""A rebuild with nothing changed stops at the stamp, without loading the libraries; any change to an
input or to the output folder makes it build again."""

from __future__ import annotations

import subprocess
import sys

import pytest

from sitegen.cli import main

# Prints whether the build loaded numpy (a full build does; a stamped no-op must not).
_PROBE = (
    "import sys; from sitegen.cli import main; code = main(sys.argv[1:]); "
    "print('numpy loaded:', 'numpy' in sys.modules); sys.exit(code)"
)


def _build(root, *extra) -> str:
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, "build", "--root", str(root), *extra], capture_output=True, text=True, check=True
    )
    return done.stdout


@pytest.fixture
def stamped(tiny_book):
    """The tiny book, built once (so it has a stamp)."""
    assert main(["build", "--root", str(tiny_book.root)]) == 0
    return tiny_book


def test_a_rebuild_with_nothing_changed_stops_before_loading_numpy(stamped):
    log = _build(stamped.root)
    assert "up to date" in log and "numpy loaded: False" in log


def _rebuild(root, capsys, *extra) -> str:
    capsys.readouterr()
    assert main(["build", "--root", str(root), *extra]) == 0
    return capsys.readouterr().out


def test_any_change_to_an_input_or_the_output_builds_again(stamped, capsys):
    root, out = stamped.root, stamped.out
    page = root / "content" / "index.md"
    changes = {
        "page": lambda: page.write_text(page.read_text() + "\nOne more sentence.\n"),
        "config": lambda: (root / "book.toml").write_text('author = "Someone else"\n'),
        "a file in the models folder": lambda: (
            (root / "models").mkdir() or (root / "models" / "notes.txt").write_text("x")
        ),
        "a file next to the pages": lambda: (root / "content" / "notes.txt").write_text("x"),
        "the bibliography": lambda: (
            (root / "book.toml").write_text('bibliography = "refs.bib"\n') or (root / "refs.bib").write_text("% none\n")
        ),
        "the bibliography edited": lambda: (root / "refs.bib").write_text("% still none\n"),
        "output edited": lambda: (out / "index.html").write_text("edited by hand"),
        "output removed": lambda: (out / "index.html").unlink(),
        "output added": lambda: (out / "stray.html").write_text("a file the build did not write"),
    }
    for change, make in changes.items():
        make()
        assert "up to date" not in _rebuild(root, capsys), change
        assert "up to date" in _rebuild(root, capsys), change  # the build it made is stamped in turn
    assert "edited by hand" not in (out / "index.html").read_text()
    assert not (out / "stray.html").exists()


@pytest.mark.parametrize("option", ["--no-cache", "--explain"])
def test_asking_for_the_work_always_does_it(stamped, option, monkeypatch):
    import sitegen.build

    def reached(*args, **kwargs):  # stands for the build: reaching it is what is tested
        raise KeyboardInterrupt

    monkeypatch.setattr(sitegen.build, "build", reached)
    assert main(["build", "--root", str(stamped.root)]) == 0  # up to date: the build is not reached
    assert main(["build", "--root", str(stamped.root), option]) == 130


def test_a_failed_build_keeps_the_stamp_of_the_output_it_left(stamped, capsys):
    page = stamped.root / "content" / "index.md"
    text = page.read_text()
    page.write_text(text + "\n```scene\nmodel: no-such-model\n```\n")
    assert main(["build", "--root", str(stamped.root)]) == 1
    page.write_text(text)  # the inputs of the stamped build again, and build/ as that build left it
    assert "up to date" in _rebuild(stamped.root, capsys)
