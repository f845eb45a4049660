"""The review page as ``tactcad watch`` serves it: the exported page as it is,
its data, scenes and sheets on their own (fast; the page under watch in
Chromium is tests/commands/test_watch.py)."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from tactcad.export.live import LiveState
from tactcad.export.live_page import checks_json
from tactcad.checks.review_results import checks_script
from tactcad.export.review_page import page_html, review_contents

IMPORTS = '{"imports": {}}'


def _contents(name="demo", scenes=None, sheet="<svg/>"):
    facts = {"design": {"name": name, "source": "d.toml", "sha256": "ab" * 32},
             "tactcad_version": "0", "cad_stack": {}, "units": "mm", "files": []}
    return review_contents(facts, [("drawings/a.svg", "a", sheet)],
                           scenes or {"s": b"glb-s", "t": b"glb-t"}, "item,part\n1,a\n", [], "A",
                           "2026-01-01", "0.187.0")


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def test_the_exported_page_is_served_as_it_is_and_reads_its_data_when_served():
    contents = _contents()
    page = page_html(contents, IMPORTS).encode()
    state = LiveState()
    state.publish("ab" * 32, "current", contents, page)
    assert state.response("/")[0] == page and state.response("/index.html")[0] == page
    assert b"fetch('/data'" in page and b"fetch('/', " not in page  # never the whole page again


def test_data_before_the_first_export_says_what_the_watch_is_doing():
    """``/data`` before anything is published: the fields the page reads (no
    data to show, which it skips) and the watch's status, not ``null``."""
    from tactcad.export.live import Loop
    from tactcad.store import Store

    state = LiveState()
    doc = json.loads(state.response("/data")[0])
    assert doc == {"seq": 0, "sha256": "", "checks": None, "data": None, "status": "starting",
                   "refusal": None}
    said = []
    state.on_change = lambda: said.append(json.loads(state.response("/data")[0]).get("status"))

    class Planless:  # the export fails at once, after the status is said
        @property
        def plan(self):
            raise OSError("no plan")

    assert Loop(lambda: Planless(), Path("unused"), Store(None), state, lambda s: None).update() \
        is False
    assert said[0] == "first export under way"
    doc = json.loads(state.response("/data")[0])
    assert doc["data"] is None and doc["status"] == "last edit refused" and "no plan" in \
        doc["refusal"]
    state.publish("ab" * 32, "current", _contents())
    assert json.loads(state.response("/data")[0])["data"] is not None


def test_data_names_scenes_and_sheets_by_sha256_and_carries_the_checks():
    state = LiveState()
    state.publish("ab" * 32, "current", _contents(name="</script>@@DATA@@"),
                  checks_js=checks_script("ab" * 32, []))
    body, kind = state.response("/data")
    doc = json.loads(body)
    assert kind == "application/json" and doc["seq"] == 1 and doc["sha256"] == "ab" * 32
    data = doc["data"]
    assert data["manifest"]["design"]["name"] == "</script>@@DATA@@"
    assert {k: v for k, v in doc["checks"].items() if k != "groups"} == {
        "design_sha256": "ab" * 32, "passed": 0, "failed": 0, "undecided": 0, "info": 0,
        "checks": []}
    assert data["scene_sha256"] == {"s": _sha(b"glb-s"), "t": _sha(b"glb-t")}
    assert "svg_base64" not in json.dumps(data)  # the sheets' bytes are fetched by sha256
    assert state.response("/scene/" + _sha(b"glb-t")) == (b"glb-t", "model/gltf-binary")
    assert state.response("/sheet/" + data["sheets"][0]["sha256"]) == (b"<svg/>", "image/svg+xml")
    for path in ("/scene/", "/scene/../s", "/sheet/" + _sha(b"glb-t"), "/scene/" + _sha(b"<svg/>"),
                 "/x/scene/" + _sha(b"glb-t")):
        assert state.response(path) is None, path


def test_a_page_may_ask_for_the_scenes_and_sheets_of_the_state_before():
    state = LiveState()
    state.publish("ab" * 32, "current", _contents(scenes={"s": b"old"}, sheet="<svg>1</svg>"))
    state.publish("ab" * 32, "current", _contents(scenes={"s": b"new"}, sheet="<svg>2</svg>"))
    assert state.response("/scene/" + _sha(b"old"))[0] == b"old"
    assert state.response("/sheet/" + _sha(b"<svg>1</svg>"))[0] == b"<svg>1</svg>"
    state.publish("ab" * 32, "current", _contents(scenes={"s": b"newer"}, sheet="<svg>3</svg>"))
    assert state.response("/scene/" + _sha(b"old")) is None
    assert state.response("/sheet/" + _sha(b"<svg>1</svg>")) is None


def test_a_preview_keeps_the_last_exported_page():
    state = LiveState()
    state.publish("ab" * 32, "current", _contents(), b"<html>exported</html>")
    state.publish("cd" * 32, "3D updated; drawings follow", _contents(scenes={"s": b"next"}))
    assert state.response("/")[0] == b"<html>exported</html>"
    assert json.loads(state.response("/data")[0])["sha256"] == "cd" * 32


def test_checks_not_written_by_tactcad_are_not_passed_on():
    assert checks_json(None) is None and checks_json("alert(1)") is None
    assert checks_json("window.TACTCAD_CHECKS = {oops;\n") is None
    assert json.loads(checks_json(checks_script("cd" * 32, [])))["failed"] == 0


def test_without_a_review_page_the_data_is_null():
    state = LiveState()
    state.publish("ab" * 32, "current", None, b"<html>page</html>")
    assert state.response("/")[0] == b"<html>page</html>"
    assert json.loads(state.response("/data")[0])["data"] is None
