"""Nothing an author wrote is shown raw: a citation, footnote or callout marker, or a code fence, still in a
page's text once it is converted (outside code) is an error at the line that holds it, saying what was
meant. (A '$' that no formula took is found earlier, line by line, by the preprocessor.)"""

from __future__ import annotations

import re
from html import unescape

from ..errors import AuthorError, SourceLoc
from .furniture import CALLOUT_TYPES

_NOT_TEXT = re.compile(r"<(pre|code|script|style)\b.*?</\1>|<!--.*?-->", re.S)
_TAG = re.compile(r"<[^>]+>")
MARKERS = (
    (
        re.compile(r"\[\^[^\]\s]*\]?"),
        "footnote marker '{}' left as text: a footnote [^name] needs its text on a line of its own, '[^name]: …'",
    ),
    (
        re.compile(r"\[[^\[\]]*?(?<![\w.])@\w[^\[\]]*\]"),
        "citation marker '{}' left as text: a citation is [@key], [@key, p. 33] or [@a; @b]",
    ),
    (
        re.compile(r"\[!(?:" + "|".join(CALLOUT_TYPES) + r")\]", re.I),  # an unknown type is named at its line
        "callout marker '{}' left as text: a GitHub callout is a quote whose first line is only "
        f"> [!TYPE], one of {', '.join(t.upper() for t in CALLOUT_TYPES)}",
    ),
    (
        re.compile(r"(?:^|\n)\s*(?:!!!|\?\?\?)\+?[^\n]*"),
        "callout marker '{}' left as text: a callout starts !!! TYPE \"Title\" on a line of its own after a "
        "blank line, its text indented by four spaces",
    ),
    (
        re.compile(r"(?:```|~~~)[^\s`~]*"),
        "code fence '{}' left as text: a fenced block starts with ``` (and its language) on a line of its own "
        "after a blank line, and ends with ``` on a line of its own",
    ),
)


def leftover_markers(html: str, prose: list[tuple[SourceLoc, str]], fallback: SourceLoc) -> list[AuthorError]:
    """An error for each marker left in the text of `html`, at the first line of `prose` that holds it."""
    text = unescape(_TAG.sub("", _NOT_TEXT.sub("", html)))
    errors = []
    for pattern, message in MARKERS:
        for match in pattern.finditer(text):
            marker = match[0].strip()
            loc = next((where for where, line in prose if marker in line), fallback)
            errors.append(AuthorError(loc, message.format(marker)))
    return errors
