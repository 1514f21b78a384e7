"""`sitegen serve --watch` on a book made by `sitegen new` (with a second page whose scene uses a
built-in model): the open page follows a prose edit by itself, keeping its scroll position and its
scene's state; a build error shows over the last good page with its file:line and goes when fixed;
an edit to the book's model recomputes only that model's scene; the reload script is in the served
pages only, never in build/; the server listens on 127.0.0.1 and serves nothing outside the output."""

from __future__ import annotations

import http.client
import json
import math
import re
import time
from pathlib import Path

import pytest
from preview import WatchServer
from scipy.integrate import quad

from sitegen.newbook import new_book

OTHER_PAGE = """+++
title = "A collision"
order = 2
+++

A scene of a built-in model beside the book's own.

```scene
model: collision
slider m1: 1..2 step 1 default 1
```
"""
SLIDER = "slider theta0: 5..175 step 5 default 60"
NARROW_VIEW = {"width": 390, "height": 640}  # a phone: the page is several screens long
HANG = 10_000  # ms: a guard against a page that never reloads; how soon it does is measured by bench/preview.py


@pytest.fixture(scope="module")
def book(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("preview") / "mybook"
    new_book(folder)
    (folder / "content" / "collision.md").write_text(OTHER_PAGE)
    return folder


@pytest.fixture(scope="module")
def server(book):
    watching = WatchServer(book)
    yield watching
    assert watching.stop() == 0


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new, 1))


def _get(server, path: str) -> tuple[int, bytes]:
    host, port = server.origin.removeprefix("http://").split(":")
    connection = http.client.HTTPConnection(host, int(port), timeout=10)
    try:
        connection.request("GET", path)
        response = connection.getresponse()
        return response.status, response.read()
    finally:
        connection.close()


def _period(theta_deg: float, length: float = 1.0, gravity: float = 9.81) -> float:
    """The period, with K(m) by quadrature (a second method beside the model's scipy.special.ellipk)."""
    m = math.sin(math.radians(theta_deg) / 2) ** 2
    k, _ = quad(lambda phi: (1 - m * math.sin(phi) ** 2) ** -0.5, 0, math.pi / 2, epsabs=1e-13)
    return 4 * math.sqrt(length / gravity) * k


def test_the_server_listens_on_loopback_and_serves_nothing_outside(server, book):
    """127.0.0.1 unless told otherwise; '..' (plain or encoded) gets a 404, never the book's files."""
    assert server.origin.startswith("http://127.0.0.1:")
    for path, name in (
        ("/../book.toml", "book.toml"),
        ("/%2e%2e/book.toml", "book.toml"),
        ("/assets/../../content/pendulum.md", "content/pendulum.md"),
        ("/..%2fmodels/pendulum/model.py", "models/pendulum/model.py"),
    ):
        status, body = _get(server, path)
        assert status == 404 and (book / name).read_bytes()[:40] not in body, path


def test_the_reload_script_is_in_served_pages_only(server, book):
    """Every served page carries the script; no file of build/ does; the event stream tells the state."""
    status, page = _get(server, "/pendulum.html")
    assert status == 200 and b'<script src="/__sitegen/reload.js" data-build="' in page
    assert page.count(b"</body>") == 1 and page.index(b"/__sitegen/reload.js") < page.index(b"</body>")
    assert not [p for p in (book / "build").rglob("*") if p.is_file() and b"__sitegen" in p.read_bytes()]
    status, script = _get(server, "/__sitegen/reload.js")
    assert status == 200 and b"EventSource" in script


def test_a_prose_edit_shows_in_the_open_page_by_itself(server, book, chromium):
    """The page reloads by itself with the new prose, where the reader was: same scroll position, same
    slider position (through the address), readouts of that position. (How soon is measured, not
    asserted: `python bench/preview.py` times saving an edit to Chromium showing it.)"""
    page = chromium.new_page(viewport=NARROW_VIEW)
    page.goto(server.url("pendulum.html"))
    page.evaluate("""() => { const s = document.querySelector('input[data-param="theta0"]');
                             s.value = '120'; s.dispatchEvent(new Event('input', {bubbles: true})); }""")
    page.wait_for_function("location.hash.includes('theta0=120')")
    page.evaluate("window.scrollTo(0, 420); window.notReloaded = true")
    scroll = page.evaluate("window.scrollY")
    assert scroll > 300
    start = time.monotonic()
    _edit(
        book / "content" / "pendulum.md", "Edit this page,", "A sentence added while the page was open. Edit this page,"
    )
    page.wait_for_function(  # `?.`: while the new page is being read it has no body yet
        "document.body?.innerText.includes('A sentence added while the page was open.')", timeout=HANG
    )
    seconds = time.monotonic() - start
    page.wait_for_load_state("load")
    page.wait_for_timeout(100)  # the scroll is put back once the page has loaded
    assert page.evaluate("window.notReloaded") is None  # a new page, not the old one patched
    assert page.evaluate("window.scrollY") == scroll
    assert page.evaluate("document.querySelector('input[data-param=\"theta0\"]').value") == "120"
    shown = page.evaluate("document.querySelector('[data-out=\"T\"]').textContent")
    assert shown == f"{_period(120):.3f} s", (shown, seconds)
    page.close()


def test_a_build_error_shows_over_the_last_good_page_and_goes_when_fixed(server, book, chromium):
    """A slider beyond the model's bound: the page keeps its content under an overlay naming the
    file and line and what is wrong; fixing it removes the overlay and reloads the page."""
    page = chromium.new_page(viewport=NARROW_VIEW)
    page.goto(server.url("pendulum.html"))
    source = book / "content" / "pendulum.md"
    line = source.read_text().splitlines().index(SLIDER) + 1
    _edit(source, SLIDER, SLIDER.replace("175", "190"))
    overlay = page.wait_for_selector("#sitegen-build-errors", timeout=10_000)
    text = overlay.inner_text()
    assert (
        f"content/pendulum.md:{line}: scene 'pendulum': slider 'theta0' max 190 exceeds the model's bound 179" in text
    ), text
    assert page.evaluate("document.querySelectorAll('[data-scene=\"pendulum\"]').length") == 1  # the last good page
    page.screenshot(path=str(book.parent / "overlay.png"))
    with page.expect_navigation(wait_until="load", timeout=10_000):  # the page reloads once the build succeeds
        _edit(source, SLIDER.replace("175", "190"), SLIDER)
    assert page.query_selector("#sitegen-build-errors") is None
    assert page.evaluate("document.querySelectorAll('[data-scene=\"pendulum\"]').length") == 1
    page.close()


def test_an_edit_to_the_books_model_recomputes_its_scene_only(server, book):
    """After the model's file changes, the rebuild computes the pendulum's scene and takes the
    collision's from the cache; the page shows the model's new digits."""
    model = book / "models" / "pendulum" / "model.py"
    _edit(
        model,
        'Output("T", "period T", "s", ("theta0", "L", "g"), decimals=3)',
        'Output("T", "period T", "s", ("theta0", "L", "g"), decimals=4)',
    )
    printed = server.lines_until("built models/pendulum/model.py", timeout=60)
    scenes = [line.strip() for line in printed if line.strip().startswith("[")]
    assert len(scenes) == 1 and " pendulum#pendulum " in scenes[0] and "computed" in scenes[0], printed
    assert re.search(r"3 pages, 2 scenes \(1 computed\)", printed[-1]), printed
    status, page = _get(server, "/pendulum.html")
    assert f'data-out="T">{_period(60):.4f} s<'.encode() in page


def _rebuilt(server, path: Path, line: str) -> None:
    """Wait for the rebuild after an edit of `path`, saving it again (same bytes) if the first save came
    before the watcher was watching (it starts once the first build is served)."""
    for _ in range(3):
        try:
            server.lines_until(line, timeout=20)
            return
        except AssertionError:
            path.write_bytes(path.read_bytes())
    server.lines_until(line, timeout=20)


def test_an_edited_picture_is_rebuilt_and_served(server, book):
    """A picture next to the pages is part of the book: editing it rebuilds, and the server sends its new bytes."""
    picture = book / "content" / "images" / "pendulum.svg"
    _edit(picture, 'fill="#1f63b5"', 'fill="#146c2e"')
    _rebuilt(server, picture, "built content/images/pendulum.svg")
    status, served = _get(server, "/images/pendulum.svg")
    assert status == 200 and served == picture.read_bytes()


def test_an_edited_bibliography_is_rebuilt(server, book):
    """The BibTeX file book.toml names (beside it, in the book's folder) is watched too."""
    bibliography = book / "references.bib"
    _edit(bibliography, "title     = {Mechanics}", "title     = {Mechanics, Course of Theoretical Physics 1}")
    _rebuilt(server, bibliography, "built references.bib")
    status, page = _get(server, "/pendulum.html")
    assert status == 200 and b"Mechanics, Course of Theoretical Physics 1" in page


def test_the_event_stream_sends_the_state_at_once(server):
    """A page that connects learns the last good build's number and that there are no errors."""
    host, port = server.origin.removeprefix("http://").split(":")
    connection = http.client.HTTPConnection(host, int(port), timeout=10)
    connection.request("GET", "/__sitegen/events")
    response = connection.getresponse()
    assert response.status == 200 and response.getheader("Content-Type") == "text/event-stream"
    lines = [response.fp.readline() for _ in range(4)]
    connection.close()
    state = json.loads(next(line for line in lines if line.startswith(b"data: "))[6:])
    assert state["errors"] == [] and state["build"] >= 1


@pytest.mark.parametrize(
    "arguments, message",
    [
        (["--dir", "build"], "serve --watch serves the book's output folder; leave out --dir"),
        ([], "no book.toml in"),
    ],
    ids=["with-dir", "outside-a-book"],
)
def test_watch_needs_a_book_and_no_dir(tmp_path, monkeypatch, capsys, arguments, message):
    """--watch builds a book: it needs one (book.toml here) and serves its output folder, no other."""
    from sitegen.cli import main

    if arguments:
        (tmp_path / "book.toml").write_text('title = "x"\n')
    monkeypatch.chdir(tmp_path)
    assert main(["serve", "--watch", "--port", "0", *arguments]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err
