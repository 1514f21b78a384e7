"""Headless Chromium, which prints HTML with its MathML and SVG to PDF: found on PATH or through
Playwright, and run once per print with a profile of its own."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "chrome")
PRINT_TIMEOUT = 600  # seconds: a book of many chapters prints in well under a minute
# The browser starts with nothing it would do on its own (updates, sync, first-run pages, network lookups).
QUIET = (
    "--headless",
    "--disable-gpu",
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
)


class ChromiumMissing(RuntimeError):
    """No Chromium to print with (a message for the author saying how to get one)."""


class PrintFailed(RuntimeError):
    """Chromium ran but wrote no PDF."""


def find_chromium(given: str | None = None) -> str:
    """The Chromium to print with: `given`, else one on PATH, else Playwright's; ChromiumMissing if none."""
    if given:
        if shutil.which(given) or Path(given).is_file():
            return shutil.which(given) or given
        raise ChromiumMissing(f"no Chromium at {given}")
    for name in NAMES:
        found = shutil.which(name)
        if found:
            return found
    installed = _playwright_chromium()
    if installed:
        return installed
    raise ChromiumMissing(
        "a PDF is printed by headless Chromium, and none was found: install one (Debian and Ubuntu: "
        "`apt install chromium`; or `pip install playwright && playwright install chromium`), "
        "or name it with --chromium PATH"
    )


def _playwright_chromium() -> str | None:
    """The Chromium that Playwright installed, if Playwright is installed and has one."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    try:
        with sync_playwright() as playwright:
            path = playwright.chromium.executable_path
    except Exception:  # Playwright without its browser, or whose driver cannot start
        return None
    return path if path and Path(path).is_file() else None


def print_pdf(chromium: str, page: Path, pdf: Path) -> None:
    """Print the HTML file `page` to `pdf` with the page size and margins its CSS asks for, its internal
    links kept as links and its headings as the PDF's outline."""
    with tempfile.TemporaryDirectory(prefix="sitegen-chromium-") as profile:
        command = [
            chromium,
            *QUIET,
            f"--user-data-dir={profile}",
            "--no-pdf-header-footer",
            "--generate-pdf-document-outline",
            f"--print-to-pdf={pdf}",
            page.resolve().as_uri(),
        ]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            command.insert(1, "--no-sandbox")  # Chromium refuses to start as root with its sandbox
        pdf.unlink(missing_ok=True)
        done = subprocess.run(command, capture_output=True, text=True, timeout=PRINT_TIMEOUT, check=False)
    if not pdf.is_file() or pdf.stat().st_size == 0:
        said = (done.stderr or done.stdout).strip().splitlines()[-3:]
        raise PrintFailed(f"{chromium} wrote no PDF (exit status {done.returncode}): {' '.join(said)}")
