"""The `sitegen` command: build, serve."""
from __future__ import annotations

import argparse
import functools
import http.server
import os
import sys
from pathlib import Path

from .errors import BuildFailed


def main(argv: list[str] | None = None) -> int:
    """Run one sitegen command; return the process exit status."""
    parser = argparse.ArgumentParser(prog="sitegen", description="Build an offline interactive physics book.")
    commands = parser.add_subparsers(dest="command", required=True)
    build_cmd = commands.add_parser("build", help="build the site into build/")
    build_cmd.add_argument("--root", type=Path, default=Path.cwd(), help="project folder (holds content/)")
    build_cmd.add_argument("--out", type=Path, default=None, help="output folder (default ROOT/build)")
    build_cmd.add_argument("--debug", action="store_true", help="show Python tracebacks")
    serve_cmd = commands.add_parser("serve", help="serve build/ on 127.0.0.1")
    serve_cmd.add_argument("--dir", type=Path, default=Path("build"))
    serve_cmd.add_argument("--port", type=int, default=8000)
    serve_cmd.add_argument("--bind", default="127.0.0.1")
    args = parser.parse_args(argv)
    if args.command == "build":
        return _build(args)
    return _serve(args)


def _build(args) -> int:
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small linear algebra is 10x faster single-threaded
    from .build import BuildConfig, build
    from .content.math import MathToolMissing

    config = BuildConfig.at(args.root, args.out)
    try:
        report = build(config)
    except BuildFailed as failure:
        for error in failure.errors:
            print(error, file=sys.stderr)
        print(f"build failed: {len(failure.errors)} error(s); {config.out} was left as it was", file=sys.stderr)
        return 1
    except MathToolMissing as problem:
        print(f"sitegen: {problem}", file=sys.stderr)
        return 2
    total = sum(report.phases.values())
    size = sum(report.files.values())
    print(f"built {report.pages} pages, {report.scenes} scenes, {report.stored_values} stored values, "
          f"{size / 1024:.0f} KiB in {total:.2f} s -> {config.out}")
    return 0


def _serve(args) -> int:
    directory = args.dir.resolve()
    if not (directory / "index.html").is_file():
        print(f"sitegen: nothing to serve in {directory}; run 'make site' first", file=sys.stderr)
        return 1
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(directory))
    with http.server.ThreadingHTTPServer((args.bind, args.port), handler) as server:
        print(f"serving {directory} at http://{args.bind}:{args.port}/index.html (Ctrl-C stops)")
        try:
            server.serve_forever()
        except KeyboardInterrupt:
            pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
