"""Property-based fuzzing (hypothesis) of everything an author writes.

Random and mutated scene blocks, front matter and whole pages go to the scene parser, the
resolver, the page reader and the whole build. Each must either succeed or report author errors
(`AuthorError`, each at a line of the file it came from); any other exception is a bug. The runs
are derandomized and keep no example database, so CI sees the same cases every time; the
number of examples each property ran is printed (pytest -s or -rP) and recorded as a property.
"""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

import pytest
from examples import examples
from helpers import write_book
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from sitegen.build import build
from sitegen.compute.scenes import resolve_scene
from sitegen.content.pages import read_page
from sitegen.content.scenes import KEYS, parse_scene_block
from sitegen.errors import AuthorError, BuildFailed, SourceLoc
from sitegen.registry import builtin_registry

MODELS = builtin_registry().models
FIGURES = builtin_registry().figures

ROOT = Path(__file__).resolve().parents[1]
PAGE = "content/page.md"

FUZZ = settings(
    derandomize=True,  # the same examples on every run and every machine
    database=None,
    deadline=None,
    print_blob=False,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
)
EXAMPLES = {name: examples(n) for name, n in {"parser": 500, "resolver": 500, "page": 200, "build": 30}.items()}


# --- what authors type --------------------------------------------------------------------------

_ALL_PARAMS = sorted({p.name for m in MODELS.values() for p in m.params})
_ALL_OUTPUTS = sorted({o.name for m in MODELS.values() for o in m.outputs})
_ALL_EFFECTS = sorted({e for m in MODELS.values() for e in m.effects})
_ALL_CHOICES = sorted({c for m in MODELS.values() for p in m.params for c in p.choices})
_JUNK = ["", "x", "colision", "m 1", "é", "M1", "m1m1", "_", "1abc", "a-b", "tau_", "NaN", "∞", "$x$", "#", "`", "::"]
_NUMBERS = [
    "0",
    "1",
    "-1",
    "0.5",
    "2",
    "3",
    "5",
    "10",
    "-5",
    "0.25",
    "0.1",
    "1e3",
    "1e-3",
    ".5",
    "5.",
    "+3",
    "007",
    "1e999",
    "-1e999",
    "1e400",
    "1E-400",
    "1e-30",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "Infinity",
    "1_000",
    "0x10",
    "½",
    "",
    "abc",
    "1..2",
]
_CHARS = list(":.|,#`$ \t-+e0123456789{}\\\"'=[]") + ["\u00a0", "é", "\u0301", "\ufeff", "\u2212", "\x00", "\u202e"]

line_text = st.text(alphabet=st.characters(exclude_characters="\n"), max_size=30)  # a line holds no newline
numbers = (
    st.sampled_from(_NUMBERS)
    | st.integers(-(10**6), 10**6).map(str)
    | st.floats().map(repr)
    | st.decimals(allow_nan=True).map(str)
)
names = st.sampled_from(_ALL_PARAMS + _JUNK)
idents = st.sampled_from(sorted(MODELS) + sorted(FIGURES) + _JUNK)
options = st.sampled_from(_ALL_CHOICES + _JUNK)
word_lists = st.lists(st.sampled_from(_ALL_OUTPUTS + _ALL_EFFECTS + _JUNK), max_size=5).map(" ".join)
captions = st.sampled_from(
    [
        "",
        "A caption.",
        "Mass $m$ and $\\frac{1}{2}mv^2$.",
        "Broken $\\frac{1}{2$ here.",
        "$$x$$",
        "*emph* [link](x.html)",
        "<b>raw</b> & <",
        "$\\unknownmacro$",
    ]
)


@st.composite
def scene_lines(draw) -> str:
    """One line of a scene block: well formed, nearly so, or junk."""
    kind = draw(
        st.sampled_from(
            [
                "model",
                "id",
                "slider",
                "list",
                "choice",
                "fix",
                "effects",
                "readouts",
                "figure",
                "caption",
                "animate",
                "junk",
                "comment",
                "blank",
            ]
        )
    )
    if kind == "model":
        return f"model: {draw(idents)}"
    if kind == "id":
        return f"id: {draw(idents | line_text)}"
    if kind == "slider":
        lo, hi, step, default = (draw(numbers) for _ in range(4))
        return f"slider {draw(names)}: {lo}..{hi} step {step} default {default}"
    if kind == "list":
        stops = draw(st.lists(numbers, min_size=1, max_size=5))
        return f"slider {draw(names)}: {', '.join(stops)} default {draw(numbers)}"
    if kind == "choice":
        offered = draw(st.lists(options, min_size=1, max_size=4))
        return f"choice {draw(names)}: {' | '.join(offered)} default {draw(options)}"
    if kind == "fix":
        return f"fix {draw(names)}: {draw(numbers)}"
    if kind in ("effects", "readouts"):
        return f"{kind}: {draw(word_lists)}"
    if kind == "figure":
        return f"figure: {draw(idents)}"
    if kind == "caption":
        return f"caption: {draw(captions)}"
    if kind == "animate":
        return f"animate: {draw(names)}"
    if kind == "comment":
        return "# " + draw(line_text)
    if kind == "blank":
        return ""
    return draw(st.sampled_from([f"{k}:" for k in KEYS] + [f"{k} x" for k in KEYS]) | line_text)


@st.composite
def mutate(draw, lines: list[str]) -> list[str]:
    """A few edits of the kinds a typo makes: a character dropped, added or changed, a line lost,
    doubled or swapped, a number or a name replaced."""
    lines = list(lines)
    for _ in range(draw(st.integers(0, 3))):
        op = draw(
            st.sampled_from(["drop_char", "add_char", "drop_line", "dup_line", "swap", "number", "name", "truncate"])
        )
        if not lines:
            break
        i = draw(st.integers(0, len(lines) - 1))
        line = lines[i]
        at = draw(st.integers(0, len(line)))
        if op == "drop_char" and line:
            lines[i] = line[: min(at, len(line) - 1)] + line[min(at, len(line) - 1) + 1 :]
        elif op == "add_char":
            lines[i] = line[:at] + draw(st.sampled_from(_CHARS)) + line[at:]
        elif op == "drop_line":
            del lines[i]
        elif op == "dup_line":
            lines.insert(i, line)
        elif op == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == "number":
            found = list(re.finditer(r"-?\d+(?:\.\d+)?", line))
            if found:
                m = found[draw(st.integers(0, len(found) - 1))]
                lines[i] = line[: m.start()] + draw(numbers) + line[m.end() :]
        elif op == "name":
            found = list(re.finditer(r"[A-Za-z_][A-Za-z0-9_]*", line))
            if found:
                m = found[draw(st.integers(0, len(found) - 1))]
                lines[i] = line[: m.start()] + draw(names | idents) + line[m.end() :]
        else:
            lines[i] = line[:at]
    return lines


def _book_blocks() -> list[list[str]]:
    """The book's own scene blocks, as seeds for mutation."""
    blocks = []
    for path in sorted((ROOT / "content").glob("*.md")):
        text = path.read_text(encoding="utf-8")
        blocks += [b.split("\n") for b in re.findall(r"^```scene\n(.*?)\n```$", text, flags=re.S | re.M)]
    return blocks


SEEDS = _book_blocks()
scene_bodies = st.lists(scene_lines(), max_size=10) | st.sampled_from(SEEDS).flatmap(mutate)


def _block(body: list[str], closed: bool = True) -> str:
    return "\n".join(["```scene", *body, *(["```"] if closed else [])])


front_matters = st.sampled_from(
    [
        '+++\ntitle = "A page"\n+++',
        '+++\ntitle = "A page"\norder = 2\nparent = "index"\nsummary = "About it."\n+++',
        '+++\ntitle = "Unclosed',
        '+++\ntitle = "A page"',
        "+++\n+++",
        "+++\ntitle = 5\n+++",
        '+++\ntitle = ""\n+++',
        '+++\ntitle = "T"\norder = "first"\n+++',
        '+++\ntitle = "T"\norder = 1.5\n+++',
        '+++\ntitle = "T"\norder = nan\n+++',
        '+++\ntitle = "T"\norder = inf\n+++',
        '+++\ntitle = "T"\norder = 99999999999999999999\n+++',
        '+++\ntitle = "T"\norder = true\n+++',
        '+++\ntitle = "T"\nparent = 3\n+++',
        '+++\ntitle = "T"\nparent = "nowhere"\n+++',
        '+++\ntitle = "T"\nparent = "page"\n+++',
        '+++\ntitle = ["T"]\n+++',
        '+++\ntitle = "T"\nsummary = { a = 1 }\n+++',
        "+++\n[title]\nx = 1\n+++",
        '+++\ntitle = "T"\ntitle = "U"\n+++',
        "---\ntitle: YAML\n---",
        "",
        '\ufeff+++\ntitle = "BOM"\n+++',
        '+++\r\ntitle = "CRLF"\r\n+++',
    ]
)
prose = st.sampled_from(
    [
        "Some prose.",
        "Inline $x^2$ math.",
        "Broken $\\frac{1}{2$ math.",
        "$$\nE = mc^2\n$$",
        "$$\nE = mc^2 $$ {#eq-energy}",
        "See (@eq-energy) and (@eq-missing).",
        "$$ unclosed display",
        "```\ncode $x$\n```",
        "~~~\nunclosed code",
        "```python\nx = 1",
        "<div>raw <b>html</b></div>",
        "| a | b |\n|---|---|\n| 1 | 2 |",
        "# Heading {#id}",
        "[link](other.html#x)",
        "$",
        "$$",
        "\\$5 and $5",
    ]
) | st.text(max_size=40)


@st.composite
def pages(draw) -> str:
    """A whole page: front matter (fine or broken), prose, math and scene blocks."""
    parts = [draw(front_matters)]
    for _ in range(draw(st.integers(0, 4))):
        if draw(st.booleans()):
            parts.append(_block(draw(scene_bodies), closed=draw(st.integers(0, 9)) > 0))
        else:
            parts.append(draw(prose))
    return "\n\n".join(parts) + draw(st.sampled_from(["\n", "", "\n\n"]))


# --- checking what came back ---------------------------------------------------------------------


def assert_author_errors(errors, path: str, first: int, last: int) -> None:
    """Each error is an AuthorError at a line of `path` between `first` and `last`, shown as
    'path:line: message' with a message that says something."""
    for error in errors:
        assert type(error) is AuthorError, repr(error)
        assert error.loc.path == path and first <= error.loc.line <= last, (str(error), first, last)
        text = str(error)
        assert text.startswith(f"{path}:{error.loc.line}: ") and len(error.message) > 10, text
        assert "Traceback" not in text and "\n" not in error.message, text


def _report(request, name: str, count: int) -> None:
    request.node.user_properties.append(("examples", count))
    print(f"\n{name}: {count} examples")
    assert count >= EXAMPLES[name] * 0.9, f"hypothesis ran only {count} examples"


# --- the properties ------------------------------------------------------------------------------


def test_scene_block_parser_never_crashes(request):
    """Random and mutated scene blocks: a spec or errors at the block's lines, never an exception."""
    count = 0

    @settings(FUZZ, max_examples=EXAMPLES["parser"])
    @given(body=scene_bodies)
    def run(body):
        nonlocal count
        count += 1
        fence = SourceLoc(PAGE, 10)
        spec, errors = parse_scene_block(body, fence)
        assert_author_errors(errors, PAGE, 10, 10 + len(body))
        if spec is None:
            assert errors

    run()
    _report(request, "parser", count)


@pytest.mark.slow
def test_scene_resolution_never_crashes(request):
    """Parsed blocks checked against the real models and figures: resolved, or author errors."""
    count = 0

    @settings(FUZZ, max_examples=EXAMPLES["resolver"])
    @given(body=scene_bodies)
    def run(body):
        nonlocal count
        spec, _ = parse_scene_block(body, SourceLoc(PAGE, 10))
        assume(spec is not None)
        count += 1
        scene, errors = resolve_scene(spec, MODELS)
        assert_author_errors(errors, PAGE, 10, 10 + len(body))
        assert (scene is None) == bool(errors)
        if scene is not None:  # what the build relies on once a scene resolves
            assert all(
                axis.count >= 1 and axis.index_of(axis.stop(k)) == k for axis, k in zip(scene.axes, scene.default_stops)
            )
            assert all(scene.model.param(p).contains(v) for p, v in scene.fixed)

    run()
    _report(request, "resolver", count)


def test_page_reader_never_crashes(request, tmp_path):
    """Whole pages, broken anywhere, and bytes that are not UTF-8: a page or errors at its lines."""
    count = 0
    folder = tmp_path
    (folder / "content").mkdir()

    @settings(FUZZ, max_examples=EXAMPLES["page"])
    @given(text=pages(), garble=st.sampled_from([None, b"\xff", b"\xc3", b"\xe2\x82", b"\x80abc"]))
    def run(text, garble):
        nonlocal count
        count += 1
        path = folder / "content" / "page.md"
        data = text.encode("utf-8")
        if garble is not None:
            data = data[: len(data) // 2] + garble + data[len(data) // 2 :]
        path.write_bytes(data)
        page, errors = read_page(path, folder)
        assert_author_errors(errors, PAGE, 1, data.count(b"\n") + 1)
        if page is None:
            assert errors

    run()
    _report(request, "page", count)


# Cheap models with small grids: the build fuzz evaluates, draws and writes every scene that resolves.
_BUILD_SEEDS = [
    [
        "model: impulse",
        "slider F_pk: 0..10 step 2 default 4",
        "slider tau: 0.1..0.5 step 0.1 default 0.2",
        "slider m: 1..3 step 1 default 2",
        "readouts: J dp dv",
        "caption: Impulse $J$.",
    ],
    [
        "model: collision",
        "id: carts",
        "slider m1: 0.5..2 step 0.5 default 1",
        "slider v1i: -2..2 step 1 default 1",
        "fix v2i: 0",
        "effects: restitution_law",
        "slider e: 0..1 step 0.5 default 1",
        "readouts: v1f v2f status",
    ],
    [
        "model: lever",
        "slider m_L: 1..3 step 1 default 2",
        "slider x_p: 0..2 step 0.5 default 1",
        "fix balance_tolerance: 0.005",
        "readouts: tau_L tau_R state",
    ],
    [
        "model: ossicles",
        "choice load: water | cochlea default water",
        "slider SPL: 40..80 step 20 default 60",
        "effects: lever area_ratio load_model",
        "readouts: G T0",
    ],
    ["model: euler_slab", "slider phi: 0..90 step 45 default 0", "slider spl: 60, 94 default 94", "animate: phi"],
    [
        "model: acoustic_energy",
        "slider SPL: 80..100 step 10 default 90",
        "slider R_r: 0..1 step 0.5 default 0",
        "effects: reflection",
    ],
]
_SMALL_NUMBERS = [
    "0",
    "1",
    "-1",
    "0.5",
    "2",
    "3",
    "-2",
    "0.25",
    "1e20",
    "-1e20",
    "1e999",
    "nan",
    "inf",
    "1e-400",
    "",
    "x",
    "2..1",
]


@st.composite
def small_mutations(draw, lines: list[str]) -> list[str]:
    """Like `mutate`, but numbers stay small enough that every grid is cheap to compute."""
    lines = list(lines)
    for _ in range(draw(st.integers(0, 3))):
        op = draw(st.sampled_from(["drop_char", "drop_line", "dup_line", "number", "name", "swap_range"]))
        if not lines:
            break
        i = draw(st.integers(0, len(lines) - 1))
        line = lines[i]
        if op == "drop_char" and line:
            at = draw(st.integers(0, len(line) - 1))
            lines[i] = line[:at] + line[at + 1 :]
        elif op == "drop_line":
            del lines[i]
        elif op == "dup_line":
            lines.insert(i, line)
        elif op == "number":
            found = list(re.finditer(r"-?\d+(?:\.\d+)?", line))
            if found:
                m = found[draw(st.integers(0, len(found) - 1))]
                lines[i] = line[: m.start()] + draw(st.sampled_from(_SMALL_NUMBERS)) + line[m.end() :]
        elif op == "name":
            found = list(re.finditer(r"[A-Za-z_][A-Za-z0-9_]*", line))
            if found:
                m = found[draw(st.integers(0, len(found) - 1))]
                lines[i] = (
                    line[: m.start()] + draw(st.sampled_from(_ALL_PARAMS + _ALL_OUTPUTS[:40] + _JUNK)) + line[m.end() :]
                )
        elif op == "swap_range":
            lines[i] = re.sub(r"(\S+)\.\.(\S+)", r"\2..\1", line)
    return lines


def _cheap(body: list[str]) -> bool:
    """Whether every scene in the block stays small: no more than 400 states, known cheap model."""
    spec, _ = parse_scene_block(body, SourceLoc(PAGE, 1))
    if spec is None:
        return True
    if spec.model in ("bubble", "chain", "kinetic", "work"):
        return False
    states = 1
    for slider in spec.sliders:
        if hasattr(slider, "options"):
            states *= len(slider.options)
        elif slider.listed:
            states *= len(slider.listed)
        elif slider.step > 0 and slider.hi >= slider.lo:
            states *= min(int((slider.hi - slider.lo) / slider.step) + 1, 10**6)
    return states <= 400


@pytest.mark.slow
def test_build_of_fuzzed_books_succeeds_or_reports_author_errors(request, tmp_path):
    """A book of a home page and a fuzzed page (front matter, prose, mutated scene blocks) builds,
    or fails with BuildFailed whose every error points into content/; nothing else escapes,
    and a failed build writes nothing."""
    count, outcomes = 0, {"built": 0, "failed": 0}
    folder = tmp_path

    @settings(FUZZ, max_examples=EXAMPLES["build"])
    @given(
        front=st.sampled_from(['+++\ntitle = "A page"\n+++'] * 3) | front_matters,
        text=prose,
        bodies=st.lists(st.sampled_from(_BUILD_SEEDS).flatmap(small_mutations), min_size=1, max_size=2),
    )
    def run(front, text, bodies):
        nonlocal count
        assume(all(_cheap(b) for b in bodies))
        count += 1
        root = Path(tempfile.mkdtemp(dir=folder))
        config = write_book(root, {"page": "\n\n".join([front, text, *(_block(b) for b in bodies)]) + "\n"})
        try:
            report = build(config, progress=None)
        except BuildFailed as failure:
            outcomes["failed"] += 1
            assert failure.errors
            for error in failure.errors:
                lines = (
                    (root / error.loc.path).read_text(encoding="utf-8").count("\n") + 1
                    if error.loc.path.endswith(".md")
                    else 1
                )
                assert_author_errors([error], error.loc.path, 1, lines)
            assert not config.out.exists()
        else:
            outcomes["built"] += 1
            assert report.pages == 2 and (config.out / "page.html").is_file()

    run()
    print(f"\nbuild fuzz outcomes: {outcomes}")
    request.node.user_properties.append(("outcomes", outcomes))
    _report(request, "build", count)
    assert outcomes["built"] >= 3 and outcomes["failed"] >= 3, outcomes
