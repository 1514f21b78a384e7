"""`sitegen serve`: binds 127.0.0.1 unless told otherwise, serves the files of its folder, and
nothing outside it — not through '..' (plain, percent-encoded, mixed), an absolute path, a
symbolic link, nor a folder listing. Traffic goes to the loopback address only.
"""

from __future__ import annotations

import http.client
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from preview import hears_ctrl_c

SECRET = b"secret outside the site"
OUTSIDE_PATHS = [
    "/../secret.txt",
    "/%2e%2e/secret.txt",
    "/%2E%2E/secret.txt",
    "/..%2fsecret.txt",
    "/%2e%2e%2fsecret.txt",
    "/.%2e/secret.txt",
    "/assets/../../secret.txt",
    "/assets/%2e%2e/%2e%2e/secret.txt",
    "/..\\secret.txt",
    "/%5c..%5csecret.txt",
    "//secret.txt",
    "/" + "../" * 12 + "etc/passwd",
    "/%2fetc%2fpasswd",
    "/link-out",
    "/assets/link-out-dir/secret.txt",
    "/sub/",
]


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """A small site to serve, with a secret file beside it and links that lead out of it."""
    top = tmp_path_factory.mktemp("serve")
    (top / "secret.txt").write_bytes(SECRET)
    site = top / "build"
    (site / "assets").mkdir(parents=True)
    (site / "sub").mkdir()
    (site / "index.html").write_bytes(b"<!DOCTYPE html><title>home</title>")
    (site / "assets" / "sitegen.css").write_bytes(b"body { color: black; }")
    (site / "sub" / "page.html").write_bytes(b"<!DOCTYPE html><title>page</title>")
    (site / "link-out").symlink_to(top / "secret.txt")
    (site / "assets" / "link-out-dir").symlink_to(top)
    return site


@pytest.fixture(scope="module")
def server(site):
    """`sitegen serve` on a free port of 127.0.0.1 (the default address); yields (host, port)."""
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    process = subprocess.Popen(
        [sys.executable, "-m", "sitegen.cli", "serve", "--dir", str(site), "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=site.parent,
        preexec_fn=hears_ctrl_c,
    )
    line = process.stdout.readline()
    assert line.startswith("serving "), (line, process.stderr.read() if process.poll() is not None else "")
    address = line.split("http://", 1)[1].split("/", 1)[0]
    host, port = address.rsplit(":", 1)
    yield host, int(port), process
    process.send_signal(signal.SIGINT)
    try:
        assert process.wait(timeout=10) == 0
    finally:
        if process.poll() is None:
            process.kill()


def get(host: str, port: int, path: str, headers: bool = False):
    """One GET with the request target sent exactly as given (http.client does not normalise it):
    (status, body), or (status, body, headers)."""
    connection = http.client.HTTPConnection(host, port, timeout=10)
    try:
        connection.request("GET", path)
        response = connection.getresponse()
        result = response.status, response.read()
        return (*result, dict(response.getheaders())) if headers else result
    finally:
        connection.close()


def test_binds_loopback_only_by_default(server):
    """Without --bind the server listens on 127.0.0.1 alone: not on all interfaces, not on
    another loopback address."""
    host, port, _ = server
    assert host == "127.0.0.1"
    listening = _listening_addresses(port)
    assert listening == ["127.0.0.1"], listening
    with pytest.raises(OSError):
        socket.create_connection(("127.0.0.2", port), timeout=2).close()


def test_serves_the_files_of_its_folder(server, site):
    """Files come back byte for byte; / is the home page."""
    host, port, _ = server
    for path, name in (
        ("/index.html", "index.html"),
        ("/", "index.html"),
        ("/assets/sitegen.css", "assets/sitegen.css"),
        ("/sub/page.html", "sub/page.html"),
        ("/index.html?x=1#y", "index.html"),
    ):
        status, body = get(host, port, path)
        assert (status, body) == (200, (site / name).read_bytes()), path


@pytest.mark.parametrize("path", OUTSIDE_PATHS)
def test_refuses_paths_out_of_its_folder(server, path):
    """Anything leading out of the folder, or to a folder listing, is 404 (or 403/400), never content."""
    host, port, _ = server
    status, body = get(host, port, path)
    assert status in (400, 403, 404), (path, status, body[:200])
    assert SECRET not in body and b"root:" not in body and b"Directory listing" not in body


@pytest.mark.parametrize("path", ["/sub", "//example.org/sub", "//example.org/%2e%2e"])
def test_redirects_stay_on_the_site(server, site, path):
    """A folder named without its slash is redirected to itself with one — a path on this server,
    never another host — where there is no listing, only the site's own home page at the top."""
    host, port, _ = server
    status, _, headers = get(host, port, path, headers=True)
    assert status in (301, 404)
    if status == 301:
        location = headers["Location"]
        assert location.startswith("/") and not location.startswith("//"), location
        status, body = get(host, port, location)
        assert (status, body) in ((404, body), (200, (site / "index.html").read_bytes())), (location, status)
        assert b"Directory listing" not in body


def test_missing_file_is_404(server):
    host, port, _ = server
    assert get(host, port, "/nowhere.html")[0] == 404


def test_nothing_to_serve_is_an_error(tmp_path):
    """A folder without index.html (no build yet) is refused with a hint, not served."""
    done = subprocess.run(
        [sys.executable, "-m", "sitegen.cli", "serve", "--dir", str(tmp_path), "--port", "0"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert (
        done.returncode == 1
        and "build the book first (sitegen build)" in done.stderr
        and "Traceback" not in done.stderr
    )


def test_port_in_use_is_an_error_without_traceback(site):
    """A port already taken gives one line saying so, exit 1."""
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        done = subprocess.run(
            [sys.executable, "-m", "sitegen.cli", "serve", "--dir", str(site), "--port", str(port)],
            capture_output=True,
            text=True,
            timeout=60,
        )
    assert done.returncode == 1 and "cannot serve on 127.0.0.1" in done.stderr and "Traceback" not in done.stderr


def _listening_addresses(port: int) -> list[str]:
    """The local addresses with a TCP socket listening on `port` (from /proc/net/tcp and tcp6)."""
    found = []
    for table, width in (("/proc/net/tcp", 8), ("/proc/net/tcp6", 32)):
        try:
            rows = Path(table).read_text().splitlines()[1:]
        except FileNotFoundError:
            continue
        for row in rows:
            local, state = row.split()[1], row.split()[3]
            address, _, hex_port = local.partition(":")
            if state == "0A" and int(hex_port, 16) == port:  # 0A: LISTEN
                raw = bytes.fromhex(address)
                if width == 8:
                    found.append(socket.inet_ntop(socket.AF_INET, raw[::-1]))
                else:
                    words = b"".join(raw[i : i + 4][::-1] for i in range(0, 16, 4))
                    found.append(socket.inet_ntop(socket.AF_INET6, words))
    return sorted(found)
