"""The preview's watcher rebuilds on what the build reads, not on the files editors and tools write beside it
while saving (a temporary renamed over the file, sed -i's copy, vim's swap file and writability test, emacs's
lock and auto-save, backups)."""

from __future__ import annotations

import threading
import time

import pytest

from sitegen.config import read_book
from sitegen.newbook import new_book
from sitegen.preview.watch import BookWatcher, watched

TEMPORARIES = [
    ".model.py.b4bce7e1c2.tmp",
    "sedA3GOwp",
    "model.py.swp",
    ".model.py.swx",
    "model.py~",
    "4913",
    ".#model.py",
    "#pendulum.md#",
    "pendulum.md.orig",
]
SOURCES = ["model.py", "pendulum.md", "extra.css", "page.html", "bench.json", "refs.bib"]


@pytest.mark.parametrize("name", TEMPORARIES)
def test_an_editors_temporary_is_not_watched(tmp_path, name):
    assert not watched(str(tmp_path / "models" / "pendulum" / name))


@pytest.mark.parametrize("name", SOURCES)
def test_a_file_the_build_may_read_is_watched(tmp_path, name):
    assert watched(str(tmp_path / "content" / name))


def test_a_save_with_its_temporaries_is_one_batch_of_the_saved_file(tmp_path):
    """Temporaries written into the models and content folders bring no batch; the saved page does, alone."""
    new_book(tmp_path / "book")
    book = read_book(tmp_path / "book")
    stop, batches = threading.Event(), []
    thread = threading.Thread(target=lambda: batches.extend(BookWatcher(book, stop).batches()), daemon=True)
    thread.start()
    time.sleep(1.0)  # the watchers are started
    try:
        for folder in (book.models / "pendulum", book.content):
            for name in TEMPORARIES:
                (folder / name).write_text("a temporary")
                (folder / name).unlink()
        time.sleep(1.5)  # several batch windows (at most 0.4 s each)
        assert batches == []
        page = book.content / "pendulum.md"
        page.write_text(page.read_text() + "\nOne more line.\n")
        deadline = time.monotonic() + 10
        while not batches and time.monotonic() < deadline:
            time.sleep(0.05)
        assert batches and all(batch == {page} for batch in batches)  # (a slow save may come in two)
    finally:
        stop.set()
        thread.join(timeout=5)
