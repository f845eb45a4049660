"""The review page as ``tactcad watch`` serves it: the page's data and scenes
on their own, the export's page itself unchanged (fast; the page under watch
in Chromium is tests/test_watch.py)."""

from __future__ import annotations

import hashlib
import json
import re

from tactcad.export.live import LiveState
from tactcad.export.live_page import checks_json, live_view
from tactcad.export.review_page import checks_script, page_data, page_html


def _page(name="demo", scenes=None) -> bytes:
    facts = {"design": {"name": name, "source": "d.toml", "sha256": "ab" * 32},
             "tactcad_version": "0", "cad_stack": {}, "units": "mm", "files": []}
    data = page_data(facts, [("drawings/a.svg", "a", "<svg/>")], ["s", "t"],
                     "item,part\n1,a\n", [], "A", "2026-01-01", "0.187.0")
    return page_html(data, scenes or {"s": b"glb-s", "t": b"glb-t"}, '{"imports": {}}').encode()


def test_the_served_page_swaps_only_the_live_reload_and_knows_its_scenes():
    page = _page()
    view = live_view(page, 7)
    digests = {"s": hashlib.sha256(b"glb-s").hexdigest(), "t": hashlib.sha256(b"glb-t").hexdigest()}
    assert view.scenes == digests and view.glbs == {digests["s"]: b"glb-s", digests["t"]: b"glb-t"}
    assert b"fetch('/', " in page and b"fetch('/', " not in view.page  # the whole page: not again
    assert b"fetch('/data'" in view.page and b"@@LIVE@@" not in view.page
    live = re.search(rb"const LIVE = (\{.*?\});", view.page).group(1)
    assert json.loads(live) == {"seq": 7, "scenes": digests}
    head = page[:page.index(b"// --- live reload")]
    assert view.page.startswith(head) and view.page.endswith(b"</script>\n</body>\n</html>\n")


def test_data_carries_the_page_data_scene_digests_and_checks():
    page = _page(name="</script>@@LIVE@@")
    state = LiveState()
    state.publish(page, "ab" * 32, "current", checks_script("ab" * 32, []))
    body, kind = state.response("/data")
    doc = json.loads(body)
    assert kind == "application/json" and doc["seq"] == 1 and doc["sha256"] == "ab" * 32
    assert doc["data"]["manifest"]["design"]["name"] == "</script>@@LIVE@@"
    assert doc["checks"] == {"design_sha256": "ab" * 32, "passed": 0, "failed": 0, "checks": []}
    glb = state.response("/scene/" + doc["scenes"]["t"])
    assert glb == (b"glb-t", "model/gltf-binary")
    assert state.response("/scene/") is None and state.response("/scene/../s") is None
    assert state.response("/index.html")[0] == live_view(page, 1).page


def test_a_page_may_ask_for_the_scenes_of_the_page_before():
    state = LiveState()
    state.publish(_page(scenes={"s": b"old"}), "ab" * 32, "current")
    state.publish(_page(scenes={"s": b"new"}), "ab" * 32, "current")
    assert state.response("/scene/" + hashlib.sha256(b"old").hexdigest())[0] == b"old"
    state.publish(_page(scenes={"s": b"newer"}), "ab" * 32, "current")
    assert state.response("/scene/" + hashlib.sha256(b"old").hexdigest()) is None


def test_checks_not_written_by_tactcad_are_not_passed_on():
    assert checks_json(None) is None and checks_json("alert(1)") is None
    assert checks_json("window.TACTCAD_CHECKS = {oops;\n") is None
    assert json.loads(checks_json(checks_script("cd" * 32, [])))["failed"] == 0


def test_a_page_that_is_not_a_review_page_is_served_as_it_is():
    state = LiveState()
    state.publish(b"<html>page</html>", "ab" * 32, "current")
    assert state.response("/")[0] == b"<html>page</html>"
    assert json.loads(state.response("/data")[0])["data"] is None
