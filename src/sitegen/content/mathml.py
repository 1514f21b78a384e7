"""MathML as a page shows it: inline math that a line may break in."""

from __future__ import annotations

import re

_TAG = re.compile(r"<(/?)([a-z]+)[^>]*?(/?)>")
# Relations after which TeX may break a line of inline math (Temml writes each as one <mo>).
_RELATIONS = {"=", "≠", "&lt;", "&gt;", "≤", "≥", "≈", "≡", "∝", "∼", "≃", "≪", "≫", "→", "⇒", "↦"}
_INLINE = re.compile(r"<math><mrow>(.*)</mrow></math>", re.S)


def breakable(mathml: str) -> str:
    """Inline MathML that a line may break after each of its top-level relations, as TeX's does: one <math>
    per piece, a <wbr> between them (no browser breaks a line inside a <math>; a long formula in a sentence
    would widen a phone's page)."""
    whole = _INLINE.fullmatch(mathml)
    if not whole:
        return mathml
    body, pieces, depth, start = whole[1], [], 0, 0
    for tag in _TAG.finditer(body):
        closing, name, empty = tag[1], tag[2], tag[3]
        depth += -1 if closing else 0 if empty else 1
        if depth < 0:  # the outer <mrow> closed before the end: not one row
            return mathml
        if depth == 0 and closing and name == "mo":
            operator = body[body.rindex(">", 0, tag.start()) + 1 : tag.start()]
            if operator in _RELATIONS and body[tag.end() :].strip():
                pieces.append(body[start : tag.end()])
                start = tag.end()
    if not pieces:
        return mathml
    pieces.append(body[start:])
    return "<wbr>".join(f"<math><mrow>{piece}</mrow></math>" for piece in pieces)


def kept_with(mathml: str, after: str) -> str:
    """Inline MathML and the punctuation right after it (`after`) on one line: every engine may break a line
    between a <math> and a full stop, which would start the next line with it."""
    if not after:
        return mathml
    last = mathml.rindex("<math")  # of a formula broken after its relations, the last piece
    return f'{mathml[:last]}<span class="nobreak">{mathml[last:]}{after}</span>'
