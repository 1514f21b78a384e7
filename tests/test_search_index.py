"""The search index's text of a page: prose by section, never what is inside drawings, scripts or comments."""

from __future__ import annotations

from sitegen.site.search import page_sections

PAGE = """<html><body><nav>Contents</nav><article>
<h1>Levers</h1><p>A lever <!-- an <svg> of it was here --> turns.</p>
<svg><g><text>outer label</text><svg><text>inner label</text></svg><text>after inner</text></g></svg>
<script type="application/json">{"q": "</svg> not prose"}</script>
<h2 id="torque">Torque</h2><p>Force times arm.</p>
</article></body></html>"""


def test_sections_hold_the_prose_and_nothing_of_drawings_scripts_or_comments():
    """Nested drawings, a script and a comment that names a tag leave no text in the index."""
    assert page_sections(PAGE) == (("", "Levers", "A lever turns."), ("torque", "Torque", "Force times arm."))
