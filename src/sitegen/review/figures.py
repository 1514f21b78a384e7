"""Figures compared: what moved in the SVG, and pixels (Chromium renders, Pillow compares)."""

from __future__ import annotations

import base64
import io
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from .tree import standalone_svg

CHROMIUM = "/usr/bin/chromium"
# Running as root needs --no-sandbox; the other flags keep Chromium from calling home.
LAUNCH_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--disable-sync",
]
SCALE = 2  # device pixels per SVG unit: crisp at 1:1 and when zoomed
ADDED, REMOVED, RECOLOURED = (31, 99, 181), (214, 87, 20), (128, 60, 160)  # ink only new, only old, both
FRAME = (90, 98, 112)  # the dashed frame around the change

_VIEWBOX = re.compile(r'viewBox="([-\d.e ]+)"')
_LAYER = re.compile(r'<(\w+) data-layer="([^"]+)"[^>]*/>')
_LAYERS_GROUP = '<g class="layers">'


class RasterUnavailable(RuntimeError):
    """Chromium cannot be driven here (Playwright missing, or no browser)."""


@dataclass(frozen=True)
class SvgChange:
    """What changed in a figure's SVG text: its size, its static drawing, which moving layers."""

    size_old: tuple[float, float]
    size_new: tuple[float, float]
    static_changed: bool
    layers_changed: tuple[str, ...]


@dataclass(frozen=True)
class PixelDiff:
    """Old and new rendered on one canvas, the difference image, and how much differs."""

    old_png: bytes
    new_png: bytes
    diff_png: bytes
    changed: int  # device pixels that differ
    total: int
    box: tuple[float, float, float, float] | None  # x0, y0, x1, y1 of the change, in SVG units
    zoom: tuple[bytes, bytes, bytes] | None = None  # old, new and difference cropped around a small change

    @property
    def fraction(self) -> float:
        return self.changed / self.total if self.total else 0.0

    def describe(self) -> str:
        """The size of the change in words."""
        if not self.changed:
            return "no pixel differs (the SVG text changed below the resolution)"
        x0, y0, x1, y1 = self.box
        return (
            f"{percent(self.fraction)} of the figure ({self.changed:,} px at {SCALE}×) differs, "
            f"within x {x0:g}–{x1:g}, y {y0:g}–{y1:g} pt"
        )


def percent(fraction: float) -> str:
    """A share as a short percentage that never rounds a change down to zero."""
    value = 100.0 * fraction
    return f"{value:.2g} %" if value < 10 else f"{value:.0f} %"


def viewbox_size(svg: str) -> tuple[float, float]:
    """Width and height of the figure in SVG units (points)."""
    found = _VIEWBOX.search(svg)
    if not found:
        return (0.0, 0.0)
    _, _, w, h = (float(v) for v in found[1].split())
    return (w, h)


def svg_change(old: str, new: str) -> SvgChange:
    """Compare two versions of a figure's SVG text part by part."""
    layers_old, layers_new = _layers(old), _layers(new)
    names = sorted(set(layers_old) | set(layers_new))
    return SvgChange(
        viewbox_size(old),
        viewbox_size(new),
        _static(old) != _static(new),
        tuple(n for n in names if layers_old.get(n) != layers_new.get(n)),
    )


def _layers(svg: str) -> dict[str, str]:
    return {m[2]: m[0] for m in _LAYER.finditer(svg)}


def _static(svg: str) -> str:
    cut = svg.rfind(_LAYERS_GROUP)
    return svg[:cut] if cut >= 0 else svg


def svg_data_uri(svg: str) -> str:
    """The figure as an <img> source (isolated from the page's ids and styles)."""
    return "data:image/svg+xml;base64," + base64.b64encode(standalone_svg(svg).encode()).decode()


class Rasterizer:
    """Chromium (through Playwright) turning SVG figures into PNGs at a fixed scale."""

    def __enter__(self) -> Rasterizer:
        try:
            from playwright.sync_api import Error, sync_playwright
        except ImportError:
            raise RasterUnavailable(
                "Playwright is not installed; `make review` installs it (or: .venv/bin/pip install -e '.[dev]')"
            ) from None
        if not Path(CHROMIUM).exists():
            raise RasterUnavailable(f"no Chromium at {CHROMIUM}; install Debian's chromium (make tools-chromium)")
        self._playwright = sync_playwright().start()
        try:
            self._browser = self._playwright.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
        except Error as error:
            self._playwright.stop()
            raise RasterUnavailable(f"Chromium did not start: {str(error).splitlines()[0]}") from None
        self._page = self._browser.new_page(device_scale_factor=SCALE)
        return self

    def __exit__(self, *exc) -> None:
        self._browser.close()
        self._playwright.stop()

    def png(self, svg: str) -> bytes:
        """The figure rendered on white at SCALE device pixels per point."""
        w, h = viewbox_size(svg)
        width, height = max(1, math.ceil(w)), max(1, math.ceil(h))
        self._page.set_viewport_size({"width": width, "height": height})
        self._page.set_content(
            '<!doctype html><html><body style="margin:0;background:#fff">'
            f'<img id="figure" style="display:block;width:{w}px;height:{h}px" src="{svg_data_uri(svg)}">'
            "</body></html>"
        )
        self._page.evaluate("document.getElementById('figure').decode()")
        return self._page.screenshot(clip={"x": 0, "y": 0, "width": width, "height": height}, animations="disabled")


def pixel_diff(old_png: bytes, new_png: bytes) -> PixelDiff:
    """Put both renderings on one white canvas and mark every pixel that differs."""
    old, new = _open(old_png), _open(new_png)
    height, width = max(old.shape[0], new.shape[0]), max(old.shape[1], new.shape[1])
    a, b = _on_canvas(old, width, height), _on_canvas(new, width, height)
    differs = (a != b).any(axis=-1)
    ys, xs = np.nonzero(differs)
    if not len(xs):
        return PixelDiff(_png(a), _png(b), _png(_diff_image(a, b, differs, None)), 0, int(differs.size), None)
    pixels = (int(xs.min()), int(ys.min()), int(xs.max()) + 1, int(ys.max()) + 1)
    image = _diff_image(a, b, differs, pixels)
    box = tuple(round(v / SCALE, 1) for v in pixels)
    return PixelDiff(
        _png(a), _png(b), _png(image), int(differs.sum()), int(differs.size), box, _zoom((a, b, image), pixels)
    )


def _open(data: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), dtype=np.int16)


def _on_canvas(pixels: np.ndarray, width: int, height: int) -> np.ndarray:
    canvas = np.full((height, width, 3), 255, dtype=np.int16)
    canvas[: pixels.shape[0], : pixels.shape[1]] = pixels
    return canvas


def _diff_image(a: np.ndarray, b: np.ndarray, differs: np.ndarray, box) -> np.ndarray:
    """The new figure faded to a light grey, with ink only in the new build in blue and ink only in
    the old one in orange (colour changes in purple), thickened so that a hairline shows, and the
    change framed."""
    grey_a, grey_b = a.mean(axis=-1), b.mean(axis=-1)
    image = np.repeat((255 - (255 - grey_b) * 0.22)[..., None], 3, axis=-1)
    if box is None:
        return image
    for mask, colour in (
        (differs, RECOLOURED),
        (differs & (grey_a < grey_b - 8), REMOVED),
        (differs & (grey_b < grey_a - 8), ADDED),
    ):
        image[_thicken(mask)] = colour
    x0, y0, x1, y1 = box
    pad = 3 * SCALE
    x0, y0, x1, y1 = (
        max(0, x0 - pad),
        max(0, y0 - pad),
        min(image.shape[1], x1 + pad) - 1,
        min(image.shape[0], y1 + pad) - 1,
    )
    dash = (np.arange(image.shape[1]) // (3 * SCALE)) % 2 == 0
    for y in (y0, y1):
        image[y, x0 : x1 + 1][dash[x0 : x1 + 1]] = FRAME
    dash = (np.arange(image.shape[0]) // (3 * SCALE)) % 2 == 0
    for x in (x0, x1):
        image[y0 : y1 + 1, x][dash[y0 : y1 + 1]] = FRAME
    return image


def _thicken(mask: np.ndarray) -> np.ndarray:
    """The mask grown by one pixel each way (a one-pixel change stays visible when scaled down)."""
    grown = mask.copy()
    grown[1:] |= mask[:-1]
    grown[:-1] |= mask[1:]
    grown[:, 1:] |= grown[:, :-1].copy()
    grown[:, :-1] |= grown[:, 1:].copy()
    return grown


def _zoom(images: tuple[np.ndarray, ...], box) -> tuple[bytes, ...] | None:
    """The images cropped around the change (shown at one image pixel per CSS pixel: twice the
    figure's size), when the change is small enough to miss."""
    x0, y0, x1, y1 = box
    height, width = images[0].shape[:2]
    if (x1 - x0) * (y1 - y0) > 0.2 * width * height:
        return None
    pad = 12 * SCALE
    x0, y0, x1, y1 = max(0, x0 - pad), max(0, y0 - pad), min(width, x1 + pad), min(height, y1 + pad)
    return tuple(_png(image[y0:y1, x0:x1]) for image in images)


def _png(pixels: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    Image.fromarray(pixels.astype(np.uint8), "RGB").save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()


def side_by_side_png(diff: PixelDiff, titles=("golden", "new", "difference")) -> bytes:
    """One image for a person to look at: old, new and the difference in a row, titled."""
    images = [Image.open(io.BytesIO(p)).convert("RGB") for p in (diff.old_png, diff.new_png, diff.diff_png)]
    gap, band = 16, 28
    width = sum(i.width for i in images) + gap * (len(images) + 1)
    height = max(i.height for i in images) + band + gap
    sheet = Image.new("RGB", (width, height), (246, 247, 249))
    draw, x = ImageDraw.Draw(sheet), gap
    for title, image in zip(titles, images):
        draw.text((x, 8), title, fill=(29, 36, 48), font_size=16)
        sheet.paste(image, (x, band))
        x += image.width + gap
    buffer = io.BytesIO()
    sheet.save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()
