"""A Markdown extension that lifts scene blocks and TeX out of the prose before Markdown sees them.

It runs ahead of Python-Markdown's own preprocessors, so it still sees the author's line numbers;
each scene or formula is replaced by an empty placeholder element (raw HTML, which Markdown passes
through untouched) that `fill_slots` swaps for the final HTML. Markdown's own stash cannot be used
this early: its whitespace normaliser strips the stash markers.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

import markdown
from markdown.extensions import Extension
from markdown.preprocessors import Preprocessor

from ..errors import AuthorError, SourceLoc
from .scenes import SceneSpec, parse_scene_block

_SCENE_FENCE = re.compile(r"^```\s*scene\s*$")
_CODE_FENCE = re.compile(r"^(```|~~~)")
_INLINE_MATH = re.compile(r"(?<![\\$\w])\$(?=[^\s$])(?P<tex>[^$\n]*?[^\s\\$])\$(?![\w$])")
_SLOT = re.compile(r'<(div|span) data-(math|scene)-slot="(\d+)"></\1>')


@dataclass(frozen=True)
class MathItem:
    """One formula: its TeX, whether it is displayed, and where the author wrote it."""

    tex: str
    display: bool
    loc: SourceLoc


@dataclass
class Extracted:
    """What the preprocessor lifted out of one page: formulas, scenes and the errors it met."""

    maths: list[MathItem] = field(default_factory=list)
    scenes: list[SceneSpec] = field(default_factory=list)
    errors: list[AuthorError] = field(default_factory=list)


class _SlotPreprocessor(Preprocessor):
    def __init__(self, md: markdown.Markdown, path: str, first_line: int, found: Extracted):
        super().__init__(md)
        self.path, self.first_line, self.found = path, first_line, found

    def run(self, lines: list[str]) -> list[str]:
        out: list[str] = []
        i = 0
        while i < len(lines):
            loc = SourceLoc(self.path, self.first_line + i)
            line = lines[i]
            if _SCENE_FENCE.match(line):
                i = self._scene(lines, i, loc, out)
            elif _CODE_FENCE.match(line):
                i = self._copy_code(lines, i, out)
            elif line.lstrip().startswith("$$"):
                i = self._display_math(lines, i, loc, out)
            else:
                out.append(_INLINE_MATH.sub(lambda m: self._inline_math(m, loc), line))
                i += 1
        return out

    def _scene(self, lines, i, loc, out) -> int:
        end = next((j for j in range(i + 1, len(lines)) if lines[j].strip() == "```"), None)
        if end is None:
            self.found.errors.append(AuthorError(loc, "scene block is not closed; end it with a line '```'"))
            return len(lines)
        spec, errors = parse_scene_block(lines[i + 1 : end], loc)
        self.found.errors.extend(errors)
        if spec is not None:
            self.found.scenes.append(spec)
            slot = f'<div data-scene-slot="{len(self.found.scenes) - 1}"></div>'
            out.extend(["", slot, ""])
        return end + 1

    def _copy_code(self, lines, i, out) -> int:
        fence = lines[i][:3]
        end = next((j for j in range(i + 1, len(lines)) if lines[j].startswith(fence)), len(lines) - 1)
        out.extend(lines[i : end + 1])
        return end + 1

    def _display_math(self, lines, i, loc, out) -> int:
        first = lines[i].lstrip()[2:]
        if first.rstrip().endswith("$$"):
            end, tex = i, first.rstrip()[:-2]
        else:
            end = next((j for j in range(i + 1, len(lines)) if lines[j].rstrip().endswith("$$")), None)
            if end is None:
                self.found.errors.append(AuthorError(loc, "display math '$$' is not closed; end it with '$$'"))
                return len(lines)
            tex = "\n".join([first, *lines[i + 1 : end], lines[end].rstrip()[:-2]])
        self.found.maths.append(MathItem(tex.strip(), True, loc))
        slot = f'<div data-math-slot="{len(self.found.maths) - 1}"></div>'
        out.extend(["", slot, ""])
        return end + 1

    def _inline_math(self, match: re.Match, loc: SourceLoc) -> str:
        self.found.maths.append(MathItem(match["tex"], False, loc))
        return f'<span data-math-slot="{len(self.found.maths) - 1}"></span>'


class SlotExtension(Extension):
    """Registers the slot preprocessor for one page (a fresh instance per page)."""

    def __init__(self, path: str, first_line: int, found: Extracted):
        super().__init__()
        self.path, self.first_line, self.found = path, first_line, found

    def extendMarkdown(self, md: markdown.Markdown) -> None:
        # Priority 35: ahead of normalize_whitespace (30) and fenced_code (25), on the author's lines.
        md.preprocessors.register(_SlotPreprocessor(md, self.path, self.first_line, self.found), "sitegen_slots", 35)


def markdown_to_html(text: str, path: str, first_line: int, found: Extracted, inline: bool = False) -> str:
    """Convert one page's Markdown (or one inline snippet) to HTML with math and scene slots."""
    md = markdown.Markdown(
        extensions=["toc", "attr_list", "md_in_html", "tables", SlotExtension(path, first_line, found)],
        extension_configs={"toc": {"permalink": False}},
    )
    html = md.convert(text)
    if inline and html.startswith("<p>") and html.endswith("</p>") and html.count("<p>") == 1:
        html = html[3:-4]
    return html


def fill_slots(html: str, maths: list[str], scenes: list[str]) -> str:
    """Replace every slot placeholder with its MathML or scene HTML."""

    def substitute(match: re.Match) -> str:
        tag, kind, index = match[1], match[2], int(match[3])
        if kind == "scene":
            return scenes[index]
        return f'<div class="equation">{maths[index]}</div>' if tag == "div" else maths[index]

    return _SLOT.sub(substitute, html)
