"""matplotlib's text measurements shared by every figure of a build, not kept per figure.

matplotlib caches the parse of a math string and the size of a text per renderer, that is per figure (and again
for the renderer that saves it), so a book's hundreds of figures measure the same tick labels over and over: a
third of the cold build's figure time. Both results depend only on their arguments (matplotlib's own caches
assume as much), so sharing them changes no byte of any figure. Imported for its effect by `style`.
"""

from __future__ import annotations

import functools
import io

from matplotlib import mathtext
from matplotlib import text as mtext
from matplotlib.backends.backend_svg import RendererSVG

_PARSERS = {"vector": mathtext.MathTextParser("path"), "raster": mathtext.MathTextParser("agg")}


def _share_math_parses() -> None:
    """Let every figure reuse matplotlib's parse of a math string, not only the figure that parsed it.

    Log axes label their ticks in math ($10^{-3}$), and matplotlib caches a parse per parser, that is per figure,
    50 at most, so a book's cold build parsed 600 times the 112 strings its figures use (about 8 s). A parse
    depends only on the kind of output and its arguments (matplotlib's own cache assumes as much), so sharing
    them changes no byte.
    """
    parse = getattr(mathtext.MathTextParser._parse_cached, "__wrapped__", None)
    if parse is None:  # the cache is a detail of matplotlib's; without it there is nothing to share
        return

    @functools.lru_cache(maxsize=4096)
    def shared(output_type, s, dpi, prop, antialiased, load_glyph_flags):
        return parse(_PARSERS[output_type], s, dpi, prop, antialiased, load_glyph_flags)

    def parse_once(self, s, dpi, prop, antialiased, load_glyph_flags):
        return shared(self._output_type, s, dpi, prop, antialiased, load_glyph_flags)

    mathtext.MathTextParser._parse_cached = parse_once


def _share_text_sizes() -> None:
    """Let every SVG figure reuse the measured size of a text (its width, height and descent).

    An SVG renderer measures text with matplotlib's stateless text-to-path converter (font metrics and the shared
    math parses), so a size depends only on the text, its font properties and whether it is math.
    """
    per_renderer = getattr(mtext, "_get_text_metrics_with_cache", None)
    if per_renderer is None:  # a detail of matplotlib's; without it there is nothing to share
        return

    @functools.lru_cache(maxsize=16384)
    def svg_size(text, fontprop, ismath, dpi):
        return _SVG_MEASURER.get_text_width_height_descent(text, fontprop, ismath)

    def size_once(renderer, text, fontprop, ismath, dpi):
        if type(getattr(renderer, "_renderer", renderer)) is RendererSVG:  # saving wraps it in a MixedModeRenderer
            return svg_size(text, fontprop.copy(), ismath, dpi)
        return per_renderer(renderer, text, fontprop, ismath, dpi)

    mtext._get_text_metrics_with_cache = size_once


def _share_text_layouts() -> None:
    """Let a text laid out again (for the layout, then to draw it) reuse its layout, as may any other text alike.

    matplotlib lays a text out (its lines, box and alignment offsets, from its font's metrics and measured sizes)
    each time it is measured or drawn: a tick label four or five times per figure, in the same state. For an SVG
    renderer the layout depends only on what the key below holds (the text's own offsets, not its position), so
    sharing it changes no byte. Wrapped and TeX texts are laid out as matplotlib does.
    """
    layout = getattr(mtext.Text, "_get_layout", None)
    if layout is None:  # a detail of matplotlib's; without it there is nothing to share
        return
    shared = {}

    def layout_once(self, renderer):
        if self.get_wrap() or self.get_usetex() or type(getattr(renderer, "_renderer", renderer)) is not RendererSVG:
            return layout(self, renderer)
        font = self._fontproperties
        key = (
            self._text,
            tuple(font.get_family()),
            font.get_slant(),
            font.get_variant(),
            font.get_weight(),
            font.get_stretch(),
            font.get_size(),
            font.get_file(),
            font.get_math_fontfamily(),
            self.get_figure(root=True).dpi,
            self._linespacing,
            self._get_multialignment(),
            self.get_rotation(),
            self.get_rotation_mode(),
            self._horizontalalignment,
            self._verticalalignment,
            self.get_parse_math(),
        )
        found = shared.get(key)
        if found is None:
            if len(shared) >= 16384:
                shared.clear()
            found = shared[key] = layout(self, renderer)
        box, lines, corner = found
        return box.frozen(), list(lines), corner  # a box of its own: callers may move theirs

    mtext.Text._get_layout = layout_once


_SVG_MEASURER = RendererSVG(1, 1, io.StringIO())  # measures only; what it would draw is dropped
_share_math_parses()
_share_text_sizes()
_share_text_layouts()
