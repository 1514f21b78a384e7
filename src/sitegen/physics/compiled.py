"""Compiled kernels (numba): a portable target, and a cache keyed by content rather than by place or time.

Every kernel is compiled for a generic x86-64 CPU (no FMA, no vector extensions the host happens to
have) and never with fastmath, so the numbers a kernel computes do not depend on the machine that
compiled it. The compiled code is cached on disk under a folder named by a digest of the kernels'
source files, numba's and llvmlite's versions and the target; the build points that cache at
`.cache/compiled/` and reports compiling (or loading) as its own step. Set SITEGEN_COMPILE_TARGET=host
to compile for the host CPU instead (used to test that the shown numbers do not change).
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import time
from contextlib import ExitStack, contextmanager
from importlib import metadata
from pathlib import Path

TARGET = os.environ.get("SITEGEN_COMPILE_TARGET", "generic")
if TARGET == "generic":  # must be set before numba builds its code generator
    os.environ["NUMBA_CPU_NAME"] = "generic"
    os.environ["NUMBA_CPU_FEATURES"] = ""

from numba.core import caching, config, types  # noqa: E402
from numba.core.registry import CPUDispatcher  # noqa: E402

config.reload_config()  # in case numba was imported before the target was set

CACHE_ENV = "SITEGEN_COMPILED_CACHE"  # where compiled code is kept; the build sets it to .cache/compiled
DEFAULT_CACHE = Path.home() / ".cache" / "sitegen" / "compiled"
_KERNELS: list = []  # every kernel, in definition order
_state = {"root": None, "ready": False}
READY = "ready"  # written into a cache folder once every kernel in it is compiled and warmed up


# error_model="numpy": a division by zero gives inf or NaN, as in numpy, instead of raising; the steppers
# reject such a step. nogil: the kernels release the GIL, so threads solve points side by side.
OPTIONS = {"nopython": True, "error_model": "numpy", "nogil": True}


def kernel(function):
    """Compile `function` with numba (on first use, from the content-keyed cache when it is there), for
    other kernels to call (`entry` makes one that the build calls from Python)."""
    # numba's wrapper that converts Python's arguments would be linked into every caller's code and
    # compiled again with it; kernels that kernels call leave it out (a tenth of the first compile).
    dispatcher = InnerKernel(function, targetoptions={**OPTIONS, "no_cpython_wrapper": True})
    _KERNELS.append(dispatcher)
    return dispatcher


def entry(function):
    """Compile `function` with numba as `kernel` does, as a kernel that the build calls from Python."""
    dispatcher = Kernel(function, targetoptions=OPTIONS)
    _KERNELS.append(dispatcher)
    return dispatcher


class Kernel(CPUDispatcher):
    """numba's dispatcher, compiled once per argument type when one kernel calls another.

    numba types a constant argument (`f(x, 0)`, `g(True)`), and a counter whose loop is not yet typed
    through, as a literal value and compiles the callee once for each value; these calls are typed by
    the plain types instead, so each kernel compiles once per signature. The numbers do not change:
    without fastmath the same operations run in the same order, folded or not.
    """

    def get_call_template(self, args, kws):
        """The call's typing, with literal argument types widened to their plain types."""
        plain = {key: types.unliteral(value) for key, value in kws.items()}
        return super().get_call_template(tuple(types.unliteral(a) for a in args), plain)


class InnerKernel(Kernel):
    """A kernel compiled without numba's Python wrapper, for other kernels to call."""

    def __call__(self, *args, **kws):
        """A call from Python (the tests'): through a twin compiled with the wrapper on first use, uncached.

        numba itself would jump to the missing wrapper and crash the process."""
        if "twin" not in self.__dict__:
            self.twin = Kernel(self.py_func, targetoptions=OPTIONS)
        return self.twin(*args, **kws)


# numba freezes a kernel's global constants into its code, and a kernel may read them from these (the
# bubble's DOP853 tableau is scipy's own): a new release of one must compile anew, not load stale code.
LIBRARIES = ("numba", "llvmlite", "numpy", "scipy")


def versions() -> str:
    """The compiling and constant-giving libraries and the target, as they enter every cache key of compiled results."""
    return ",".join(f"{name}=={metadata.version(name)}" for name in LIBRARIES) + f",target={target_name()}"


def target_name() -> str:
    """The CPU the kernels are compiled for: `generic`, or the host's name and features."""
    if TARGET == "generic":
        return "generic"
    import llvmlite.binding as llvm

    return f"{llvm.get_host_cpu_name()}:{llvm.get_host_cpu_features().flatten()}"


def source_key() -> str:
    """Digest of the kernels' source files, the library versions and the target: the cache's folder name."""
    files = sorted({Path(k.py_func.__code__.co_filename) for k in _KERNELS} | {Path(__file__)})
    text = "".join(f"{f.name}:{hashlib.sha256(f.read_bytes()).hexdigest()}\n" for f in files) + versions()
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cache_folder() -> Path:
    """Where this process keeps and finds the compiled code of the current kernels."""
    return Path(os.environ.get(CACHE_ENV) or DEFAULT_CACHE) / source_key()


def is_cached(root: Path) -> bool:
    """Whether preparing the kernels from `root` compiles nothing: this process has them already, or their
    compiled code is complete under `root`."""
    return _state["ready"] or (root / source_key() / READY).exists()


def use_cache(root: Path) -> None:
    """Keep compiled code under `root` (before the first kernel runs); children of this process inherit it."""
    os.environ[CACHE_ENV] = str(root)


def prepare(warm_up, part: str | None = None, parts: tuple[str, ...] = ()) -> tuple[float, bool]:
    """Compile every kernel or load it from the cache, then run `warm_up` (which calls the entry points).

    Returns (seconds, whether anything was compiled rather than loaded). Idempotent within a process.
    `part` (one of `parts`, the names of sets of entry points that processes may compile side by side):
    `warm_up` calls only that part's entry points; the cache is marked complete only by a call without one.
    A process that would compile what another is compiling into the same folder waits for it, then loads.
    """
    start = time.perf_counter()
    if _state["ready"]:
        return 0.0, False
    root = cache_folder()
    _state["root"] = root
    if ContentLocator not in caching.CacheImpl._locator_classes:
        caching.CacheImpl._locator_classes.insert(0, ContentLocator)
    for dispatcher in _KERNELS:
        dispatcher.enable_caching()
    before = {id(d): len(d.stats.cache_misses) for d in _KERNELS}
    with ExitStack() as held:
        for name in [part] if part else parts or ["all"]:
            held.enter_context(_compiling(root, name))
        warm_up()
    if part is None:
        _state["ready"] = True
        root.mkdir(parents=True, exist_ok=True)
        (root / READY).touch()
    compiled = any(len(d.stats.cache_misses) > before[id(d)] for d in _KERNELS)
    return time.perf_counter() - start, compiled


@contextmanager
def _compiling(root: Path, part: str):
    """Hold the lock of one part of the kernels in cache folder `root` (processes take turns compiling it)."""
    root.parent.mkdir(parents=True, exist_ok=True)
    with open(root.parent / f"{root.name}.{part}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        yield


class ContentLocator(caching._CacheLocator):
    """numba's cache locator for sitegen's kernels: one folder per content digest, stamped by it too.

    numba's own locators write next to the source (in __pycache__) or key by the source folder's path;
    this one keys by content, like the table cache, so a fresh clone and a worktree share nothing by
    accident and an edited kernel never meets a stale entry.
    """

    def __init__(self, py_func, py_file):
        self._py_file = py_file  # numba names it when it warns that a function cannot be cached
        self._lineno = py_func.__code__.co_firstlineno

    def get_cache_path(self):
        return str(_state["root"])

    def get_source_stamp(self):
        return _state["root"].name

    def get_disambiguator(self):
        return str(self._lineno)

    @classmethod
    def from_function(cls, py_func, py_file):
        if _state["root"] is None or not any(py_func is k.py_func for k in _KERNELS):
            return None
        locator = cls(py_func, py_file)
        locator.ensure_cache_path()
        return locator
