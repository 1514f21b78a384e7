"""The phases that read: the pages, each scene block against the models and figures, and the math."""

from __future__ import annotations

from dataclasses import replace

from ..compute.cache import scene_key
from ..compute.scenes import resolve_scene
from ..content.math import convert_math as tex_to_mathml
from ..content.pages import discover_pages, read_page
from ..content.reports import unknown_part_error
from ..errors import AuthorError, SourceLoc
from ..registry import unknown_figure_message
from ..render.layers import layer_errors
from ..site.report import report_parts
from .record import Book, SceneRecord
from .run import BuildRun


def read_pages(book: Book, run: BuildRun) -> Book:
    """Parse every page under content/ (front matter, Markdown, scene blocks, formulas); report every
    plugin that failed to load or declares a name twice."""
    config, pages = run.config, []
    for problem in run.registry.problems:
        run.error(problem)
    for path in discover_pages(config.content):
        page, errors = read_page(path, config.root)
        for error in errors:
            run.error(error)
        if page is not None:
            pages.append(page)
    slugs = {p.slug for p in pages}
    for page in pages:
        if page.parent and page.parent not in slugs:
            run.error(
                AuthorError(
                    SourceLoc(page.source, 1),
                    f"parent '{page.parent}' is not a page; pages: {', '.join(sorted(slugs))}",
                )
            )
    if pages and "index" not in slugs:
        run.error(
            AuthorError(
                SourceLoc(str(config.content.relative_to(config.root)), 1),
                "the book needs a home page, content/index.md",
            )
        )
    return replace(book, pages=tuple(pages))


def resolve_scenes(book: Book, run: BuildRun) -> Book:
    """A record for every scene block that resolves against the models and figures; an error for every
    one that does not, and for every report block naming a part no one provides."""
    records = []
    for page in book.pages:
        seen: set[str] = set()
        for index, spec in enumerate(page.extracted.scenes):
            if spec.id in seen:
                run.error(
                    AuthorError(
                        spec.loc, f"another scene on this page has id '{spec.id}'; add 'id: <unique-name>'", spec.id
                    )
                )
                continue
            seen.add(spec.id)
            record = resolve_record(page, index, spec, run)
            if record is not None:
                records.append(record)
        _check_report_blocks(page, run)
    return replace(book, scenes=tuple(records))


def resolve_record(page, index: int, spec, run: BuildRun) -> SceneRecord | None:
    """The record of scene block `spec` (the `index`-th of `page`) with its resolved scene, figure, caption,
    outputs and key; None after logging its errors."""
    scene, errors = resolve_scene(spec, run.registry.models, run.registry.broken)
    figure = figure_name(spec)
    if scene is not None and figure not in run.registry.figures:
        errors.append(
            AuthorError(spec.loc_of("figure"), unknown_figure_message(figure, spec.model, run.registry), spec.id)
        )
    for error in errors:
        run.error(error)
    if errors:
        return None
    record = SceneRecord(page, index, scene, run.registry.figures[figure])
    layers = None
    with run.scene(
        record, "listing its figure's layers"
    ):  # the figure's own code: a mistake in it is named at its line
        layers = record.view.layers(scene)
    errors = layer_errors(scene, layers, record.view, run.config.root) if layers is not None else []
    for error in errors:
        run.error(error)
    if layers is None or errors:
        return None
    outputs = shown_outputs(scene, layers)
    caption = page.extracted.captions[record.index]
    return replace(record, caption=caption, outputs=tuple(outputs), key=scene_key(scene, outputs))


def figure_name(spec) -> str:
    """The figure that draws a scene: the one it names, else its model's."""
    return spec.figure or spec.model


def needed_outputs(scene, view) -> list[str]:
    """The outputs a scene shows: its readouts and whatever its figure's layers read."""
    return shown_outputs(scene, view.layers(scene))


def shown_outputs(scene, layers) -> list[str]:
    """The outputs a scene shows: its readouts and whatever `layers` (its figure's) read."""
    names = [o.name for o in scene.readouts]
    names += [o.why_from for o in scene.readouts if o.why_from and o.why_from not in names]
    for layer in layers:
        names += sorted(layer.outputs() - set(names))
    return names


def _check_report_blocks(page, run: BuildRun) -> None:
    parts = report_parts(run.registry.models)
    for block in page.extracted.reports:
        if block.part not in parts:
            run.error(unknown_part_error(block, parts))


def convert_math(book: Book, run: BuildRun) -> Book:
    """MathML for every formula of every page (one Temml run for the whole book, or none if cached)."""
    items = [m for page in book.pages for m in page.extracted.maths]
    mathml, errors = tex_to_mathml(items, run.cached)
    for error in errors:
        run.error(error)
    by_page, start = {}, 0
    for page in book.pages:
        by_page[page.slug] = tuple(mathml[start : start + len(page.extracted.maths)])
        start += len(page.extracted.maths)
    return replace(book, mathml=by_page)
