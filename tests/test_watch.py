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

import pytest

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
    state.publish(b"<html>page</html>", "ab" * 32, "current")
    server = make_server(state, 0)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        base = f"http://127.0.0.1:{server.server_address[1]}"
        assert _get(base + "/") == (200, b"<html>page</html>")
        code, body = _get(base + "/state")
        assert code == 200 and json.loads(body)["seq"] == 1
        assert _get(base + "/../etc/passwd")[0] == 404
    finally:
        server.shutdown()
        server.server_close()


def test_a_refused_edit_keeps_the_last_page(tmp_path):
    state = LiveState()
    state.publish(b"good", "cd" * 32, "current")

    def load():
        raise DesignError("arms.lengths_mm[1]", -3.0, "2 <= value <= 20 mm")

    lines = []
    assert Loop(load, tmp_path, Store(None), state, lines.append).update() is False
    doc = json.loads(state.as_json())
    assert doc["seq"] == 1 and state.page == b"good"
    assert "arms.lengths_mm[1] = -3.0" in doc["refusal"] and "2 <= value" in doc["refusal"]
    assert "arms.lengths_mm[1]" in lines[0]


def test_bad_port_is_refused_naming_the_option(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "tactcad.cli", "watch", "--port", "80", "--out",
                           str(tmp_path / "o")], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "--port" in proc.stderr and "Traceback" not in proc.stderr


@pytest.mark.slow
def test_watch_session_in_chromium(tmp_path):
    from tactcad.checks.review_browser import BrowserMissing, browser_page, chromium_path
    from tactcad.design.array import DEFAULT_DESIGN
    from tactcad.studies.bench_watch import _free_port, _state, _wait, edit_first_arm

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
                             str(tmp_path / "store")], stderr=subprocess.PIPE, text=True)
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
            edit_first_arm(design, 4.6)
            page.wait_for_function(f"window.__review.shownSha256 !== {json.dumps(first)}",
                                   timeout=120000)
            assert page.evaluate("window.__review.view()") == view
            assert not page.locator('#tree label[data-instance="element_3"] input').is_checked()
            assert page.locator('#tree label[data-instance="element_4"] input').is_checked()
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
