"""TeX to MathML at build time, with Temml run once per build by node."""
from __future__ import annotations

import hashlib
import json
import os
import subprocess
from pathlib import Path

from ..errors import AuthorError
from .markdown_ext import MathItem

SCRIPT = Path(__file__).with_name("tex2mathml.js")


class MathToolMissing(RuntimeError):
    """node or the Temml package is not installed (a set-up problem, not an author error)."""


def convert_math(items: list[MathItem], node_modules: Path, remember=None) -> tuple[list[str], list[AuthorError]]:
    """MathML for each formula (in order), and an author error for each formula Temml rejects.

    `remember(kind, key, compute)` may serve a previous run's conversion of the same formulas.
    """
    unique = sorted({(m.tex, m.display) for m in items})
    if not unique:
        return [], []
    key = hashlib.sha256(json.dumps([unique, _converter_version(node_modules)]).encode()).hexdigest()
    converted = remember("math", key, lambda: json.dumps(_run_temml(unique, node_modules)).encode()) if remember \
        else json.dumps(_run_temml(unique, node_modules)).encode()
    results = dict(zip(unique, json.loads(converted)))
    mathml, errors = [], []
    for item in items:
        result = results[(item.tex, item.display)]
        if "error" in result:
            errors.append(AuthorError(item.loc, f"TeX cannot be converted: {_first_line(result['error'])} (in '{item.tex}')"))
        mathml.append(result.get("mathml", ""))
    return mathml, errors


def _converter_version(node_modules: Path) -> str:
    """What the MathML depends on besides the TeX: Temml's version and our script."""
    try:
        version = json.loads((node_modules / "temml" / "package.json").read_text())["version"]
    except (FileNotFoundError, KeyError, ValueError):
        version = "missing"
    return f"temml {version}; {hashlib.sha256(SCRIPT.read_bytes()).hexdigest()}"


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
