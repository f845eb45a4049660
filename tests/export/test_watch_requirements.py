"""Under watch, a design that fails requirements is current but says so: the
terminal line counts them and the served state lists them for the page's
red banner."""

from __future__ import annotations

import json

from tactcad.export.live import requirements_not_met, unmet_words
from tactcad.export.live_server import LiveState, state_update, Held


def _manifest(tmp_path, verdicts):
    matrix = [{"requirement": f"r{i}", "pass": v != "fail", "verdict": v}
              for i, v in enumerate(verdicts)]
    (tmp_path / "manifest.json").write_text(json.dumps(
        {"requirements": {"closed_form_matrix": matrix}}))


def test_the_failed_requirements_are_counted_from_the_exports_manifest(tmp_path):
    assert requirements_not_met(tmp_path) == ([], 0)  # no manifest: nothing to say
    _manifest(tmp_path, ["pass", "fail", "undecided", "fail"])
    assert requirements_not_met(tmp_path) == (["r1", "r3"], 4)
    assert unmet_words(["r1", "r3"], 4) == "2 of 4 requirements not met: r1, r3"


def test_the_served_state_carries_them_to_the_server_process():
    state = LiveState()
    state.publish("ab" * 32, "current", unmet=("kr_over_km",))
    assert json.loads(state.as_json())["unmet"] == ["kr_over_km"]
    assert not state.previewed  # still the current export
    served = LiveState()
    update, _ = state_update(state, Held())
    served.apply(update)
    assert json.loads(served.as_json())["unmet"] == ["kr_over_km"]
    state.publish("ab" * 32, "current")
    assert json.loads(state.as_json())["unmet"] == []


def test_the_page_never_asks_watch_for_a_file_it_lacks():
    from tactcad.export.live_server import NO_CHECKS_JS

    state = LiveState()
    body, kind = state.response("/checks.js")  # before tactcad check has run
    assert body == NO_CHECKS_JS and kind.startswith("text/javascript")
    state.publish("ab" * 32, "current", checks_js="window.TACTCAD_CHECKS = {};\n")
    assert state.response("/checks.js")[0] == b"window.TACTCAD_CHECKS = {};\n"
