"""A build's progress lines as `sitegen build` shows them: on a terminal with a live bar, in a log line by line."""

from __future__ import annotations


class BuildProgress:
    """Build progress: one line per phase and per scene, and while a long scene computes, how far it got.
    On a terminal a live bar of scenes follows the last line, and a scene's updates replace each other
    in place; in a log every update is a line of its own."""

    def __init__(self, stream, explain: bool):
        self.stream, self.explain, self.tty = stream, explain, stream.isatty()
        self.bar_shown = False

    def __call__(self, line: str) -> None:
        if not self.explain:
            line = line.split(": ", 1)[0] if line.startswith("[") else line  # "computed: new" -> "computed"
        if self.bar_shown:
            self.stream.write("\r\x1b[2K")
        if self.tty and line.endswith(" stops/s"):  # an update inside a scene: shown until the next line
            self.stream.write(line)
            self.bar_shown = True
            self.stream.flush()
            return
        self.stream.write(line + "\n")
        done, total = _scene_counter(line)
        if self.tty and total and done < total:
            filled = 30 * done // total
            self.stream.write(f"[{'#' * filled}{'.' * (30 - filled)}] {done}/{total} scenes")
        self.bar_shown = bool(self.tty and total and done < total)
        self.stream.flush()


def _scene_counter(line: str) -> tuple[int, int]:
    """(3, 7) from a scene line "[3/7] ..."; (0, 0) for any other line."""
    if not line.startswith("["):
        return 0, 0
    done, _, total = line[1 : line.index("]")].partition("/")
    return int(done), int(total)
