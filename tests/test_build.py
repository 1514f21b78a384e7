"""The built site as a whole: determinism, budgets, self-containment, and the command line."""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
from helpers import tree, write_book

from sitegen.site.assemble import scene_data_file, scene_data_json
from sitegen.site.sizes import gzip_bytes

ROOT = Path(__file__).resolve().parents[1]
PAGE_BUDGET_GZIP = 400 * 1024
SCRIPT_BUDGET = 24 * 1024  # the design's budget for the one script, unminified


def _cli_build(out: Path, seed: str, root: Path = ROOT, *options: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONHASHSEED": seed}
    return subprocess.run(
        [sys.executable, "-m", "sitegen.cli", "build", "--root", str(root), "--out", str(out), *options],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )


@pytest.mark.slow
def test_builds_are_byte_identical_across_folders_and_hash_seeds(tiny_book, tiny_site, tmp_path):
    """A build of the tiny book from its cache, into another folder under another hash seed in another
    process, gives the bytes of the session's build (from nothing, in this process): the cache's round
    trip, the rendering and the assembly are stable."""
    seed = "2" if os.environ.get("PYTHONHASHSEED") == "1" else "1"  # not this process's seed
    out = tmp_path / "b" / "out"
    assert _cli_build(out, seed, tiny_book.root).returncode == 0
    assert tree(out) == tree(tiny_site)


@pytest.mark.slow
def test_computing_from_nothing_is_deterministic_across_hash_seeds(tiny_book, tiny_site, tmp_path):
    """The tiny book (a scene of every model family, an ODE among them) computed from nothing under
    another hash seed, in another process whose work runs in two worker processes, gives the bytes of the
    session's build (in one process)."""
    done = _cli_build(tmp_path / "cold", "3", tiny_book.root, "--no-cache", "--jobs", "2")
    assert done.returncode == 0, done.stderr
    assert tree(tmp_path / "cold") == tree(tiny_site)


def test_output_holds_no_absolute_paths_or_dates(built_site):
    """Nothing in build/ mentions the machine's folders or a timestamp."""
    for name, data in tree(built_site).items():
        if name.endswith((".html", ".css", ".js")):
            text = data.decode()
            assert str(ROOT) not in text and str(built_site) not in text, name
            assert not re.search(r"20\d\d-\d\d-\d\dT\d\d:\d\d", text), name


def _page_load_bytes(site: Path, page: str) -> tuple[int, int]:
    """Raw and gzip bytes of a page plus every asset it links, the search index (loaded when the search
    box is first used) counted as if always loaded."""
    html = (site / page).read_text()
    assets = set(re.findall(r'(?:href|src|data-index)="(assets/[^"]+)"', html)) | {"assets/latinmodern-math.woff2"}
    assert "assets/search.js" in assets, "the search box names its index"
    files = [site / page, *(site / a for a in sorted(assets))]
    return sum(f.stat().st_size for f in files), sum(gzip_bytes(f.read_bytes()) for f in files)


PAGES = sorted(p.name for p in (ROOT / "content").glob("*.md"))


@pytest.mark.parametrize("page", [name.replace(".md", ".html") for name in PAGES])
def test_page_and_what_it_loads_fit_the_budget(built_site, page):
    """Each page with its script, stylesheet, math font and search index stays within 400 KB gzip."""
    raw, packed = _page_load_bytes(built_site, page)
    assert packed <= PAGE_BUDGET_GZIP, f"{page}: {packed / 1024:.0f} KB gzip (raw {raw / 1024:.0f} KB)"


def test_one_small_script(built_site):
    """The page script is one file within 24 KB unminified, loaded as a classic script by every page;
    the only other script is the search index with its code, a classic script that the search box
    loads when first used (assets/search.js)."""
    assert sorted(p.name for p in (built_site / "assets").glob("*.js")) == ["search.js", "sitegen.js"]
    assert (built_site / "assets" / "sitegen.js").stat().st_size <= SCRIPT_BUDGET
    assert (built_site / "assets" / "search.js").read_text().startswith("window.sitegenSearchIndex = {")
    for page in built_site.glob("*.html"):
        html = page.read_text()
        scripts = re.findall(r"<script\b[^>]*>", html)
        assert all('type="module"' not in s for s in scripts)
        assert '<script src="assets/sitegen.js" defer></script>' in html
        assert 'data-index="assets/search.js"' in html


@pytest.mark.parametrize("page", ["index.html", "newtons-laws.html"])
def test_pages_are_self_contained(built_site, page):
    """No URL leaves the site, no link points at a bare directory, every local link exists."""
    html = (built_site / page).read_text()
    links = [u for u in re.findall(r'(?:href|src)="([^"#]+)', html) if not u.startswith("data:")]
    assert not [u for u in links if re.match(r"[a-z]+:", u)], "external URL"
    for link in links:
        assert not link.endswith("/") and (built_site / link).is_file(), link


def test_scene_tables_are_strict_json(built_site):
    """Each scene's data script (one per scene, named in its element) keeps strict JSON (no NaN/Infinity), with no
    raw '<', '>' or '&', and keeps it by the scene element's id."""
    html = (built_site / "newtons-laws.html").read_text()
    scenes = re.findall(r'<figure class="scene" id="([^"]+)" data-scene="[^"]+" data-src="([^"]+)"', html)
    assert len(scenes) == (ROOT / "content" / "newtons-laws.md").read_text().count("```scene")
    for dom_id, name in scenes:
        script = (built_site / name).read_bytes()
        assert script.startswith(b"(window.sitegenScenes = window.sitegenScenes || {})[" + json.dumps(dom_id).encode())
        block = scene_data_json(script)
        assert not re.search(r"[<>&]", block)
        json.loads(block, parse_constant=lambda name: pytest.fail(f"non-finite constant {name}"))


def test_a_scene_data_script_gives_back_its_json_whatever_the_text_holds():
    """The data script keeps its JSON text as a string literal: text with " = ", "] = ", quotes and
    backslashes (a caption's formula, say) comes back unchanged, and the file is named by its content."""
    payload = json.dumps({"caption": 'F = ma, a["x"] = 1 \\ (window.sitegenScenes = {})', "n": [1, 2]})
    page, scene = SimpleNamespace(slug="laws"), SimpleNamespace(id="cart")
    name, script = scene_data_file(page, scene, payload)
    assert scene_data_json(script) == payload
    assert name.startswith("assets/scenes/laws.cart.") and name.endswith(".js")
    assert scene_data_file(page, scene, payload + " ")[0] != name


def test_math_is_converted_at_build_time(built_site):
    """Every formula became MathML; no TeX delimiters or placeholders are left in the page."""
    html = (built_site / "newtons-laws.html").read_text()
    assert html.count("<math") > 20
    text = re.sub(r"<(script|math)\b.*?</\1>", "", html, flags=re.S)
    assert "$" not in text and "data-math-slot" not in html and "data-scene-slot" not in html
    assert "𝐅" in html  # \mathbf F as a bold mathematical letter, which Chromium renders


def test_cli_reports_author_errors_without_traceback(tmp_path, capsys):
    """`sitegen build` on a broken book prints file:line errors, exits 1 and keeps quiet about Python."""
    from sitegen.cli import main

    write_book(tmp_path, {"index": '+++\ntitle = "Book"\n+++\n\n```scene\nmodel: colision\n```\n'})
    assert main(["build", "--root", str(tmp_path)]) == 1
    stderr = capsys.readouterr().err
    assert "content/index.md:6: scene 'colision': unknown model 'colision'" in stderr
    assert "Traceback" not in stderr
    assert not (tmp_path / "build").exists()


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.mark.parametrize("tty", [False, True], ids=["log", "terminal"])
def test_progress_inside_a_scene_is_a_line_in_a_log_and_replaced_on_a_terminal(tty):
    """In a log every update inside a long scene is a line of its own; on a terminal each replaces
    the last, and the scene's own line replaces the updates when it ends."""
    from sitegen.progress import BuildProgress

    stream = _Terminal() if tty else io.StringIO()
    progress = BuildProgress(stream, explain=False)
    for done in (16, 32):
        progress(f"  page#scene {done:>12,} of 48 stops, 8 stops/s")
    progress("[1/2] page#scene      48 stops    6.00 s  computed: new")
    text = stream.getvalue()
    if not tty:
        assert text.splitlines() == [
            "  page#scene           16 of 48 stops, 8 stops/s",
            "  page#scene           32 of 48 stops, 8 stops/s",
            "[1/2] page#scene      48 stops    6.00 s  computed",
        ]
    else:
        shown = text.split("\r\x1b[2K")
        assert shown[1] == "  page#scene           32 of 48 stops, 8 stops/s"  # the second update replaced the first
        assert shown[2].startswith("[1/2] page#scene      48 stops    6.00 s  computed\n[") and shown[2].endswith(
            "1/2 scenes"
        )
