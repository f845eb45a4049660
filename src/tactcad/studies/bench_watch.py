"""``tactcad bench watch``: how soon a saved edit shows under ``tactcad watch``.

A ``tactcad watch`` process runs on a copy of the design; the review page is
open in headless Chromium. Each round changes one arm length in the design
file and times, from the save:

* ``first_update_s``: until the page's 3D view shows the new design;
* ``full_update_s``: until every file of the export is current (the watch's
  state says so).

Beside them, from the watch process's own log, the seconds it spent per round
on the 3D view (``watch_3d_s``) and on the whole update (``watch_export_s``,
from the change seen to the export current), so the browser's share shows.

Medians over the rounds; goals on two cores: first <= 2 s, full <= 4 s.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

FIRST_GOAL_S = 2.0
FULL_GOAL_S = 4.0
ARM_LINE_PREFIX = "lengths_mm = ["


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _state(port: int) -> dict:
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/state", timeout=5) as r:
        return json.loads(r.read())


def _wait(pred, timeout_s: float, what: str, step_s: float = 0.02):
    end = time.perf_counter() + timeout_s
    while time.perf_counter() < end:
        try:
            got = pred()
        except OSError:
            got = None
        if got:
            return got
        time.sleep(step_s)
    raise TimeoutError(f"bench watch: {what} not seen within {timeout_s:g} s")


def edit_first_arm(design: Path, length_mm: float) -> None:
    """Set the first element's arm length in the design file (text edit, so the
    file's comments stay), saved by rename as editors do."""
    lines = design.read_text(encoding="utf-8").splitlines(keepends=True)
    for k, line in enumerate(lines):
        if line.startswith(ARM_LINE_PREFIX):
            rest = line[len(ARM_LINE_PREFIX):].split(",", 1)[1]
            lines[k] = f"{ARM_LINE_PREFIX}{length_mm:g},{rest}"
            break
    else:
        raise ValueError(f"{design}: no '{ARM_LINE_PREFIX}...' line to edit")
    tmp = design.with_suffix(".tmp")
    tmp.write_text("".join(lines), encoding="utf-8")
    os.replace(tmp, design)


def watch_figures(files: list[Path], rounds: int = 5, log=print) -> dict:
    """Run the benchmark (see module doc) on a copy of ``files``: the design
    file first, then the rigs and scenes files it uses.

    Raises:
        BrowserMissing: no Chromium or Playwright.
        TimeoutError: the watch process did not answer in time.
    """
    from tactcad.checks.review_browser import browser_page
    with tempfile.TemporaryDirectory(prefix="tactcad-bench-watch-") as tmp:
        folder = Path(tmp)
        design = files[0]
        copy = folder / design.name
        for f in files:
            target = folder / (design.name if f == files[0] else f.name)
            shutil.copyfile(f, target)
        port = _free_port()
        proc = subprocess.Popen([sys.executable, "-m", "tactcad.cli", "watch", "--design", str(copy),
                                 "--out", str(folder / "out"), "--port", str(port),
                                 "--cache", str(folder / "store")],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        try:
            t0 = time.perf_counter()
            _wait(lambda: _state(port).get("status") == "current", 600, "the first export", 0.2)
            log(f"first export current after {time.perf_counter() - t0:.1f} s")
            first, full = [], []
            with browser_page(offline=False) as page:
                page.goto(f"http://127.0.0.1:{port}/")
                page.wait_for_function("window.__review && window.__review.shownSha256", timeout=60000)
                for k in range(rounds + 1):  # the first round warms the process up
                    before = _state(port)
                    shown = page.evaluate("window.__review.shownSha256")
                    t_save = time.perf_counter()
                    edit_first_arm(copy, 4.0 + 0.03 * (k + 1))  # a new length each round: no store hit
                    page.wait_for_function(f"window.__review.shownSha256 !== {json.dumps(shown)}",
                                           timeout=120000, polling=10)
                    t_first = time.perf_counter() - t_save
                    _wait(lambda: (lambda s: s["status"] == "current" and s["seq"] > before["seq"] + 1)(
                        _state(port)), 120, "the full update")
                    t_full = time.perf_counter() - t_save
                    log(f"round {k}: first update {t_first:.2f} s, full update {t_full:.2f} s"
                        + (" (warm-up, not counted)" if k == 0 else ""))
                    if k:
                        first.append(t_first)
                        full.append(t_full)
        finally:
            proc.send_signal(signal.SIGINT)
            try:
                _, err = proc.communicate(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                _, err = proc.communicate()
    own = watch_log_seconds(err)
    return {"first_update_s": round(statistics.median(first), 3),
            "full_update_s": round(statistics.median(full), 3),
            "first_update_rounds_s": [round(t, 3) for t in first],
            "full_update_rounds_s": [round(t, 3) for t in full],
            "first_goal_s": FIRST_GOAL_S, "full_goal_s": FULL_GOAL_S,
            "watch_3d_s": own["3d"][-rounds:], "watch_export_s": own["export"][-rounds:],
            "watch_exit_code": proc.returncode, "cpus": os.cpu_count()}


def watch_log_seconds(log: str) -> dict[str, list[float]]:
    """The seconds ``tactcad watch`` logged per update: ``3d`` (3D view
    updated in ...) and ``export`` (export current in ...), first export included."""
    import re

    return {"3d": [float(x) for x in re.findall(r"3D view updated in ([\d.]+) s", log)],
            "export": [float(x) for x in re.findall(r"export current in ([\d.]+) s", log)]}
