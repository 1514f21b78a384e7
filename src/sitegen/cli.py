"""The `sitegen` command: new, build, serve, review, bench, models, and accept-figures/check-figures for the figure
goldens."""

from __future__ import annotations

import argparse
import gc
import os
import signal
import sys
import time
import traceback
from pathlib import Path

from . import stamp
from .config import BookConfig, ConfigError, read_book
from .errors import BuildFailed, SceneCrashed
from .progress import BuildProgress


def main(argv: list[str] | None = None) -> int:
    """Run one sitegen command; return the process exit status."""
    args = command_parser().parse_args(argv)
    if args.command == "new":
        return _new(args.folder)
    try:
        book = read_book(args.root, required=_needs_book(args))
    except ConfigError as problem:
        print(f"sitegen: {problem}", file=sys.stderr)
        return 2
    # The book's compiled code: read once, when the kernels are first imported (physics/compiled.py).
    if not os.environ.get("SITEGEN_COMPILED_CACHE"):
        os.environ["SITEGEN_COMPILED_CACHE"] = str(book.root / ".cache" / "compiled")
    return COMMANDS[args.command](args, book)


def run() -> None:
    """The `sitegen` process: `main`, then an exit that leaves the heap to the operating system."""
    try:
        code = main()
    except KeyboardInterrupt:  # Ctrl-C before a command's own work began (while it loads, say)
        print("sitegen: interrupted", file=sys.stderr)
        code = 130
    # At exit the interpreter would search the whole heap for reference cycles to free, objects the process
    # gives back anyway: after a build (numba's, scipy's and matplotlib's objects) that took about a second.
    gc.disable()
    gc.freeze()
    sys.exit(code)


def command_parser() -> argparse.ArgumentParser:
    """The command line: every subcommand with its options."""
    parser = argparse.ArgumentParser(
        prog="sitegen",
        description="Build an offline interactive physics book.",
        epilog="Every command works on the book in the current folder (the folder of its "
        "book.toml), or in the folder given with --root.",
    )
    commands = parser.add_subparsers(dest="command", required=True)
    new_cmd = commands.add_parser(
        "new",
        help="write a new book into DIR (a new or empty folder)",
        description="write a new book into DIR: book.toml, a home page, a chapter with "
        "a scene of the book's own model, and a test of that model",
    )
    new_cmd.add_argument("folder", type=Path, metavar="DIR")
    build_cmd = _command(
        commands, "build", "build the site into the book's output folder (book.toml 'output', default build/)"
    )
    build_cmd.add_argument("--out", type=Path, default=None, help="output folder (default: the book's)")
    build_cmd.add_argument(
        "--explain", action="store_true", help="say for each scene why it was computed or that it was cached"
    )
    _build_options(build_cmd)
    serve_cmd = _command(commands, "serve", "serve the built site on 127.0.0.1")
    serve_cmd.add_argument("--dir", type=Path, default=None, help="folder to serve (default: the book's output folder)")
    serve_cmd.add_argument("--port", type=int, default=8000, help="port (default 8000; 0: any free port)")
    serve_cmd.add_argument(
        "--host",
        "--bind",
        dest="host",
        default="127.0.0.1",
        help="address to listen on (default 127.0.0.1: this machine only)",
    )
    serve_cmd.add_argument(
        "--watch",
        action="store_true",
        help="build the book, then rebuild it when its pages, book.toml, theme or models change; "
        "open pages reload by themselves and show a failed build's errors",
    )
    _executor_options(serve_cmd)
    review_cmd = _command(commands, "review", "compare two builds: the figures, tables and text that changed")
    review_cmd.add_argument("trees", nargs="*", type=Path, metavar="BUILD", help="OLD NEW, or with --base only NEW")
    review_cmd.add_argument(
        "--base",
        metavar="REV",
        help="build git revision REV in a temporary worktree as OLD; NEW defaults to the book's output folder",
    )
    review_cmd.add_argument("--out", type=Path, default=None, help="report folder (default ./build-review)")
    review_cmd.add_argument(
        "--no-render", action="store_true", help="do not render figures to PNG (no Chromium needed)"
    )
    for name, text in (
        ("accept-figures", "rewrite the book's figure goldens from a build (refused in CI)"),
        ("check-figures", "compare a build's figures with the book's goldens (exit 1 on a difference)"),
    ):
        golden_cmd = _command(commands, name, text)
        golden_cmd.add_argument(
            "--build", type=Path, default=None, help="the built site (default: the book's output folder)"
        )
        golden_cmd.add_argument(
            "--goldens",
            type=Path,
            default=None,
            help="the goldens folder (default: book.toml 'goldens', else goldens/)",
        )
    bench_cmd = _command(commands, "bench", "measure accuracy against cost; write content/accuracy/bench.json")
    bench_cmd.add_argument("--out", type=Path, default=None, help="results file (default CONTENT/accuracy/bench.json)")
    bench_cmd.add_argument(
        "--quick", action="store_true", help="a few points, one run each: a smoke test, not a measurement"
    )
    pdf_cmd = _command(commands, "pdf", "build the site, then print the whole book as one PDF (needs Chromium)")
    pdf_cmd.add_argument(
        "--output", type=Path, default=None, help="the PDF to write (default: book.pdf in the book's folder)"
    )
    pdf_cmd.add_argument("--chromium", default=None, metavar="PATH", help="the Chromium to print with")
    _build_options(pdf_cmd)
    pdf_cmd.set_defaults(out=None, explain=False)  # the site goes where `sitegen build` puts it
    models_cmd = _command(commands, "models", "list the models a book can use: parameters, outputs, effects, numerics")
    models_cmd.add_argument("name", nargs="?", help="one model (default: every model)")
    models_cmd.add_argument(
        "--builtin", action="store_true", help="only sitegen's built-in models (as in docs/models.md)"
    )
    return parser


def _build_options(command) -> None:
    """The options of a command that builds the site: where its work runs, the cache, tracebacks."""
    command.add_argument("--debug", action="store_true", help="show Python tracebacks")
    _executor_options(command)
    command.add_argument(
        "--no-cache",
        action="store_true",
        help="compute every scene; neither read nor write tables in "
        ".cache/ (compiled code is still kept in .cache/compiled/)",
    )


def _executor_options(command) -> None:
    """Where a command's work runs: here, in local processes, or on a Dask cluster."""
    command.add_argument(
        "--jobs",
        type=_jobs,
        default=1,
        metavar="N|auto",
        help="run the work in N local processes, or one per core with 'auto' (default 1: in this process)",
    )
    command.add_argument("--scheduler", default=None, metavar="tcp://HOST:PORT", help="run the work on a Dask cluster")


def _jobs(text: str) -> int | str:
    """--jobs: a positive number, or auto (compute.executors.AUTO)."""
    if text == "auto" or (text.isdigit() and int(text) > 0):
        return text if text == "auto" else int(text)
    raise argparse.ArgumentTypeError(f"must be a positive number or 'auto', not {text!r}")


def _needs_book(args) -> bool:
    """Whether the command must find book.toml: not when every folder it uses is given."""
    if args.command == "serve":
        return args.dir is None or args.watch
    if args.command == "review":
        return args.base is not None or len(args.trees) < 2
    if args.command in ("accept-figures", "check-figures"):
        return args.build is None or args.goldens is None
    return not (args.command == "models" and args.builtin)


def _command(commands, name: str, text: str):
    command = commands.add_parser(name, help=text, description=text)
    command.add_argument(
        "--root",
        type=Path,
        default=Path.cwd(),
        help="the book's folder, which holds book.toml (default: the current folder)",
    )
    return command


def _new(folder: Path) -> int:
    from .newbook import FolderNotEmpty, new_book

    try:
        written = new_book(folder)
    except FolderNotEmpty as problem:
        print(f"sitegen: {problem}", file=sys.stderr)
        return 2
    print(
        f"wrote a new book into {folder}: {', '.join(written)}\n"
        f"next: cd {folder} && sitegen build (then open build/index.html), or sitegen serve --watch to see "
        f"each edit in the browser as you save it"
    )
    return 0


def _review(args, book: BookConfig) -> int:
    from .review.command import run_review

    return run_review(args.trees, args.base, book.root, args.out, render=not args.no_render, new=book.output)


def _goldens(args, book: BookConfig) -> int:
    from .review.command import run_accept, run_check

    run = run_accept if args.command == "accept-figures" else run_check
    return run(args.build or book.output, args.goldens or book.goldens)


def _models(args, book: BookConfig) -> int:
    from .reference import models_reference
    from .registry import builtin_registry, load_registry

    registry = builtin_registry() if args.builtin else load_registry(book)
    for problem in registry.problems:
        print(problem, file=sys.stderr)
    if args.name and args.name not in registry.models:
        print(f"sitegen: no model '{args.name}'; models: {', '.join(sorted(registry.models))}", file=sys.stderr)
        return 2
    print(models_reference(registry, [args.name] if args.name else None), end="")
    return 1 if registry.problems else 0


def _pdf(args, book: BookConfig) -> int:
    built = _build(args, book)
    if built != 0:
        return built
    from .pdf import BrokenLinks, ChromiumMissing, PrintFailed, make_pdf

    out = (args.output or book.root / "book.pdf").resolve()
    start = time.perf_counter()
    try:
        made = make_pdf(book, book.output, out, args.chromium)
    except ChromiumMissing as problem:
        print(f"sitegen: {problem}", file=sys.stderr)
        return 2
    except (PrintFailed, BrokenLinks) as problem:
        print(f"sitegen: {problem}", file=sys.stderr)
        return 3
    print(
        f"printed {made.pages} pages, {made.size / 1024:.0f} KiB in {time.perf_counter() - start:.1f} s "
        f"({made.prints} prints) -> {made.path}"
    )
    return 0


def _build(args, book: BookConfig) -> int:
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small linear algebra is 10x faster single-threaded
    out = (args.out or book.output).resolve()
    if not book.content.is_dir():
        print(
            f"sitegen: no folder {book.relative(book.content)} in {book.root}: a book's pages are "
            f"{book.relative(book.content)}/index.md and its other pages",
            file=sys.stderr,
        )
        return 2
    stamped = not (args.no_cache or args.explain)  # both ask for the work itself, so neither stops early
    inputs = stamp.inputs_digest(book) if stamped else None
    last = stamp.up_to_date(book, out, inputs) if stamped else None
    if last is not None:
        print(
            f"up to date: no page, model, setting or library changed since the last build of {last['pages']} "
            f"pages, {last['scenes']} scenes -> {out}"
        )
        return 0
    from .build import BuildConfig, build
    from .content.math import MathToolMissing
    from .phases.run import Terminated, stop_on_sigterm
    from .registry import raising_line

    options = {"jobs": args.jobs, "scheduler": args.scheduler, "cache": None if args.no_cache else book.root / ".cache"}
    config = BuildConfig(book.root, book.content, out, book=book, **options)
    try:
        with stop_on_sigterm():
            report = build(config, progress=BuildProgress(sys.stdout, args.explain))
    except BuildFailed as failure:
        for error in failure.errors:
            print(error, file=sys.stderr)
        print(f"build failed: {len(failure.errors)} error(s); {config.out} was left as it was", file=sys.stderr)
        return 1
    except MathToolMissing as problem:
        print(f"sitegen: {problem}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as stop:
        print(
            f"build {'stopped' if isinstance(stop, Terminated) else 'interrupted'}; {config.out} holds the last "
            f"complete build",
            file=sys.stderr,
        )
        return 128 + signal.SIGTERM if isinstance(stop, Terminated) else 130
    except SceneCrashed as crash:  # an exception in a model's, a figure's or sitegen's code, met on one scene
        if args.debug:  # the traceback, then the same line and status as without --debug
            traceback.print_exception(crash.error, file=sys.stderr)
        print(f"sitegen: {crash}\n{config.out} holds the last complete build{_rerun(args)}", file=sys.stderr)
        return 3
    except OSError as problem:  # the machine's side: a folder that cannot be written, a full disk
        if args.debug:
            traceback.print_exception(problem, file=sys.stderr)
        print(f"sitegen: {problem}; {config.out} holds the last complete build", file=sys.stderr)
        return 2
    except Exception as problem:  # a bug in sitegen or in a model, not in the book
        if args.debug:
            traceback.print_exception(problem, file=sys.stderr)
        where = raising_line(problem, [], book)
        print(
            f"sitegen: {where}: {type(problem).__name__}: {problem}\n"
            f"{config.out} holds the last complete build{_rerun(args)}",
            file=sys.stderr,
        )
        return 3
    if stamped:
        stamp.write_stamp(book, out, inputs, {"pages": report.pages, "scenes": report.scenes})
    total = sum(report.phases.values())
    size = sum(report.files.values())
    print(
        f"built {report.pages} pages, {report.scenes} scenes ({report.computed} computed, {report.cached} cached), "
        f"{report.stored_values} stored values, {size / 1024:.0f} KiB in {total:.2f} s -> {config.out}"
    )
    return 0


def _rerun(args) -> str:
    """The advice after a crash: how to see the traceback, unless it was just shown."""
    return "" if args.debug else "; run again with --debug for the traceback"


def _bench(args, book: BookConfig) -> int:
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    from .accuracy.bench import run_bench, summary_lines
    from .accuracy.experiments import FULL, QUICK
    from .content.bench_results import BENCH_NAME, write_results

    if not book.content.is_dir():
        print(f"sitegen: no folder {book.relative(book.content)} in {book.root}", file=sys.stderr)
        return 2
    out = args.out or book.content / BENCH_NAME
    results = run_bench(book.root, QUICK if args.quick else FULL, progress=lambda line: print(line, flush=True))
    write_results(results, out)
    print("\n".join(summary_lines(results)))
    print(f"wrote {out}")
    return 0


def _serve(args, book: BookConfig) -> int:
    from .preview.server import Live, site_server

    if args.watch and args.dir is not None:
        print("sitegen: serve --watch serves the book's output folder; leave out --dir", file=sys.stderr)
        return 2
    directory = (args.dir or book.output).resolve()
    if not args.watch and not (directory / "index.html").is_file():
        print(f"sitegen: nothing to serve in {directory}; build the book first (sitegen build)", file=sys.stderr)
        return 1
    live = Live() if args.watch else None
    try:
        server = site_server(directory, args.host, args.port, live)
    except OSError as problem:
        print(
            f"sitegen: cannot serve on {args.host}:{args.port}: {problem.strerror or problem}; choose another --port",
            file=sys.stderr,
        )
        return 1
    if args.watch:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
        from .preview.watch import serve_watching

        return serve_watching(book, directory, server, live, jobs=args.jobs, scheduler=args.scheduler)
    with server:
        host, port = server.server_address[:2]
        print(f"serving {directory} at http://{host}:{port}/index.html (Ctrl-C stops)", flush=True)
        try:
            server.serve_forever()
        except KeyboardInterrupt:
            pass
    return 0


COMMANDS = {
    "build": _build,
    "serve": _serve,
    "review": _review,
    "accept-figures": _goldens,
    "check-figures": _goldens,
    "bench": _bench,
    "models": _models,
    "pdf": _pdf,
}

if __name__ == "__main__":
    run()
