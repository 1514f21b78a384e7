"""TeX to MathML at build time, with Temml run once per build by node."""
from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

from ..errors import AuthorError
from .markdown_ext import MathItem

SCRIPT = Path(__file__).with_name("tex2mathml.js")


class MathToolMissing(RuntimeError):
    """node or the Temml package is not installed (a set-up problem, not an author error)."""


def convert_math(items: list[MathItem], node_modules: Path) -> tuple[list[str], list[AuthorError]]:
    """MathML for each formula (in order), and an author error for each formula Temml rejects."""
    unique = sorted({(m.tex, m.display) for m in items})
    if not unique:
        return [], []
    results = dict(zip(unique, _run_temml(unique, node_modules)))
    mathml, errors = [], []
    for item in items:
        result = results[(item.tex, item.display)]
        if "error" in result:
            errors.append(AuthorError(item.loc, f"TeX cannot be converted: {_first_line(result['error'])} (in '{item.tex}')"))
        mathml.append(result.get("mathml", ""))
    return mathml, errors


def _run_temml(formulas: list[tuple[str, bool]], node_modules: Path) -> list[dict]:
    if not (node_modules / "temml").is_dir():
        raise MathToolMissing(f"Temml is not installed in {node_modules}; run 'make site' (it runs 'npm ci')")
    env = {**os.environ, "NODE_PATH": str(node_modules)}
    try:
        done = subprocess.run(
            ["node", str(SCRIPT)], input=json.dumps(formulas), capture_output=True, text=True, env=env, check=False
        )
    except FileNotFoundError:
        raise MathToolMissing("node is not installed; sitegen runs Temml with node at build time") from None
    if done.returncode != 0:
        raise MathToolMissing(f"Temml failed: {done.stderr.strip()}")
    return json.loads(done.stdout)


def _first_line(message: str) -> str:
    """Temml's message without the underlined copy of the formula it appends."""
    return message.strip().split("\n")[0].rstrip(": ")
