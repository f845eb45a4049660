"""Under watch, a design that fails requirements is current but says so: the
terminal line counts them and the served state lists them for the page's
red banner."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tactcad.export.live import requirements_not_met, unmet_words
from tactcad.export.live_server import LiveState, state_update, Held

GRASPER = Path(__file__).resolve().parents[2] / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


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


def test_the_export_line_names_each_failed_requirement_with_its_margin(tmp_path):
    from tactcad.export.live import unmet_line

    assert unmet_line(tmp_path) == ""  # no manifest: nothing to say
    matrix = [{"requirement": "full_scale_force_N", "verdict": "pass", "margin_rel": 0.3},
              {"requirement": "kobj_resolution_rel", "verdict": "fail", "margin_rel": -0.559},
              {"requirement": "k_tolerance_rel", "informational": True, "verdict": "info"},
              {"requirement": "kr_over_km", "verdict": "fail", "margin_rel": -0.2,
               "allowed_margin_rel": -0.1}]
    (tmp_path / "manifest.json").write_text(json.dumps(
        {"requirements": {"closed_form_matrix": matrix}}))
    assert unmet_line(tmp_path) == (
        "2 of 4 requirements not met: kobj_resolution_rel (margin -55.9 %), kr_over_km "
        "(margin -20.0 % (allowed -10.0 %)); `tactcad verify` for the table")
    _manifest(tmp_path, ["pass", "info"])
    assert unmet_line(tmp_path) == ""  # every one met: nothing, as under watch


class _Result:
    """What the export command reads of an export's result."""

    def __init__(self, out):
        self.out_dir = out

    def summary_lines(self):
        return ["1 files"]

    def as_json(self):
        return {"out": str(self.out_dir)}


@pytest.mark.parametrize("json_flag", [False, True])
def test_a_metal_export_ends_with_the_requirements_not_met(tmp_path, monkeypatch, json_flag):
    from conftest import run_cli

    import tactcad.export.run as export_run

    out = tmp_path / "x"

    def fake_export(project, folder, **kw):  # the manifest export writes, failing one
        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "manifest.json").write_text(json.dumps({"requirements": {
            "closed_form_matrix": [{"requirement": "kobj_resolution_rel", "verdict": "fail",
                                    "margin_rel": -0.559},
                                   {"requirement": "kr_over_km", "verdict": "pass"}]}}))
        return _Result(folder)

    monkeypatch.setattr(export_run, "export", fake_export)
    r = run_cli("export", "--design", str(GRASPER), "--out", str(out), "--quiet",
                *(["--json"] if json_flag else []))
    assert r.returncode == 0, r.stderr  # the files are written: not a failure
    line = ("1 of 2 requirements not met: kobj_resolution_rel (margin -55.9 %); "
            "`tactcad verify` for the table")
    if json_flag:
        assert json.loads(r.stdout)["out"] == str(out) and line in r.stderr
    else:
        assert r.stdout.splitlines()[-1] == line
