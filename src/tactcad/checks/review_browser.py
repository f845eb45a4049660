"""Open the review page in a real, headless Chromium (Playwright driving the
system's browser: no browser download) and measure it.

The browser runs offline (every request refused) with software WebGL
(SwiftShader), as on a machine without a GPU.
"""

from __future__ import annotations

import os
import shutil
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator

from tactcad.errors import TactcadError

CHROMIUM_ARGS = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"]
CANDIDATES = ("chromium", "chromium-browser", "google-chrome")


class BrowserMissing(TactcadError):
    """No Chromium, or no Playwright, to open the page with."""


def chromium_path() -> str:
    """The system Chromium: ``$TACTCAD_CHROMIUM``, else the first of
    ``chromium``, ``chromium-browser``, ``google-chrome`` on the PATH.

    Raises:
        BrowserMissing: none found (``make test`` installs Debian's ``chromium``).
    """
    exe = os.environ.get("TACTCAD_CHROMIUM") or next(
        (p for p in map(shutil.which, CANDIDATES) if p), None)
    if not exe:
        raise BrowserMissing("no Chromium found (install Debian's chromium: "
                             "sh scripts/install-system-deps.sh as root, or set TACTCAD_CHROMIUM)")
    return exe


@contextmanager
def browser_page(offline: bool = True, width: int = 1400, height: int = 900) -> Iterator:
    """A Playwright page in headless Chromium; page errors collected in ``page.errors``.

    Raises:
        BrowserMissing: no Chromium or no Playwright.
    """
    try:
        from playwright.sync_api import sync_playwright
    except ImportError as exc:
        raise BrowserMissing("the playwright package is missing (make env installs it)") from exc
    exe = chromium_path()
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=exe, args=CHROMIUM_ARGS)
        try:
            ctx = browser.new_context(offline=offline, viewport={"width": width, "height": height})
            page = ctx.new_page()
            page.errors = []
            page.on("pageerror", lambda e: page.errors.append(str(e)))
            yield page
        finally:
            browser.close()


def wait_first_frame(page, timeout_s: float = 30.0) -> None:
    """Wait until the page has drawn its first scene."""
    page.wait_for_function("window.__review && window.__review.firstFrameMs !== null",
                           timeout=timeout_s * 1000)


def canvas_is_blank(page) -> bool:
    """True when every pixel of the 3D canvas has one colour (nothing drawn)."""
    return page.evaluate("""() => {
        const c = document.querySelector('#view canvas');
        const gl = c.getContext('webgl2') || c.getContext('webgl');
        const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
        const px = new Uint8Array(w * h * 4);
        gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
        for (let i = 4; i < px.length; i += 4) {
            if (px[i] !== px[0] || px[i + 1] !== px[1] || px[i + 2] !== px[2]) return false;
        }
        return true;
    }""")


@dataclass(frozen=True)
class PageLoad:
    bytes: int
    first_frame_s: float  # navigation start -> first frame of the first scene, page clock
    wall_s: float  # goto() -> first frame, measured outside the browser
    instances: int


def measure_page(path: Path, screenshot: Path | None = None) -> PageLoad:
    """Open ``path`` from ``file://`` offline and time its first frame.

    Raises:
        BrowserMissing: no Chromium or no Playwright.
        TactcadError: the page raised an error or drew nothing.
    """
    path = Path(path).resolve()
    with browser_page() as page:
        t0 = time.perf_counter()
        page.goto(path.as_uri())
        wait_first_frame(page)
        wall = time.perf_counter() - t0
        if page.errors:
            raise TactcadError(f"{path}: the page raised: {page.errors[0]}")
        if canvas_is_blank(page):
            raise TactcadError(f"{path}: the 3D view drew nothing")
        ff = page.evaluate("window.__review.firstFrameMs") / 1000
        n = page.evaluate("window.__review.instances.length")
        if screenshot is not None:
            page.screenshot(path=str(screenshot))
    return PageLoad(path.stat().st_size, ff, wall, n)
