"""What a cache key knows of code: the hash of a module's source and of every module it imports (within
sitegen and within the module's own package, transitively), and the versions of the numerical libraries.

A module's imports are read from its source (import statements anywhere in its body), so a key follows the
files a model really uses and nothing else; sources are hashed, never judged by their modification time.
"""

from __future__ import annotations

import ast
import collections
import functools
import hashlib
import importlib.util
import sys
from importlib import metadata
from pathlib import Path

from ..physics import compiled

PACKAGE_ROOT = Path(__file__).resolve().parents[1]  # src/sitegen
LIBRARIES = ("numpy", "scipy", "matplotlib", "numba", "llvmlite")


def source_digest(modules: frozenset[str]) -> str:
    """Hash of the source of `modules` and of every module of theirs and of sitegen they import, transitively."""
    seen = source_hashes(modules)
    return sha("".join(f"{n}:{seen[n]}\n" for n in sorted(seen)))


def source_hashes(modules: frozenset[str]) -> dict[str, str]:
    """{module: hash of its source} for `modules` and what they import, transitively, within sitegen
    and within each module's own top-level package (a plugin's other modules; not numpy, not other plugins)."""
    roots = {"sitegen"} | {_top(m) for m in modules}
    seen: dict[str, str] = {}
    pending = sorted(modules)
    while pending:
        name = pending.pop()
        if name in seen or _top(name) not in roots:
            continue
        seen[name], imports = _module_record(name)
        pending.extend(imports)
    return seen


def _top(module: str) -> str:
    """The top-level package of a module name; a book's models count one by one (BOOK.<name>)."""
    parts = module.split(".")
    return ".".join(parts[:2]) if parts[0] == "sitegen_book_models" else parts[0]


def forget_sources() -> None:
    """Drop the remembered source hashes, so the next key reads the files again (what each source
    imports stays remembered by its hash: a long-lived process re-parses only the files that changed)."""
    _module_record.cache_clear()


@functools.cache
def _module_record(name: str) -> tuple[str, tuple[str, ...]]:
    """A module's source hash and the modules it imports that have source files (read once per process)."""
    path = _module_path(name)
    source = path.read_bytes()
    sha = hashlib.sha256(source).hexdigest()
    return sha, tuple(
        f for f in _imported_names(name, source, sha, path.name == "__init__.py") if _module_path(f) is not None
    )


_IMPORTED: dict[tuple[str, str, bool], tuple[str, ...]] = {}  # (module, source hash, is package) -> what it names


def _imported_names(name: str, source: bytes, sha: str, is_package: bool) -> tuple[str, ...]:
    """What a module's source imports (parsed once per distinct source: parsing is most of a key's cost)."""
    key = (name, sha, is_package)
    if key not in _IMPORTED:
        _IMPORTED[key] = tuple(_imports(name, source, is_package))
    return _IMPORTED[key]


def digest(*parts: str) -> str:
    """One hash of several strings."""
    return sha("\x00".join(parts))


@functools.cache
def library_digest() -> str:
    """Hash of the versions of the numerical and plotting libraries and of the compiled code's target CPU."""
    return sha(",".join(f"{lib}=={library_version(lib)}" for lib in LIBRARIES) + f",target={compiled.target_name()}")


@functools.cache
def library_version(name: str) -> str:
    """An installed package's version (looked up once per process)."""
    return metadata.version(name)


def _module_path(name: str) -> Path | None:
    """The source file of a module (None when it has none, or is no module: `from x import a_function`)."""
    module = sys.modules.get(name)
    if module is not None:
        file = getattr(module, "__file__", None)
        return Path(file) if file and file.endswith(".py") else None
    if _top(name) == "sitegen":
        relative = Path(*name.split(".")[1:])
        for path in (PACKAGE_ROOT / relative / "__init__.py", PACKAGE_ROOT / relative.with_suffix(".py")):
            if path.exists():
                return path
        return None
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):  # a parent that is a module, not a package: `name` is an attribute
        return None
    return Path(spec.origin) if spec and spec.origin and spec.origin.endswith(".py") else None


def _imports(name: str, source: bytes, is_package: bool) -> list[str]:
    """Absolute names of what a module imports (modules, or names from them), anywhere in its body
    (imports inside functions count: the chain imports its reference integrator only to check)."""
    package = name if is_package else name.rpartition(".")[0]
    found = []
    for node in _statements(ast.parse(source)):
        if isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(max(node.level - 1, 0)):
                base = base.rpartition(".")[0]
            target = (
                f"{base}.{node.module}" if node.level and node.module else (base if node.level else node.module or "")
            )
            found.append(target)
            found.extend(f"{target}.{alias.name}" for alias in node.names)  # `from . import x` imports a module
        elif isinstance(node, ast.Import):
            found.extend(alias.name for alias in node.names)
    return [f for f in dict.fromkeys(found) if f]


_BLOCKS = (ast.stmt, ast.excepthandler, ast.match_case)  # what holds statements; expressions never do


def _statements(tree: ast.Module):
    """The module and every node that holds statements (statements, nested ones included, except handlers
    and match cases), in the order ast.walk meets them (breadth first), without visiting the expressions:
    they are most of a module's nodes and hold no import."""
    todo = collections.deque([tree])
    while todo:
        node = todo.popleft()
        yield node
        for field in node._fields:
            value = getattr(node, field, None)
            if isinstance(value, list):
                todo.extend(child for child in value if isinstance(child, _BLOCKS))


def sha(text: str) -> str:
    """The SHA-256 of a text, in hex."""
    return hashlib.sha256(text.encode()).hexdigest()
