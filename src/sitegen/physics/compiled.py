"""Compiled kernels (numba): a portable target, and a cache folder named by the kernels' content.

A kernel is a function decorated with `kernel`: numba's `njit` with `cache=True`, error_model="numpy" (a
division by zero gives inf or NaN, as in numpy, instead of raising; the steppers reject such a step) and
nogil (a long solve leaves the preview's server thread free to answer). Kernels live in files named `kernel_*.py`
beside their model, and only numba's documented settings are used, each set in the environment before numba is imported:

- NUMBA_CPU_NAME=generic and no CPU features: every kernel is compiled for a generic x86-64 CPU (no FMA,
  no vector extensions the host happens to have) and never with fastmath, so the numbers it computes do not
  depend on the machine that compiled it. SITEGEN_COMPILE_TARGET=host compiles for the host CPU instead
  (used to test that the shown numbers do not change).
- NUMBA_CACHE_DIR: the folder SITEGEN_COMPILED_CACHE names (the `sitegen` command sets it to the book's
  .cache/compiled/), then a folder named by a digest of every kernel file, of the compiling libraries'
  versions and of the target. numba checks a kernel against its own file only; a kernel calls kernels of
  other files and freezes their module constants into its code, so an edit to any of them must meet a fresh
  folder. (numba also stamps entries with their file's modification time: a checkout that rewrites the
  files compiles again, into the same folder.)

The first call of a kernel in a process compiles it or loads it from that folder; the build makes that call
before it sends out work (see phases/scenes.py), so a pool's workers only load.
"""

from __future__ import annotations

import hashlib
import os
from importlib import metadata
from pathlib import Path

TARGET = os.environ.get("SITEGEN_COMPILE_TARGET", "generic")
CACHE_ENV = "SITEGEN_COMPILED_CACHE"  # where compiled code is kept; the `sitegen` command sets .cache/compiled
DEFAULT_CACHE = Path.home() / ".cache" / "sitegen" / "compiled"
# Every file whose code or constants a kernel compiles in: the kernels of every model, and this file.
KERNEL_FILES = (*sorted(Path(__file__).parents[1].glob("models/*/kernel_*.py")), Path(__file__))
LIBRARIES = ("numba", "llvmlite", "numpy")  # what compiles a kernel, and the numpy it compiles against


def target_name() -> str:
    """The CPU the kernels are compiled for: `generic`, or the host's name and features."""
    if TARGET == "generic":
        return "generic"
    import llvmlite.binding as llvm

    return f"{llvm.get_host_cpu_name()}:{llvm.get_host_cpu_features().flatten()}"


def versions() -> str:
    """The compiling libraries and the target, as they enter every cache key of compiled results."""
    return ",".join(f"{name}=={metadata.version(name)}" for name in LIBRARIES) + f",target={target_name()}"


def source_key() -> str:
    """Digest of the kernel files, the library versions and the target: the cache's folder name."""
    text = "".join(f"{f.name}:{hashlib.sha256(f.read_bytes()).hexdigest()}\n" for f in KERNEL_FILES) + versions()
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cache_folder() -> Path:
    """Where this process keeps and finds the compiled code of the current kernels."""
    return Path(os.environ.get(CACHE_ENV) or DEFAULT_CACHE) / source_key()


if TARGET == "generic":
    os.environ["NUMBA_CPU_NAME"] = "generic"
    os.environ["NUMBA_CPU_FEATURES"] = ""
else:  # numba's default: the host (a parent's generic settings are not inherited)
    os.environ.pop("NUMBA_CPU_NAME", None)
    os.environ.pop("NUMBA_CPU_FEATURES", None)
os.environ["NUMBA_CACHE_DIR"] = str(cache_folder())  # a child process computes its own (its files may differ)

import numba  # noqa: E402  (after its settings: numba reads them once, at import)

if numba.config.CPU_NAME != ("generic" if TARGET == "generic" else None):
    raise ImportError(
        "numba was imported before sitegen.physics.compiled, so its kernels would not be compiled for the "
        "portable target; import sitegen first, or set NUMBA_CPU_NAME=generic and NUMBA_CPU_FEATURES=''"
    )


def kernel(function):
    """`function` compiled with numba on its first call (or loaded from the cache folder)."""
    return numba.njit(cache=True, error_model="numpy", nogil=True)(function)
