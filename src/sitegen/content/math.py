"""TeX to MathML at build time, with Temml (vendored in temml/) run once per build by node."""

from __future__ import annotations

import hashlib
import json
import subprocess
from pathlib import Path

from ..errors import AuthorError
from .markdown_ext import MathItem

SCRIPT = Path(__file__).with_name("tex2mathml.js")
TEMML = Path(__file__).with_name("temml") / "temml.min.js"  # Temml's browser build, as npm ships it
TEMML_CSS = TEMML.with_name("Temml-Latin-Modern.css")


class MathToolMissing(RuntimeError):
    """node is not on PATH (a set-up problem, not an author error)."""


def convert_math(items: list[MathItem], cached=None) -> tuple[list[str], list[AuthorError]]:
    """MathML for each formula (in order), and an author error for each formula Temml rejects.

    `cached(kind, key, compute)` may serve a previous run's conversion of the same formulas.
    """
    unique = sorted({(m.tex, m.display) for m in items})
    if not unique:
        return [], []
    key = hashlib.sha256(json.dumps([unique, _converter_version()]).encode()).hexdigest()
    converted = (
        cached("math", key, lambda: json.dumps(_run_temml(unique)).encode())
        if cached
        else json.dumps(_run_temml(unique)).encode()
    )
    results = dict(zip(unique, json.loads(converted)))
    mathml, errors = [], []
    for item in items:
        result = results[(item.tex, item.display)]
        if "error" in result:
            errors.append(
                AuthorError(item.loc, f"TeX cannot be converted: {_first_line(result['error'])} (in '{item.tex}')")
            )
        mathml.append(result.get("mathml", ""))
    return mathml, errors


def _converter_version() -> str:
    """What the MathML depends on besides the TeX: Temml's code and our script."""
    return "; ".join(hashlib.sha256(path.read_bytes()).hexdigest() for path in (TEMML, SCRIPT))


def _run_temml(formulas: list[tuple[str, bool]]) -> list[dict]:
    try:
        done = subprocess.run(
            ["node", str(SCRIPT), str(TEMML)], input=json.dumps(formulas), capture_output=True, text=True, check=False
        )
    except FileNotFoundError:
        raise MathToolMissing(
            "node is not on PATH: sitegen converts TeX to MathML with Temml, run by Node.js "
            "(install it, e.g. 'apt-get install nodejs', and build again)"
        ) from None
    if done.returncode != 0:
        raise MathToolMissing(f"Temml failed: {done.stderr.strip()}")
    return json.loads(done.stdout)


def _first_line(message: str) -> str:
    """Temml's message without the underlined copy of the formula it appends."""
    return message.strip().split("\n")[0].rstrip(": ")
