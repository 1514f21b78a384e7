"""sitegen's built-in models, one plugin folder each: the model, its figure and their helpers.

Each folder's `__init__.py` declares its `MODELS` as a plain dict and its `FIGURES` through
`figures_when_asked`; the registry (sitegen.registry) lists the folders. Nothing here imports a model:
importing this package loads none of them.
"""

from __future__ import annotations

import importlib
import sys


def figures_when_asked(package: str, **views: str):
    """A plugin package's module `__getattr__` that makes its `FIGURES` (name: an instance of the class named,
    from the package's `figure` module) when first asked for.

    A worker process imports a model's package to unpickle the model, and tabulating draws nothing: so the
    figures, and matplotlib with them, stay out of a worker (about 0.8 s of each worker's start)."""

    def __getattr__(name: str):
        if name != "FIGURES":
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module = importlib.import_module(f"{package}.figure")
        figures = {key: getattr(module, view)() for key, view in views.items()}
        sys.modules[package].FIGURES = figures  # made once
        return figures

    return __getattr__
