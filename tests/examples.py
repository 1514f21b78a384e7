"""How many examples a property-based test runs: every one in `make test`, a share in `make check`.

`make check` is the inner loop: it runs each property on the first fifth of its (derandomized, so
always the same) examples; `make test` and CI run them all. SITEGEN_EXAMPLE_SHARE sets the share.
"""

from __future__ import annotations

import os

SHARE = float(os.environ.get("SITEGEN_EXAMPLE_SHARE", "1"))
FEWEST = 10  # a property checked on fewer examples than this checks little


def examples(full: int) -> int:
    """The examples to run of a property that runs `full` of them in the complete suite."""
    return full if SHARE >= 1 else max(min(full, FEWEST), round(full * SHARE))
