"""Three browser engines behind one small interface, for the reader's checks in each (tests/reader_checks.py):

- Chromium: Debian's, through Playwright (a page of the test module's browser, tests/browser.py);
- Firefox ESR: Debian's, through puppeteer-core over WebDriver BiDi, from node (tests/firefox.js);
- WebKitGTK (the engine of Safari and of every browser on an iPhone): Debian's MiniBrowser through
  WebKitWebDriver and selenium, in a virtual X display of its own (Xvfb).

An `Engine` is one browser with one tab: it loads a document, runs a function in it, resizes its viewport,
takes a screenshot of it and presses keys. Scripts are given as the statements of a function of `arg` and
return JSON. WebKitWebDriver reports no console messages: a site read in WebKit is a copy whose pages
start with a script of the tests' own that collects errors and warnings (`instrumented`).
"""

from __future__ import annotations

import base64
import io
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
FIREFOX = "/usr/bin/firefox-esr"
MINIBROWSER = "/usr/lib/x86_64-linux-gnu/webkit2gtk-4.1/MiniBrowser"
WEBKIT_DRIVER = "/usr/bin/WebKitWebDriver"
WEBKIT_LIBRARY = "libwebkit2gtk-4.1.so.0"  # MiniBrowser's engine (the driver has no --version)
ENGINES = ("chromium", "firefox", "webkit")

# What WebKit's pages run first (see `instrumented`): errors, failed loads, unhandled rejections, console
# errors and warnings, kept in a list that `WebKit.errors` reads.
ERROR_LOG_SCRIPT = """<script>(function () {
  var log = window.__testErrors = [];
  window.addEventListener("error", function (e) {
    log.push(e.target === window ? "pageerror: " + e.message + " (" + e.filename + ":" + e.lineno + ")"
      : "failed to load " + (e.target.src || e.target.href));
  }, true);
  window.addEventListener("unhandledrejection", function (e) { log.push("unhandled rejection: " + e.reason); });
  ["error", "warn"].forEach(function (kind) {
    var original = console[kind];
    console[kind] = function () {
      log.push(kind + ": " + Array.prototype.join.call(arguments, " "));
      return original.apply(console, arguments);
    };
  });
})();</script>"""


# The library's own version, asked in a process of its own (loading it here would load GTK into the test run).
_WEBKIT_VERSION_PY = f"""
import ctypes
lib = ctypes.CDLL({WEBKIT_LIBRARY!r})
print(".".join(str(getattr(lib, f"webkit_get_{{part}}_version")()) for part in ("major", "minor", "micro")))
"""


def _first_line(command: list[str]) -> str:
    """The first line `command` prints ("" if it cannot run)."""
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return ""
    return done.stdout.strip().split("\n")[0] if done.returncode == 0 else ""


def installed_versions() -> list[str]:
    """Each engine's name and version as its binary or library tells it ("Chromium 156.0.8078.114", "Firefox
    ESR 153.8.0", "WebKitGTK 2.50.6"), or that it is not installed."""
    from sitegen.review.figures import CHROMIUM

    found = {
        "Chromium": re.match(r"Chromium (\S+)", _first_line([CHROMIUM, "--version"])),  # "... built on Debian ..."
        "Firefox ESR": re.match(r"Mozilla Firefox (\S+?)(esr)?$", _first_line([FIREFOX, "--version"])),
        "WebKitGTK": re.match(r"(\d+\.\d+\.\d+)$", _first_line([sys.executable, "-c", _WEBKIT_VERSION_PY])),
    }
    return [f"{name} {match.group(1)}" if match else f"{name} not installed" for name, match in found.items()]


def _expression(function: str, arg) -> str:
    """A call of `function` (its source) with `arg`, as an expression whose value is a promise of the JSON text of
    its result (the function may return a promise: it is waited for)."""
    return f"new Promise(done => done(({function})({json.dumps(arg)}))).then(value => JSON.stringify(value))"


def _parsed(text):
    return None if text is None else json.loads(text)


class Engine:
    """One browser with one tab."""

    name = ""
    version = ""
    shown: str | None = None  # the address of the document the tests last loaded and left as it is

    def load(self, url: str) -> None:
        """Load `url` as a new document and wait for its load event and its fonts."""
        raise NotImplementedError

    def evaluate(self, function: str, arg=None):
        """Call `function` (the source of a JavaScript function of one argument) with `arg` in the document;
        what it returns, through JSON (as Playwright's `page.evaluate` does: tests/browser.py's helpers take
        an engine as they take a page)."""
        raise NotImplementedError

    def run(self, body: str, arg=None):
        """Run `body` (statements of a function of `arg`) in the document; what it returns, through JSON."""
        return self.evaluate(f"(arg) => {{ {body} }}", arg)

    size: tuple[int, int] | None = None  # the viewport's, as last set

    def resize(self, width: int, height: int) -> None:
        """Make the viewport `width` × `height` CSS pixels (nothing to do if it is: a resize of a long page
        costs WebKit a second or two)."""
        if self.size != (width, height):
            self._resize(width, height)
            self.size = (width, height)

    def _resize(self, width: int, height: int) -> None:
        raise NotImplementedError

    def screenshot(self) -> Image.Image:
        """The viewport as an RGB image, one pixel per CSS pixel (WebKit's may show a frame drawn a moment
        before: see `screenshot_showing`)."""
        raise NotImplementedError

    def screenshot_showing(self, colour: tuple[int, int, int], timeout: float = 5.0):
        """(screenshot, where): the first screenshot that shows a pixel of `colour` (a mark the test has just
        drawn, proving the screenshot is of the page as it is now), and the top left pixel of that colour."""
        end = time.monotonic() + timeout
        while True:
            shot = self.screenshot()
            found = np.argwhere(np.all(np.abs(np.asarray(shot).astype(int) - colour) < 8, axis=2))
            if len(found):
                return shot, tuple(found.min(axis=0))
            assert time.monotonic() < end, f"{self.name}: no pixel of {colour} in a screenshot after {timeout} s"
            time.sleep(0.1)

    def click(self, selector: str) -> None:
        """Click the first element `selector` finds, with the mouse."""
        raise NotImplementedError

    def press(self, key: str) -> None:
        """Press a key ("Escape", "ArrowDown", "Enter", "Tab") in the element with the focus."""
        raise NotImplementedError

    def type(self, text: str) -> None:
        """Type `text` into the element with the focus."""
        raise NotImplementedError

    def errors(self) -> list[str]:
        """Page errors and console errors or warnings logged since the last call."""
        raise NotImplementedError

    def close(self) -> None:
        raise NotImplementedError

    def wait_for(self, body: str, arg=None, timeout: float = 10.0):
        """Run `body` until it returns something true, and that value: through a navigation too (a script
        run while one document gives way to the next may fail), an AssertionError after `timeout` s."""
        end = time.monotonic() + timeout
        while True:
            try:
                value, error = self.run(body, arg), None
            except Exception as failure:  # the document went away under the script
                value, error = None, failure
            if value or time.monotonic() > end:
                assert value, f"{self.name}: still false after {timeout} s: {body} ({error or 'no error'})"
                return value
            time.sleep(0.05)


class Chromium(Engine):
    """A page of a Playwright browser (tests/browser.py launches Debian's Chromium)."""

    name = "chromium"

    def __init__(self, browser):
        from browser import logged_page

        self.page, self._errors = logged_page(browser, viewport={"width": 1280, "height": 900})
        self.version = f"Chromium {browser.version}"

    def load(self, url):
        from browser import front, load

        load(front(self.page), url)

    def evaluate(self, function, arg=None):
        from browser import front

        return front(self.page).evaluate(function, arg)  # a tab behind others gets a frame a second

    def _resize(self, width, height):
        self.page.set_viewport_size({"width": width, "height": height})

    def screenshot(self):
        from browser import front

        return Image.open(io.BytesIO(front(self.page).screenshot())).convert("RGB")

    def click(self, selector):
        from browser import front

        front(self.page).click(selector)

    def press(self, key):
        self.page.keyboard.press(key)

    def type(self, text):
        self.page.keyboard.type(text)

    def errors(self):
        found = list(self._errors)
        self._errors.clear()
        return found

    def close(self):
        self.page.close()


class Firefox(Engine):
    """Firefox ESR through puppeteer-core (tests/firefox.js, a node process spoken to in JSON lines)."""

    name = "firefox"

    def __init__(self):
        self.process = subprocess.Popen(
            ["node", str(Path(__file__).with_name("firefox.js")), FIREFOX],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        self.version = "Firefox " + self._call("version").split("/", 1)[-1]

    def _call(self, op: str, **arguments):
        self.process.stdin.write(json.dumps({"op": op, **arguments}) + "\n")
        self.process.stdin.flush()
        line = self.process.stdout.readline()
        assert line, f"Firefox's driver ended (exit status {self.process.poll()})"
        answer = json.loads(line)
        if "error" in answer:
            raise RuntimeError(f"Firefox: {op}: {answer['error']}")
        return answer["value"]

    def load(self, url):
        from browser import SETTLED

        self._call("load", url=url, settled=SETTLED)

    def evaluate(self, function, arg=None):
        return _parsed(self._call("run", script=_expression(function, arg)))

    def _resize(self, width, height):
        self._call("resize", width=width, height=height)

    def screenshot(self):
        return Image.open(io.BytesIO(base64.b64decode(self._call("screenshot")))).convert("RGB")

    def click(self, selector):
        self._call("click", selector=selector)

    def press(self, key):
        self._call("press", key=key)

    def type(self, text):
        self._call("type", text=text)

    def errors(self):
        return self._call("errors")

    def close(self):
        self.process.stdin.close()
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


# MiniBrowser's toolbar keeps its window at least 447 px wide; with its widgets shrunk the window (and the
# viewport) can be as narrow as a phone's.
GTK_CSS = (
    "toolbar *, entry, button { min-width: 0; min-height: 0; padding: 0; margin: 0; font-size: 1px; border-width: 0; }"
    "\n"
)


class WebKit(Engine):
    """MiniBrowser (WebKitGTK) through WebKitWebDriver and selenium, in a virtual X display of its own."""

    name = "webkit"

    def __init__(self, scratch: Path):
        from selenium import webdriver
        from selenium.webdriver.webkitgtk.options import Options
        from selenium.webdriver.webkitgtk.service import Service

        (scratch / "gtk-3.0").mkdir(parents=True, exist_ok=True)
        (scratch / "gtk-3.0" / "gtk.css").write_text(GTK_CSS)
        self.display = subprocess.Popen(
            ["Xvfb", "-displayfd", "1", "-nolisten", "tcp", "-screen", "0", "1920x1200x24"],
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
        )
        number = self.display.stdout.readline().strip()  # the free display Xvfb chose (as xvfb-run -a does)
        assert number.isdigit(), f"Xvfb did not start (exit status {self.display.poll()})"
        options = Options()
        options.binary_location = MINIBROWSER
        options.add_argument("--automation")
        environment = {**os.environ, "DISPLAY": f":{number}", "XDG_CONFIG_HOME": str(scratch)}
        service = Service(executable_path=WEBKIT_DRIVER, env=environment)
        try:
            self.driver = webdriver.WebKitGTK(options=options, service=service)
        except Exception:
            self._stop_display()
            raise
        self.version = f"WebKitGTK {self.driver.capabilities.get('browserVersion')}"
        self._kept: list[str] = []  # what earlier documents logged

    def load(self, url):
        self._kept += self._logged()
        self.driver.get("about:blank")
        self.driver.get(url)  # returns once the document has loaded
        from browser import SETTLED

        failed = self.driver.execute_async_script(
            f"const done = arguments[arguments.length - 1]; {SETTLED}.then(() => done(null), e => done(String(e)));"
        )
        assert failed is None, failed

    def evaluate(self, function, arg=None):
        answer = self.driver.execute_async_script(
            "const answer = arguments[arguments.length - 1];"
            f"{_expression(function, arg)}"
            ".then(text => answer([text]), error => answer(String(error && error.stack || error)));"
        )
        if not isinstance(answer, list):
            raise RuntimeError(f"WebKit: {answer}")
        return _parsed(answer[0])

    def _resize(self, width, height):
        """The window's size set so that the viewport has the size asked (the window adds its toolbar). The
        window takes its new size a moment after it is asked to: the viewport is watched until it has it."""
        window = [width, height]
        for _ in range(5):
            self.driver.set_window_size(*window)
            end = time.monotonic() + 2
            while time.monotonic() < end:
                inner = self.driver.execute_script("return [innerWidth, innerHeight]")
                if inner == [width, height]:
                    return
                time.sleep(0.05)
            window = [window[0] + width - inner[0], window[1] + height - inner[1]]
        raise AssertionError(f"WebKit's viewport is {inner}, not {[width, height]}")

    def screenshot(self):
        return Image.open(io.BytesIO(self.driver.get_screenshot_as_png())).convert("RGB")

    def _keys(self, keys: str) -> None:
        from selenium.webdriver.common.action_chains import ActionChains

        ActionChains(self.driver).send_keys(keys).perform()

    def click(self, selector):
        from selenium.webdriver.common.by import By

        self.driver.find_element(By.CSS_SELECTOR, selector).click()

    def press(self, key):
        from selenium.webdriver.common.keys import Keys

        names = {"Escape": Keys.ESCAPE, "ArrowDown": Keys.ARROW_DOWN, "ArrowUp": Keys.ARROW_UP, "Enter": Keys.ENTER}
        self._keys(names.get(key, key))

    def type(self, text):
        self._keys(text)

    def _logged(self) -> list[str]:
        return self.driver.execute_script("const log = window.__testErrors; return log ? log.splice(0) : [];")

    def errors(self):
        found = self._kept + self._logged()
        self._kept = []
        return found

    def _stop_display(self):
        self.display.terminate()
        self.display.wait(timeout=10)

    def close(self):
        try:
            self.driver.quit()
        finally:
            self._stop_display()


def instrumented(site: Path, into: Path) -> Path:
    """A copy of the built `site` in `into` whose every page runs ERROR_LOG_SCRIPT first (for WebKit): after
    its character set, before anything else."""
    shutil.copytree(site, into)
    for page in into.rglob("*.html"):
        text = page.read_text()
        start = text.index("<meta charset=")
        start = text.index(">", start) + 1
        page.write_text(text[:start] + ERROR_LOG_SCRIPT + text[start:])
    return into
