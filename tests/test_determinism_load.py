"""Same sources, same bytes, whatever the load and the CPU: a small book of bubble scenes built beside a busy
CPU, and with its kernels compiled for the host CPU instead of the portable target, against a quiet build."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import tree, write_book

pytestmark = pytest.mark.slow  # bubble books built in other processes, beside spinning CPUs

ROOT = Path(__file__).resolve().parents[1]
BOOK = """+++
title = "Bubbles"
+++

# Bubbles

A chain first, then two bubbles.

```scene
model: chain
slider N: 4, 8 default 8
```

```scene
model: bubble
id: driven
fix R0: 4.5
slider p_a: 0.5..1.5 step 0.5 default 1.5
slider f: 10, 26.5 default 26.5
effects: gas, vdw_hard_core, surface_tension, viscosity, drive, keller_miksis
readouts: driven_R_max driven_t_Rmax driven_R_min driven_t_Rmin driven_mach driven_flag driven_solver
```

```scene
model: bubble
id: blake
slider R0: 0.1, 1, 10 default 1
slider depth: 0.98..1.02 step 0.02 default 1
effects: gas, vapour, surface_tension, viscosity, ramp
fix kappa: 1
readouts: ramp_growth ramp_R_max ramp_flag ramp_solver
```
"""


NOTES = """+++
title = "Notes"
+++

# Notes

A page with no scene.
"""


def _book(folder: Path, compiled: Path = ROOT / ".cache" / "compiled") -> Path:
    """A book of two small bubble scenes and a page of text, whose compiled code is kept in `compiled` (by
    default the project's, shared) and whose tables are its own."""
    write_book(folder, {"index": BOOK, "notes": NOTES})
    (folder / ".cache").mkdir()
    compiled.mkdir(parents=True, exist_ok=True)
    (folder / ".cache" / "compiled").symlink_to(compiled)
    return folder


def _build(root: Path, out: Path, *options: str, **env: str) -> str:
    done = subprocess.run(
        [sys.executable, "-m", "sitegen.cli", "build", "--root", str(root), "--out", str(out), "--no-cache", *options],
        capture_output=True,
        text=True,
        env={**os.environ, **env},
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture(scope="module")
def quiet(tmp_path_factory) -> tuple[Path, str]:
    """The book built from nothing on a machine left alone, with the portable target: its folder and its log."""
    root = _book(tmp_path_factory.mktemp("quiet") / "book")
    return root, _build(root, root.parent / "site")


def test_a_build_beside_a_busy_cpu_is_byte_identical_to_a_quiet_one(quiet, tmp_path):
    """Every core kept busy by spinning processes while a build runs: no output depends on the clock."""
    root, _ = quiet
    cores = (
        len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 2
    )  # ours, not the host's
    spinners = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(cores)]
    try:
        _build(root, tmp_path / "busy")
    finally:
        for spinner in spinners:
            spinner.kill()
            spinner.wait()
    assert tree(tmp_path / "busy") == tree(root.parent / "site")


def test_kernels_compiled_for_the_host_cpu_show_the_same_bytes_as_the_portable_ones(quiet, tmp_path):
    """The same book with the kernels compiled for this machine's CPU (its FMA and vector units allowed)
    gives the same site as with the portable target the build uses. The host's kernels are compiled afresh into
    the book's .cache/compiled/, where the worker processes load them (they compile nothing into another folder)."""
    root, generic = quiet
    fresh = _book(tmp_path / "book", compiled=tmp_path / "compiled")
    home = tmp_path / "home"  # where compiled code would go if a process were not told the book's folder
    host = _build(
        fresh,
        tmp_path / "host",
        "--jobs",
        "2",
        SITEGEN_COMPILE_TARGET="host",
        SITEGEN_COMPILED_CACHE="",
        HOME=str(home),
    )
    assert "compile   bubble: its first stop in" in host, host
    assert any(p.name.startswith("kernel_march.") for p in (tmp_path / "compiled").rglob("*")), "not compiled there"
    assert not (home / ".cache" / "sitegen").exists(), sorted(str(p) for p in home.rglob("*"))
    assert tree(tmp_path / "host") == tree(root.parent / "site")
