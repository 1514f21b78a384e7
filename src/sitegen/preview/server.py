"""Serving a built site: the files of one folder and nothing outside it, on 127.0.0.1 unless told
otherwise.

With a `Live` state (`sitegen serve --watch`) every HTML page is sent with a small script added
(`reload.js`; the files on disk stay as the build wrote them), which follows the rebuilds through an
event stream: it reloads the page after a good build and shows a failed build's errors over the
last good page. Nothing is cached by the browser then, so a reload always gets the new files.
"""

from __future__ import annotations

import functools
import html
import http.server
import io
import json
import os
import threading
import urllib.parse
from pathlib import Path

PREFIX = "/__sitegen/"  # the preview's own addresses, beside the site's files
EVENTS, SCRIPT = PREFIX + "events", PREFIX + "reload.js"
RELOAD_JS = Path(__file__).with_name("reload.js")
PING_SECONDS = 10.0  # an idle event stream sends a comment this often, so a closed page ends its thread
NOT_BUILT = '<!DOCTYPE html><html lang="en"><title>Not built</title><body><p>{}</p></body></html>'


class Live:
    """What the open pages follow: the number of the last good build and the errors of the last
    attempt (none when it succeeded), with a version that changes on every attempt."""

    def __init__(self):
        self._changed = threading.Condition()
        self.build, self.errors, self.version, self.closed = 0, (), 0, False

    def publish(self, built: bool, errors: list[str] | tuple[str, ...] = ()) -> None:
        """Record one attempt: a good build (its files are in place), or the errors of a failed one."""
        with self._changed:
            self.build += bool(built)
            self.errors, self.version = tuple(errors), self.version + 1
            self._changed.notify_all()

    def close(self) -> None:
        """End every event stream (the server is stopping)."""
        with self._changed:
            self.closed = True
            self._changed.notify_all()

    def state_after(self, version: int, timeout: float) -> tuple[int, str] | None:
        """(version, the state as JSON) once the version differs from `version`; None after `timeout`
        seconds without a change, or once closed."""
        with self._changed:
            self._changed.wait_for(lambda: self.version != version or self.closed, timeout)
            if self.closed or self.version == version:
                return None
            return self.version, json.dumps({"build": self.build, "errors": list(self.errors)}, ensure_ascii=False)


class SiteHandler(http.server.SimpleHTTPRequestHandler):
    """Serves the files of one folder and nothing else: no listings, no path out of it (not through
    '..', encoded or not, nor a symbolic link). With `live`, pages carry the reload script."""

    def __init__(self, *args, live: Live | None = None, **kwargs):
        self.live = live
        super().__init__(*args, **kwargs)

    def do_GET(self):
        route = urllib.parse.urlsplit(self.path).path
        if self.live and route == EVENTS:
            return self._events()
        if self.live and route == SCRIPT:
            return self._send(200, "text/javascript; charset=utf-8", RELOAD_JS.read_bytes(), body=True)
        return super().do_GET()

    def send_head(self):
        root = os.path.realpath(self.directory)
        target = os.path.realpath(self.translate_path(self.path))
        if target != root and not target.startswith(root + os.sep):
            self.send_error(404, "File not found")
            return None
        if self.live:
            del self.headers["If-Modified-Since"]  # a rebuild within the same second must not get a 304
            route = urllib.parse.urlsplit(self.path).path
            page = os.path.join(target, "index.html") if route.endswith("/") else target
            if page.endswith(".html"):
                return self._page(page)
        return super().send_head()

    def _page(self, path: str):
        """A page with the reload script before </body>; a page not (yet) built is a 404 that has it too,
        so the errors of a failed first build show, and the page appears once it is built."""
        build = self.live.build  # read before the file: a rebuild in between costs one reload more, never one less
        try:
            with open(path, "rb") as file:
                status, page = 200, file.read()
        except (FileNotFoundError, IsADirectoryError, NotADirectoryError):
            status, page = (
                404,
                NOT_BUILT.format(
                    html.escape(f"No page {urllib.parse.urlsplit(self.path).path} in this build.")
                ).encode(),
            )
        tag = f'<script src="{SCRIPT}" data-build="{build}"></script>\n'.encode()
        at = page.rfind(b"</body>")
        page = page[:at] + tag + page[at:] if at >= 0 else page + tag
        return self._send(status, "text/html; charset=utf-8", page)

    def _send(self, status: int, kind: str, data: bytes, body: bool = False):
        self.send_response(status)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        if body:
            self.wfile.write(data)
            return None
        return io.BytesIO(data)

    def _events(self) -> None:
        """The build's state as server-sent events: now, then after every attempt, until the page goes."""
        self.close_connection = True
        self.send_response(200)
        self.send_header("Content-Type", "text/event-stream")
        self.end_headers()
        try:
            self.wfile.write(b"retry: 500\n\n")
            version = -1
            while not self.live.closed:
                state = self.live.state_after(version, PING_SECONDS)
                if state:
                    version, data = state
                self.wfile.write(f"data: {data}\n\n".encode() if state else b": ping\n\n")
                self.wfile.flush()
        except (BrokenPipeError, ConnectionResetError):
            pass  # the page was closed or reloaded

    def end_headers(self):
        if self.live:
            self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def list_directory(self, path):
        self.send_error(404, "No listing; link to a file")
        return None

    def log_message(self, format, *args):
        if not (self.live and self.path.startswith(PREFIX)):  # not a line per page view's event stream
            super().log_message(format, *args)


def site_server(directory: Path, host: str, port: int, live: Live | None = None) -> http.server.ThreadingHTTPServer:
    """A server of `directory` at host:port (port 0: any free one); OSError when it cannot listen there."""
    handler = functools.partial(SiteHandler, directory=str(directory), live=live)
    server = http.server.ThreadingHTTPServer((host, port), handler)
    server.daemon_threads = True
    return server
