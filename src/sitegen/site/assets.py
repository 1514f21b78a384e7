"""Static assets: the page script, the stylesheet (ours plus Temml's), and a subset math font."""

from __future__ import annotations

import hashlib
import io
import logging
import re
from html import unescape
from pathlib import Path

import fontTools

from ..content.math import TEMML_CSS

logging.getLogger("fontTools.subset").setLevel(logging.ERROR)  # it notes dropping tables we do not need

STATIC = Path(__file__).with_name("static")
FONT_FILE = "latinmodern-math.woff2"
_FONT_FACE = re.compile(r"@font-face\s*\{[^}]*\}\s*")
_TEMML_FONT_RULES = re.compile(r"(\*\.mathscr|mo\.tml-prime)\s*\{[^}]*\}\s*")
_MATH_ELEMENT = re.compile(r"<math\b.*?</math>", re.S)
_TAG = re.compile(r"<[^>]+>")


def script() -> bytes:
    """The one script every page loads."""
    return (STATIC / "sitegen.js").read_bytes()


def search_code() -> bytes:
    """The code of the search box (it follows the index in assets/search.js)."""
    return (STATIC / "search.js").read_bytes()


def stylesheet(extra: tuple[Path, ...] = ()) -> bytes:
    """Our stylesheet, the rules Temml's MathML needs (its font faces removed), then the book theme's
    CSS files (`extra`), in that order so that a theme's rules win."""
    temml_css = TEMML_CSS.read_text(encoding="utf-8")
    temml_css = _TEMML_FONT_RULES.sub("", _FONT_FACE.sub("", temml_css))
    ours = (STATIC / "sitegen.css").read_text(encoding="utf-8")
    text = ours + "\n/* Rules for Temml's MathML (MIT licence), from temml/dist/Temml-Latin-Modern.css */\n" + temml_css
    for path in extra:
        text += f"\n/* {path.name}, from the book's theme */\n" + path.read_text(encoding="utf-8")
    return text.encode()


def theme_css(theme: Path) -> tuple[Path, ...]:
    """The CSS files a book's theme adds (every *.css directly in its theme folder, by name)."""
    return tuple(sorted(theme.glob("*.css"))) if theme.is_dir() else ()


def math_characters(html: str) -> set[str]:
    """The characters the formulas (<math> elements) of a page's HTML show."""
    return {c for element in _MATH_ELEMENT.findall(html) for c in unescape(_TAG.sub("", element))}


def math_font(characters: set[str], cached=None) -> bytes:
    """Latin Modern Math cut down to `characters` (those the pages' formulas use) and a few every
    formula may need, with their variants."""
    text = "".join(sorted(characters | set("()[]{}|=+−0123456789√")))  # √: <msqrt> draws it without a text character
    if cached is None:
        return _subset_font(text)
    font_hash = hashlib.sha256((STATIC / FONT_FILE).read_bytes()).hexdigest()
    key = hashlib.sha256(f"{text}\x00{font_hash}\x00fonttools {fontTools.version}".encode()).hexdigest()
    return cached("fonts", key, lambda: _subset_font(text))


def _subset_font(text: str) -> bytes:
    # Imported here: a build whose font is cached (most rebuilds) never subsets one, and fontTools' subsetter
    # takes a fifth of a second to import.
    from fontTools import subset
    from fontTools.ttLib import TTFont

    font = TTFont(STATIC / FONT_FILE, recalcTimestamp=False)  # keep head.modified: byte-stable output
    options = subset.Options()
    options.layout_features = ["*"]
    options.flavor = "woff2"
    options.name_IDs = ["*"]
    subsetter = subset.Subsetter(options)
    subsetter.populate(text=text)
    subsetter.subset(font)
    buffer = io.BytesIO()
    font.save(buffer)
    return buffer.getvalue()
