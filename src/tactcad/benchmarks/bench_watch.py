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

Then the load test: simulated reviewers' browsers (threads, 127.0.0.1 only)
ask the page's routes for a bounded time while one-arm edits are saved one
after the other; every request's latency and error is recorded
(:mod:`tactcad.benchmarks.watch_load`). Goal on two cores: 40 clients for 30 s,
no error, p99 <= 250 ms.
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
import threading
import time
import urllib.request
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

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


def arm_length_of_edit(k: int) -> float:
    """The first arm's length (mm) saved by edit ``k`` (0, 1, ...): 4.03, 4.06, ...,
    a new one each edit up to 133 edits (no store hit), within the example's 4 ... 8 mm."""
    return round(4.0 + (0.03 * (k + 1)) % 4.0, 3)


@dataclass
class WatchSession:
    """A ``tactcad watch`` process on a copy of a design, its stderr read as it
    comes (a full pipe would stop the watch)."""

    proc: subprocess.Popen
    port: int
    design: Path  # the copy the edits are saved to
    lines: list[str] = field(default_factory=list)
    edits: int = 0  # edits saved so far (each a new arm length)

    def edit(self) -> None:
        """Save the next one-arm edit."""
        edit_first_arm(self.design, arm_length_of_edit(self.edits))
        self.edits += 1

    def stderr(self) -> str:
        return "".join(self.lines)


@contextmanager
def watch_session(files: list[Path], log=print, store_from: Path | None = None
                  ) -> Iterator[WatchSession]:
    """A watch (:class:`WatchSession`) on a copy of ``files`` (the design file
    first, then the rigs and scenes files it uses) in a temporary folder, once
    its first export is current; stopped with SIGINT (killed after 30 s) on leaving.
    Its store of finished jobs starts empty (a cold first export), or as a
    copy of the store folder ``store_from``.

    Raises:
        TimeoutError: the first export was not current within 600 s.
    """
    with tempfile.TemporaryDirectory(prefix="tactcad-bench-watch-") as tmp:
        folder = Path(tmp)
        copy = folder / files[0].name
        for f in files:
            shutil.copyfile(f, folder / (files[0].name if f == files[0] else f.name))
        if store_from is not None:
            shutil.copytree(store_from, folder / "store")
        port = _free_port()
        proc = subprocess.Popen([sys.executable, "-m", "tactcad.cli", "watch", "--design", str(copy),
                                 "--out", str(folder / "out"), "--port", str(port),
                                 "--cache", str(folder / "store")],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        session = WatchSession(proc, port, copy)
        reader = threading.Thread(target=lambda: session.lines.extend(proc.stderr), daemon=True)
        reader.start()
        try:
            t0 = time.perf_counter()
            _wait(lambda: _state(port).get("status") == "current", 600, "the first export", 0.2)
            log(f"first export current after {time.perf_counter() - t0:.1f} s")
            yield session
        finally:
            proc.send_signal(signal.SIGINT)
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            reader.join(timeout=10)


def _current_after(port: int, seq: int) -> bool:
    """True when the watch's state is past ``seq`` by the 3D view and the export
    (two states) and current."""
    state = _state(port)
    return state["status"] == "current" and state["seq"] > seq + 1


def browser_rounds(session: WatchSession, rounds: int, log=print) -> dict:
    """Time ``rounds`` one-arm edits, after a warm-up one, in headless Chromium
    (see the module doc): the medians and each round's seconds.

    Raises:
        BrowserMissing: no Chromium or Playwright.
        TimeoutError: the page or the watch did not show an edit in time.
    """
    from tactcad.checks.review_browser import browser_page

    port, first, full = session.port, [], []
    with browser_page(offline=False) as page:
        page.goto(f"http://127.0.0.1:{port}/")
        page.wait_for_function("window.__review && window.__review.shownSha256", timeout=60000)
        for k in range(rounds + 1):  # the first round warms the process up
            before = _state(port)
            shown = page.evaluate("window.__review.shownSha256")
            t_save = time.perf_counter()
            session.edit()  # a new length each round: no store hit
            page.wait_for_function(f"window.__review.shownSha256 !== {json.dumps(shown)}",
                                   timeout=120000, polling=10)
            t_first = time.perf_counter() - t_save
            _wait(lambda seq=before["seq"]: _current_after(port, seq), 120, "the full update")
            t_full = time.perf_counter() - t_save
            log(f"round {k}: first update {t_first:.2f} s, full update {t_full:.2f} s"
                + (" (warm-up, not counted)" if k == 0 else ""))
            if k:
                first.append(t_first)
                full.append(t_full)
    return {"first_update_s": round(statistics.median(first), 3),
            "full_update_s": round(statistics.median(full), 3),
            "first_update_rounds_s": [round(t, 3) for t in first],
            "full_update_rounds_s": [round(t, 3) for t in full],
            "first_goal_s": FIRST_GOAL_S, "full_goal_s": FULL_GOAL_S}


def edits_until(session: WatchSession, deadline: float, log=print) -> int:
    """Save one-arm edits one after the other, each once the one before is current,
    until ``deadline`` (``time.perf_counter()``); how many were saved."""
    saved = 0
    while time.perf_counter() < deadline:
        before = _state(session.port)
        session.edit()
        saved += 1
        try:
            _wait(lambda seq=before["seq"]: _current_after(session.port, seq),
                  deadline - time.perf_counter(), "the edit", 0.1)
        except TimeoutError:  # the load ends while the watch exports: no new edit
            log(f"edit {saved}: still exporting at the end of the load")
            break
        log(f"edit {saved}: current")
    return saved


def load_test(session: WatchSession, clients: int, seconds: float, log=print) -> dict:
    """``clients`` simulated reviewers for ``seconds`` while one-arm edits are saved
    one after the other (:mod:`tactcad.benchmarks.watch_load`): the figures."""
    from tactcad.benchmarks.watch_load import run_load

    log(f"load: {clients} clients for {seconds:g} s, one-arm edits saved meanwhile")
    return run_load(session.port, clients, seconds, lambda deadline: edits_until(session,
                                                                                  deadline, log))


def watch_figures(files: list[Path], rounds: int = 5, log=print, clients: int = 0,
                  load_seconds: float = 30.0, store_from: Path | None = None) -> dict:
    """Run the benchmark (see module doc) on a copy of ``files``: the design
    file first, then the rigs and scenes files it uses; ``rounds`` browser
    rounds (0: none), then, with ``clients`` > 0, the load test
    (:func:`load_test`) for ``load_seconds``, its figures under ``load``.
    The watch's store starts empty, or as a copy of ``store_from``
    (:func:`watch_session`); the figures are of the edits after the first export.

    Raises:
        BrowserMissing: no Chromium or Playwright (with ``rounds`` > 0).
        TimeoutError: the watch process did not answer in time.
    """
    figures: dict = {}
    with watch_session(files, log, store_from) as session:
        if rounds:
            figures.update(browser_rounds(session, rounds, log))
            _wait(lambda: len(watch_log_seconds(session.stderr())["export"]) >= rounds + 2, 10,
                  "the watch's log line of the last round")  # the first export, warm-up, rounds
        before_load = {k: len(v) for k, v in watch_log_seconds(session.stderr()).items()}
        if clients:
            figures["load"] = load_test(session, clients, load_seconds, log)
    own = watch_log_seconds(session.stderr())
    if rounds:
        figures.update({"watch_3d_s": own["3d"][:before_load["3d"]][-rounds:],
                        "watch_export_s": own["export"][:before_load["export"]][-rounds:]})
    if clients:  # the watch's own update seconds under the load: what the load costs it
        figures["load"]["watch_export_s"] = own["export"][before_load["export"]:]
    return {**figures, "watch_exit_code": session.proc.returncode, "cpus": os.cpu_count()}


def watch_log_seconds(log: str) -> dict[str, list[float]]:
    """The seconds ``tactcad watch`` logged per update: ``3d`` (3D view
    updated in ...) and ``export`` (export current in ...), first export included."""
    import re

    return {"3d": [float(x) for x in re.findall(r"3D view updated in ([\d.]+) s", log)],
            "export": [float(x) for x in re.findall(r"export current in ([\d.]+) s", log)]}
