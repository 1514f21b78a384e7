"""`make bench`: a shelf, not a chapter. Builds generated shelves of 1, 4 and 16 copies of the chapter
"Newton's laws" (content/newtons-laws.md: six scenes, no bubble), each copy's scenes with a slider
range shortened by a different number of steps so that every scene must be computed, and prints per
shelf: the cold build (empty cache) in one process (`--jobs 1`) and with a worker per core (`--jobs auto`), the
peak memory of the latter (and that of the largest process it started: node converting the math, or a worker
process), and a rebuild with nothing changed.

Each build runs in a fresh process (`sitegen build`), which reports its own peak resident memory. Python's
compiled bytecode is kept, and an untimed build makes it first, as every run after a user's first finds it;
without it each build would also time Python compiling about a thousand modules (2 s on a 2-core machine).
Usage: python bench/shelf.py [COPIES ...]   (default 1 4 16)
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
import time
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CHAPTER = ROOT / "content" / "newtons-laws.md"
BIBLIOGRAPHY = ROOT / "content" / "references.bib"  # the chapter cites it
_RANGE = re.compile(r"^slider (\w+): (\S+)\.\.(\S+) step (\S+) default (\S+)$")
_PEAK = (
    "import resource, sys; from sitegen.cli import main; code = main(sys.argv[1:]); "
    "print('peak_kib', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, "
    "resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss); sys.exit(code)"
)


def shifted_chapter(text: str, shift: int) -> str:
    """The chapter with each scene's roomiest range slider ending `shift` steps lower (so no two
    copies share a scene's cache key) and its title numbered."""
    blocks = re.split(r"(```scene\n.*?```)", text, flags=re.S)
    for i in range(1, len(blocks), 2):
        lines = blocks[i].split("\n")
        sliders = [(n, _RANGE.match(line)) for n, line in enumerate(lines) if _RANGE.match(line)]
        n, found = max(sliders, key=lambda s: _room(s[1]))
        name, lo, hi, step, default = found.groups()
        lines[n] = f"slider {name}: {lo}..{_minus_steps(hi, step, shift)} step {step} default {default}"
        blocks[i] = "\n".join(lines)
    return re.sub(r'^title = "(.*)"$', rf'title = "\1 ({shift + 1})"', "".join(blocks), count=1, flags=re.M)


def _room(found: re.Match) -> float:
    """Steps between a slider's default and its maximum."""
    _, _, hi, step, default = found.groups()
    return (float(hi) - float(default)) / _value(step)


def _value(step: str) -> float:
    top, _, bottom = step.partition("/")
    return float(top) / float(bottom or 1)


def _minus_steps(hi: str, step: str, shift: int) -> str:
    """`hi` lowered by `shift` steps, written as a decimal; a fractional step (1/60) moves by the fewest
    whole steps whose length is a short decimal (3 frames: 0.05)."""
    length = Fraction(step)
    stride = next(m for m in range(1, length.denominator + 1) if (m * length * 10**6).denominator == 1)
    lowered = Fraction(hi) - shift * stride * length
    return format(Decimal(lowered.numerator) / Decimal(lowered.denominator), "f")


def on_its_own(text: str, copy: int) -> str:
    """The chapter as copy number `copy` of a shelf: its labels numbered (a label is unique in a book), links to
    the book's other pages as their text, and references to other pages' labels the word "elsewhere"."""
    own = set(re.findall(r"\{#([\w-]+)\}", text))
    scenes = set(re.findall(r"^id: ([\w-]+)$", text, flags=re.M))
    text = re.sub(r"\{#([\w-]+)\}", rf"{{#\1-{copy}}}", text)
    text = re.sub(r"\[([^\]]+)\]\((?!https?:)[\w-]+\.html[^)]*\)", r"\1", text)

    def reference(found: re.Match) -> str:
        label = found.group(1)
        return f"(@{label}-{copy})" if label in own else found.group(0) if label in scenes else "elsewhere"

    return re.sub(r"\(@([\w-]+)\)", reference, text)


def make_shelf(root: Path, copies: int) -> None:
    """A book of a home page and `copies` shifted copies of the chapter (with the book's bibliography)."""
    content = root / "content"
    content.mkdir(parents=True)
    (content / "index.md").write_text('+++\ntitle = "A shelf"\n+++\n\nThe same chapter, again and again.\n')
    text = CHAPTER.read_text()
    for k in range(copies):
        (content / f"chapter-{k + 1:02d}.md").write_text(shifted_chapter(on_its_own(text, k + 1), k))
    (content / BIBLIOGRAPHY.name).write_bytes(BIBLIOGRAPHY.read_bytes())
    (root / "book.toml").write_text(f'bibliography = "content/{BIBLIOGRAPHY.name}"\n')


def _build_env() -> dict[str, str]:
    """The builds' environment: this checkout's package, one BLAS thread, and bytecode kept."""
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "PYTHONPATH": str(ROOT / "src")}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def compile_bytecode() -> None:
    """Build a one-chapter shelf once, untimed, so that the timed builds read compiled bytecode rather than make it."""
    with tempfile.TemporaryDirectory() as folder:
        make_shelf(Path(folder), 1)
        timed_build(Path(folder))


def timed_build(root: Path, *options: str) -> tuple[float, float, float]:
    """Seconds and peak resident MiB of `sitegen build --root ROOT OPTIONS` in a fresh process, and of the largest
    process it started (node converting the math, or a worker process)."""
    start = time.perf_counter()
    command = [sys.executable, "-c", _PEAK, "build", "--root", str(root), *options]
    done = subprocess.run(command, capture_output=True, text=True, env=_build_env())
    seconds = time.perf_counter() - start
    if done.returncode:
        raise SystemExit(f"the shelf did not build:\n{done.stderr}")
    peak, child = re.search(r"peak_kib (\d+) (\d+)", done.stdout).groups()
    return seconds, int(peak) / 1024, int(child) / 1024


def main(counts: list[int]) -> None:
    print(
        "shelf: copies of the chapter 'Newton's laws' (6 scenes "
        "each), every scene computed; one fresh process per build"
    )
    compile_bytecode()
    print(
        f"{'chapters':>8} {'scenes':>7} {'cold s':>8} {'auto s':>8} {'s/chapter':>10} "
        f"{'peak MiB':>9} {'child MiB':>10} {'no-op s':>8}"
    )
    for copies in counts:
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            make_shelf(root, copies)
            cold, _, _ = timed_build(root, "--no-cache", "--jobs", "1")
            auto, peak, child = timed_build(root, "--no-cache", "--jobs", "auto")
            timed_build(root)  # the cache filled
            noop, _, _ = timed_build(root)
            print(
                f"{copies:>8} {6 * copies:>7} {cold:>8.2f} {auto:>8.2f} {auto / copies:>10.2f} {peak:>9.0f} "
                f"{child:>10.0f} {noop:>8.2f}",
                flush=True,
            )


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [1, 4, 16])
