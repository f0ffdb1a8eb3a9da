"""``make report-check``: open the HTML report in headless Chromium and check its first screen.

The report (``snakemake --report``) is a page whose JavaScript renders the workflow's
description next to the rule graph, in a full-height pane that centres its content: a
description taller than the window pushes its own title above the top, where it cannot be
scrolled to. This check opens the report at a desktop size in headless Chromium, lets the
report's JavaScript run, saves a screenshot of the first screen, and passes only when the
title is inside that screen and not covered by anything.

It drives Debian's ``chromium`` through ``chromedriver`` with the W3C WebDriver protocol over
HTTP (``urllib``), so it needs no Python package beyond the standard library.

Run as ``python -m rodimpact.tools.report_check results/report.html --screenshot
results/report_screenshot.png``; the exit status is 0 when the title is visible, 1 when it is
not, 2 when the browser could not be driven.
"""

from __future__ import annotations

import argparse
import base64
import json
import logging
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["CHROMEDRIVER", "CHROMIUM", "ChromeError", "TitleBox", "check_report", "main", "title_box"]

log = logging.getLogger(__name__)

#: Debian's browser and its driver (``apt-get install chromium chromium-driver``).
CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = Path("/usr/bin/chromedriver")

#: The window the report is checked in, px (width, height); its viewport is what the browser's own
#: frame leaves of it (1400 x 757 in Chromium's headless mode).
WINDOW = (1400, 900)

#: Chromium's switches: headless, no network of its own, no first-run chores.
CHROME_ARGS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
)

#: The report's title: the heading docutils makes of the description's title, inside the
#: description (snakemake's own navigation bar has an ``h1`` too, outside it).
TITLE_SELECTOR = ".prose h1.title, .prose h1"

#: Read in the page once the report has rendered: the title's box and the window's size, and
#: whether the title is the element at its own centre (nothing covers it).
_MEASURE = """
const title = document.querySelector(arguments[0]);
const loading = document.getElementById("loading-screen");
const busy = loading !== null && getComputedStyle(loading).display !== "none";
if (title === null || busy) { return null; }
const box = title.getBoundingClientRect();
const x = box.left + box.width / 2, y = box.top + box.height / 2;
const hit = document.elementFromPoint(x, y);
return {text: title.textContent.trim(), top: box.top, bottom: box.bottom, left: box.left, right: box.right,
        width: window.innerWidth, height: window.innerHeight,
        uncovered: hit !== null && (hit === title || title.contains(hit))};
"""


class ChromeError(RuntimeError):
    """Chromium or chromedriver is missing, or did not answer as the protocol says."""


@dataclass(frozen=True)
class TitleBox:
    """Where the report's title is on the first screen, px from the window's top left corner.

    Attributes
    ----------
    text : str
        The title.
    top, bottom, left, right : float
        Its bounding box (``getBoundingClientRect``), px.
    width, height : float
        The window's inner size, px.
    uncovered : bool
        The title is the element found at its own centre (no other element lies over it).
    """

    text: str
    top: float
    bottom: float
    left: float
    right: float
    width: float
    height: float
    uncovered: bool

    @property
    def visible(self) -> bool:
        """The whole box lies inside the window, is not empty, and nothing covers it."""
        return (
            self.uncovered
            and 0.0 <= self.top < self.bottom <= self.height
            and 0.0 <= self.left < self.right <= self.width
        )


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class _Driver:
    """A chromedriver process and one browser session, spoken to over HTTP (W3C WebDriver)."""

    def __init__(self, chromium: Path, chromedriver: Path, profile: Path, timeout_s: float) -> None:
        for binary in (chromium, chromedriver):
            if not binary.is_file():
                raise ChromeError(f"{binary} is missing: apt-get install -y chromium chromium-driver")
        self.port = _free_port()
        self.timeout_s = timeout_s
        self.process = subprocess.Popen(
            [str(chromedriver), f"--port={self.port}"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
        self.session = ""
        try:
            self._wait_ready()
            width, height = WINDOW
            options = {
                "binary": str(chromium),
                "args": [*CHROME_ARGS, f"--window-size={width},{height}", f"--user-data-dir={profile}"],
            }
            answer = self.call(
                "POST",
                "/session",
                {"capabilities": {"alwaysMatch": {"browserName": "chrome", "goog:chromeOptions": options}}},
            )
            self.session = answer["sessionId"]
        except BaseException:
            self.close()
            raise

    def _wait_ready(self) -> None:
        deadline = time.monotonic() + self.timeout_s
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise ChromeError(f"chromedriver exited with status {self.process.returncode}")
            try:
                if self.call("GET", "/status").get("ready"):
                    return
            except (ChromeError, OSError):
                pass
            time.sleep(0.1)
        raise ChromeError(f"chromedriver did not get ready within {self.timeout_s:g} s")

    def call(self, method: str, path: str, body: dict[str, Any] | None = None) -> Any:
        """One WebDriver command; its ``value``."""
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(
            f"http://127.0.0.1:{self.port}{path}",
            data=data,
            method=method,
            headers={"Content-Type": "application/json"},
        )
        try:
            with urllib.request.urlopen(request, timeout=self.timeout_s) as response:
                answer = json.loads(response.read())
        except urllib.error.HTTPError as error:
            detail = error.read().decode(errors="replace")[:500]
            raise ChromeError(f"{method} {path}: HTTP {error.code}: {detail}") from error
        except urllib.error.URLError as error:
            raise ChromeError(f"{method} {path}: {error.reason}") from error
        return answer.get("value")

    def command(self, method: str, path: str, body: dict[str, Any] | None = None) -> Any:
        """A command of this session."""
        return self.call(method, f"/session/{self.session}{path}", body)

    def close(self) -> None:
        if self.session:
            try:
                self.call("DELETE", f"/session/{self.session}")
            except ChromeError as error:
                log.warning("closing the browser session: %s", error)
            self.session = ""
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()


def title_box(driver: _Driver, timeout_s: float) -> TitleBox:
    """The title's box, once the report's JavaScript has drawn the first screen."""
    deadline = time.monotonic() + timeout_s
    while True:
        box = driver.command("POST", "/execute/sync", {"script": _MEASURE, "args": [TITLE_SELECTOR]})
        if box is not None:
            time.sleep(0.5)  # the rule graph (vega) lays out after the first frame: measure once more
            box = driver.command("POST", "/execute/sync", {"script": _MEASURE, "args": [TITLE_SELECTOR]})
            return TitleBox(**box)
        if time.monotonic() > deadline:
            raise ChromeError(f"the report drew no title ({TITLE_SELECTOR}) within {timeout_s:g} s")
        time.sleep(0.2)


def check_report(
    report: str | Path,
    screenshot: str | Path,
    *,
    chromium: Path = CHROMIUM,
    chromedriver: Path = CHROMEDRIVER,
    timeout_s: float = 60.0,
) -> TitleBox:
    """Open ``report`` in headless Chromium at :data:`WINDOW`, save the first screen as the PNG
    ``screenshot``, and return where the title is.

    Raises
    ------
    FileNotFoundError
        ``report`` does not exist.
    ChromeError
        The browser is missing or could not be driven, or the page drew no title in time.
    """
    report = Path(report).resolve()
    if not report.is_file():
        raise FileNotFoundError(f"{report}: no report (make report builds it)")
    with tempfile.TemporaryDirectory(prefix="report-check-") as profile:
        driver = _Driver(chromium, chromedriver, Path(profile), timeout_s)
        try:
            driver.command("POST", "/url", {"url": report.as_uri()})
            box = title_box(driver, timeout_s)
            png = base64.b64decode(driver.command("GET", "/screenshot"))
        finally:
            driver.close()
    screenshot = Path(screenshot)
    screenshot.parent.mkdir(parents=True, exist_ok=True)
    screenshot.write_bytes(png)
    log.info(
        "%s: title %r at top %.0f px, bottom %.0f px, left %.0f px, right %.0f px in the %.0f x %.0f px "
        "viewport of a %d x %d window%s; screenshot %s",
        report,
        box.text,
        box.top,
        box.bottom,
        box.left,
        box.right,
        box.width,
        box.height,
        *WINDOW,
        "" if box.uncovered else " (covered)",
        screenshot,
    )
    return box


def main(argv: Sequence[str] | None = None) -> int:
    """The command line: 0 when the title is visible on the first screen, 1 when not, 2 on a
    browser error."""
    parser = argparse.ArgumentParser(
        prog="python -m rodimpact.tools.report_check", description=__doc__.split("\n\n")[0]
    )
    parser.add_argument("report", nargs="?", default="results/report.html")
    parser.add_argument("--screenshot", default="results/report_screenshot.png")
    parser.add_argument("--timeout", type=float, default=60.0, help="s to wait for the browser and the page")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    try:
        box = check_report(args.report, args.screenshot, timeout_s=args.timeout)
    except (ChromeError, FileNotFoundError) as error:
        log.error("%s", error)
        return 2
    if not box.visible:
        log.error(
            "the report's title %r is not inside the first %.0f x %.0f screen (top %.0f px, bottom %.0f px%s): "
            "shorten workflow/report/workflow.rst",
            box.text,
            box.width,
            box.height,
            box.top,
            box.bottom,
            "" if box.uncovered else ", covered by another element",
        )
        return 1
    log.info("the report's title is visible on the first screen")
    return 0


if __name__ == "__main__":
    sys.exit(main())
