"""`sitegen bench` in a book of its own (tests/authors/pendulum: a pendulum whose period comes from solve_ivp,
checked against its elliptic-integral closed form), and the work–precision experiment read from declarations.

The end-to-end tests run the bench and the build on a copy of the book (its model declares a short ladder, so
the bench takes seconds). They check what the bench measured and what the page shows; the one that depends on
times (the scene's RK45 at rtol 1e-12 is dominated by DOP853) has a margin of about four to one. The rest
check the experiment's rules on plain data and declarations, with no clock.
"""

from __future__ import annotations

import ast
import contextlib
import io
import json
import re
import shutil
from pathlib import Path

import pytest

from sitegen.accuracy.experiments import FULL, QUICK, RTOLS, ladder, trials
from sitegen.build import BuildConfig, build
from sitegen.cli import main
from sitegen.content.bench_results import BENCH_NAME
from sitegen.physics import Model
from sitegen.physics.numerics import BenchScene, Numerics
from sitegen.site.report import summary

ROOT = Path(__file__).resolve().parents[1]
BOOK = Path(__file__).resolve().parent / "authors" / "pendulum"
METHODS = ("RK45", "DOP853", "LSODA")


@pytest.fixture(scope="module")
def benched(tmp_path_factory) -> tuple[Path, str, dict]:
    """The book copied, benchmarked (its own bench.json) and built: (built site, bench printout, bench.json)."""
    root = tmp_path_factory.mktemp("pendulum") / "book"
    shutil.copytree(BOOK, root, ignore=shutil.ignore_patterns(".cache", "bench.json", "__pycache__"))
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["bench", "--root", str(root)]) == 0
    bench = json.loads((root / "content" / BENCH_NAME).read_text())
    build(BuildConfig.at(root, root / "build", cache=None), progress=None)
    return root / "build", printed.getvalue(), bench


@pytest.mark.slow
def test_the_bench_measures_every_declared_method_over_its_ladder(benched):
    """One panel (the one scene), each method at rtol 1e-4, 1e-8 and 1e-12, every run with an error and a time."""
    _, _, bench = benched
    (panel,) = bench["models"]["pendulum"]["methods"]["panels"]
    measured = {(r["method"], r["value"]) for r in panel["runs"]}
    assert measured == {(m, rtol) for m in METHODS for rtol in (1e-4, 1e-8, 1e-12)}
    assert all(summary.usable(r) and r["evaluations"] > 0 for r in panel["runs"])
    assert panel["own"] == {"method": "RK45", "value": 1e-12, "text": "method RK45, rtol 1e-12"}


@pytest.mark.slow
def test_the_errors_follow_the_tolerances(benched):
    """Against the elliptic-integral period each method's error falls as rtol tightens (deterministic: no clock)."""
    _, _, bench = benched
    (panel,) = bench["models"]["pendulum"]["methods"]["panels"]
    for method in METHODS:
        errors = [summary.find(panel["runs"], method, rtol)["error"] for rtol in (1e-4, 1e-8, 1e-12)]
        assert errors[0] > 100 * errors[1] > 100 * errors[2] / 1e2 and errors[2] < 1e-10, method


@pytest.mark.slow
def test_the_diagram_has_a_line_per_method_and_rings_the_scenes_setting(benched):
    """The pendulum's part: an SVG whose legend names each declared method, the front and the ringed setting."""
    site, _, _ = benched
    html = (site / "accuracy.html").read_text()
    part = re.search(r'<div class="report-part" id="methods-pendulum">(.*?)</div>\n(?!</div>)', html, re.S)
    assert part, "the model's part is on the page"
    svg = re.search(r"<svg.*?</svg>", part[1], re.S)[0]
    legend = set(re.findall(r"<text[^>]*>([^<]+)</text>", svg))
    assert {*METHODS, "Pareto front", "scene's setting: RK45 rtol 1e-12"} <= {t.strip() for t in legend}


@pytest.mark.slow
def test_the_scenes_caption_links_to_its_models_part(benched):
    """The caption of the numerical scene links to the model's part of the accuracy page, which is there."""
    site, _, _ = benched
    swing = (site / "swing.html").read_text()
    assert 'href="accuracy.html#methods-pendulum"' in swing
    assert 'id="methods-pendulum"' in (site / "accuracy.html").read_text()


@pytest.mark.slow
def test_the_dominated_setting_is_reported_with_the_better_choice(benched):
    """RK45 at rtol 1e-12 takes about four times DOP853's time for the same digits: the bench names DOP853."""
    site, printed, _ = benched
    line = next(line for line in printed.splitlines() if line.strip().startswith("swing#swing: its setting"))
    assert "is dominated by DOP853" in line
    assert "It is dominated: DOP853" in (site / "accuracy.html").read_text()


# --- the rules, on declarations and plain data -------------------------------------------------------------


class Solver(Model):
    """A model with one method per kind of setting (nothing is evaluated)."""

    name, title, params, outputs = "solver", "Solver", (), ()
    numerics = Numerics("ivp", tolerance=1e-6, rtol=1e-6)
    methods = {"ivp": {"rtol": 1e-6}, "grid": {"nodes": 32}, "leapfrog": {"step": 0.01}, "transform": {}}


class Shorter(Solver):
    ladders = {"rtol": (1e-2, 1e-4), "grid": {"nodes": (8, 16)}, "leapfrog": {"step": ()}}


@pytest.mark.parametrize(
    "model, method, expected",
    [
        (Solver, "ivp", RTOLS),
        (Solver, "grid", (4, 8, 16, 32, 64, 128, 256, 512, 1024)),
        (Solver, "leapfrog", (0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125)),
        (Solver, "transform", ()),
        (Shorter, "ivp", (1e-2, 1e-4)),
        (Shorter, "grid", (8, 16)),
        (Shorter, "leapfrog", ()),
    ],
    ids=["rtol", "nodes", "step", "no-setting", "own-rtol", "own-nodes", "own-empty"],
)
def test_each_kind_of_setting_has_its_ladder_unless_the_model_declares_one(model, method, expected):
    """rtol 1e-3…1e-12, nodes 4…1024, the declared step ×4…÷32; a model's ladder replaces the default."""
    assert ladder(model, method) == pytest.approx(expected)


def test_a_scene_is_measured_at_its_own_settings_first_then_each_ladder():
    """The scene's settings (here off every ladder) come first; each other method keeps its declared settings."""
    own = Numerics("ivp", tolerance=1e-6, rtol=3e-7)
    scene = type("Scene", (), {"model": Shorter(own)})()
    found = trials(BenchScene("page#scene", scene, (), ()), FULL)
    assert list(found) == [("ivp", 3e-7), ("ivp", 1e-2), ("ivp", 1e-4), ("grid", 8), ("grid", 16), ("transform", None)]
    assert found["grid", 8] == Numerics("grid", tolerance=1e-6, nodes=8)
    assert list(trials(BenchScene("page#scene", scene, (), ()), QUICK)) == list(found)  # 2 values: no shorter


def _panel(*runs, own=("m", 1e-9)):
    rows = [
        {"method": m, "setting": "rtol", "value": v, "error": e, "time_s": t, "status": "ok"} for m, v, e, t in runs
    ]
    return {"own": {"method": own[0], "value": own[1]}, "runs": rows}


@pytest.mark.parametrize(
    "runs, better",
    [
        ((("m", 1e-9, 1e-10, 1.0), ("n", 1e-9, 2e-11, 0.5)), "n"),
        ((("m", 1e-9, 1.3e-10, 1.0), ("n", 1e-9, 1.5e-10, 0.5)), "n"),  # the same digits: as accurate
        ((("m", 1e-9, 1e-10, 1.0), ("n", 1e-9, 2e-10, 0.5)), None),  # a digit fewer
        ((("m", 1e-9, 1e-10, 1.0), ("n", 1e-9, 1e-11, 0.9)), None),  # faster, but within the timing noise
        ((("m", 1e-9, 1e-10, 1.0), ("n", 1e-12, 1e-13, 0.3), ("o", 1e-9, 1e-10, 0.2)), "o"),  # the fastest
    ],
    ids=["faster-and-better", "same-digits", "a-digit-fewer", "not-clearly-faster", "fastest-of-two"],
)
def test_a_setting_is_dominated_only_by_a_clearly_faster_one_with_as_many_digits(runs, better):
    """At most 80 % of the time and at least as many correct digits (floor of −log10 error)."""
    found = summary.dominating(_panel(*runs))
    assert (found and found["method"]) == better


def test_the_accuracy_package_imports_no_model():
    """accuracy/ reads models through their declarations only: no module of sitegen.models is imported there."""
    imported = []
    for path in sorted((ROOT / "src" / "sitegen" / "accuracy").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                imported.append((path.name, "." * node.level + (node.module or "")))
            elif isinstance(node, ast.Import):
                imported += [(path.name, alias.name) for alias in node.names]
    assert [(f, m) for f, m in imported if re.search(r"(^|\.)models(\.|$)", m)] == []
