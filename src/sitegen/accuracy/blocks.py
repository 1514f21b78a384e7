"""The ```accuracy-report``` block: which part of the accuracy report a page shows at that spot.

    ```accuracy-report
    show: chain
    ```

The block is lifted out of the Markdown like a scene (content/markdown_ext.py) and filled when
the site is assembled, from bench.json and the build's own accuracy records (accuracy/page.py).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import AuthorError, SourceLoc

PARTS = {
    "machine": "where and when the timings were measured",
    "chain": "the chain's work–precision diagram",
    "bubble-A": "the work–precision diagram of bubble case A",
    "bubble-B": "the work–precision diagram of bubble case B",
    "bubble-C": "the work–precision diagram of bubble case C",
    "settings": "the bubble scenes' settings: every stop's shown digits against time",
    "digits": "what one more digit costs, measured",
    "resolution": "grid resolution against interpolation error and bytes",
    "scenes": "the table of the numerically checked scenes of this build",
    "build": "cold build time and table bytes of every scene, bytes of every page",
}


@dataclass(frozen=True)
class ReportBlock:
    """One accuracy-report block: the part it shows and where the author wrote it."""

    part: str
    loc: SourceLoc


def parse_report_block(lines: list[str], loc: SourceLoc) -> tuple[ReportBlock | None, list[AuthorError]]:
    """The block's one directive, `show: <part>`; errors name the line and list the parts."""
    directives = [(i, line.strip()) for i, line in enumerate(lines) if line.strip() and not line.strip().startswith("#")]
    known = ", ".join(PARTS)
    if len(directives) != 1 or not directives[0][1].startswith("show:"):
        return None, [AuthorError(loc, f"an accuracy-report block holds one line 'show: <part>'; parts: {known}")]
    offset, text = directives[0]
    part = text.split(":", 1)[1].strip()
    if part not in PARTS:
        where = SourceLoc(loc.path, loc.line + 1 + offset)
        return None, [AuthorError(where, f"accuracy-report: unknown part '{part}'; parts: {known}")]
    return ReportBlock(part, loc), []
