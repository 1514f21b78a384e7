"""The accuracy–cost experiments (`sitegen bench`) and the "Accuracy and cost" page.

The experiments are checked on their error measurements — against closed forms, a second exact
method, and known perturbations — never on their timings. The page is checked in the built book.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from sitegen.accuracy.resolution import LINES, interpolation_error, resolution_experiment
from sitegen.build import BuildConfig, build
from sitegen.cli import main
from sitegen.content.bench_results import BENCH_NAME, load_results
from sitegen.errors import BuildFailed
from sitegen.models.bubble.bench import bubble_problem, case_errors, collapse_errors, extrema, skip_reason, solve_case
from sitegen.models.chain.bench import ROUND_TRIP as CHAIN_T
from sitegen.models.chain.bench import by_eigh as chain_by_eigh
from sitegen.models.chain.bench import exact_after_round_trip as chain_exact
from sitegen.models.chain.bench import pulse_error as chain_error
from sitegen.models.chain.bench import run_ivp as run_chain_ivp
from sitegen.models.chain.bench import run_verlet, verlet_steps
from sitegen.registry import builtin_registry
from sitegen.site.report import report_parts, summary
from sitegen.site.report.html import sci

MODELS = builtin_registry().models
DEFAULTS = MODELS["bubble"].defaults()

ROOT = Path(__file__).resolve().parents[1]


# --- the chain ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", [16, 64], ids=["N=16", "N=64"])
def test_verlet_error_falls_fourfold_per_halving_of_the_step(n):
    """Velocity Verlet is second order: ν 0.2 → 0.1 divides max|u − u_DST| by 4 (within 10 %)."""
    exact = chain_exact(n)
    coarse, fine = (chain_error(run_verlet(n, nu).u[-1], exact) for nu in (0.2, 0.1))
    assert 3.6 <= coarse / fine <= 4.4


def test_verlet_steps_hit_the_courant_number():
    """N = 64 (a = 1/65), ν = 0.5 over T = 2: 260 steps, as in physics.md §11.1."""
    assert verlet_steps(64, 0.5) == 260 and math.isclose(CHAIN_T, 2.0)


@pytest.mark.parametrize("n", [8, 64, 256], ids=["N=8", "N=64", "N=256"])
def test_dst_reference_agrees_with_a_dense_eigendecomposition(n):
    """The chain's reference (DST) and an independent eigh solution agree to 1e-11 of the amplitude."""
    assert chain_error(chain_by_eigh(n), chain_exact(n)) <= 1e-11


@pytest.mark.parametrize("rtol, bound", [(1e-6, 1e-4), (1e-9, 1e-7)], ids=["rtol=1e-6", "rtol=1e-9"])
def test_dop853_chain_error_follows_its_tolerance(rtol, bound):
    """DOP853 on N = 64 over one round trip: error below 100·rtol (measured 3.2e-6 and 2.6e-9)."""
    result = run_chain_ivp(64, "DOP853", rtol)
    assert result.status == 0 and chain_error(result.u[-1], chain_exact(64)) <= bound


def test_chain_error_measures_a_known_offset():
    """Negative control: the exact answer shifted by 1e-3 at one mass measures exactly 1e-3."""
    exact = chain_exact(32)
    shifted = exact.copy()
    shifted[5] += 1e-3
    assert chain_error(shifted, exact) == pytest.approx(1e-3, rel=1e-9)


# --- the bubble ---------------------------------------------------------------------------------------------


def test_dop853_preset_A_at_rtol_1e_9_is_within_1e_7_of_the_analytic_collapse():
    """Case A, DOP853 rtol 1e-9: max |ΔR|/R0 ≤ 1e-7 against betaincinv (measured 3.5e-10), stop time ≤ 1e-8 rel."""
    run = solve_case(bubble_problem("A", DEFAULTS), "DOP853", 1e-9)
    errors = collapse_errors(run, bubble_problem("A", DEFAULTS))
    assert errors["curve"] <= 1e-7 and errors["t_stop"] <= 1e-8


def test_analytic_collapse_has_no_error_against_itself():
    """The closed-form run measured against the closed form: 0 up to rounding (≤ 1e-14)."""
    pb = bubble_problem("A", DEFAULTS)
    errors = collapse_errors(solve_case(pb, "analytic", 0.0), pb)
    assert errors["curve"] <= 1e-14 and errors["t_stop"] <= 1e-14


def test_collapse_error_measures_a_known_offset():
    """Negative control: the analytic curve raised by 2e-4 R0 measures 2e-4."""
    run = solve_case(bubble_problem("A", DEFAULTS), "analytic", 0.0)
    raised = dataclasses.replace(run, r=run.r + 2e-4)
    assert collapse_errors(raised, bubble_problem("A", DEFAULTS))["curve"] == pytest.approx(2e-4, rel=1e-6)


def test_driven_readout_errors_measure_known_perturbations():
    """Case B readouts: a run whose R_max is 1e-5 larger (relative) than the reference measures exactly that."""
    pb = bubble_problem("B", DEFAULTS)
    reference = solve_case(pb, "DOP853", 1e-8)
    period = 2 * math.pi / pb.omega
    r_max = extrema(reference, period)[0]
    maxima = reference.maxima.copy()
    maxima[np.argmax(maxima[:, 1]), 1] = r_max * (1 + 1e-5)
    errors = case_errors("B", pb, dataclasses.replace(reference, maxima=maxima), reference)
    assert errors["R_max"] == pytest.approx(1e-5, rel=1e-6) and errors["R_min"] == 0 and errors["curve"] == 0


def test_driven_bubble_extrema_are_the_reference_readouts():
    """Case B (one period): R_max/R0 = 6.8115 and R_min/R0 = 0.17624 at t/T = 0.51661 (physics.md K4 preset B)."""
    pb = bubble_problem("B", DEFAULTS)
    r_max, r_min, t_min = extrema(solve_case(pb, "DOP853", 1e-10), 2 * math.pi / pb.omega)
    assert f"{r_max:.4f}" == "6.8115" and f"{r_min:.5f}" == "0.17624" and f"{t_min:.5f}" == "0.51661"


@pytest.mark.parametrize(
    "case, method, rtol, skipped",
    [
        ("C", "RK45", 1e-9, True),
        ("C", "DOP853", 1e-12, True),
        ("C", "RK45", 1e-6, False),
        ("C", "LSODA", 1e-12, False),
        ("B", "Radau", 1e-12, True),
        ("B", "Radau", 1e-9, False),
        ("B", "DOP853", 1e-12, False),
    ],
    ids=[
        "C-RK45-1e-9",
        "C-DOP853-1e-12",
        "C-RK45-1e-6",
        "C-LSODA-1e-12",
        "B-Radau-1e-12",
        "B-Radau-1e-9",
        "B-DOP853-1e-12",
    ],
)
def test_hopeless_combinations_are_skipped_with_a_reason(case, method, rtol, skipped):
    """Explicit methods on stiff C beyond two tolerances and Radau beyond 1e-10 on B are skipped, with a reason."""
    reason = skip_reason(case, method, rtol)
    assert (reason is not None) == skipped and (reason is None or len(reason) > 20)


# --- interpolation error against bytes ---------------------------------------------------------------------


@pytest.mark.parametrize(
    "line, axis, nodes",
    [("v1f", "w1", 2), ("dv", "inverse", 2), ("K_after", "quadratic", 3)],
    ids=["v1f-in-w1", "dv-in-1/m", "K_after-quadratic-in-e"],
)
def test_exactly_structured_axes_interpolate_to_round_off(line, axis, nodes):
    """Along w1 = m1/(m1+m2), 1/m and quadratically in e, 2–3 nodes reproduce the model at every stop to 1e-12."""
    error, _ = interpolation_error(LINES[line], axis, nodes)
    assert error <= 1e-12


def test_two_node_line_in_e_misses_the_parabola_by_its_sagitta():
    """K_after(e) = K_before − ½µΔ²(1 − e²) with µ = 2/3, Δ = 4: a chord through e = 0, 1 misses by
    16/3 · ¼ = 4/3 at e = ½."""
    error, _ = interpolation_error(LINES["K_after"], "linear", 2)
    assert error == pytest.approx(4 / 3, abs=1e-12)


@pytest.mark.parametrize(
    "line, axis, nodes, expected",
    [
        ("v1f", "linear", 17, 0.11),
        ("v1f", "log", 65, 4.9e-4),
        ("dv", "linear", 65, 1.29),
        ("dv", "log", 65, 3.6e-3),
        ("MA", "linear", 65, 51.0),
    ],
    ids=["v1f-linear-17", "v1f-log-65", "dv-linear-65", "dv-log-65", "MA-linear-65"],
)
def test_plain_axes_reproduce_the_measured_table(line, axis, nodes, expected):
    """The errors of physics.md §12 for linear and log axes (to the two digits it quotes)."""
    error, _ = interpolation_error(LINES[line], axis, nodes)
    assert error == pytest.approx(expected, rel=0.05)


def test_every_stop_row_stores_each_stop_at_four_bytes():
    """The 'every stop' rows: no interpolation error, 4 bytes per stop (201 for MA over x_p 0..2)."""
    rows = {row["line"]: row for row in resolution_experiment() if row["axis"] == "per stop"}
    assert rows["MA"]["bytes_float32"] == 804 and all(row["error"] == 0 for row in rows.values())


# --- the headline figures -----------------------------------------------------------------------------------


def _runs(points, method="m"):
    return [
        {"method": method, "rtol": 10.0**-k, "error": e, "time_s": t, "status": "ok"}
        for k, (t, e) in enumerate(points, 3)
    ]


def test_per_digit_cost_of_a_second_order_method_is_root_ten():
    """Error ∝ h², time ∝ 1/h: each extra digit multiplies the time by √10."""
    steps = [0.1 / 2**k for k in range(5)]
    assert summary.per_digit_cost(_runs([(1 / h, h**2) for h in steps])) == pytest.approx(math.sqrt(10), rel=1e-9)


def test_pareto_front_keeps_only_runs_nothing_beats():
    """Of (1 s, 1e-3), (2 s, 1e-2), (3 s, 1e-6), (4 s, 1e-5): the first and the third."""
    runs = _runs([(1, 1e-3), (2, 1e-2), (3, 1e-6), (4, 1e-5)])
    assert [r["time_s"] for r in summary.pareto(runs)] == [1, 3]


@pytest.mark.parametrize(
    "value, text",
    [
        (2.1e-7, "2.1 × 10<sup>−7</sup>"),
        (1e-12, "10<sup>−12</sup>"),
        (3.6e4, "3.6 × 10<sup>4</sup>"),
        (1.333, "1.3"),
        (51.3, "51"),
        (267.0, "270"),
        (0.0832, "0.083"),
        (0.0, "0"),
        (None, "—"),
    ],
    ids=["mantissa", "power", "large", "one", "tens", "hundreds", "hundredths", "zero", "missing"],
)
def test_numbers_are_written_as_the_captions_write_them(value, text):
    """sci(): two significant digits, as a power of ten outside 0.01…10⁴; 0 and a dash for none."""
    assert sci(value) == text


# --- the command and the JSON -------------------------------------------------------------------------------


def test_quick_bench_writes_strict_json_with_the_expected_keys(tmp_path):
    """`sitegen bench --quick` on a one-scene book writes strict, sorted JSON with every section; a book without
    numerical scenes measures no model (the impulse is a closed form)."""
    root = tmp_path / "book"
    (root / "content").mkdir(parents=True)
    (root / "book.toml").write_text("")
    (root / "content" / "index.md").write_text(
        '+++\ntitle = "Try"\n+++\n\n```scene\nmodel: impulse\nid: pulse\nslider m: 1..4 step 1 default 2\n```\n'
    )
    out = tmp_path / "bench.json"
    assert main(["bench", "--quick", "--root", str(root), "--out", str(out)]) == 0
    text = out.read_text()
    data = json.loads(text, parse_constant=lambda name: pytest.fail(f"non-finite {name}"))
    assert text == json.dumps(data, indent=1, sort_keys=True, allow_nan=False, ensure_ascii=False) + "\n"
    assert {"schema", "machine", "plan", "models", "resolution", "build", "seconds"} <= set(data)
    assert {"cpu", "cores", "python", "numpy", "scipy", "date"} <= set(data["machine"])
    assert data["models"] == {} and data["resolution"] == []
    assert set(data["build"]["scenes"]) == {"index#pulse"} and "index.html" in data["build"]["pages"]


def test_committed_bench_results_cover_every_experiment():
    """content/accuracy/bench.json (the page's source) holds a full run: chain N = 64 and 256, cases A, B, C with the
    compiled solvers beside scipy's, and the settings sweep of every bubble scene."""
    data = load_results(ROOT / "content" / BENCH_NAME)
    assert data is not None, "run `make bench` to write content/accuracy/bench.json"
    chain, bubble = (data["models"][name]["experiments"] for name in ("chain", "bubble"))
    assert [p["title"] for p in chain["chain-round-trip"]["panels"]] == [
        "chain of N = 64 masses",
        "chain of N = 256 masses",
    ]
    assert {f"bubble-{case}" for case in "ABC"} <= set(bubble)
    assert {r["method"] for r in bubble["bubble-B"]["panels"][0]["runs"]} == {
        "RK45",
        "DOP853",
        "Radau",
        "BDF",
        "LSODA",
        "compiled-DOP853",
        "compiled-Radau",
    }
    bubble_scenes = {
        f"newtons-laws-examples#{s}" for s in ("rayleigh-collapse", "driven-bubble", "driven-map", "blake-threshold")
    }
    sweeps = bubble["settings"]["scenes"]
    assert set(sweeps) == bubble_scenes
    for sweep in sweeps.values():  # at the chosen setting no shown value is wrong at any stop
        assert next(r for r in sweep["runs"] if r["rtol"] == sweep["chosen"])["wrong"] == 0


# --- the report blocks --------------------------------------------------------------------------------------


def _book_with(tmp_path: Path, block: str) -> BuildConfig:
    """A home page and an accuracy page holding one report block (no bench.json, no scenes)."""
    content = tmp_path / "content"
    content.mkdir(exist_ok=True)
    (content / "index.md").write_text('+++\ntitle = "Book"\n+++\n\nHome.\n')
    (content / "accuracy.md").write_text(f'+++\ntitle = "Accuracy"\n+++\n\nText.\n\n```accuracy-report\n{block}\n```\n')
    return BuildConfig(tmp_path, content, tmp_path / "build", cache=None)


def test_unknown_report_part_is_an_author_error_at_its_line(tmp_path):
    """`show: nope` names the file, the line and the parts there are (the book's and the models')."""
    with pytest.raises(BuildFailed) as failure:
        build(_book_with(tmp_path, "show: nope"), progress=None)
    parts = ", ".join(report_parts(MODELS))
    assert "chain, bubble, chain-round-trip, bubble-A, bubble-B, bubble-C, settings" in parts  # models, their own
    assert [str(e) for e in failure.value.errors] == [
        f"content/accuracy.md:8: accuracy-report: unknown part 'nope'; parts: {parts}"
    ]


@pytest.mark.parametrize(
    "part, text",
    [
        ("chain-round-trip", "No benchmark results yet"),
        ("chain", "No benchmark results yet"),
        ("scenes", "No numerical scenes were checked"),
    ],
    ids=["experiment-without-bench", "model-without-bench", "scenes-without-records"],
)
def test_report_blocks_say_clearly_when_there_is_nothing_to_show(tmp_path, part, text):
    """Without bench.json a bench part says how to get one; with no records the scene table says so."""
    config = _book_with(tmp_path, f"show: {part}")
    build(config, progress=None)
    html = (config.out / "accuracy.html").read_text()
    assert text in html and "data-report-slot" not in html


# --- the page in the built book ------------------------------------------------------------------------------


def test_accuracy_page_is_built_and_linked_from_the_home_page(built_site):
    """build/accuracy.html exists, the home page links to it, and no report slot is left unfilled."""
    assert (built_site / "accuracy.html").is_file()
    assert 'href="accuracy.html"' in (built_site / "index.html").read_text()
    assert not any("data-report-slot" in p.read_text() for p in built_site.glob("*.html"))


@pytest.mark.parametrize(
    "figure", ["chain-round-trip", "bubble-A", "bubble-B", "bubble-C", "settings", "bubble", "resolution"]
)
def test_accuracy_page_has_each_diagram_with_its_numbers(built_site, figure):
    """Each diagram: an inline SVG with a label, a caption and a table of the numbers behind it."""
    html = (built_site / "accuracy.html").read_text()
    found = re.search(
        rf'<figure class="report-figure" id="fig-{figure}">(.*?)</figure>\s*'
        r'<details class="report-data">(.*?)</details>',
        html,
        re.S,
    )
    assert (
        found
        and "<svg" in found[1]
        and 'role="img"' in found[1]
        and "<figcaption>" in found[1]
        and "<table" in found[2]
    )
    if figure != "resolution":
        assert "chosen:" in found[1] or "scene's setting:" in found[1], "the chosen setting is marked"


def test_every_checked_scene_has_its_row_and_its_caption_links_to_it(built_site):
    """Each caption link to accuracy.html#acc-… lands on a table row of the accuracy page, and each row is linked."""
    accuracy = (built_site / "accuracy.html").read_text()
    rows = set(re.findall(r'<tr id="(acc-[^"]+)"', accuracy))
    links = {
        anchor
        for page in built_site.glob("*.html")
        for anchor in re.findall(r'href="accuracy\.html#(acc-[^"]+)"', page.read_text())
    }
    assert rows and rows == links


def test_accuracy_page_quotes_the_machine_and_date_of_the_bench_run(built_site):
    """The page names the date and CPU of the committed bench run (the source of its timings)."""
    machine = load_results(ROOT / "content" / BENCH_NAME)["machine"]
    html = (built_site / "accuracy.html").read_text()
    assert machine["date"] in html and machine["cpu"] in html


def test_a_cold_timing_forgets_every_model_memo():
    """The per-scene cold times start from nothing: the bubble's memo of solved points (in its model
    folder, not in physics/) is emptied too, or every repeat after the first would time a lookup."""
    from sitegen.accuracy.build_costs import clear_model_caches
    from sitegen.models.bubble import solve
    from sitegen.models.bubble.presets import preset_problem

    pb, _ = preset_problem("A")
    solve.solve(pb)
    assert solve.solve.cache_info().currsize > 0
    clear_model_caches()
    assert solve.solve.cache_info().currsize == 0


def test_the_reports_diagrams_from_bench_alone_are_drawn_once_and_not_again_when_cached(tmp_path):
    """`bench_figures` (what the report draws from bench.json alone) gives every diagram of the report's parts that
    needs only bench.json, by the key the page caches it under; with those in the cache it draws none."""
    from sitegen.compute.cache import TableCache
    from sitegen.site.report import ReportContext, bench_figures, report_part
    from sitegen.site.report.html import FIGURES_KIND

    bench = load_results(ROOT / "tests" / "book" / "content" / BENCH_NAME)
    registry = builtin_registry()
    parts = ["machine", "chain-round-trip", "bubble-B", "digits", "scenes"]  # two diagrams; the scenes need the build
    drawn = bench_figures(bench, parts, registry.models, registry.reports)
    assert len(drawn) == 2
    assert all(svg.count(b"<svg") == 2 for svg in drawn.values())  # each wide and narrow

    asked = {}

    def cached(kind, key, compute):  # the page's own rendering, with this build's (empty) records
        asked[key] = compute()
        return asked[key]

    context = ReportContext(bench, (), (), (), {}, cached, registry.models, registry.reports)
    for part in parts:
        report_part(part, context)
    assert {key: asked[key] for key in drawn} == drawn

    cache = TableCache(tmp_path / "cache")
    for key, svg in drawn.items():
        cache.cached(FIGURES_KIND, key, lambda svg=svg: svg)
    assert bench_figures(bench, parts, registry.models, registry.reports, cache) == {}
