"""A Markdown extension that lifts scene blocks and TeX out of the prose before Markdown sees them.

It runs before Python-Markdown's own preprocessors, so it still sees the author's line numbers;
each scene or formula is replaced by an empty placeholder element (raw HTML, which Markdown passes
through untouched) that `fill_slots` swaps for the final HTML. Markdown's own stash cannot be used
this early: its whitespace normaliser strips the stash markers.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from html import escape

import markdown
from markdown.extensions import Extension
from markdown.preprocessors import Preprocessor

from ..errors import AuthorError, SourceLoc
from . import furniture, prose
from .furniture import Figure
from .mathml import breakable, kept_with
from .prose import Citation, Link
from .reports import ReportBlock, parse_report_block
from .scenes import SceneSpec, parse_scene_block

_SCENE_FENCE = re.compile(r"^```\s*scene\s*$")
_REPORT_FENCE = re.compile(r"^```\s*accuracy-report\s*$")
_CODE_FENCE = re.compile(r"^(```|~~~)")
_FENCE_RUN = re.compile(r"^(`{3,}|~{3,})")
_INLINE_MATH = re.compile(r"(?<![\\$\w])\$(?=[^\s$])(?P<tex>[^$\n]*?[^\s\\$])\$(?![\w$])")
# A placeholder, and the punctuation right after it (kept on the line of an inline formula: see `kept_with`).
_SLOT = re.compile(r'<(div|span) data-(math|scene|report|cite)-slot="(\d+)(?:-(\d+))?"></\1>([.,;:!?)\]’”]*)')
_LIST_BREAK = re.compile(r"\\(qquad|begin|end)\b|[{}]")
_HAND_TAG = re.compile(r"\\tag(\*?)\{([^{}]*)\}")  # \tag{2a} (shown "(2a)") or \tag*{A} (shown "A")
_DISPLAY_END = re.compile(r"^(?P<tex>.*)\$\$\s*(?:\{#(?P<label>eq-[a-z0-9-]+)\})?\s*$")
_REF_SLOT = re.compile(r'<a data-ref="([a-z0-9-]+)"></a>')
_HEADING_LABEL = re.compile(r"^#{1,6}\s.*\{#(?P<label>sec-[^}\s]*)[^}]*\}\s*$")
_LABEL_NAME = re.compile(r"^(eq|fig|tbl|sec)-[a-z0-9]+(?:-[a-z0-9]+)*$")


@dataclass(frozen=True)
class MathItem:
    """One formula: its TeX, whether it is displayed, where the author wrote it, and its label."""

    tex: str
    display: bool
    loc: SourceLoc
    label: str | None = None  # "eq-name" for a numbered display equation
    tag: str | None = None  # the number a display's own \tag gives it, as shown: "(2a)"


@dataclass(frozen=True)
class Label:
    """A place on a page that `(@name)` refers to: an equation, a figure (an image or a scene), a table or a
    section, its number on the page (None for a section: it is referred to by its title) and its element's id."""

    name: str
    kind: str  # "equation", "figure", "table" or "section"
    number: int | None
    loc: SourceLoc
    anchor: str


@dataclass
class Extracted:
    """What the preprocessor lifted out of one page: formulas, scenes, labels, citations, links and the
    errors it met."""

    maths: list[MathItem] = field(default_factory=list)
    scenes: list[SceneSpec] = field(default_factory=list)
    reports: list[ReportBlock] = field(default_factory=list)  # accuracy-report blocks, filled at assembly
    errors: list[AuthorError] = field(default_factory=list)
    numbers: dict[str, int] = field(default_factory=dict)  # equation label -> its number on the page
    references: list[tuple[str, SourceLoc]] = field(default_factory=list)
    labels: list[Label] = field(default_factory=list)  # in page order
    figures: list[Figure] = field(default_factory=list)  # pictures on lines of their own
    citations: list[Citation] = field(default_factory=list)
    links: list[Link] = field(default_factory=list)
    captions: list[str] = field(default_factory=list)  # each scene's caption as HTML (math still as slots)
    prose: list[tuple[SourceLoc, str]] = field(default_factory=list)  # the lines outside code and blocks
    figure_count: int = 0
    table_count: int = 0

    def next_figure(self) -> int:
        """The number of the page's next figure (images and scenes count alike)."""
        self.figure_count += 1
        return self.figure_count

    def scene_number(self, index: int) -> int:
        """The figure number of the page's scene at `index`."""
        anchor = f"scene-{self.scenes[index].id}"
        return next(label.number for label in self.labels if label.anchor == anchor and label.kind == "figure")


class _SlotPreprocessor(Preprocessor):
    def __init__(self, md: markdown.Markdown, path: str, first_line: int, extracted: Extracted):
        super().__init__(md)
        self.path, self.first_line, self.extracted = path, first_line, extracted

    def run(self, lines: list[str]) -> list[str]:
        out: list[str] = []
        i = 0
        while i < len(lines):
            loc = SourceLoc(self.path, self.first_line + i)
            line = lines[i]
            if _SCENE_FENCE.match(line):
                i = self._scene(lines, i, loc, out)
            elif _REPORT_FENCE.match(line):
                i = self._report(lines, i, loc, out)
            elif _CODE_FENCE.match(line.lstrip()):
                i = self._copy_code(lines, i, loc, out)
            elif line.lstrip().startswith("$$"):
                i = self._display_math(lines, i, loc, out)
            else:
                self._furniture(lines, i, loc, out)
                i += 1
        return out

    def _furniture(self, lines, i, loc, out) -> None:
        """One line of prose: a figure or a table's caption on its own, or text with math, references,
        citations and links."""
        line, extracted = lines[i], self.extracted
        extracted.prose.append((loc, line))
        problem = furniture.callout_problem(line, loc)
        if problem:
            extracted.errors.append(problem)
        alone = (i == 0 or not lines[i - 1].strip()) and (i + 1 == len(lines) or not lines[i + 1].strip())
        figure = furniture.figure_line(line, loc, extracted.figure_count + 1, extracted) if alone else None
        caption = furniture.table_caption(line, lines[i - 1] if i else "")
        heading = _HEADING_LABEL.match(line)
        if figure is not None:
            self._figure(figure, line, loc, out)
        elif caption is not None:
            self._table_caption(*caption, loc, out)
        else:
            if heading:
                self._label(heading["label"], "section", None, loc)
            out.append(self._prose(line, loc))

    def _prose(self, text: str, loc: SourceLoc) -> str:
        """Prose with its math, references and citations as placeholders, its links recorded."""
        text = _INLINE_MATH.sub(lambda m: self._inline_math(m, loc), text)

        def rest(stretch: str) -> str:
            problem = prose.unconverted_dollar(stretch, loc)
            if problem:
                self.extracted.errors.append(problem)
            prose.record_links(stretch, loc, self.extracted)
            return prose.citation_slots(prose.reference_slots(stretch, loc, self.extracted), loc, self.extracted)

        return prose.outside_code(text, rest)

    def _figure(self, figure: Figure, line: str, loc: SourceLoc, out: list[str]) -> None:
        extracted = self.extracted
        if figure.label:
            extracted.next_figure()
            self._label(figure.label, "figure", figure.number, loc)
        extracted.links.append(Link(figure.src, loc, True, figure.alt))
        extracted.figures.append(figure)
        if not figure.caption:  # a picture without a caption (its alt text given in braces)
            src, alt = escape(figure.src), escape(figure.alt)
            out.extend(["", f'<figure class="figure"><img src="{src}" alt="{alt}"></figure>', ""])
            return
        out.extend(["", self._prose(figure.caption, loc), f'{{: data-figure="{len(extracted.figures) - 1}"}}', ""])

    def _table_caption(self, caption: str, label: str | None, loc: SourceLoc, out: list[str]) -> None:
        number = ""
        if label:
            self.extracted.table_count += 1
            number = str(self.extracted.table_count)
            self._label(label, "table", self.extracted.table_count, loc)
        attrs = f'data-table-caption="{number}"' + (f' data-table-label="{label}"' if label else "")
        out.extend(["", self._prose(caption, loc), f"{{: {attrs}}}", ""])

    def _label(self, name: str, kind: str, number: int | None, loc: SourceLoc, anchor: str | None = None) -> None:
        prefix = {"equation": "eq", "figure": "fig", "table": "tbl", "section": "sec"}[kind]
        if anchor is None and not _LABEL_NAME.match(name):
            self.extracted.errors.append(
                AuthorError(
                    loc,
                    f"label '{name}' is not a {kind} label: write {{#{prefix}-name}}, lower-case letters, "
                    "digits and '-'",
                )
            )
            return
        self.extracted.labels.append(Label(name, kind, number, loc, anchor or name))

    def _scene(self, lines, i, loc, out) -> int:
        end = self._block_end(lines, i, loc, "scene")
        if end is None:
            return self._after_unclosed(lines, i)
        spec, errors = parse_scene_block(lines[i + 1 : end], loc)
        self.extracted.errors.extend(errors)
        if spec is not None:
            self.extracted.scenes.append(spec)
            self._label(spec.id, "figure", self.extracted.next_figure(), loc, anchor=f"scene-{spec.id}")
            # the caption now, so that its citations and references come in the page's order
            line = spec.loc_of("caption").line
            self.extracted.captions.append(markdown_to_html(spec.caption, self.path, line, self.extracted, inline=True))
            slot = f'<div data-scene-slot="{len(self.extracted.scenes) - 1}"></div>'
            out.extend(["", slot, ""])
        return end + 1

    def _report(self, lines, i, loc, out) -> int:
        end = self._block_end(lines, i, loc, "accuracy-report")
        if end is None:
            return self._after_unclosed(lines, i)
        block, errors = parse_report_block(lines[i + 1 : end], loc)
        self.extracted.errors.extend(errors)
        if block is not None:
            self.extracted.reports.append(block)
            out.extend(["", f'<div data-report-slot="{len(self.extracted.reports) - 1}"></div>', ""])
        return end + 1

    def _block_end(self, lines, i, loc, kind: str) -> int | None:
        """The closing fence of the block opened at line i, or None (one error at the opening line).

        A block that runs into the next fence was never closed: reading on to that block's closing
        fence would swallow it and set every later fence off by one, so the error is reported once,
        here, where the author can fix it.
        """
        for j in range(i + 1, len(lines)):
            if lines[j].strip() == "```":
                return j
            if _CODE_FENCE.match(lines[j].lstrip()):
                line = self.first_line + j
                self.extracted.errors.append(
                    AuthorError(
                        loc,
                        f"{kind} block is not closed: line {line} opens another "
                        "block; end this one with a line '```' before it",
                    )
                )
                return None
        self.extracted.errors.append(AuthorError(loc, f"{kind} block is not closed; end it with a line '```'"))
        return None

    @staticmethod
    def _after_unclosed(lines, i) -> int:
        """Where reading goes on after an unclosed block: at the next fence, or at the end of the page."""
        return next((j for j in range(i + 1, len(lines)) if _CODE_FENCE.match(lines[j].lstrip())), len(lines))

    def _copy_code(self, lines, i, loc, out) -> int:
        """A fenced code block as it is (its text is code, not prose); the fence closes at a line of the same
        character at least as long, as CommonMark has it."""
        fence = _FENCE_RUN.match(lines[i].lstrip())[1]
        closing = re.compile(rf"^\s*{re.escape(fence[0])}{{{len(fence)},}}\s*$")
        end = next((j for j in range(i + 1, len(lines)) if closing.match(lines[j])), None)
        if end is None:
            self.extracted.errors.append(AuthorError(loc, f"code block is not closed; end it with a line '{fence}'"))
            end = len(lines) - 1
        out.extend(lines[i : end + 1])
        return end + 1

    def _display_math(self, lines, i, loc, out) -> int:
        first = lines[i].lstrip()[2:]
        closing = _DISPLAY_END.match(first)
        if closing:
            end, tex = i, closing["tex"]
        else:
            end = self._display_end(lines, i, loc)
            if end is None:  # the prose after it stays prose: only the opening line is left out
                return i + 1
            closing = _DISPLAY_END.match(lines[end])
            tex = "\n".join([first, *lines[i + 1 : end], closing["tex"]])
        label = closing["label"]
        # a number written by hand is shown as a label's is (see `_display`)
        hand = _HAND_TAG.search(tex)
        tag = None if hand is None else hand[2] if hand[1] else f"({hand[2]})"
        pieces = split_display(_HAND_TAG.sub("", tex).strip())
        if label:
            if label not in self.extracted.numbers:  # a label used twice is reported by the book-wide check
                self.extracted.numbers[label] = len(self.extracted.numbers) + 1
                self._label(label, "equation", self.extracted.numbers[label], loc)
            else:
                self.extracted.labels.append(Label(label, "equation", self.extracted.numbers[label], loc, label))
        first = len(self.extracted.maths)
        self.extracted.maths += [MathItem(piece, True, loc, label, tag) for piece in pieces]
        span = f"{first}-{len(self.extracted.maths) - 1}" if len(pieces) > 1 else f"{first}"
        out.extend(["", f'<div data-math-slot="{span}"></div>', ""])
        return end + 1

    def _display_end(self, lines, i, loc) -> int | None:
        """The line that closes the display opened at line i, or None (one error at the opening line).

        A display holds no blank line and no fence (as in Pandoc): reading on past one would take the prose
        that follows for TeX, and pair every later '$$' with the wrong partner."""
        for j in range(i + 1, len(lines)):
            if _DISPLAY_END.match(lines[j]):
                return j
            if not lines[j].strip() or _CODE_FENCE.match(lines[j].lstrip()):
                what = "the blank line" if not lines[j].strip() else "the fence"
                self.extracted.errors.append(
                    AuthorError(
                        loc,
                        f"display math '$$' is not closed before {what} at line {self.first_line + j}; "
                        "end it with '$$' (a display holds no blank line)",
                    )
                )
                return None
        self.extracted.errors.append(AuthorError(loc, "display math '$$' is not closed; end it with '$$'"))
        return None

    def _inline_math(self, match: re.Match, loc: SourceLoc) -> str:
        self.extracted.maths.append(MathItem(match["tex"], False, loc))
        return f'<span data-math-slot="{len(self.extracted.maths) - 1}"></span>'


def split_display(tex: str) -> list[str]:
    """A displayed list of equations ("a = b, \\qquad c = d") as its items, split at each \\qquad outside braces
    and environments, so that a narrow screen can stack them; any other display is one piece."""
    pieces, depth, start = [], 0, 0
    for match in _LIST_BREAK.finditer(tex):
        token = match[0]
        if token in ("{", "\\begin"):
            depth += 1
        elif token in ("}", "\\end"):
            depth -= 1
        elif depth == 0:
            pieces.append(tex[start : match.start()].strip())
            start = match.end()
    pieces.append(tex[start:].strip())
    return [piece for piece in pieces if piece] or [tex]


class SlotExtension(Extension):
    """Registers the slot preprocessor for one page (a fresh instance per page)."""

    def __init__(self, path: str, first_line: int, extracted: Extracted):
        super().__init__()
        self.path, self.first_line, self.extracted = path, first_line, extracted

    def extendMarkdown(self, md: markdown.Markdown) -> None:
        # Priority 35: before normalize_whitespace (30) and fenced_code (25), on the author's lines.
        md.preprocessors.register(
            _SlotPreprocessor(md, self.path, self.first_line, self.extracted), "sitegen_slots", 35
        )


def markdown_to_html(text: str, path: str, first_line: int, extracted: Extracted, inline: bool = False) -> str:
    """Convert one page's Markdown (or one inline snippet) to HTML with slots for math, scenes, citations and
    references."""
    md = markdown.Markdown(
        extensions=[
            "toc",
            "attr_list",
            "md_in_html",
            "tables",
            *furniture.MARKDOWN_EXTENSIONS,
            furniture.FurnitureExtension(extracted),
            SlotExtension(path, first_line, extracted),
        ],
        extension_configs={"toc": {"permalink": False}, **furniture.MARKDOWN_CONFIGS},
    )
    html = md.convert(text)
    if inline and html.startswith("<p>") and html.endswith("</p>") and html.count("<p>") == 1:
        html = html[3:-4]
    return html


def _display(extracted: Extracted, mathml, first: int, last: int | None) -> str:
    """A displayed formula, or (`last` given) a list of them, with its number if it has one: a label's, or the
    display's own \\tag. The number sits outside the math, at the right margin on the last line's baseline,
    the same in every browser (Temml's \\tag is a table cell that each engine places elsewhere)."""
    item = extracted.maths[first]
    # a list of equations: its items wrap onto lines of their own where the line is too short for all
    items = "".join(mathml[first : (first if last is None else last) + 1])
    kind = "equation" if last is None else "equation list"
    number = f"({extracted.numbers[item.label]})" if item.label else None if item.tag is None else escape(item.tag)
    if number is None:
        return f'<div class="{kind}">{items}</div>'
    if last is not None:
        items = f'<span class="items">{items}</span>'
    anchor = f' id="{item.label}"' if item.label else ""
    return f'<div class="{kind} numbered"{anchor}>{items}<span class="eqno">{number}</span></div>'


def fill_slots(html: str, extracted: Extracted, mathml, scenes, reports=(), citations=(), reference=None) -> str:
    """Replace every placeholder with its MathML, scene HTML, report part, citation or reference
    (`reference(label)`: the link to a label, with its number)."""

    def substitute(match: re.Match) -> str:
        tag, kind, index, after = match[1], match[2], int(match[3]), match[5]
        if kind == "scene":
            return scenes[index] + after
        if kind == "report":
            return reports[index] + after
        if kind == "cite":
            return citations[index] + after
        if tag == "span":
            return kept_with(breakable(mathml[index]), after)
        return _display(extracted, mathml, index, None if match[4] is None else int(match[4])) + after

    html = _SLOT.sub(substitute, html)
    return _REF_SLOT.sub(lambda m: reference(m[1]), html) if reference else html
