"""The ```accuracy-report``` block: which part of the accuracy report a page shows at that spot.

    ```accuracy-report
    show: chain
    ```

The block is lifted out of the Markdown like a scene (content/markdown_ext.py) and filled when
the page is assembled, from bench.json and the build's own accuracy records (site/report/). Which
parts exist depends on the models of the build, so the part's name is checked when scenes are
resolved, at the line where the author wrote it.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import AuthorError, SourceLoc


@dataclass(frozen=True)
class ReportBlock:
    """One accuracy-report block: the part it shows, where the block starts and where the part is named."""

    part: str
    loc: SourceLoc
    part_loc: SourceLoc


def parse_report_block(lines: list[str], loc: SourceLoc) -> tuple[ReportBlock | None, list[AuthorError]]:
    """The block's one directive, `show: <part>`; an error names the line and says what to write."""
    directives = [
        (i, line.strip()) for i, line in enumerate(lines) if line.strip() and not line.strip().startswith("#")
    ]
    if len(directives) != 1 or not directives[0][1].startswith("show:"):
        return None, [AuthorError(loc, "an accuracy-report block holds one line 'show: <part>'")]
    offset, text = directives[0]
    return ReportBlock(text.split(":", 1)[1].strip(), loc, SourceLoc(loc.path, loc.line + 1 + offset)), []


def unknown_part_error(block: ReportBlock, parts: list[str]) -> AuthorError:
    """The error of a block naming a part that no one provides."""
    return AuthorError(block.part_loc, f"accuracy-report: unknown part '{block.part}'; parts: {', '.join(parts)}")
