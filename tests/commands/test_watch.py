"""``tactcad watch``: the server and the refusal path (fast), and a real session
in Chromium (slow): an edit shows in the page with the camera and hidden parts
kept, a bad edit shows its refusal, Ctrl-C ends it cleanly."""

from __future__ import annotations

import json
import shutil
import signal
import subprocess
import sys
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from conftest import ctrl_c_at_its_default, warm_store_copy
from tactcad.errors import DesignError
from tactcad.commands.watch import watched_files
from tactcad.export.live import LiveState, Loop, make_server
from tactcad.store import Store


def _get(url: str) -> tuple[int, bytes]:
    try:
        with urllib.request.urlopen(url, timeout=5) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as exc:
        return exc.code, b""


def test_server_serves_the_page_and_its_state():
    import threading

    state = LiveState()
    state.publish("ab" * 32, "current", None, b"<html>page</html>")
    server = make_server(state, 0)
    threading.Thread(target=server.serve_forever, args=(0.05,), daemon=True).start()
    try:
        base = f"http://127.0.0.1:{server.server_address[1]}"
        assert _get(base + "/") == (200, b"<html>page</html>")
        code, body = _get(base + "/state")
        assert code == 200 and json.loads(body)["seq"] == 1
        assert _get(base + "/../etc/passwd")[0] == 404
        head = urllib.request.Request(base + "/", method="HEAD")
        with urllib.request.urlopen(head, timeout=5) as r:  # GET's headers, no body
            assert r.status == 200 and r.headers["Content-Length"] == "17" and r.read() == b""
    finally:
        server.shutdown()
        server.server_close()


def test_a_client_leaving_mid_download_prints_no_traceback(capfd):
    """A reload while the 6 MB page downloads resets the connection: no traceback
    in the terminal; the server goes on answering."""
    import socket
    import struct
    import threading

    state = LiveState()
    state.publish("ab" * 32, "current", None, b"x" * 8_000_000)
    server = make_server(state, 0)
    threading.Thread(target=server.serve_forever, args=(0.05,), daemon=True).start()
    try:
        port = server.server_address[1]
        for _ in range(3):
            s = socket.create_connection(("127.0.0.1", port))
            s.sendall(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n")
            s.recv(100)
            s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
            s.close()  # a reset, the page half read
        assert _get(f"http://127.0.0.1:{port}/state")[0] == 200
    finally:
        server.shutdown()
        server.server_close()
    err = capfd.readouterr().err
    assert "Traceback" not in err and "ConnectionResetError" not in err


def test_a_refused_edit_keeps_the_last_page(tmp_path):
    state = LiveState()
    state.publish("cd" * 32, "current", None, b"good")

    def load():
        raise DesignError("arms.lengths_mm[1]", -3.0, "2 <= value <= 20 mm")

    lines = []
    assert Loop(load, tmp_path, Store(None), state, lines.append).update() is False
    doc = json.loads(state.as_json())
    assert doc["seq"] == 1 and state.page == b"good"
    assert "arms.lengths_mm[1] = -3.0" in doc["refusal"] and "2 <= value" in doc["refusal"]
    assert "arms.lengths_mm[1]" in lines[0]


def test_a_failed_export_is_shown_as_a_refusal_and_the_session_stays(tmp_path, project):
    """An export that fails (here its folder stopped being an export folder; a full
    disk alike) is shown like a refused edit, not the end of the session."""
    state = LiveState()
    state.publish("cd" * 32, "current", None, b"good")
    (tmp_path / "notes.txt").write_text("not an export")
    lines = []
    loop = Loop(lambda: project, tmp_path, Store(None), state, lines.append)
    assert loop.update() is False
    doc = json.loads(state.as_json())
    assert doc["seq"] == 1 and state.page == b"good"
    assert doc["refusal"].startswith("the export failed: --out") and "manifest.json" in doc["refusal"]
    assert lines[-1].startswith("refused (the last good export stays):")
    # the export failing after the 3D preview of the edit: the page goes back to the last good
    state.publish("ef" * 32, "3D updated; drawings follow", None)
    assert loop.update() is False
    doc = json.loads(state.as_json())
    assert doc["sha256"] == "cd" * 32 and doc["seq"] == 3 and doc["refusal"]
    assert json.loads(state.response("/data")[0]) == {"seq": 3, "sha256": "cd" * 32,
                                                      "checks": None, "data": None}


def test_bad_port_is_refused_naming_the_option(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "tactcad.cli", "watch", "--port", "80", "--out",
                           str(tmp_path / "o")], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "--port" in proc.stderr and "Traceback" not in proc.stderr


@pytest.mark.slow
def test_watch_session_in_chromium(tmp_path, default_store):
    from tactcad.checks.review_browser import BrowserMissing, browser_page, chromium_path
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.benchmarks.bench_watch import _free_port, _state, _wait, edit_first_arm

    try:
        chromium_path()
    except BrowserMissing as exc:
        pytest.skip(str(exc))
    files = watched_files(DEFAULT_DESIGN)
    for f in files:
        shutil.copyfile(f, tmp_path / f.name)
    design = tmp_path / DEFAULT_DESIGN.name
    port = _free_port()
    proc = subprocess.Popen([sys.executable, "-m", "tactcad.cli", "watch", "--design", str(design),
                             "--out", str(tmp_path / "out"), "--port", str(port), "--cache",
                             str(warm_store_copy(default_store, tmp_path / "store"))],
                            stderr=subprocess.PIPE, text=True, preexec_fn=ctrl_c_at_its_default)
    try:
        _wait(lambda: _state(port)["status"] == "current", 600, "the first export", 0.2)
        with browser_page(offline=False) as page:
            page.goto(f"http://127.0.0.1:{port}/")
            page.wait_for_function("window.__review && window.__review.shownSha256")
            first = page.evaluate("window.__review.shownSha256")
            assert first == _state(port)["sha256"]
            # the reviewer turns the model and hides one element
            box = page.locator("#view canvas").bounding_box()
            page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
            page.mouse.down()
            page.mouse.move(box["x"] + box["width"] / 2 + 120, box["y"] + box["height"] / 2 + 40)
            page.mouse.up()
            page.locator('#tree label[data-instance="element_3"] input').uncheck()
            view = page.evaluate("window.__review.view()")
            asked = []  # what the page downloads from here on
            page.on("request", lambda r: asked.append(r.url.split("?")[0]))
            base = f"http://127.0.0.1:{port}"
            sheets_before = _sheet_digests(base)
            edit_first_arm(design, 4.6)
            page.wait_for_function(f"window.__review.shownSha256 !== {json.dumps(first)}",
                                   timeout=120000)
            assert page.evaluate("window.__review.view()") == view
            assert not page.locator('#tree label[data-instance="element_3"] input').is_checked()
            assert page.locator('#tree label[data-instance="element_4"] input').is_checked()
            # the update read the page's data and the changed scene, not the page again
            page.wait_for_function("window.__review.updates >= 2", timeout=120000)
            assert base + "/data" in asked
            # only the sheets whose bytes changed were fetched, each once
            changed = {d for p, d in _sheet_digests(base).items() if sheets_before.get(p) != d}
            page.wait_for_function("[...document.querySelectorAll('.sheet img')]"
                                   ".every(i => i.complete && i.naturalWidth > 0)")
            assert changed and sorted(u for u in asked if "/sheet/" in u) == \
                sorted(f"{base}/sheet/{d}" for d in changed)
            # the 3D-first update fetched the shown scene; the full one had the same bytes
            assert sum(u.startswith(base + "/scene/") for u in asked) == 1
            assert base + "/" not in asked and base + "/index.html" not in asked
            assert page.errors == []
            # a bad edit: the refusal in the page, the model stays
            text = design.read_text().replace("lengths_mm = [4.6,", "lengths_mm = [-3,", 1)
            design.write_text(text)
            page.wait_for_selector("#refusal.shown", timeout=60000)
            refusal = page.locator("#refusal").inner_text()
            assert "arms.lengths_mm[1] = -3" in refusal and "allowed" in refusal
            assert page.evaluate("window.__review.shownSha256") != first  # the last good one
    finally:
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    assert proc.returncode == 0 and "Traceback" not in err and "stopped" in err
    assert "arms.lengths_mm[1] = -3" in err


def _sheet_digests(base: str) -> dict[str, str]:
    """{sheet path: sha256} of the page's data as the watch serves it now."""
    return {s["path"]: s["sha256"] for s in json.loads(_get(base + "/data")[1])["data"]["sheets"]}


class _Session:
    """A ``tactcad watch`` process on a copy of the default design, its
    stderr read line by line."""

    def __init__(self, tmp_path, store):
        import queue
        import threading

        from tactcad.design.array_plan import DEFAULT_DESIGN

        folder = tmp_path / "design"
        folder.mkdir(exist_ok=True)
        for f in watched_files(DEFAULT_DESIGN):
            shutil.copyfile(f, folder / f.name)
        self.design, self.out = folder / DEFAULT_DESIGN.name, tmp_path / "out"
        self.proc = subprocess.Popen([sys.executable, "-m", "tactcad.cli", "watch", "--design",
                                      str(self.design), "--out", str(self.out), "--port", "0",
                                      "--cache", str(store)], stderr=subprocess.PIPE, text=True,
                                     preexec_fn=ctrl_c_at_its_default)
        self.lines: list[str] = []
        self._queue: queue.Queue = queue.Queue()
        self._reader = threading.Thread(
            target=lambda: [self._queue.put(x) for x in self.proc.stderr], daemon=True)
        self._reader.start()

    def all_lines(self) -> str:
        """Every line, once the process has ended."""
        self._reader.join(timeout=30)
        while not self._queue.empty():
            self.lines.append(self._queue.get())
        return "".join(self.lines)

    def next_export(self, timeout_s: float = 600) -> str:
        """The next 'export current' line."""
        import queue

        while True:
            try:
                line = self._queue.get(timeout=timeout_s)
            except queue.Empty:
                raise AssertionError("no export in time:\n" + "".join(self.lines)) from None
            self.lines.append(line)
            if "export current" in line:
                return line

    def edit(self, arm_mm: float) -> str:
        from tactcad.benchmarks.bench_watch import edit_first_arm

        edit_first_arm(self.design, arm_mm)
        return self.next_export()

    def children(self) -> set[int]:
        from pathlib import Path

        return {int(p) for f in Path(f"/proc/{self.proc.pid}/task").glob("*/children")
                for p in f.read_text().split()}


def _worker(line: str) -> tuple[int, int]:
    """(jobs made by the worker, its pid) from an 'export current' line."""
    import re

    found = re.search(r"(\d+) made by the worker process, pid (\d+)", line)
    assert found, line
    return int(found[1]), int(found[2])


def _read(path: str) -> bytes:
    """The bytes of a /proc file (b"" once the process has gone)."""
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        return b""


def _gone(pids, timeout_s: float = 15.0) -> bool:
    import os
    import time

    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        alive = [p for p in pids if os.path.exists(f"/proc/{p}")
                 and b"(zombie)" not in _read(f"/proc/{p}/status")]
        if not alive:
            return True
        time.sleep(0.2)
    return False


@pytest.mark.slow
def test_watch_keeps_one_drawing_worker_that_degrades_and_ends_cleanly(tmp_path, monkeypatch,
                                                                       default_store):
    """The drawings of every run are made by one worker process kept for the
    session (not the watch process); a killed worker leaves the run to make
    them itself, the next run has a new one; the files the worker and the
    FreeCAD process kept for the session made are a plain export's, byte for
    byte; Ctrl-C ends the watch and its children, kill -9 too. The session
    starts from the default design's store, so the jobs the edits change are
    the ones made in the session, and the plain export makes them afresh."""
    import os

    from tactcad.design.project import load_project
    from tactcad.export.run import export

    monkeypatch.delenv("TACTCAD_WORKERS", raising=False)
    store = warm_store_copy(default_store, tmp_path / "store")
    s = _Session(tmp_path, store)
    try:
        _, pid = _worker(s.next_export())
        assert pid not in (0, s.proc.pid) and pid in s.children()
        made, same = _worker(s.edit(4.3))  # a one-arm edit: its drawing, the sheet, the PDF
        assert made >= 3 and same == pid
        man = json.loads((s.out / "manifest.json").read_text())
        assert "drawings/element_a4p3mm.svg" in {f["path"] for f in man["files"]}
        os.kill(pid, signal.SIGKILL)
        made, _ = _worker(s.edit(4.6))  # the run makes the drawings itself
        assert made == 0
        man = json.loads((s.out / "manifest.json").read_text())
        assert "drawings/element_a4p6mm.svg" in {f["path"] for f in man["files"]}
        made, again = _worker(s.edit(4.9))  # and the next run has a new worker
        assert made >= 3 and again not in (pid, s.proc.pid)
        children = s.children()  # the worker and the FreeCAD process kept for the review files
        assert any(b"freecad" in _read(f"/proc/{k}/cmdline").lower() for k in children)
    finally:
        s.proc.send_signal(signal.SIGINT)
        s.proc.wait(timeout=60)
    err = s.all_lines()
    assert s.proc.returncode == 0 and "stopped" in err and "Traceback" not in err
    assert again in children and _gone(children)
    plain = tmp_path / "plain"
    export(load_project(s.design), plain, log=lambda line: None,
           store=Store(warm_store_copy(default_store, tmp_path / "plain-store")))
    script = Path(__file__).resolve().parents[2] / "scripts" / "compare_exports.py"
    same = subprocess.run([sys.executable, str(script), str(s.out), str(plain)],
                          capture_output=True, text=True)
    assert same.returncode == 0, same.stdout
    # kill -9 of the watch: its worker dies with it
    (tmp_path / "again").mkdir()
    s2 = _Session(tmp_path / "again", store)
    try:
        _, pid = _worker(s2.next_export())
        s2.proc.kill()
        s2.proc.wait(timeout=60)
        assert _gone([pid])
    finally:
        if s2.proc.poll() is None:
            s2.proc.kill()


@pytest.mark.slow
def test_served_scenes_follow_the_last_choice_and_free_the_ones_left(exported, project):
    """Served by the watch's server: a big scene chosen and at once a small one (the big
    one's bytes arriving last) shows the small one; scenes shown in turn do not pile up
    on the GPU; a highlighted part stays highlighted in a scene parsed again."""
    import threading
    import time

    from tactcad.checks.review_browser import BrowserMissing, browser_page, chromium_path
    from tactcad.export.job import Run
    from tactcad.export.jobs import review_contents_of
    from tactcad.export.review_page import REVIEW_PAGE, ReviewContents

    try:
        chromium_path()
    except BrowserMissing as exc:
        pytest.skip(str(exc))
    out, _ = exported
    contents = review_contents_of(Run(project, out), out)
    state = LiveState()
    state.publish(project.plan.design_hash, "current", contents, (out / REVIEW_PAGE).read_bytes())
    names = contents.data["scenes"]
    big = max(names, key=lambda n: len(contents.scenes[n]))
    small = min(names, key=lambda n: len(contents.scenes[n]))
    slow, answer = contents.data["scene_sha256"][big], state.response

    def late(path):  # the big scene's bytes come a second late
        if path.endswith(slow):
            time.sleep(1.0)
        return answer(path)

    state.response = late
    server = make_server(state, 0)
    threading.Thread(target=server.serve_forever, args=(0.05,), daemon=True).start()

    def choose(*scenes, late_ms=0):
        """Choose the scenes in turn at once; return when the last is shown (and
        ``late_ms`` more, for a late answer to an earlier choice to arrive)."""
        page.evaluate("""(names) => { const s = document.querySelector('#scene-select');
            for (const n of names) { s.value = n; s.dispatchEvent(new Event('change')); } }""",
                      list(scenes))
        page.wait_for_function(f"window.__review.scene === {json.dumps(scenes[-1])}",
                               timeout=60000)
        page.wait_for_timeout(late_ms)

    try:
        with browser_page(offline=False) as page:
            page.goto(f"http://127.0.0.1:{server.server_address[1]}/")
            page.wait_for_function("window.__review && window.__review.ready")
            page.wait_for_timeout(500)
            page.locator("#tree .instance").first.click()  # highlight one instance
            lit = page.evaluate("window.__review.lit()")
            first = names[0]
            choose(big, small, late_ms=1500)  # the big scene's bytes arrive meanwhile
            shown = "[window.__review.scene, document.querySelector('#scene-select').value]"
            assert page.evaluate(shown) == [small, small]
            choose(first)
            held = page.evaluate("window.__review.gpu().geometries")
            for _ in range(2):
                choose(small)
                choose(first)
            assert page.evaluate("window.__review.gpu().geometries") == held
            assert len(lit) == 1 and page.evaluate("window.__review.lit()") == lit
            # an update without the scene shown: the first one, fitted as when chosen
            fitted = page.evaluate("window.__review.view()")
            choose(big)
            kept = {n: b for n, b in contents.scenes.items() if n != big}
            state.publish(project.plan.design_hash, "current", ReviewContents(
                {**contents.data, "scenes": list(kept)}, kept, contents.sheets))
            page.wait_for_function("window.__review.scene !== %s" % json.dumps(big))
            page.wait_for_timeout(500)
            assert page.evaluate("window.__review.scene") == first
            view = page.evaluate("window.__review.view()")
            assert sum(view, []) == pytest.approx(sum(fitted, []))
            assert page.errors == []
    finally:
        server.shutdown()
        server.server_close()


def test_keep_only_drops_what_the_design_no_longer_has():
    from tactcad.export.live_parts import keep_only

    solids, meshes = {"a": 1, "b": 2, "c": 3}, {"a": 4, "d": 5}
    assert keep_only({"a", "c"}, solids, meshes) == 2
    assert solids == {"a": 1, "c": 3} and meshes == {"a": 4}


@pytest.mark.slow
def test_a_long_session_keeps_the_parts_of_the_current_design_only(tmp_path, monkeypatch,
                                                                  default_store):
    """Edit after edit, the watch process holds the solids and meshes of the design
    it shows (every part of the array and its scenes), not of every earlier edit;
    the drawing worker drops its own as a run begins."""
    import pickle

    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.design.project import load_project
    from tactcad.export.job import Run, solid_key
    from tactcad.export.jobs import all_jobs
    from tactcad.export import worker as w
    from tactcad.benchmarks.bench_watch import edit_first_arm

    monkeypatch.setenv("TACTCAD_WORKERS", "0")  # this process makes everything
    for f in watched_files(DEFAULT_DESIGN):
        shutil.copyfile(f, tmp_path / f.name)
    design = tmp_path / DEFAULT_DESIGN.name
    loop = Loop(lambda: load_project(design), tmp_path / "out",
                Store(warm_store_copy(default_store, tmp_path / "store")),
                LiveState(), lambda s: None)
    assert loop.update()
    edit_first_arm(design, 4.3)
    assert loop.update()
    before = set(loop.solids)
    edit_first_arm(design, 4.6)
    assert loop.update()
    project = load_project(design)
    now = {solid_key(s) for s in Run(project, tmp_path).inventory[0].values()}
    assert set(loop.solids) == now and set(loop.meshes) <= now
    assert len(before - now) == 1  # the 4.3 mm arm's element is gone
    # the worker: a run begins with only its own jobs' parts kept
    w._KEPT["solids"].update({"gone": object(), next(iter(now)): "kept"})
    w._begin_run(pickle.dumps((project, tmp_path, Store(None), None, all_jobs)))
    assert "gone" not in w._KEPT["solids"] and next(iter(now)) in w._KEPT["solids"]
    w._KEPT["solids"].clear()
    w._INHERITED.clear()


def _descendants(pid: int) -> set[int]:
    """Every process below ``pid`` (children, theirs...)."""
    from pathlib import Path

    found: set[int] = set()
    todo = [pid]
    while todo:
        for f in Path(f"/proc/{todo.pop()}/task").glob("*/children"):
            try:
                kids = {int(p) for p in f.read_text().split()}
            except OSError:  # ended meanwhile
                continue
            todo += sorted(kids - found)
            found |= kids
    return found


@pytest.mark.slow
def test_sigterm_mid_update_ends_the_watch_cleanly(tmp_path, default_store):
    """SIGTERM while an edit is being exported: the watch says "stopped" and exits
    with 0 (docs/how-to/watch.md: stopping is a watch's normal end), leaving no staging folder
    in or beside --out, and none of its processes (drawing worker, freecadcmd,
    server process) behind; the last good export stays whole."""
    import time

    from tactcad.benchmarks.bench_watch import edit_first_arm

    s = _Session(tmp_path, warm_store_copy(default_store, tmp_path / "store"))
    try:
        s.next_export()
        before = json.loads((s.out / "manifest.json").read_text())
        children = _descendants(s.proc.pid)
        assert len(children) >= 3  # the worker, freecadcmd, the server process (and more)
        edit_first_arm(s.design, 4.4)
        deadline = time.monotonic() + 300
        while not list(tmp_path.glob(".out.staging-*")):  # the edit's export is under way
            assert time.monotonic() < deadline and s.proc.poll() is None, \
                "no export of the edit began"
            time.sleep(0.01)
        children |= _descendants(s.proc.pid)
        s.proc.send_signal(signal.SIGTERM)
        code = s.proc.wait(timeout=120)
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
    err = s.all_lines()
    assert code == 0 and "watch: stopped" in err and "Traceback" not in err, err
    assert err.count("export current") == 1  # the edit's export was cut short
    assert "leaked" not in err and "left behind" not in err
    assert not list(tmp_path.glob(".out.*")) and not list(s.out.glob(".*staging*"))
    assert json.loads((s.out / "manifest.json").read_text()) == before
    assert _gone(children)


def test_a_ctrl_c_lost_on_its_way_still_stops_the_watch():
    """A Ctrl-C whose KeyboardInterrupt something swallows (here: a bare
    except, as in a library call) is still noted in the watch's stop event,
    which ends the session after the update; the handlers are put back."""
    import os
    import threading
    import time

    from tactcad.commands.watch import note_stop_signals

    before = signal.getsignal(signal.SIGINT)
    # a fresh interpreter's handler, whatever this worker's earlier tests left
    signal.signal(signal.SIGINT, signal.default_int_handler)
    stop = threading.Event()
    restore = note_stop_signals(stop)

    def ctrl_c_until_noted() -> None:
        # sent again while not noted: a C system() in another thread of this
        # worker ignores SIGINT process-wide while it runs, and a signal sent
        # then is gone
        for _ in range(500):
            if stop.is_set():
                return
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.01)  # the handler runs here, in the main thread

    try:
        for _ in range(3):
            try:
                ctrl_c_until_noted()
                break
            except KeyboardInterrupt:  # lost on its way: nobody re-raises it
                pass
        assert stop.is_set()
    finally:
        restore()
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
        signal.signal(signal.SIGINT, before)


def test_a_companion_named_as_a_symbolic_link_loop_is_watched_not_a_crash(tmp_path):
    (tmp_path / "a.toml").symlink_to("b.toml")
    (tmp_path / "b.toml").symlink_to("a.toml")
    design = tmp_path / "d.toml"
    design.write_text('[files]\nrigs = "a.toml"\n', encoding="utf-8")
    files = watched_files(design)  # the refusal is the loader's; the watch waits for the fix
    folder = tmp_path.resolve()
    assert files == [folder / "d.toml", folder / "a.toml", folder / "scenes.toml"]



@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_stop_at_the_programs_first_line_is_held_until_the_command_answers_it(tmp_path, signum):
    """Ctrl-C or SIGTERM the moment ``python -m tactcad`` has its stop
    handlers (its first line; the command line's modules load after it): the
    watch's own end (exit 0, "stopped", no traceback), not an interrupted import."""
    from tactcad.benchmarks.watch_stop import stop_round

    design = tmp_path / "d.toml"
    design.write_text("", encoding="utf-8")  # never exported: the stop comes first
    got = stop_round([design], "start", signum, 0.0, wait_s=60)
    assert got.exit_code == 0 and got.stopped_line and not got.traceback, got
    assert got.left_behind == 0, got


def test_a_command_stopped_while_it_loads_reports_the_interrupt_without_a_traceback(tmp_path):
    """Not a watch: the held Ctrl-C is the command's interrupt (exit 130, its line)."""
    from tactcad.benchmarks.watch_stop import program_started

    proc = subprocess.Popen([sys.executable, "-m", "tactcad", "export", "--design",
                             str(tmp_path / "none.toml"), "--out", str(tmp_path / "out")],
                            stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=ctrl_c_at_its_default)
    assert program_started(proc)
    proc.send_signal(signal.SIGINT)
    err = proc.communicate(timeout=60)[1]
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "interrupted" in err, err


@pytest.mark.slow
def test_a_watch_stopped_at_random_moments_ends_with_its_status(tmp_path, default_store):
    """Ctrl-C (to the whole process group, as a terminal sends it) or SIGTERM
    at random moments of the start-up, the first export, an edit's export and
    serving: each watch ends with exit 0, its "stopped" line, no traceback
    and no process of its group left (``tactcad bench watch-stop`` runs 20
    and times them; a hang shows here as a round that did not end)."""
    import random

    from tactcad.benchmarks.watch_stop import EDIT_WINDOW_S, stop_round
    from tactcad.design.array_plan import DEFAULT_DESIGN

    rng = random.Random()
    store = warm_store_copy(default_store, tmp_path / "store")
    files = watched_files(DEFAULT_DESIGN)
    rounds = [("start", signal.SIGINT, rng.uniform(0.0, 6.0)),
              ("start", signal.SIGTERM, rng.uniform(0.0, 6.0)),
              ("edit", signal.SIGINT, rng.uniform(0.0, EDIT_WINDOW_S))]
    for phase, signum, moment in rounds:
        got = stop_round(files, phase, signum, moment, store_from=store, wait_s=120)
        assert got.ended_s is not None, got  # it ended at all
        assert got.exit_code == 0 and got.stopped_line and not got.traceback, got
        assert got.left_behind == 0, got


@pytest.mark.parametrize("argv, streams", [
    (["watch", "--json", "--poll"], True),
    (["--quiet", "watch", "--json"], True),
    (["verify", "--json"], False),
])
def test_watch_json_lines_go_out_as_they_happen_not_held_for_one_object(monkeypatch, argv,
                                                                        streams):
    # every event of `watch --json | consumer` arrived at once when the watch stopped:
    # stdout was held to merge warnings into one JSON object, as for the other commands
    import io

    from tactcad import cli

    seen = []

    def dispatch(argv, as_json):
        seen.append(isinstance(sys.stdout, io.StringIO))
        print('{"event": "x"}')
        return 0

    monkeypatch.setattr(cli, "dispatch", dispatch)
    assert cli.run_command(argv) == 0
    assert seen == [not streams] and cli.streams_json_lines(argv) is streams


def test_the_files_said_watched_are_those_the_project_has_or_names(tmp_path):
    """watch in a comb project said it watched rigs.toml, a file a comb has not."""
    from tactcad.commands.watch import named_files
    from tactcad.project_folder import new_project

    comb = new_project(tmp_path / "comb", example="grasper_jaw_10mm").design
    folder = comb.parent.resolve()
    assert named_files(comb) == [folder / "comb.toml", folder / "scenes.toml"]
    assert folder / "rigs.toml" in watched_files(comb)  # still watched for, never said
    design = tmp_path / "d.toml"
    design.write_text('[files]\nrigs = "mine.toml"\n', encoding="utf-8")
    assert [p.name for p in named_files(design)] == ["d.toml", "mine.toml"]  # named: said
