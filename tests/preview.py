"""Helpers for the tests of `sitegen serve --watch`: the command in a process of its own, its output
collected line by line, stopped with Ctrl-C (SIGINT)."""

from __future__ import annotations

import os
import queue
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

SERVE_WATCH = [sys.executable, "-m", "sitegen.cli", "serve", "--watch", "--port", "0"]


def hears_ctrl_c() -> None:
    """In a server's process before it starts: Ctrl-C (SIGINT) stops it, even when the tests themselves were
    started in the background by a shell without job control, which makes its children ignore SIGINT."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


class WatchServer:
    """`sitegen serve --watch` run in `book` (by `command`, default this checkout's): its address once
    it serves, and every line it prints."""

    def __init__(self, book: Path, command: list[str] | None = None, env: dict | None = None):
        self.book = book
        self.process = subprocess.Popen(
            command or SERVE_WATCH,
            cwd=book,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env={**(env or os.environ), "PYTHONUNBUFFERED": "1"},
            preexec_fn=hears_ctrl_c,
        )
        self.lines: queue.Queue[str] = queue.Queue()
        self.seen: list[str] = []
        threading.Thread(target=self._read, daemon=True).start()
        serving = self.wait_for("serving ", timeout=300)
        self.origin = serving.split(" at ", 1)[1].split("/index.html", 1)[0]

    def _read(self) -> None:
        for line in self.process.stdout:
            self.lines.put(line.rstrip("\n"))

    def wait_for(self, start: str, timeout: float = 30) -> str:
        """The next line that starts with `start` (AssertionError with what was printed, after `timeout` s)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                line = self.lines.get(timeout=0.1)
            except queue.Empty:
                if self.process.poll() is not None and self.lines.empty():
                    break
                continue
            self.seen.append(line)
            if line.startswith(start):
                return line
        raise AssertionError(f"no line starting {start!r} within {timeout} s; printed:\n" + "\n".join(self.seen))

    def lines_until(self, start: str, timeout: float = 30) -> list[str]:
        """Every line up to and including the next that starts with `start`."""
        first = len(self.seen)
        self.wait_for(start, timeout)
        return self.seen[first:]

    def url(self, name: str) -> str:
        return f"{self.origin}/{name}"

    def stop(self) -> int:
        """Ctrl-C, then the exit status."""
        self.process.send_signal(signal.SIGINT)
        try:
            return self.process.wait(timeout=20)
        finally:
            if self.process.poll() is None:
                self.process.kill()
