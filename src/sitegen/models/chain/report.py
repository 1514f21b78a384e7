"""The chain's part of the accuracy report: its work–precision diagram, its findings and its cost per digit."""

from __future__ import annotations

from html import escape

from ...render.work_precision import Panel, Point, Series, work_precision_figure
from ...site.report import summary
from ...site.report.html import MISSING, duration, figure, figure_html, label_html, run_point, sci, table


class ChainReport:
    """What the accuracy report shows of the chain's bench results (bench.json's "chain")."""

    def part(self, name: str, context) -> str:
        """The part `name` (the chain declares one: "chain")."""
        return chain_part(context)

    def findings(self, bench: dict) -> list[str]:
        """One sentence per chain size."""
        return [_chain_sentence(bench["chain"], n) for n in sorted({r["N"] for r in bench["chain"]["runs"]})]

    def per_digit(self, bench: dict) -> list[tuple[str, dict]]:
        """Per chain size: the time multiplier per extra digit of each method."""
        return [
            (f"chain, N = {n}", summary.chain_headlines(bench["chain"], n)["per_digit"])
            for n in sorted({r["N"] for r in bench["chain"]["runs"]})
        ]


def chain_part(context) -> str:
    """The chain's work–precision diagram (one panel per N) and its numbers."""
    if not context.bench:
        return MISSING
    chain = context.bench["chain"]
    sizes = sorted({run["N"] for run in chain["runs"]})
    label = (
        "Work–precision diagram of the chain of masses: error against time for each method, one panel per chain size."
    )

    def draw(narrow):
        return work_precision_figure(
            [_chain_panel(chain, n) for n in sizes],
            "median wall time per run (ms)",
            "max |u − u_DST| / A",
            "labels: ν = cΔt/a for Verlet, rtol = 10⁻ⁿ for RK45 and DOP853",
            narrow,
        )

    svg = figure(context, "chain", chain, label, draw)
    caption = (
        "One round trip (t = 2L/c) of the Gaussian pulse, σ = 0.05 L. Each line is a method; the number "
        "beside a point is its Courant number ν (velocity Verlet) or n in rtol = 10⁻ⁿ (RK45, DOP853). "
        "The ringed point is what the page uses: the exact DST solution, whose own error is its "
        "disagreement with a dense eigendecomposition."
    )
    rows = [
        [
            str(r["N"]),
            r["method"],
            f"rtol {summary.exponent_text(r['rtol'])}" if r["rtol"] else escape(r["setting"]),
            f"{r['steps']:,}",
            f"{r['evaluations']:,}",
            sci(r["error"]),
            duration(r["time_s"]),
            str(r["repeats"]),
        ]
        for r in chain["runs"]
    ]
    numbers = table(
        ["N", "method", "setting", "steps", "force evaluations", "error", "median time", "runs"],
        rows,
        "Every run of the chain experiment",
    )
    return figure_html("chain", svg, label, caption, numbers)


def _chain_panel(chain: dict, n: int) -> Panel:
    runs = [r for r in chain["runs"] if r["N"] == n and summary.usable(r)]
    series = [Series(method, tuple(run_point(r) for r in group)) for method, group in summary.methods(runs).items()]
    dst = summary.find(runs, "exact DST")
    chosen = Point(dst["time_s"] * 1e3, dst["error"], "chosen: exact DST") if dst else None
    return Panel(f"chain of N = {n} masses", tuple(series), chosen=chosen, floor=1e-16, ceiling=10.0)


def _chain_sentence(chain: dict, n: int) -> str:
    head = summary.chain_headlines(chain, n)
    parts = [f"<strong>Chain, N = {n}.</strong>"]
    if head["dst"]:
        parts.append(
            f"The exact DST solution takes {duration(head['dst']['time_s'])} per frame and agrees with a "
            f"dense eigendecomposition to {sci(head['dst']['error'])}."
        )
    if head["halving"]:
        h = head["halving"]
        parts.append(
            f"Halving Verlet's step (ν {h['from']:g} → {h['to']:g}) divides its error by {h['error']:.1f} "
            f"and multiplies its time by {h['time']:.1f}."
        )
    if head["cheapest_1e-6"]:
        c = head["cheapest_1e-6"]
        parts.append(
            f"The cheapest integrator within {sci(1e-6)} is {label_html(c)}: {duration(c['time_s'])}, "
            f"{head['dst_advantage']:.0f} times the DST's time for a worse answer."
        )
    return " ".join(parts)
