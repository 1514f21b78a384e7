"""sitegen's built-in models, one plugin folder each: the model, its figure and their helpers.

Each folder's `__init__.py` declares its `MODELS` and `FIGURES` (and `REPORTS`) as plain dicts; the
registry (sitegen.registry) lists the folders. Nothing here imports a model: importing this package
loads none of them.
"""
